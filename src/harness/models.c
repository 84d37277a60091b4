#include "clock.h"
#include "models.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "analytic.h"
#include "joint_law.h"
#include "reference.h"
#include "scene.h"

/* A contact that begins with a penetration rate below 1 mm/s is the pin
 * settling onto the wall, not an impact: it is counted as continuous
 * contact, and its hysteresis damping uses this rate as the impact velocity
 * (a smaller one would make the damping term of the LN-type laws, which
 * divides by it, unbounded). Pin speeds in the paper's case are ~10 m/s. */
#define IMPACT_VELOCITY_MIN_M_S 1e-3

const char *fb_model_kind_name(fb_model_kind k) {
  return k == FB_KIND_ODE ? "ode" : (k == FB_KIND_REFERENCE ? "reference" : "analytic");
}

static int ends_with(const char *s, const char *suffix) {
  size_t n = strlen(s), m = strlen(suffix);
  return n >= m && strcmp(s + n - m, suffix) == 0;
}

void fb_model_lengths(const fb_case *c, const char *name, fb_linkage *out) {
  if (ends_with(name, "-stackup") || strncmp(name, "ode-clearance", 13) == 0 ||
      strncmp(name, "reference", 9) == 0)
    fb_case_stackup_lengths(c, out);
  else
    *out = c->nominal;
}

static int sample_finite(const fb_sample *x) {
  return isfinite(x->t) && isfinite(x->crank_angle) && isfinite(x->coupler_angle) &&
         isfinite(x->coupler_omega) && isfinite(x->coupler_alpha) &&
         isfinite(x->follower_angle) && isfinite(x->follower_omega) &&
         isfinite(x->follower_alpha);
}

static size_t step_count(const fb_case *c) {
  return (size_t)llround(fb_case_duration(c) / c->solver.h);
}

static fb_status run_analytic(fb_model_run *r, const fb_case *c, fb_diag *diag) {
  size_t n = step_count(c) + 1;
  fb_status st = fb_analytic_sample(&r->series, &r->lengths, c->branch, c->crank_angle0,
                                    fb_case_omega2(c), c->solver.h, n, diag);
  if (st == FB_OK) r->steps = n;
  return st;
}

static fb_status run_ode(fb_model_run *r, const fb_case *c, int clearance_model, int faceted,
                         fb_progress_fn progress, void *user, fb_diag *diag) {
  fb_scene_def def;
  memset(&def, 0, sizeof def);
  if (clearance_model >= 0) {
    fb_status st = fb_joint_laws(def.law, c, (fb_clearance_model)clearance_model, diag);
    if (st != FB_OK) return st;
    def.clearance_mask = c->clearance.mask;
    def.radial_clearance = c->radial_clearance;
    def.pin_radius = 0.5 * c->pin_diameter;
    def.mapping = (fb_mapping)c->clearance.mapping;
    def.friction = c->clearance.friction;
    def.impact_velocity_min = IMPACT_VELOCITY_MIN_M_S;
    def.pin_length = c->pin_length;
    def.faceted_n = faceted ? c->clearance.faceted_n : 0;
  }
  const double pen_limit = fb_case_penetration_limit(c);
  def.lengths = r->lengths;
  /* the case's start, the same state the reference starts from */
  fb_status sst = fb_start_resolve(&def.start, c, &r->lengths, def.clearance_mask, diag);
  if (sst != FB_OK) return sst;
  def.start_given = 1;
  def.branch = c->branch;
  def.crank_angle0 = c->crank_angle0;
  def.omega2 = fb_case_omega2(c);
  def.gravity = c->gravity;
  for (int i = 0; i < 3; i++) def.link[i] = c->link[i];
  def.solver = c->solver;
  fb_scene *scene = NULL;
  fb_status st = fb_scene_create(&scene, &def, diag);
  if (st != FB_OK) return st;
  size_t n = step_count(c);
  if (fb_series_init(&r->series, n + 1) != FB_OK ||
      fb_series_enable_contact(&r->series, def.clearance_mask) != FB_OK) {
    fb_scene_destroy(scene);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for %zu samples", n + 1);
  }
  fb_sample x;
  fb_scene_sample(scene, &x);
  fb_series_push(&r->series, &x);
  size_t report_every = n / 100 + 1;
  for (size_t k = 1; k <= n; k++) {
    st = fb_scene_step(scene, diag);
    if (st == FB_ERR_NUMERIC) { /* ODE's own fatal check: this model stops, the others run */
      snprintf(r->status, sizeof r->status, "%.200s", diag->msg);
      st = FB_OK;
      break;
    }
    if (st != FB_OK) break;
    fb_scene_sample(scene, &x);
    if (!sample_finite(&x)) {
      snprintf(r->status, sizeof r->status, "nan at t = %.6g s (step %zu)", x.t, k);
      break;
    }
    int pj;
    const double pen = fb_scene_penetration(scene, &pj);
    if (pen > pen_limit) {
      fb_case_penetration_status(r->status, sizeof r->status, pen, pj, pen_limit, x.t, k);
      break;
    }
    fb_series_push(&r->series, &x);
    double drift = fb_scene_joint_drift(scene);
    if (drift > r->joint_drift_max) r->joint_drift_max = drift;
    if (progress && k % report_every == 0) progress(r->name, (double)k / (double)n, user);
  }
  r->steps = fb_scene_steps(scene);
  fb_scene_destroy(scene);
  return st;
}

