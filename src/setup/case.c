#include "case.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "closed_form.h"
#include "model_table.h"
#include "reference.h"

void fb_case_grashof_text(const fb_case *c, char *out, size_t size) {
  fb_closed_form_of(c->mechanism)->class_text(c, out, size);
}

fb_status fb_case_check_run(const fb_case *c, fb_diag *diag) {
  if (c->solver.h_mode == FB_STEP_ADAPTIVE && !(c->solver.h_max >= c->solver.h_min))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "[solver] h_max_s = %g: the longest adaptive step must not be below "
                       "h_min_s = %g",
                       c->solver.h_max, c->solver.h_min);
  const double dur = fb_case_duration(c);
  /* the run's length as the case gives it: a time, or revolutions at a speed */
  char run[160];
  if (c->duration_s > 0.0) snprintf(run, sizeof run, "[run] duration_s = %g", c->duration_s);
  else
    snprintf(run, sizeof run, "[run] revolutions = %g at [drive] speed_rpm = %g", c->revolutions,
             c->crank_speed * 60.0 / (2.0 * M_PI));
  if (!(c->solver.h > 0.0) || c->solver.h >= dur)
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "[solver] h_s = %g: the step size must be positive and smaller than the "
                       "run (%g s for %s)", c->solver.h, dur, run);
  if (dur / c->solver.h > 1e9)
    return fb_diag_set(diag, FB_ERR_RANGE, "[solver] h_s = %g over %g s (%s) is %.3g steps: "
                       "more than 1e9 steps", c->solver.h, dur, run, dur / c->solver.h);
  const int driven = !(c->planar.on && c->planar.undriven); /* a revolution to count */
  if (driven && c->revolutions < 2.0 && c->peaks == FB_PEAKS_STEADY)
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "[run] revolutions = %g: the steady peak window starts after the first "
                       "revolution, so run at least 2, or take peaks over the whole run "
                       "([run] peaks = all)",
                       c->revolutions);
  return FB_OK;
}

fb_status fb_case_check(const fb_case *c, fb_diag *diag) {
  const fb_closed_form *cf = fb_closed_form_of(c->mechanism);
  fb_status st = cf->check_case(c, diag);
  if (st != FB_OK) return st;
  for (int i = 0; i < cf->tolerances_checked; i++)
    if (!(c->plus_minus[i] >= 0.0) || c->plus_minus[i] >= c->nominal.length[i])
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "[tolerance] %s_plus_minus_mm = %g: a tolerance must be >= 0 and smaller "
                         "than the length [linkage] %s_mm = %g",
                         fb_link_name(i), c->plus_minus[i] * 1e3, fb_link_name(i),
                         c->nominal.length[i] * 1e3);
  if (cf->check_options && (st = cf->check_options(c, diag)) != FB_OK) return st;
  const fb_mech_desc *mech = fb_case_mech(c);
  for (int i = 0; i < c->model_count; i++) {
    const fb_model *m;
    st = fb_model_lookup(&m, c->models[i], diag);
    if (st != FB_OK) return st;
    if (!fb_model_builds(m, c->mechanism))
      return fb_diag_set(diag, FB_ERR_ARG,
                         "[run] models: model '%s' does not build a %s yet ([linkage] "
                         "type = %s); fourbar models lists each model's mechanisms",
                         c->models[i], mech->type, mech->type);
  }
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
  if (cf->check_drivable && (st = cf->check_drivable(c, diag)) != FB_OK) return st;
  if ((st = fb_case_check_run(c, diag)) != FB_OK) return st;
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
    if (m->engine == FB_ENGINE_REFERENCE && fb_model_has_clearance(m) &&
        (st = fb_reference_joints_check(c, diag)) != FB_OK)
      return st;
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
