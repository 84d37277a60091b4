#include "case.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "linkage.h"
#include "mech_kinematics.h"
#include "slider_crank_invdyn.h"
#include "model_table.h"

static fb_status check_drivable(const fb_linkage *lk, const char *which, fb_diag *diag) {
  double lo, hi;
  int full;
  fb_diag inner;
  fb_status st = fb_linkage_crank_range(lk, &lo, &hi, &full, &inner);
  if (st != FB_OK)
    return fb_diag_set(diag, st, "%s linkage cannot be assembled: %s", which, inner.msg);
  /* (by the class's tolerance: the strict test alone can pass on roundoff) */
  if (fb_linkage_grashof(lk) == FB_GRASHOF_CHANGE_POINT) {
    char g[512];
    fb_linkage_grashof_text(g, sizeof g, lk);
    return fb_diag_set(diag, FB_ERR_ASSEMBLY,
                       "%s linkage: %s; a crank driven at constant speed cannot pass a fold: "
                       "make s + l differ from p + q (s + l < p + q for a crank-rocker) with "
                       "[linkage] crank_mm, coupler_mm, follower_mm, ground_mm",
                       which, g);
  }
  if (!full)
    return fb_diag_set(diag, FB_ERR_ASSEMBLY,
                       "%s linkage (%s): the crank cannot turn fully, but it is driven "
                       "at constant speed: it reaches only crank angles with |theta2| in "
                       "[%.3f, %.3f] deg; "
                       "a driven crank needs coupler + follower > crank + ground and "
                       "|coupler - follower| < |ground - crank|",
                       which, fb_grashof_name(fb_linkage_grashof(lk)), lo * 180.0 / M_PI,
                       hi * 180.0 / M_PI);
  return FB_OK;
}

/* the slider-crank's counterpart of the Grashof line: its class by
 * coupler against crank + |offset|, the stroke and the dead centres, the
 * smallest transmission angle */
static void slider_crank_text(const fb_case *c, char *out, size_t size) {
  const fb_slider_crank sc = fb_slider_crank_of(&c->nominal);
  const double sum = sc.crank + fabs(sc.offset);
  const size_t n = (size_t)snprintf(
      out, size, "slider-crank, %s: coupler %.6g mm against crank + |offset| = %.6g mm (margin %.4g mm)",
      fb_sc_class_name(fb_slider_crank_class(&sc)), sc.coupler * 1e3, sum * 1e3,
      (sc.coupler - sum) * 1e3);
  fb_slider_crank_limits lim;
  if (n < size && fb_slider_crank_limit_positions(&lim, &sc, NULL) == FB_OK)
    snprintf(out + n, size - n, "; stroke %.6g mm between the dead centres x = %.6g and %.6g mm; "
             "smallest transmission angle %.4g deg", lim.stroke * 1e3, lim.x_min * 1e3,
             lim.x_max * 1e3, lim.transmission_min * 180.0 / M_PI);
}

void fb_case_grashof_text(const fb_case *c, char *out, size_t size) {
  if (c->mechanism == FB_MECH_SLIDER_CRANK) {
    slider_crank_text(c, out, size);
    return;
  }
  fb_linkage_grashof_text(out, size, &c->nominal);
  size_t n = strlen(out);
  fb_linkage su;
  fb_case_stackup_lengths(c, &su);
  const fb_grashof gn = fb_linkage_grashof(&c->nominal), gs = fb_linkage_grashof(&su);
  if (gs != gn && n < size)
    n += (size_t)snprintf(out + n, size - n, "; at the stack-up corner: %s", fb_grashof_name(gs));
  double sl, pq, tol = 0.0;
  fb_linkage_grashof_sums(&c->nominal, &sl, &pq, NULL, NULL);
  for (int i = 0; i < FB_LINK_COUNT; i++) tol += c->plus_minus[i];
  if (gn != FB_GRASHOF_CHANGE_POINT && tol > 0.0 && fabs(pq - sl) <= tol && n < size)
    snprintf(out + n, size - n, "; within the length tolerances (+- %.4g mm summed) the linkage "
             "can reach the change point, %.4g mm away", tol * 1e3, fabs(pq - sl) * 1e3);
}

/* a slider-crank's lengths (nominal and at the stack-up corner), its one
 * clearance joint (the piston pin) and the models that build it */
