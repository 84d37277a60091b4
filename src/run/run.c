#include "run.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "clock.h"
#include "mech_kinematics.h"
#include "model_table.h"
#include "reference.h"
#include "resolution.h"
#include "tolerance.h"


/* the n output bodies' peaks of p relative to ref's (mechanism.h's body[]) */
static void rel_peaks(fb_peaks *out, const fb_peaks *p, const fb_peaks *ref, int n) {
  for (int k = 0; k < n; k++) {
    const fb_body_peaks *in = &p->body[k], *rf = &ref->body[k];
    fb_body_peaks *o = &out->body[k];
    o->omega_max = fb_metrics_rel(in->omega_max, rf->omega_max);
    o->omega_min = fb_metrics_rel(in->omega_min, rf->omega_min);
    o->alpha_max = fb_metrics_rel(in->alpha_max, rf->alpha_max);
    o->alpha_min = fb_metrics_rel(in->alpha_min, rf->alpha_min);
  }
}

static void warn(fb_model_result *m, const fb_warning *w) {
  if (m->warning_count < FB_RUN_WARNINGS) m->warnings[m->warning_count++] = *w;
}

/* revolution 1 alone (start-up peaks, first impact), and the warnings that
 * look at the whole run: penalty validity, a saturated crank drive */
static void startup_and_warnings(fb_model_result *m, const fb_run *r) {
  const fb_case *c = &r->c;
  const fb_series *s = &m->run.series;
  fb_diag inner;
  m->first_impact_joint = -1;
  if (fb_metrics_peaks_between(&m->startup, &m->startup_at, s, 0.0, r->t_startup_end, &inner) ==
      FB_OK) {
    m->has_startup = 1;
    if (m->run.model->engine == FB_ENGINE_ANALYTIC && s->t[s->n - 1] >= r->t_startup_end - c->solver.h)
      m->startup = m->exact; /* a whole revolution of the periodic motion */
  }
  for (int j = 0; j < FB_MECH_MAX_JOINTS && m->first_impact_joint < 0; j++)
    if (m->run.clearance_mask & s->contact_mask & (1 << j)) m->first_impact_joint = j;
  if (m->first_impact_joint >= 0)
    fb_metrics_first_impact(&m->first_impact, s, m->first_impact_joint, c->radial_clearance,
                            m->run.model->rigid);
  for (int j = 0; j < FB_MECH_MAX_JOINTS; j++) {
    if (!(s->contact_mask & (1 << j))) continue;
    for (size_t i = 0; i < s->n && s->t[i] < r->t_startup_end; i++) {
      m->startup_force_max = fmax(m->startup_force_max, s->contact[j][FB_C_FORCE][i]);
      m->startup_penetration_max = fmax(m->startup_penetration_max, s->contact[j][FB_C_PEN][i]);
    }
  }
  m->penetration_max_run = fb_metrics_penetration_max(s);
  if (m->penetration_max_run > FB_PENALTY_VALIDITY_FACTOR * c->radial_clearance) {
    const fb_warning w = {.kind = FB_WARN_PENALTY_VALIDITY,
                          .value = m->penetration_max_run,
                          .limit = c->radial_clearance,
                          .ratio = m->penetration_max_run / c->radial_clearance,
                          .factor = FB_PENALTY_VALIDITY_FACTOR,
                          .t = NAN};
    warn(m, &w);
  }
  /* the named warning of a contact the step does not resolve (resolution.h) */
  for (int j = 0; j < FB_MECH_MAX_JOINTS && m->run.has_provenance; j++) {
    const fb_contact_provenance *p = &m->run.provenance[j];
    if (!(m->run.clearance_mask & (1 << j)) || p->contact_steps == 0 ||
        !(p->h_omega_max > FB_H_OMEGA_C_BOUND))
      continue;
    /* how the step was chosen, so the warning can say what to change */
    const fb_solver *sv = &r->scene.source.solver;
    const double h_cap = 2.0 * M_PI / (c->crank_speed * FB_H_AUTO_STEPS_PER_REV);
    int how = FB_WARN_STEP_FIXED;
    if (sv->h_mode == FB_STEP_AUTO || (sv->h_mode == FB_STEP_DEFAULT && c->clearance.mask))
      how = sv->h >= h_cap * (1.0 - 1e-9) ? FB_WARN_STEP_AUTO_CAP : FB_WARN_STEP_AUTO_CONTACT;
    fb_warning w = {.kind = FB_WARN_UNDER_RESOLVED,
                    .value = p->h_omega_max,
                    .limit = FB_H_OMEGA_C_BOUND,
                    .ratio = M_PI / p->h_omega_max,
                    .t = NAN,
                    .h = sv->h,
                    .h_auto = how};
    snprintf(w.what, sizeof w.what, "%s", fb_case_joint_name(c, j));
    warn(m, &w);
  }
  if (fb_engine_steps_world(m->run.model->engine)) {
    const double omega2 = fb_case_omega2(c);
    double lag = 0.0, t_lag = 0.0;
    for (size_t i = 0; i < s->n; i++) {
      const double d = fabs(s->crank_angle[i] - (c->crank_angle0 + omega2 * s->t[i]));
      if (d > lag) lag = d, t_lag = s->t[i];
    }
    const fb_engine *e = fb_engine_get(m->run.model->engine, NULL);
    if (lag > FB_DRIVE_LAG_WARN_RAD && e && e->drive_key) {
      /* the key of the engine's drive (ODE's is a capped velocity motor,
       * MuJoCo's a flywheel) */
      fb_warning w = {.kind = FB_WARN_DRIVE_SATURATED, .value = lag, .limit = FB_DRIVE_LAG_WARN_RAD,
                      .t = t_lag};
      snprintf(w.what, sizeof w.what, "%s", e->drive_key);
      warn(m, &w);
    }
  }
}