fb_status fb_model_run_one(fb_model_run *out, const fb_case *c, const char *name,
                           fb_progress_fn progress, void *user, fb_diag *diag) {
  memset(out, 0, sizeof *out);
  snprintf(out->name, sizeof out->name, "%s", name);
  snprintf(out->status, sizeof out->status, "ok");
  out->h = c->solver.h;
  fb_model_lengths(c, name, &out->lengths);
  double t0 = fb_clock_s();
  fb_status st;
  if (strcmp(name, "analytic") == 0 || strcmp(name, "analytic-stackup") == 0) {
    out->kind = FB_KIND_ANALYTIC;
    st = run_analytic(out, c, diag);
  } else if (strcmp(name, "ode-ideal-nominal") == 0 || strcmp(name, "ode-ideal-stackup") == 0) {
    out->kind = FB_KIND_ODE;
    st = run_ode(out, c, -1, 0, progress, user, diag);
  } else if (strcmp(name, "ode-clearance-restitution") == 0 ||
             strcmp(name, "ode-clearance-impact") == 0 ||
             strcmp(name, "ode-clearance-faceted") == 0) {
    /* the faceted model uses the impact law through ODE's collider */
    out->kind = FB_KIND_ODE;
    out->clearance_mask = c->clearance.mask;
    const int faceted = strcmp(name, "ode-clearance-faceted") == 0;
    st = run_ode(out, c,
                 strcmp(name, "ode-clearance-restitution") == 0 ? FB_CLEARANCE_RESTITUTION
                                                                : FB_CLEARANCE_IMPACT,
                 faceted, progress, user, diag);
  } else if (strcmp(name, "reference") == 0 || strcmp(name, "reference-restitution") == 0) {
    out->kind = FB_KIND_REFERENCE;
    out->clearance_mask = 1 << FB_JOINT_B;
    fb_contact_law law[4];
    st = fb_joint_laws(law, c,
                       strcmp(name, "reference") == 0 ? FB_CLEARANCE_IMPACT : FB_CLEARANCE_RESTITUTION,
                       diag);
    if (st == FB_OK) st = fb_reference_run(&out->series, &out->steps, c, &law[FB_JOINT_B], 0, diag);
    if (st == FB_ERR_NUMERIC) { /* the reference failing is a result, not an error */
      snprintf(out->status, sizeof out->status, "%.200s", diag->msg);
      st = FB_OK;
    }
  } else {
    st = fb_diag_set(diag, FB_ERR_ARG, "unknown model '%s'", name);
  }
  out->wall_s = fb_clock_s() - t0;
  if (progress) progress(out->name, 1.0, user);
  return st;
}

void fb_model_run_free(fb_model_run *r) { fb_series_free(&r->series); }