static fb_status check_slider_crank(const fb_case *c, fb_diag *diag) {
  fb_linkage su;
  fb_case_stackup_lengths(c, &su);
  const fb_linkage *lk[2] = {&c->nominal, &su};
  static const char *const which[2] = {"nominal", "stack-up"};
  for (int k = 0; k < 2; k++) {
    fb_diag inner;
    if (fb_mech_check_lengths(FB_MECH_SLIDER_CRANK, lk[k], &inner) != FB_OK)
      return fb_diag_set(diag, FB_ERR_ASSEMBLY,
                         "%s slider-crank ([linkage] crank_mm = %g, coupler_mm = %g, offset_mm = "
                         "%g): %s; a crank driven at constant speed needs coupler > crank + "
                         "|offset|",
                         which[k], lk[k]->length[FB_CRANK] * 1e3, lk[k]->length[FB_COUPLER] * 1e3,
                         lk[k]->length[FB_LENGTH_OFFSET] * 1e3, inner.msg);
  }
  for (int i = 0; i < 2; i++)
    if (!(c->plus_minus[i] >= 0.0) || c->plus_minus[i] >= c->nominal.length[i])
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "[tolerance] %s_plus_minus_mm = %g: a tolerance must be >= 0 and smaller "
                         "than the length [linkage] %s_mm = %g",
                         fb_link_name(i), c->plus_minus[i] * 1e3, fb_link_name(i),
                         c->nominal.length[i] * 1e3);
  /* the joints the description lets carry clearance: the piston pin */
  const fb_mech_desc *mech = fb_case_mech(c);
  for (int j = 0; j < mech->njoints; j++)
    if ((c->clearance.mask & (1 << j)) && !mech->joint[j].clearance_ok)
      return fb_diag_set(diag, FB_ERR_ARG,
                         "[clearance] joints names %s: a slider-crank's clearance joint is its "
                         "piston pin, %s (the models and the reference take it there; "
                         "ground-crank and crank-coupler are ideal, and the prismatic "
                         "slider-ground is a guide, not a pin): set joints = %s or none",
                         mech->joint[j].name, mech->joint[mech->reference_joint].name,
                         mech->joint[mech->reference_joint].name);
  if (c->clearance.mask && c->clearance.penalty == FB_PENALTY_SOURCE_PAPER)
    return fb_diag_set(diag, FB_ERR_ARG,
                       "[clearance] penalty = paper: the paper's stiffness recipe (its Tables II "
                       "and III) is the four-bar's, from its coupler and follower accelerations; "
                       "for a slider-crank use penalty = physical, goldsmith or explicit");
  if (c->stackup.worst)
    return fb_diag_set(diag, FB_ERR_ARG,
                       "[tolerance] stackup = worst: the worst corner is searched for the "
                       "four-bar only; give a slider-crank's corner as max, min, nominal or "
                       "its characters (crank, coupler, offset, then any)");
  for (int i = 0; i < c->model_count; i++) {
    const fb_model *m;
    fb_status st = fb_model_lookup(&m, c->models[i], diag);
    if (st != FB_OK) return st;
    if (!fb_model_builds(m, FB_MECH_SLIDER_CRANK))
      return fb_diag_set(diag, FB_ERR_ARG,
                         "[run] models: model '%s' does not build a slider-crank yet ([linkage] "
                         "type = slider-crank); fourbar models lists each model's mechanisms",
                         c->models[i]);
  }
  return FB_OK;
}

/* a four-bar case's models: a planar-only model (model_table.h) builds
 * planar cases alone */
static fb_status check_fourbar_models(const fb_case *c, fb_diag *diag) {
  for (int i = 0; i < c->model_count; i++) {
    const fb_model *m = fb_model_find(c->models[i]);
    if (m && !fb_model_builds(m, FB_MECH_FOURBAR))
      return fb_diag_set(diag, FB_ERR_ARG,
                         "[run] models: model '%s' builds planar cases only ([linkage] type = "
                         "planar, through the engine kit), not the four-bar yet; fourbar models "
                         "lists each model's mechanisms",
                         c->models[i]);
  }
  return FB_OK;
}