/* a model whose matched impacts miss the bound is wrong; one that leaves
 * its reference is divergent (its later peaks compare two histories) */
static void divergence_warnings(fb_model_result *m, const char *ref) {
  const fb_divergence *d = &m->divergence;
  const double worst = fmax(d->force_rel_max, d->penetration_rel_max);
  if (d->matched > 0 && !(worst <= FB_MATCHED_IMPACT_ERROR_BOUND)) {
    /* both still together: the model is wrong, not the sequence chaotic;
     * parted later: the model missed the bound before it diverged */
    m->matched_error = d->diverged ? FB_MATCHED_ERROR_THEN_DIVERGENT : FB_MATCHED_ERROR_KEPT;
    fb_warning w = {.kind = FB_WARN_ERROR_BOUND, .value = worst,
                    .limit = FB_MATCHED_IMPACT_ERROR_BOUND, .t = NAN};
    snprintf(w.what, sizeof w.what, "matched-impact peaks against %s", ref);
    warn(m, &w);
  }
  if (d->diverged) {
    m->peaks_unconverged = 1;
    fb_warning w = {.kind = FB_WARN_DIVERGENT, .value = d->crank_angle, .t = d->t,
                    .limit = d->t_end, .ratio = (double)d->matched};
    snprintf(w.what, sizeof w.what, "%s", ref);
    warn(m, &w);
  }
}

