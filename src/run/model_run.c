#include "model_run.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "clock.h"
#include "reference.h"

/* 1 when the time, the input angle and the n output bodies' position,
 * velocity and acceleration of x are all finite */
static int sample_finite(const fb_sample *x, int n) {
  if (!isfinite(x->t) || !isfinite(x->crank_angle)) return 0;
  for (int k = 0; k < n; k++)
    if (!isfinite(x->body[k][FB_Q_POS]) || !isfinite(x->body[k][FB_Q_VEL]) ||
        !isfinite(x->body[k][FB_Q_ACC]))
      return 0;
  return 1;
}

/* the engine's reason for a failed step (or create, self NULL) */
static void engine_stop(fb_stop *out, const fb_engine *e, const void *self, fb_status st,
                        double t, size_t k, const fb_model_scene *sm, const fb_diag *diag) {
  memset(out, 0, sizeof *out);
  out->engine = fb_engine_name(sm->model->engine); /* e may be the kit adapter */
  out->joint = -1;
  if (self && e->stopped) {
    e->stopped(self, out);
    if (!out->engine) out->engine = fb_engine_name(sm->model->engine);
    if (out->joint >= 0) out->joint_name = fb_case_joint_name(&sm->def->source, out->joint);
    if (out->kind != FB_STOP_NONE) return;
  }
  out->kind = st == FB_ERR_NOMEM ? FB_STOP_ALLOCATION : FB_STOP_SOLVER;
  out->t = t;
  out->step = k;
  snprintf(out->detail, sizeof out->detail, "%.150s", diag ? diag->msg : "");
}

/* create and the series storage (timed together as setup_s; create as
 * stepping for an engine that computes its series there), then def->steps
 * steps, each sampled and checked */
static fb_status run_engine(fb_model_run *r, const fb_engine *e, const fb_model_scene *sm,
                            fb_progress_fn progress, void *user, fb_diag *diag) {
  const fb_scene *def = sm->def;
  void *self = NULL;
  if (!e->create) /* fb_engine_runner hands the kit adapter for an engine without one */
    return fb_diag_set(diag, FB_ERR_ARG, "the %s engine has no build of a four-bar or a "
                       "slider-crank (no create, no engine kit binding)", e->name);
  const double t0 = fb_clock_s();
  fb_status st = e->create(&self, sm, diag);
  const double create_s = fb_clock_s() - t0;
  r->setup_s = create_s;
  if (st == FB_ERR_NUMERIC) { /* nothing to sample: a result, not an error */
    engine_stop(&r->stop, e, NULL, st, 0.0, 0, sm, diag);
    return FB_OK;
  }
  if (st != FB_OK) return st;
  const size_t n = def->steps;
  if (fb_series_init_mech(&r->series, n + 1, fb_case_mech(&def->source)) != FB_OK ||
      fb_series_enable_contact(&r->series, sm->clearance_mask) != FB_OK ||
      (e->reactions && fb_series_enable_loads(&r->series) != FB_OK)) {
    e->destroy(self);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for %zu samples", n + 1);
  }
  for (int j = 0; j < FB_MECH_MAX_JOINTS; j++) r->series.impact_floor[j] = def->impact_floor[j];
  fb_series_touch(&r->series); /* its page faults are set-up, not stepping */
  r->setup_s = fb_clock_s() - t0;
  fb_sample x;
  e->sample(self, &x);
  if (e->reactions) e->reactions(self, x.reaction, &x.drive_torque);
  fb_series_push(&r->series, &x);
  const size_t report_every = n / 100 + 1;
  const double deadline = def->source.wall_deadline;
  double stepping = 0.0;
  const int outputs = fb_series_output_count(&r->series);
  for (size_t k = 1; k <= n; k++) {
    /* [run] max_wall_s holds for every engine: a model still stepping at
     * the run's deadline stops there, with its reason (the clock is read
     * every FB_WALL_CHECK_STEPS steps) */
    if (deadline > 0.0 && k % FB_WALL_CHECK_STEPS == 0 && fb_clock_s() > deadline) {
      r->stop.kind = FB_STOP_WALL_TIME;
      r->stop.t = x.t;
      r->stop.step = k;
      r->stop.limit = def->source.max_wall_s;
      r->stop.t_end = def->duration;
      break;
    }
    /* timed here unless the engine times its own stepping (stepping_s):
     * two clock reads a step, ~5 % of Simbody's harness at 36k steps */
    const double ts = e->stepping_s ? 0.0 : fb_clock_s();
    st = e->step(self, diag);
    if (!e->stepping_s) stepping += fb_clock_s() - ts;
    if (st == FB_ERR_NUMERIC || st == FB_ERR_NOMEM) { /* the engine gave up (ODE's own fatal
                                   check or its step memory, the reference's integrator): this
                                   model stops with its reason, the others run */
      engine_stop(&r->stop, e, self, st, x.t, k, sm, diag);
      st = FB_OK;
      break;
    }
    if (st != FB_OK) break;
    e->sample(self, &x);
    if (e->reactions) e->reactions(self, x.reaction, &x.drive_torque);
    if (!sample_finite(&x, outputs)) {
      r->stop.kind = FB_STOP_NONFINITE;
      r->stop.t = x.t;
      r->stop.step = k;
      break;
    }
    if (e->guarded) {
      fb_engine_contact ct;
      e->contact(self, &ct);
      if (ct.penetration > def->penetration_limit) {
        r->stop.kind = FB_STOP_PENETRATION;
        r->stop.t = x.t;
        r->stop.step = k;
        r->stop.joint = ct.joint;
        r->stop.joint_name = fb_case_joint_name(&def->source, ct.joint);
        r->stop.value = ct.penetration;
        r->stop.limit = def->penetration_limit;
        break;
      }
    }
    fb_series_push(&r->series, &x);
    const double drift = e->drift(self);
    if (drift > r->joint_drift_max) r->joint_drift_max = drift;
    if (progress && k % report_every == 0) progress(r->name, (double)k / (double)n, user);
  }
  /* values an engine reports one step late belong to the step's start, and
   * spikes of a discrete motion are refined between its steps (series.h),
   * so every model's accelerations and peaks compare like with like */
  if (e->step_values_lag) fb_series_attribute_to_step_start(&r->series);
  if (e->refine_peaks && e->refine)
    e->refine(self, &r->series, FB_REFERENCE_REFINE_FRACTION,
              fb_case_peak_window_from(&def->source));
  else if (e->refine_peaks)
    fb_series_refine_peaks(&r->series, FB_REFERENCE_REFINE_FRACTION,
                           fb_case_peak_window_from(&def->source));
  r->stepping_s = e->stepping_s ? e->stepping_s(self) : stepping;
  if (e->computes_in_create) { /* its computation, not its set-up */
    r->setup_s -= create_s;
    r->stepping_s += create_s;
  }
  r->steps = e->steps(self);
  if (e->step_stats && sm->solver.h_mode == FB_STEP_ADAPTIVE) {
    r->has_step_stats = 1;
    e->step_stats(self, &r->step_stats);
  }
  if (e->provenance && sm->clearance_mask) {
    r->has_provenance = 1;
    for (int j = 0; j < FB_MECH_MAX_JOINTS; j++)
      if (sm->clearance_mask & (1 << j)) e->provenance(self, j, &r->provenance[j]);
  }
  e->destroy(self);
  return st;
}