fb_status fb_case_check(const fb_case *c, fb_diag *diag) {
  if (c->mechanism == FB_MECH_FOURBAR && !c->planar.on) {
    fb_status st = check_fourbar_models(c, diag);
    if (st != FB_OK) return st;
  }
  if (c->mechanism == FB_MECH_SLIDER_CRANK) {
    fb_status st = check_slider_crank(c, diag);
    if (st != FB_OK) return st;
  }
  fb_status st = c->mechanism == FB_MECH_SLIDER_CRANK
                     ? FB_OK
                     : fb_linkage_check(&c->nominal, diag);
  if (st != FB_OK) return st;
  for (int i = 0; i < FB_LINK_COUNT && c->mechanism == FB_MECH_FOURBAR; i++)
    if (!(c->plus_minus[i] >= 0.0) || c->plus_minus[i] >= c->nominal.length[i])
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "[tolerance] %s_plus_minus_mm = %g: a tolerance must be >= 0 and smaller "
                         "than the length [linkage] %s_mm = %g",
                         fb_link_name(i), c->plus_minus[i] * 1e3, fb_link_name(i),
                         c->nominal.length[i] * 1e3);
  for (int i = 0; i < 3; i++) {
    const fb_link_mass *m = &c->link[i];
    if (!(m->mass > 0.0) || !isfinite(m->mass))
      return fb_diag_set(diag, FB_ERR_RANGE, "%s mass = %g kg: a mass must be positive",
                         fb_link_name(i), m->mass);
    if (!(m->inertia > 0.0) || !(m->inertia_long > 0.0) || !(m->inertia_transverse > 0.0))
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "%s moments of inertia (%g, %g, %g) kg m^2: each must be positive",
                         fb_link_name(i), m->inertia, m->inertia_long, m->inertia_transverse);
    /* triangle inequality of principal moments: a physical body */
    double a = m->inertia, b = m->inertia_long, t = m->inertia_transverse;
    if (a > b + t || b > a + t || t > a + b)
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "[mass] %s_inertia_kg_mm2 = %g, %s_inertia_long_kg_mm2 = %g and "
                         "%s_inertia_transverse_kg_mm2 = %g violate the triangle inequality of "
                         "principal moments (each at most the sum of the other two): no rigid "
                         "body has them",
                         fb_link_name(i), a * 1e6, fb_link_name(i), b * 1e6, fb_link_name(i),
                         t * 1e6);
  }
  if (!(c->radial_clearance < 0.5 * c->pin_diameter))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "[pin] radial_clearance_um = %g (or the clearance of [pin] fit): must be "
                       "smaller than the pin radius, [pin] diameter_mm / 2 = %g mm",
                       c->radial_clearance * 1e6, 0.5 * c->pin_diameter * 1e3);
  if (c->mechanism == FB_MECH_FOURBAR) {
    st = check_drivable(&c->nominal, "nominal", diag);
    if (st != FB_OK) return st;
    fb_linkage su;
    fb_case_stackup_lengths(c, &su);
    st = check_drivable(&su, "stack-up", diag);
    if (st != FB_OK) return st;
  }
  if (c->solver.h_mode == FB_STEP_ADAPTIVE && !(c->solver.h_max >= c->solver.h_min))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "[solver] h_max_s = %g: the longest adaptive step must not be below "
                       "h_min_s = %g",
                       c->solver.h_max, c->solver.h_min);
  double dur = fb_case_duration(c);
  if (!(c->solver.h > 0.0) || c->solver.h >= dur)
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "[solver] h_s = %g: the step size must be positive and smaller than the "
                       "run (%g s for [run] revolutions = %g at [drive] speed_rpm = %g)",
                       c->solver.h, dur, c->revolutions, c->crank_speed * 60.0 / (2.0 * M_PI));
  if (dur / c->solver.h > 1e9)
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "[solver] h_s = %g over %g s ([run] revolutions = %g at [drive] "
                       "speed_rpm = %g) is %.3g steps: more than 1e9 steps",
                       c->solver.h, dur, c->revolutions, c->crank_speed * 60.0 / (2.0 * M_PI),
                       dur / c->solver.h);
  if (c->revolutions < 2.0 && c->peaks == FB_PEAKS_STEADY)
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "[run] revolutions = %g: the steady peak window starts after the first "
                       "revolution, so run at least 2, or take peaks over the whole run "
                       "([run] peaks = all)",
                       c->revolutions);
  if (c->clearance.penetration_limit < 0.0)
    return fb_diag_set(diag, FB_ERR_RANGE, "[clearance] penetration_limit_um = %g: must be >= 0",
                       c->clearance.penetration_limit * 1e6);
  if (c->clearance.ovality > 0.0 && c->clearance.bore != FB_CASE_BORE_ELLIPSE)
    return fb_diag_set(diag, FB_ERR_ARG,
                       "[clearance] ovality_um = %g with bore = circle: an ovality needs "
                       "bore = ellipse", c->clearance.ovality * 1e6);
  if (c->clearance.ovality >= c->radial_clearance + 0.5 * c->pin_diameter)
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "[clearance] ovality_um = %g: must be smaller than the hole radius %g um",
                       c->clearance.ovality * 1e6,
                       (c->radial_clearance + 0.5 * c->pin_diameter) * 1e6);
  int uses_ccd = 0;
  for (int i = 0; i < c->model_count; i++) {
    const fb_model *m;
    st = fb_model_lookup(&m, c->models[i], diag);
    if (st != FB_OK) return st;
    if (fb_model_has_clearance(m) && c->clearance.mask == 0)
      return fb_diag_set(diag, FB_ERR_ARG,
                         "model '%s' needs at least one clearance joint ([clearance] joints)",
                         c->models[i]);
    /* h_s = adaptive follows the project's contact law through the exact
     * collider (ODE, MuJoCo): refused here, before anything runs, for a
     * model that would otherwise run at a fixed step or stop */
    const char *why = fb_model_adaptive_refusal(m, fb_case_collider_of(c));
    if (c->solver.h_mode == FB_STEP_ADAPTIVE && why)
      return fb_diag_set(diag, FB_ERR_ARG,
                         "[solver] h_s = adaptive with [run] models %s: the adaptive step "
                         "follows the project's contact law through the exact collider in ODE "
                         "and MuJoCo only; %s: give h_s = auto or a step in s for this model "
                         "(or run it in a [variant.NAME] with its own h_s)",
                         c->models[i], why);
    if (fb_model_has_clearance(m) &&
        fb_model_collider(m, fb_case_collider_of(c)) == FB_COLLIDER_CCD)
      uses_ccd = 1;
  }
  if (c->clearance.bore == FB_CASE_BORE_ELLIPSE && !uses_ccd)
    return fb_diag_set(diag, FB_ERR_ARG,
                       "[clearance] bore = ellipse: only the libccd collider models a non-circular "
                       "bore; list ode-clearance-ccd or set collider = ccd");
  return FB_OK;
}