static fb_status measure(fb_model_result *m, const fb_run *r, fb_diag *diag) {
  const fb_case *c = &r->c;
  const double omega2 = fb_case_omega2(c);
  fb_status st = fb_mech_peaks(&m->exact, c->mechanism, &m->run.lengths, c->branch, omega2, diag);
  if (st != FB_OK) return st;
  const fb_series *s = &m->run.series;
  const int outputs = fb_series_output_count(s);
  startup_and_warnings(m, r);
  if (s->n == 0 || s->t[s->n - 1] < r->t_window) return FB_OK; /* stopped in the run-in */
  st = fb_metrics_peaks_between(&m->peaks, &m->peaks_at, s, r->t_window, INFINITY, diag);
  if (st != FB_OK) return st;
  if (m->run.model->engine == FB_ENGINE_ANALYTIC) m->peaks = m->exact; /* the refined extremes */
  m->has_peaks = 1;
  /* for the analytic model this measures the sampling floor of the grid */
  st = fb_metrics_error(&m->error, s, r->t_window, &m->run.lengths, c->branch,
                        c->crank_angle0, omega2, &m->exact, diag);
  if (st != FB_OK) return st;
  m->has_error = 1;
  if (m->run.model->engine != FB_ENGINE_ANALYTIC && m->run.model->joints == FB_JOINTS_IDEAL) {
    double worst = 0.0;
    for (int k = 0; k < outputs; k++) {
      const fb_body_error *b = &m->error.body[k];
      const double v[4] = {b->omega_max_rel, b->omega_min_rel, b->alpha_max_rel, b->alpha_min_rel};
      for (int q = 0; q < 4; q++) worst = isfinite(v[q]) ? fmax(worst, fabs(v[q])) : INFINITY;
    }
    if (worst > FB_IDEAL_PEAK_ERROR_BOUND) {
      fb_warning w = {.kind = FB_WARN_ERROR_BOUND, .value = worst,
                      .limit = FB_IDEAL_PEAK_ERROR_BOUND, .t = NAN};
      snprintf(w.what, sizeof w.what, "largest peak omega/alpha relative (against the analytic)");
      warn(m, &w);
    }
  }
  rel_peaks(&m->delta_vs_nominal, &m->peaks, &r->analytic_nominal, outputs);
  if (m->run.clearance_mask) {
    /* ratios against the model's ideal model (model table) if it ran, else
     * the exact analytic peaks of the same (stack-up) lengths */
    const fb_peaks *ref = &m->exact;
    snprintf(m->spikes_reference, sizeof m->spikes_reference, "analytic-stackup");
    const fb_model *ideal = fb_model_ideal_of(m->run.model);
    for (int i = 0; i < r->n; i++)
      if (ideal && r->model[i].run.model == ideal && r->model[i].has_peaks) {
        ref = &r->model[i].peaks;
        snprintf(m->spikes_reference, sizeof m->spikes_reference, "%s", ideal->name);
      }
    /* each output body's largest |alpha| of the ideal motion, its spikes' scale */
    double ra[FB_MECH_MAX_OUTPUTS] = {0.0};
    for (int k = 0; k < outputs; k++)
      ra[k] = fmax(fabs(ref->body[k].alpha_max), fabs(ref->body[k].alpha_min));
    st = fb_metrics_spikes(&m->spikes, s, r->t_window, ra[0], ra[1], &m->error, diag);
    if (st != FB_OK) return st;
    m->has_spikes = 1;
  }
  return FB_OK;
}

/* one model's wall time per sample on an idle machine [s]: its engine's
 * (fb_engine.cost_per_sample) */
static double model_cost(const fb_model *m, const fb_case *c) {
  const fb_engine *e = fb_engine_get(m->engine, NULL);
  return e && e->cost_per_sample ? e->cost_per_sample(m, c) : FB_COST_DEFAULT_S;
}

/* the bytes one sample of model m keeps in its series (series.h): time,
 * crank angle and 3 per output body, FB_CONTACT_COLS per clearance joint,
 * the load columns (drive torque, x and y per joint) where its engine
 * reports reactions */
static double sample_bytes(const fb_model *m, const fb_case *c) {
  const fb_mech_desc *mech = fb_case_mech(c);
  int outputs = 0, joints = 0;
  for (int b = 0; b < mech->nbodies; b++) outputs += mech->body[b].output;
  for (int j = 0; j < mech->njoints; j++) joints += (c->clearance.mask >> j) & 1;
  const fb_engine *e = fb_engine_get(m->engine, NULL);
  if (e) e = fb_engine_runner(e, m, c, NULL); /* the kit adapter keeps no loads */
  double cols = 2.0 + 3.0 * outputs;
  if (m->joints == FB_JOINTS_CLEARANCE) cols += (double)(FB_CONTACT_COLS * joints);
  if (e && e->reactions) cols += 1.0 + 2.0 * mech->njoints;
  return cols * (double)sizeof(double);
}