fb_status fb_model_run_one(fb_model_run *out, const fb_scene *def, const fb_model *m,
                           fb_progress_fn progress, void *user, fb_diag *diag) {
  memset(out, 0, sizeof *out);
  snprintf(out->name, sizeof out->name, "%s", m->name);
  out->stop.kind = FB_STOP_NONE;
  out->stop.engine = fb_engine_name(m->engine);
  out->stop.joint = -1;
  out->model = m;
  out->h = def->solver.h;
  out->lengths = def->lengths[m->lengths];
  double t0 = fb_clock_s(), c0 = fb_clock_cpu_s();
  fb_model_scene sm;
  fb_status st = fb_scene_select(&sm, def, m, diag);
  const fb_engine *e = st == FB_OK ? fb_engine_get(m->engine, diag) : NULL;
  if (e) e = fb_engine_runner(e, m, &def->source, diag); /* its own, or its kit binding's */
  if (st == FB_OK && !e) st = FB_ERR_ARG;
  if (st == FB_OK) {
    if (m->engine != FB_ENGINE_ANALYTIC && m->engine != FB_ENGINE_REFERENCE)
      out->builder = fb_engine_is_kit_adapter(e) ? "kit" : "hand";
    out->clearance_mask = sm.clearance_mask;
    out->collider = sm.clearance_mask ? sm.collider : FB_COLLIDER_NONE;
    out->segments = sm.collider == FB_COLLIDER_CCD ? sm.ccd_segments : sm.faceted_n;
    out->bore_ovality = sm.bore_ovality;
    st = run_engine(out, e, &sm, progress, user, diag);
  }
  out->wall_s = fb_clock_s() - t0;
  out->cpu_s = fb_clock_cpu_s() - c0;
  if (progress) progress(out->name, 1.0, user);
  return st;
}

void fb_model_run_free(fb_model_run *r) { fb_series_free(&r->series); }

double fb_model_run_output_length(const fb_model_run *r, const fb_case *c) {
  int out[FB_MECH_MAX_OUTPUTS];
  return fb_mech_outputs(fb_case_mech(c), out) > 0 ? r->lengths.length[out[0]] : NAN;
}