void fb_run_estimate(const fb_case *c, double *bytes, double *seconds) {
  const double steps = fb_case_duration(c) / c->solver.h + 1.0;
  /* an ensemble's members (ensemble.h) run its clearance models and
   * references again, in ceil((n - 1) / jobs) rounds of jobs workers */
  const int n = c->member ? 1 : c->ensemble > 1 ? c->ensemble : 1;
  const int jobs = c->jobs > 1 ? (c->jobs < n - 1 ? c->jobs : n - 1) : 1;
  const double rounds = n > 1 ? ceil((double)(n - 1) / (double)jobs) : 0.0;
  /* an ensemble the run may add by itself (ensemble_auto, run_case.c):
   * not in the time, which it estimates and weighs when it needs one, but
   * in the memory, its members' series beside the run's */
  const int n_auto = !c->member && n <= 1 && c->ensemble_auto > 1 ? c->ensemble_auto : n;
  const int jobs_mem = c->jobs > 1 ? (c->jobs < n_auto - 1 ? c->jobs : n_auto - 1) : 1;
  *bytes = FB_COST_PROGRAM_BYTES;
  *seconds = 0.0;
  /* a member costs what the model costs in a member (a reference: no check
   * integration, reference.h) */
  fb_case *as_member = rounds > 0.0 ? malloc(sizeof *as_member) : NULL;
  if (as_member) {
    *as_member = *c;
    as_member->member = 1;
  }
  for (int i = 0; i < c->model_count; i++) {
    const fb_model *m = fb_model_find(c->models[i]);
    if (!m) continue;
    const int member = m->joints == FB_JOINTS_CLEARANCE || m->engine == FB_ENGINE_REFERENCE;
    const fb_engine *e = fb_engine_get(m->engine, NULL);
    if (e) e = fb_engine_runner(e, m, c, NULL); /* the kit adapter holds its series too */
    /* an HDF5 series is built in memory before it is written (series_hdf5.c):
     * at most the samples' own size again; an engine that computes its
     * series in create (engine.h), or the kit adapter, holds its own beside the run's, and a
     * reference's check integration (run.c) one more */
    const double copies = 1.0 + (c->series == FB_SERIES_HDF5) + (member && n_auto > 1 ? jobs_mem : 0) +
                          (e && (e->computes_in_create || fb_engine_is_kit_adapter(e))) +
                          (m->engine == FB_ENGINE_REFERENCE && !c->member);
    *bytes += steps * sample_bytes(m, c) * copies;
    const double per_member = member && rounds > 0.0 ? model_cost(m, as_member ? as_member : c) : 0.0;
    *seconds += steps * FB_COST_LOAD_FACTOR * (model_cost(m, c) + rounds * per_member);
  }
  free(as_member);
}

/* refuses what cannot fit, before anything is reserved (c: the step
 * resolved); est (may be NULL) receives the estimate: seconds, bytes */
static fb_status check_cost(const fb_case *c, double est[2], fb_diag *diag) {
  double bytes, seconds;
  fb_run_estimate(c, &bytes, &seconds);
  if (est) est[0] = seconds, est[1] = bytes;
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  const double memory = pages > 0 && page > 0 ? (double)pages * (double)page : 0.0;
  const double steps = fb_case_duration(c) / c->solver.h + 1.0;
  /* the step as the case gave it: an adaptive run samples every h_min_s */
  const int adaptive = c->solver.h_mode == FB_STEP_ADAPTIVE;
  char step[96];
  snprintf(step, sizeof step, adaptive ? "[solver] h_s = adaptive, sampled every h_min_s = %g s"
                                       : "[solver] h_s = %g s", c->solver.h);
  const char *raise = adaptive ? "raise h_min_s" : "raise h_s";
  if (memory > 0.0 && bytes > FB_COST_MEMORY_FRACTION * memory)
    return fb_diag_set(diag, FB_ERR_RANGE, "[run] revolutions = %g with %s: %d "
                       "models x %.3g samples would reserve an estimated %.3g GB, more than %.0f %% "
                       "of this machine's %.3g GB (estimated wall time %.3g s): lower revolutions "
                       "or %s", c->revolutions, step, c->model_count, steps,
                       bytes / 1e9, 100.0 * FB_COST_MEMORY_FRACTION, memory / 1e9, seconds, raise);
  if (seconds > c->max_wall_s) {
    char what[160] = "";
    if (!c->member && c->ensemble > 1)
      snprintf(what, sizeof what, ", with [run] ensemble = %d (its members run the clearance "
               "models and references again)", c->ensemble);
    return fb_diag_set(diag, FB_ERR_RANGE, "[run] revolutions = %g with %s: %d "
                       "models x %.3g steps%s take an estimated %.3g s (%.3g GB; each engine's "
                       "cost per step with its options: [solver] stepper and quick_iterations, "
                       "[bullet] solver and iterations, [simbody] accuracy, the collider), more "
                       "than [run] max_wall_s = %g s: lower revolutions, %s or raise max_wall_s",
                       c->revolutions, step, c->model_count, steps, what, seconds, bytes / 1e9,
                       c->max_wall_s, raise);
  }
  return FB_OK;
}

/* check_cost at the step the models will take (the corner and h_s = auto
 * or adaptive resolved, as fb_scene_from_case does: an adaptive run
 * samples every h_min_s), before anything else checks or reserves */
static fb_status check_cost_resolved(const fb_case *c, int *over_cost, double est[2],
                                     fb_diag *diag) {
  *over_cost = 0;
  fb_case *k = malloc(sizeof *k);
  if (!k) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  *k = *c;
  fb_status st = fb_tol_resolve_worst(k, diag);
  if (st == FB_OK) st = fb_case_resolve_step(k, diag);
  if (st == FB_OK) *over_cost = (st = check_cost(k, est, diag)) != FB_OK;
  free(k);
  return st;
}

/* the reference's own error estimate: the same integration at a tighter
 * tolerance, compared with it like a model with its reference (reference.h) */
static void reference_estimate(fb_model_result *m, const fb_run *r) {
  fb_model_scene sm;
  fb_diag inner;
  double tol;
  if (fb_scene_select(&sm, &r->scene, m->run.model, &inner) != FB_OK ||
      fb_reference_tolerance(&tol, &inner) != FB_OK)
    return;
  const double check = fmax(tol / FB_REFERENCE_CHECK_FACTOR, FB_REFERENCE_TOL_MIN);
  if (!(check < tol)) return; /* already at the floor: nothing tighter to compare with */
  fb_series s;
  memset(&s, 0, sizeof s);
  size_t steps = 0;
  fb_stop stop;
  memset(&stop, 0, sizeof stop);
  const int cj = fb_case_compared_joint(&r->c);
  const fb_status ran = fb_reference_run_joints(&s, &steps, &sm.def->source, sm.law, check,
                                                &stop, &inner);
  for (int j = 0; j < FB_MECH_MAX_JOINTS; j++) /* as its model's */
    s.impact_floor[j] = r->scene.impact_floor[j];
  if (ran == FB_OK &&
      stop.kind == FB_STOP_NONE &&
      fb_metrics_vs_reference(&m->ref_estimate, &m->run.series, &s, r->t_window, cj,
                              &inner) == FB_OK) {
    m->has_ref_estimate = 1;
    const fb_reference_error *e = &m->ref_estimate;
    /* the force peak and every output body's alpha peaks */
    int moved = !(fabs(e->force_max_rel) <= FB_UNCONVERGED_REL);
    for (int k = 0; k < fb_series_output_count(&m->run.series); k++)
      moved |= !(fabs(e->body[k].alpha_max_rel) <= FB_UNCONVERGED_REL) ||
               !(fabs(e->body[k].alpha_min_rel) <= FB_UNCONVERGED_REL);
    if (moved) m->peaks_unconverged = 1;
    m->ref_tol = tol;
    m->ref_check_tol = check;
    m->ref_check_steps = steps;
    /* what else converged: how long it stays with its check, and the
     * check's impact statistics (compared with an ensemble, ensemble.c) */
    const fb_case *c = &r->c;
    m->has_check_divergence =
        fb_metrics_divergence(&m->check_divergence, &m->run.series, &s, cj,
                              c->radial_clearance, fb_model_run_output_length(&m->run, c),
                              2.0 * M_PI / c->crank_speed, &inner) == FB_OK;
    fb_impact_values v = {0};
    m->has_check_stats = fb_impact_values_add(&v, &s, cj, r->t_window, &inner) == FB_OK &&
                         v.n > 0 && fb_impact_stats_of(&m->check_stats, &v, &inner) == FB_OK;
    fb_impact_values_free(&v);
  }
  fb_series_free(&s);
}

static fb_status run_once(fb_run *r, const fb_case *c, fb_progress_fn progress, void *user,
                         fb_diag *diag) {
  const double t0 = fb_clock_s();
  memset(r, 0, sizeof *r);
  int over_cost;
  double est[2] = {0.0, 0.0};
  fb_status cost = check_cost_resolved(c, &over_cost, est, diag);
  if (cost != FB_OK) return cost;
  /* the scene stage: the case resolved once for every model */
  fb_status rc = fb_scene_from_case(&r->scene, c, diag);
  if (rc != FB_OK) return rc;
  r->c = r->scene.source;
  c = &r->c;
  r->estimate_s = est[0];
  r->estimate_bytes = est[1];
  /* [run] peaks: from t = 0, or after the first revolution (a hair below one
   * revolution so the sample at exactly one period counts) */
  r->t_window = fb_case_peak_window_from(c);
  r->t_startup_end = 2.0 * M_PI / c->crank_speed - 0.5 * c->solver.h;
  fb_status st = fb_mech_peaks(&r->analytic_nominal, c->mechanism, &c->nominal, c->branch,
                               fb_case_omega2(c), diag);
  if (st != FB_OK) return st;
  r->scene_s = fb_clock_s() - t0;
  for (int i = 0; i < c->model_count; i++) {
    fb_model_result *m = &r->model[i];
    const fb_model *row;
    st = fb_model_lookup(&row, c->models[i], diag);
    if (st == FB_OK) st = fb_model_run_one(&m->run, &r->scene, row, progress, user, diag);
    r->n = i + 1;
    const double tm = fb_clock_s();
    if (st == FB_OK) st = measure(m, r, diag);
    r->metrics_s += fb_clock_s() - tm;
    if (st != FB_OK) {
      fb_run_free(r);
      return st;
    }
  }
  /* each exact-collider clearance model against the reference of its law,
   * at the compared joint (fb_case_compared_joint) */
  const double tc = fb_clock_s();
  const int cj = fb_case_compared_joint(c);
  for (int i = 0; i < r->n; i++) {
    fb_model_result *m = &r->model[i];
    const fb_model *want = fb_model_reference_of(m->run.model);
    if (!want || !m->has_peaks) continue;
    for (int k = 0; k < r->n; k++) {
      const fb_model_result *ref = &r->model[k];
      if (ref->run.model != want || !ref->has_peaks) continue;
      fb_diag inner;
      if (fb_metrics_vs_reference(&m->ref_error, &m->run.series, &ref->run.series, r->t_window,
                                  cj, &inner) == FB_OK) {
        m->has_ref_error = 1;
        snprintf(m->ref_name, sizeof m->ref_name, "%s", want->name);
      }
      if (fb_metrics_divergence(&m->divergence, &m->run.series, &ref->run.series, cj,
                                c->radial_clearance, fb_model_run_output_length(&m->run, c),
                                2.0 * M_PI / c->crank_speed, &inner) == FB_OK) {
        m->has_divergence = 1;
        divergence_warnings(m, want->name);
      }
    }
  }
  r->metrics_s += fb_clock_s() - tc;
  for (int i = 0; i < r->n && !c->member; i++) {
    fb_model_result *m = &r->model[i];
    if (m->run.model->engine == FB_ENGINE_REFERENCE && m->has_peaks &&
        m->run.stop.kind == FB_STOP_NONE) {
      const double te = fb_clock_s(), ce = fb_clock_cpu_s();
      reference_estimate(m, r);
      m->check_s = fb_clock_s() - te;
      m->check_cpu_s = fb_clock_cpu_s() - ce;
    }
  }
  return FB_OK;
}

/* largest h omega_c over the clearance models' contact steps (0: none) */
static double h_omega_c_max(const fb_run *r) {
  double w = 0.0;
  for (int i = 0; i < r->n; i++) {
    const fb_model_run *m = &r->model[i].run;
    for (int j = 0; j < 4 && m->has_provenance; j++)
      if ((m->clearance_mask & (1 << j)) && m->provenance[j].contact_steps > 0 &&
          isfinite(m->provenance[j].h_omega_max))
        w = fmax(w, m->provenance[j].h_omega_max);
  }
  return w;
}

/* the models the engine kit builds (fb_engine_runner) against a clearance
 * at the driven joint, the joint between the ground and the input body
 * (fb_model_clearance_at_drive) */
static fb_status clearance_at_drive(const fb_case *c, fb_diag *diag) {
  const fb_mech_desc *mech = fb_case_mech(c);
  const int j = fb_mech_driven_joint(mech);
  if (j < 0 || !((c->clearance.mask >> j) & 1)) return FB_OK;
  for (int i = 0; i < c->model_count; i++) {
    const fb_model *m = fb_model_find(c->models[i]);
    const fb_engine *e = m ? fb_engine_get(m->engine, NULL) : NULL;
    const int kit = e && fb_engine_is_kit_adapter(fb_engine_runner(e, m, c, NULL));
    fb_status st = m ? fb_model_clearance_at_drive(m, kit, mech->joint[j].name, diag) : FB_OK;
    if (st != FB_OK) return st;
  }
  return FB_OK;
}

fb_status fb_run_preflight(const fb_case *c, int *over_cost, fb_diag *diag) {
  *over_cost = 0;
  fb_status st = clearance_at_drive(c, diag);
  if (st != FB_OK) return st;
  fb_scene *def = malloc(sizeof *def);
  if (!def) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  st = check_cost_resolved(c, over_cost, NULL, diag);
  if (st == FB_OK) st = fb_scene_from_case(def, c, diag);
  free(def);
  return st;
}

static fb_status run_models_timed(fb_run *r, const fb_case *c, fb_progress_fn progress,
                                  void *user, fb_diag *diag);

fb_status fb_run_models(fb_run *r, const fb_case *c, fb_progress_fn progress, void *user,
                        fb_diag *diag) {
  if (c->member && c->wall_deadline > 0.0) return run_models_timed(r, c, progress, user, diag);
  /* [run] max_wall_s holds while the models run, not only in the estimate:
   * a model still running at the deadline stops there (FB_STOP_WALL_TIME);
   * an ensemble's members keep the deadline of the run they belong to */
  fb_case *timed = malloc(sizeof *timed);
  if (!timed) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  *timed = *c;
  timed->wall_deadline = fb_clock_s() + c->max_wall_s;
  fb_status st = run_models_timed(r, timed, progress, user, diag);
  free(timed);
  return st;
}

static fb_status run_models_timed(fb_run *r, const fb_case *c, fb_progress_fn progress,
                                  void *user, fb_diag *diag) {
  double t_try = fb_clock_s(), redo = 0.0;
  fb_status st = run_once(r, c, progress, user, diag);
  if (st != FB_OK) return st;
  const double upfront[2] = {r->estimate_s, r->estimate_bytes}; /* the first estimate */
  const int auto_step = c->solver.h_mode == FB_STEP_AUTO ||
                        (c->solver.h_mode == FB_STEP_DEFAULT && c->clearance.mask);
  r->h_auto = auto_step && !c->member;
  r->h_auto_estimate = r->c.solver.h;
  r->h_omega_c_max = h_omega_c_max(r);
  /* h_s = auto: the stiffest contact state the run reached decides; a run
   * that passed the bound is redone at the step that keeps it, with a margin */
  int tries = 0;
  while (r->h_auto && r->h_omega_c_max > FB_H_OMEGA_C_BOUND && tries < FB_H_AUTO_RETRIES) {
    fb_case again = r->c;
    again.solver.h = r->c.solver.h * FB_H_OMEGA_C_BOUND / r->h_omega_c_max * FB_H_AUTO_MARGIN;
    again.solver.h_mode = FB_STEP_FIXED;
    const double estimate = r->h_auto_estimate;
    fb_run_free(r);
    redo += fb_clock_s() - t_try; /* the run this one replaces */
    t_try = fb_clock_s();
    st = run_once(r, &again, progress, user, diag);
    if (st != FB_OK) return st;
    tries++;
    r->h_auto = 1;
    r->h_auto_estimate = estimate;
    r->h_rechosen = tries;
    r->h_omega_c_max = h_omega_c_max(r);
    r->c.solver.h_mode = c->solver.h_mode; /* the case asked for auto */
  }
  r->redo_s = redo;
  r->estimate_s = upfront[0];
  r->estimate_bytes = upfront[1];
  return FB_OK;
}

void fb_run_free(fb_run *r) {
  for (int i = 0; i < r->n; i++) {
    fb_model_run_free(&r->model[i].run);
    for (int k = 0; k < FB_ENSEMBLE_MAX; k++) fb_impact_values_free(&r->model[i].member_impacts[k]);
  }
  r->n = 0;
}

void fb_run_estimated_work(const fb_run *r, double *wall_s, double *cpu_s) {
  /* an ensemble the run adds by itself has its own estimate (ensemble.h),
   * a run h_s = auto redid at a smaller step is another run (h_auto_redo) */
  const int own = r->ensemble_auto <= 1;
  *wall_s = own ? r->ensemble_wall_s : 0.0;
  *cpu_s = own ? r->ensemble_cpu_s : 0.0;
  for (int i = 0; i < r->n; i++) {
    *wall_s += r->model[i].run.wall_s + r->model[i].check_s;
    *cpu_s += r->model[i].run.cpu_s + r->model[i].check_cpu_s;
  }
}
