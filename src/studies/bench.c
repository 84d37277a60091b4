#include "bench.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model_table.h"
#include "run.h"

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double omega_peak_error(const fb_error *e) {
  return fmax(fmax(fabs(e->coupler.omega_max_rel), fabs(e->coupler.omega_min_rel)),
              fmax(fabs(e->follower.omega_max_rel), fabs(e->follower.omega_min_rel)));
}

double fb_bench_alpha_spike(const fb_body_peaks *p) {
  return fmax(fabs(p->alpha_max), fabs(p->alpha_min));
}

double fb_bench_rel_parts(double *rel, const double *a, const double *b, int n) {
  double worst = 0.0;
  for (int i = 0; i < n; i++) {
    rel[i] = b[i] != 0.0 ? (a[i] - b[i]) / fabs(b[i]) : NAN;
    worst = isfinite(rel[i]) && isfinite(worst) ? fmax(worst, fabs(rel[i])) : NAN;
  }
  return worst;
}

/* the peaks a row's error compares: clearance (q = 1) force, penetration and
 * the two alpha spikes; ideal (q = 0) the four omega peaks. 0: the model did
 * not reach its window */
static int row_peaks(double out[4], const fb_model_result *m, int q) {
  if (m->run.stop.kind != FB_STOP_NONE || !m->has_peaks) return 0;
  if (q == 0) {
    out[0] = m->peaks.coupler.omega_max;
    out[1] = m->peaks.coupler.omega_min;
    out[2] = m->peaks.follower.omega_max;
    out[3] = m->peaks.follower.omega_min;
    return 1;
  }
  if (!m->has_spikes) return 0;
  out[FB_BENCH_PART_FORCE] = m->spikes.force_max;
  out[FB_BENCH_PART_PENETRATION] = m->spikes.penetration_max;
  out[FB_BENCH_PART_ALPHA_COUPLER] = fb_bench_alpha_spike(&m->peaks.coupler);
  out[FB_BENCH_PART_ALPHA_FOLLOWER] = fb_bench_alpha_spike(&m->peaks.follower);
  return 1;
}

/* the step-halving figure of rows[0..nrows): case k once more at h/2 (its
 * reference left out), row i's peaks (kept in its halving_part by the caller)
 * against those of model idx[i] there, of kind kind[i] (row_peaks' q) */
static fb_status halving(fb_bench_row *rows, int nrows, const int *idx, const int *kind,
                         const fb_case *k, fb_diag *diag) {
  fb_case k2 = *k;
  k2.solver.h = 0.5 * k->solver.h;
  k2.solver.h_mode = FB_STEP_FIXED;
  if (k2.model_count > 2) k2.model_count = 2; /* the reference is not needed */
  static fb_run r2;
  fb_status st = fb_run_case(&r2, &k2, NULL, NULL, diag);
  if (st != FB_OK) return st;
  for (int i = 0; i < nrows; i++) {
    fb_bench_row *b = &rows[i];
    double at_h[4], at_h2[4], rel[4];
    for (int p = 0; p < 4; p++) at_h[p] = b->halving_part[p];
    for (int p = 0; p < 4; p++) b->halving_part[p] = NAN;
    if (!isfinite(at_h[0]) || !row_peaks(at_h2, &r2.model[idx[i]], kind[i])) continue;
    b->halving = fb_bench_rel_parts(rel, at_h, at_h2, 4);
    if (kind[i])
      for (int p = 0; p < 4; p++) b->halving_part[p] = rel[p];
  }
  fb_run_free(&r2);
  return FB_OK;
}

/* runs case k up to max_reps (<= 3) times, again while its first `timed`
 * models (1 or 2) together took at most FB_BENCH_REPEAT_BELOW_S; r keeps the
 * last run, walls[q][rep] the wall times of model q without the set-up
 * (MuJoCo compiles its model, 0.6 to 14 ms here), setups[q][rep] the set-up
 * (0 when not timed), *reps the runs */
static fb_status timed_runs(fb_run *r, const fb_case *k, int timed, int max_reps,
                            double walls[2][3], double setups[2][3], double stepping[2][3],
                            int *reps, fb_diag *diag) {
  for (int rep = 0; rep < max_reps; rep++) {
    fb_status st = fb_run_case(r, k, NULL, NULL, diag);
    if (st != FB_OK) return st;
    for (int q = 0; q < 2; q++) {
      const fb_model_run *mr = &r->model[q].run;
      walls[q][rep] = q < timed ? mr->wall_s - mr->setup_s : 0.0;
      setups[q][rep] = q < timed ? mr->setup_s : 0.0;
      stepping[q][rep] = q < timed ? mr->stepping_s : 0.0;
    }
    *reps = rep + 1;
    if (rep == max_reps - 1 || walls[0][rep] + walls[1][rep] > FB_BENCH_REPEAT_BELOW_S) break;
    fb_run_free(r);
  }
  return FB_OK;
}

/* One configuration's timing, kept by bench_point for the rounds that
 * retime() runs after the whole grid: its case without the untimed
 * reference, its rows and what a row's cost divides by. */
typedef struct {
  fb_case k;
  int timed;          /* models timed (1 or 2), the first of k's */
  int row[2];         /* row of model q, -1 where it has none */
  double revs[2];     /* revolutions model q simulated; 0: no cost per revolution */
  double steps[2];    /* its steps */
  double walls[2][3]; /* wall time of each round, set-up excluded [s] */
  double setups[2][3];
  double stepping[2][3]; /* of walls, the engine's stepping [s] */
  double samples[2];     /* output samples of each model's run [-] */
  int reps;
} bench_timing;

/* the configurations bench_point has timed in this fb_bench_run (one bench
 * at a time, as bench_point's static run) */
static struct {
  bench_timing *t;
  int n, cap;
} timings;

static fb_status timing_add(const bench_timing *t, fb_diag *diag) {
  if (timings.n == timings.cap) {
    const int cap = timings.cap ? 2 * timings.cap : 64;
    bench_timing *g = realloc(timings.t, (size_t)cap * sizeof *g);
    if (!g) return fb_diag_set(diag, FB_ERR_NOMEM, "bench: out of memory for the timings");
    timings.t = g;
    timings.cap = cap;
  }
  timings.t[timings.n++] = *t;
  return FB_OK;
}

/* a row's cost from its configuration's rounds: the median wall time per
 * simulated revolution and per step, the median set-up */
static void timing_apply(fb_bench_row *rows, bench_timing *t) {
  for (int q = 0; q < t->timed; q++) {
    /* the round of the median wall time gives the split too */
    int order[3] = {0, 1, 2};
    for (int i = 0; i < t->reps; i++)
      for (int j = i + 1; j < t->reps; j++)
        if (t->walls[q][order[j]] < t->walls[q][order[i]]) {
          const int o = order[i];
          order[i] = order[j];
          order[j] = o;
        }
    const int mid = order[t->reps / 2];
    const double stepping = t->stepping[q][mid];
    qsort(t->walls[q], (size_t)t->reps, sizeof(double), cmp_double);
    qsort(t->setups[q], (size_t)t->reps, sizeof(double), cmp_double);
    if (t->row[q] < 0) continue;
    fb_bench_row *b = &rows[t->row[q]];
    const double wall = t->walls[q][t->reps / 2];
    b->repeats = t->reps;
    b->setup_s = t->setups[q][t->reps / 2];
    b->wall_per_rev = t->revs[q] > 0.0 ? wall / t->revs[q] : NAN;
    b->stepping_per_rev = t->revs[q] > 0.0 ? stepping / t->revs[q] : NAN;
    b->sampling_per_rev = t->revs[q] > 0.0 ? (wall - stepping) / t->revs[q] : NAN;
    b->samples_per_rev = t->revs[q] > 0.0 ? t->samples[q] / t->revs[q] : NAN;
    b->us_per_step = t->steps[q] > 0.0 ? 1e6 * wall / t->steps[q] : NAN;
  }
}

/* one configuration: runs case k (its models: an ideal stack-up model, and
 * with clearance at B the clearance impact model and the reference) once,
 * appends one row per engine model (the ideal one only when with_ideal) and
 * keeps its timing for the rounds of retime() */
static fb_status bench_point(fb_bench_row *rows, int *n, fb_case *k, const char *engine,
                             const char *stepper, int mapping, int with_ideal, fb_diag *diag) {
  const int with_clearance = k->model_count > 1;
  bench_timing tm;
  memset(&tm, 0, sizeof tm);
  tm.timed = with_clearance ? 2 : 1;
  tm.row[0] = tm.row[1] = -1;
  static fb_run r;
  fb_status st0 = timed_runs(&r, k, tm.timed, 1, tm.walls, tm.setups, tm.stepping, &tm.reps, diag);
  if (st0 != FB_OK) return st0;
  const int first = *n;
  int qs[2];
  for (int q = 0; q < (with_clearance ? 2 : 1); q++) {
    if (q == 0 && !with_ideal) continue;
    if (*n == FB_BENCH_MAX_ROWS)
      return fb_diag_set(diag, FB_ERR_NOMEM, "bench: more than %d rows (FB_BENCH_MAX_ROWS)",
                         FB_BENCH_MAX_ROWS);
    qs[*n - first] = q;
    tm.row[q] = *n;
    fb_bench_row *b = &rows[(*n)++];
    const fb_model_result *m = &r.model[q];
    memset(b, 0, sizeof *b);
    b->row = m->run.model;
    snprintf(b->model, sizeof b->model, "%s", m->run.name);
    snprintf(b->engine, sizeof b->engine, "%s", engine);
    snprintf(b->stepper, sizeof b->stepper, "%s", stepper);
    b->h = m->run.h; /* as run: [solver] h_s = auto resolved */
    b->h_auto = k->solver.h_mode == FB_STEP_AUTO;
    b->h_adaptive = k->solver.h_mode == FB_STEP_ADAPTIVE;
    b->steps_taken = m->run.has_step_stats ? (double)m->run.step_stats.steps : (double)m->run.steps;
    b->mapping = q == 0 ? -1 : mapping;
    b->world_erp = mapping >= 0 ? k->solver.world_erp : NAN;
    b->world_cfm = mapping >= 0 ? k->solver.world_cfm : NAN;
    b->stop = m->run.stop;
    b->error = NAN;
    if (m->run.stop.kind == FB_STOP_NONE) {
      if (q == 0 && m->has_error) b->error = omega_peak_error(&m->error);
    }
    for (int p = 0; p < FB_BENCH_PARTS; p++) b->part[p] = b->halving_part[p] = NAN;
    b->halving = NAN;
    b->ecc_direction_rms = m->has_ref_error && m->run.stop.kind == FB_STOP_NONE
                               ? m->ref_error.ecc_direction_rms
                               : NAN;
    double mine[4];
    if (q == 1 && m->has_ref_error && row_peaks(mine, m, 1)) {
      double theirs[4];
      if (row_peaks(theirs, &r.model[2], 1))
        b->error = fb_bench_rel_parts(b->part, mine, theirs, FB_BENCH_PARTS);
    }
    /* this row's peaks, for the halving run below */
    if (!b->h_auto && row_peaks(mine, m, q))
      for (int p = 0; p < 4; p++) b->halving_part[p] = mine[p];
    snprintf(b->collider, sizeof b->collider, "%s",
             q == 0 ? "-" : fb_collider_name(m->run.collider));
    b->segments = q == 0 ? 0 : m->run.segments;
    b->force_vs_exact = b->pen_vs_exact = b->alpha_vs_exact = b->cost_vs_exact = NAN;
  }
  /* per revolution actually simulated: a run that stopped early covered
   * less; one that stopped within its first step has no cost per revolution
   * (NaN, printed "-"). The time the samples cover: steps x h for a
   * fixed-step engine, not for one whose steps are its integrator's own
   * (Simbody) */
  for (int q = 0; q < tm.timed; q++) {
    const fb_model_run *mr = &r.model[q].run;
    const fb_series *ser = &mr->series;
    const double covered = ser->n > 1 ? ser->t[ser->n - 1] : 0.0;
    const double simulated = covered * k->crank_speed / (2.0 * M_PI);
    tm.revs[q] = mr->steps > 1 && simulated > 0.0 ? simulated : 0.0;
    tm.steps[q] = (double)mr->steps;
    tm.samples[q] = (double)ser->n;
  }
  fb_run_free(&r);
  tm.k = *k;
  tm.k.model_count = tm.timed; /* the rounds time; the reference is not needed */
  fb_status st1 = timing_add(&tm, diag);
  if (st1 != FB_OK) return st1;
  timing_apply(rows, &timings.t[timings.n - 1]);
  if (k->solver.h_mode == FB_STEP_FIXED && *n > first)
    return halving(rows + first, *n - first, qs, qs, k, diag);
  return FB_OK;
}

/* the case of one configuration: 2 revolutions, the engine's ideal stack-up
 * model, and its clearance impact model beside the reference when the case
 * has clearance at the crank-coupler joint alone (the reference's scope) */
void fb_bench_models(fb_engine_id e, const fb_model **ideal, const fb_model **clearance) {
  *ideal = fb_model_match(e, FB_LENGTHS_STACKUP, FB_JOINTS_IDEAL, FB_MODEL_LAW_NONE,
                          FB_COLLIDER_NONE);
  *clearance = fb_model_match(e, FB_LENGTHS_STACKUP, FB_JOINTS_CLEARANCE, FB_MODEL_LAW_IMPACT,
                              FB_COLLIDER_EXACT);
}

static void bench_case(fb_case *k, const fb_case *c, double h, fb_engine_id engine) {
  *k = *c;
  k->revolutions = 2;
  /* h = 0: [solver] h_s = auto, resolved by the run's scene stage */
  k->solver.h = h > 0.0 ? h : c->solver.h;
  k->solver.h_mode = h > 0.0 ? FB_STEP_FIXED : FB_STEP_AUTO;
  const fb_model *models[3];
  fb_bench_models(engine, &models[0], &models[1]);
  models[2] = fb_model_reference_of(models[1]);
  k->model_count = k->clearance.mask == (1 << FB_JOINT_B) ? 3 : 1;
  for (int q = 0; q < k->model_count; q++)
    snprintf(k->models[q], FB_NAME_SIZE, "%s", models[q]->name);
}

/* the collider axis: segments of the ccd rings; 0 stands for the faceted
 * model with the case's ring */
static const int collider_rings[] = {16, 64, 256, 1024, 0};
#define COLLIDER_RINGS ((int)(sizeof collider_rings / sizeof collider_rings[0]))
static const double collider_hs[2] = {1e-5, 1e-6};

static double rel(double a, double b) { return b != 0.0 ? (a - b) / fabs(b) : NAN; }

/* one run of the collider axis: ODE's exact collider, the model of ring
 * ring, the reference; rows for the model (and, with the first ring, the
 * exact collider) */
static fb_status collider_run(fb_bench_row *rows, int *n, const fb_case *c, double h, int ring,
                              fb_diag *diag) {
  fb_case k = *c;
  k.revolutions = 2;
  k.solver.h = h;
  k.solver.h_mode = FB_STEP_FIXED;
  k.solver.stepper = FB_STEPPER_WORLD;
  k.solver.world_erp = 0.2;
  k.solver.world_cfm = 1e-10;
  k.clearance.collider = FB_CASE_COLLIDER_EXACT;
  if (ring > 0) {
    k.clearance.segments = ring;
    k.clearance.segments_given = 0; /* the faceted ring stays the case's */
  }
  const fb_model *exact = fb_model_match(FB_ENGINE_ODE, FB_LENGTHS_STACKUP, FB_JOINTS_CLEARANCE,
                                         FB_MODEL_LAW_IMPACT, FB_COLLIDER_EXACT);
  const fb_model *model = fb_model_match(FB_ENGINE_ODE, FB_LENGTHS_STACKUP, FB_JOINTS_CLEARANCE,
                                         FB_MODEL_LAW_IMPACT,
                                         ring > 0 ? FB_COLLIDER_CCD : FB_COLLIDER_FACETED);
  const fb_model *models[3] = {exact, model, fb_model_reference_of(exact)};
  k.model_count = 3;
  for (int q = 0; q < 3; q++) snprintf(k.models[q], FB_NAME_SIZE, "%s", models[q]->name);
  double walls[2][3], setups[2][3], stepping[2][3];
  int reps;
  static fb_run r;
  fb_status st = timed_runs(&r, &k, 2, 3, walls, setups, stepping, &reps, diag);
  if (st != FB_OK) return st;
  const fb_model_result *ex = &r.model[0], *ref = &r.model[2];
  double us[2];
  for (int q = 0; q < 2; q++) {
    qsort(walls[q], (size_t)reps, sizeof(double), cmp_double);
    const fb_model_run *m = &r.model[q].run;
    us[q] = m->steps > 0 ? 1e6 * walls[q][reps / 2] / (double)m->steps : NAN;
  }
  const int first = *n, kinds[2] = {1, 1};
  int idx[2];
  for (int q = ring == collider_rings[0] ? 0 : 1; q < 2 && *n < FB_BENCH_MAX_ROWS; q++) {
    const fb_model_result *m = &r.model[q];
    fb_bench_row *b = &rows[(*n)++];
    memset(b, 0, sizeof *b);
    b->row = m->run.model;
    snprintf(b->model, sizeof b->model, "%s", m->run.name);
    snprintf(b->engine, sizeof b->engine, "ode");
    snprintf(b->stepper, sizeof b->stepper, "world");
    b->h = h;
    b->mapping = k.clearance.mapping;
    b->world_erp = k.solver.world_erp;
    b->world_cfm = k.solver.world_cfm;
    b->stop = m->run.stop;
    snprintf(b->collider, sizeof b->collider, "%s", fb_collider_name(m->run.collider));
    b->segments = m->run.segments;
    b->repeats = reps;
    b->collider_axis = 1;
    b->us_per_step = us[q];
    const double simulated = (double)m->run.steps * m->run.h * k.crank_speed / (2.0 * M_PI);
    b->wall_per_rev = m->run.steps > 1 && simulated > 0.0 ? walls[q][reps / 2] / simulated : NAN;
    b->stepping_per_rev = b->sampling_per_rev = NAN; /* the axis compares cost per step */
    b->samples_per_rev = simulated > 0.0 ? (double)m->run.series.n / simulated : NAN;
    b->error = NAN;
    b->force_vs_exact = b->pen_vs_exact = b->alpha_vs_exact = b->cost_vs_exact = NAN;
    for (int p = 0; p < FB_BENCH_PARTS; p++) b->part[p] = b->halving_part[p] = NAN;
    b->halving = NAN;
    b->ecc_direction_rms = m->has_ref_error && m->run.stop.kind == FB_STOP_NONE
                               ? m->ref_error.ecc_direction_rms
                               : NAN;
    idx[*n - first - 1] = q;
    double mine[4], theirs[4];
    if (row_peaks(mine, m, 1))
      for (int p = 0; p < 4; p++) b->halving_part[p] = mine[p];
    if (m->run.stop.kind != FB_STOP_NONE || !m->has_spikes || !ex->has_spikes) continue;
    /* against the reference (the faceted row names none: compared here) */
    fb_reference_error re;
    fb_diag inner;
    if (ref->has_peaks && fb_metrics_vs_reference(&re, &m->run.series, &ref->run.series,
                                                  r.t_window, FB_JOINT_B, &inner) == FB_OK &&
        row_peaks(mine, m, 1) && row_peaks(theirs, ref, 1))
      b->error = fb_bench_rel_parts(b->part, mine, theirs, FB_BENCH_PARTS);
    b->has_vs_exact = 1;
    b->force_vs_exact = rel(m->spikes.force_max, ex->spikes.force_max);
    b->pen_vs_exact = rel(m->spikes.penetration_max, ex->spikes.penetration_max);
    b->alpha_vs_exact = rel(m->spikes.alpha_peak_ratio_coupler, ex->spikes.alpha_peak_ratio_coupler);
    b->impacts = m->spikes.impacts;
    b->impacts_exact = ex->spikes.impacts;
    b->cost_vs_exact = us[q] / us[0];
  }
  fb_run_free(&r);
  k.model_count = 2;
  if (*n > first) return halving(rows + first, *n - first, idx, kinds, &k, diag);
  return FB_OK;
}

/* Bullet's own knobs: solver (and its iterations) x h, with the case's
 * mapping; *done counts the points for progress over total */
static fb_status bullet_grid(fb_bench_row *rows, int *n, const fb_case *c,
                             void (*progress)(double fraction, void *user), void *user, int *done,
                             int total, fb_diag *diag) {
  const double bh[FB_BENCH_BULLET_STEPS] = {1e-4, 1e-5, 1e-6, 0.0}; /* 0: auto */
  const int iters[FB_BENCH_BULLET_SOLVERS] = {10, 50, 100, 0};   /* 0: mlcp-dantzig */
  for (int si = 0; si < FB_BENCH_BULLET_SOLVERS; si++)
    for (int hi = 0; hi < FB_BENCH_BULLET_STEPS; hi++) {
      fb_case k;
      bench_case(&k, c, bh[hi], FB_ENGINE_BULLET);
      k.bullet.solver = iters[si] ? FB_BULLET_SEQUENTIAL_IMPULSE : FB_BULLET_MLCP_DANTZIG;
      k.bullet.iterations = iters[si] ? iters[si] : c->bullet.iterations;
      char stepper[32];
      if (iters[si]) snprintf(stepper, sizeof stepper, "si-%d", iters[si]);
      else snprintf(stepper, sizeof stepper, "mlcp");
      const int first = *n;
      fb_status st = bench_point(rows, n, &k, "bullet", stepper, k.clearance.mapping, 1, diag);
      if (st != FB_OK) return st;
      for (int i = first; i < *n; i++) rows[i].world_cfm = 0.0; /* Bullet's pin rows are hard */
      if (progress) progress((double)++*done / total, user);
    }
  return FB_OK;
}

/* Simbody's grid (docs/engines.md): integrator x accuracy at the case's
 * output step, models simbody-ideal-stackup and simbody-clearance-impact
 * beside the reference; with ODE's dWorldStep rows (matched mapping, world
 * ERP/CFM 0.2, 1e-10, h 1e-4, 1e-5, 1e-6 s and auto) when ode_rows, so that
 * one run compares the two engines' costs. */
static fb_status simbody_grid(fb_bench_row *rows, int *n, const fb_case *c, int ode_rows,
                              void (*progress)(double fraction, void *user), void *user,
                              fb_diag *diag) {
  const double acc[6] = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8};
  const double oh[4] = {1e-4, 1e-5, 1e-6, 0.0}; /* 0: auto */
  const int total = FB_SIMBODY_INTEGRATOR_COUNT * 6 + (ode_rows ? 4 : 0);
  int done = 0;
  for (int ii = 0; ii < FB_SIMBODY_INTEGRATOR_COUNT; ii++)
    for (int ai = 0; ai < 6; ai++) {
      fb_case k;
      bench_case(&k, c, 0.0, FB_ENGINE_SIMBODY);
      k.solver.h = c->solver.h; /* the case's output step, as run */
      k.solver.h_mode = c->solver.h_mode;
      k.simbody.integrator = ii;
      k.simbody.accuracy = acc[ai];
      char stepper[32];
      snprintf(stepper, sizeof stepper, "%s %.0e", fb_simbody_integrator_name(ii), acc[ai]);
      fb_status st = bench_point(rows, n, &k, "simbody", stepper, -1, 1, diag);
      if (st != FB_OK) return st;
      if (progress) progress((double)++done / total, user);
    }
  for (int hi = 0; hi < (ode_rows ? 4 : 0); hi++) {
    fb_case k;
    bench_case(&k, c, oh[hi], FB_ENGINE_ODE);
    k.solver.stepper = FB_STEPPER_WORLD;
    k.solver.world_erp = 0.2;
    k.solver.world_cfm = 1e-10;
    k.clearance.mapping = FB_MAPPING_MATCHED;
    fb_status st = bench_point(rows, n, &k, "ode", "world", FB_MAPPING_MATCHED, 1, diag);
    if (st != FB_OK) return st;
    if (progress) progress((double)++done / total, user);
  }
  return FB_OK;
}

/* The default grid (FB_BENCH_DEFAULT): each engine at the settings its
 * section of docs/engines.md recommends for this stiff closed loop, every
 * model on the case's output grid unless the row is a fixed step of its
 * own (the cost split into stepping and sampling says what the grid costs):
 * ODE dWorldStep at h = 1e-5 s, auto and adaptive (accuracy 0.3); MuJoCo
 * with the case's integrators at h = 1e-5 s, 3e-6 s and adaptive (0.3);
 * Bullet's MLCP at h = 1e-5 s and auto; Simbody rkmerson at accuracy 1e-4
 * and 1e-6 and cpodes at 1e-6 on the case's grid. *done counts the points
 * for progress over total. */
#define DEFAULT_POINTS 13
static fb_status default_grid(fb_bench_row *rows, int *n, const fb_case *c,
                              void (*progress)(double fraction, void *user), void *user,
                              int *done, int total, fb_diag *diag) {
  const int mujoco = fb_engine_available(FB_ENGINE_MUJOCO);
  const int bullet = fb_engine_available(FB_ENGINE_BULLET);
  const int simbody = fb_engine_available(FB_ENGINE_SIMBODY);
  for (int p = 0; p < DEFAULT_POINTS; p++) {
    fb_case k;
    char stepper[32];
    const char *engine = "ode";
    int mapping = -1;
    if (p < 3) { /* ODE: 1e-5 s, auto, adaptive */
      bench_case(&k, c, p == 0 ? 1e-5 : 0.0, FB_ENGINE_ODE);
      if (p == 2) {
        k.solver.h_mode = FB_STEP_ADAPTIVE;
        k.solver.h = k.solver.h_min;
        k.solver.accuracy = 0.3;
      }
      if (k.solver.stepper == FB_STEPPER_QUICK)
        snprintf(stepper, sizeof stepper, "quick-%d%s", k.solver.quick_iterations, p == 2 ? "-a0.3" : "");
      else
        snprintf(stepper, sizeof stepper, "world%s", p == 2 ? "-a0.3" : "");
      mapping = p == 2 && k.clearance.mapping == FB_MAPPING_MATCHED ? FB_MAPPING_MATCHED_STATIC
                                                                     : (int)k.clearance.mapping;
    } else if (p < 6) { /* MuJoCo: 1e-5 s, 3e-6 s, adaptive */
      if (!mujoco) continue;
      engine = "mujoco";
      bench_case(&k, c, p == 3 ? 1e-5 : p == 4 ? 3e-6 : 0.0, FB_ENGINE_MUJOCO);
      if (p == 5) {
        k.solver.h_mode = FB_STEP_ADAPTIVE;
        k.solver.h = k.solver.h_min;
        k.solver.accuracy = 0.3;
      }
      snprintf(stepper, sizeof stepper, "%s%s", fb_mujoco_integrator_name(k.mujoco.integrator),
               p == 5 ? "-a0.3" : "");
    } else if (p < 8) { /* Bullet: MLCP at 1e-5 s and auto */
      if (!bullet) continue;
      engine = "bullet";
      bench_case(&k, c, p == 6 ? 1e-5 : 0.0, FB_ENGINE_BULLET);
      k.bullet.solver = FB_BULLET_MLCP_DANTZIG;
      snprintf(stepper, sizeof stepper, "mlcp");
      mapping = (int)k.clearance.mapping;
    } else if (p < 11) { /* Simbody on the case's grid */
      if (!simbody) continue;
      engine = "simbody";
      bench_case(&k, c, 0.0, FB_ENGINE_SIMBODY);
      k.solver.h = c->solver.h;
      k.solver.h_mode = c->solver.h_mode;
      k.simbody.integrator = p == 10 ? FB_SIMBODY_CPODES : FB_SIMBODY_RKMERSON;
      k.simbody.accuracy = p == 8 ? 1e-4 : 1e-6;
      snprintf(stepper, sizeof stepper, "%s %.0e", fb_simbody_integrator_name(k.simbody.integrator),
               k.simbody.accuracy);
    } else { /* ODE's tuned ideal rows: world ERP 1 at 1.5e-5 and 2e-5 s */
      bench_case(&k, c, p == 11 ? 1.5e-5 : 2e-5, FB_ENGINE_ODE);
      k.model_count = 1;
      k.solver.stepper = FB_STEPPER_WORLD;
      k.solver.world_erp = 1.0;
      k.solver.world_cfm = 1e-10;
      snprintf(stepper, sizeof stepper, "world");
      mapping = 0;
    }
    const int first = *n;
    fb_status st = bench_point(rows, n, &k, engine, stepper, mapping, 1, diag);
    if (st != FB_OK) return st;
    if (strcmp(engine, "bullet") == 0)
      for (int i = first; i < *n; i++) rows[i].world_cfm = 0.0; /* Bullet's pin rows are hard */
    if (progress) progress((double)++*done / total, user);
  }
  return FB_OK;
}

/* the rounds of the timing: each configuration bench_point ran is run again
 * (its timed models only) FB_BENCH_ROUNDS - 1 times, one configuration after
 * the other in grid order, round after round, while its first run took at
 * most FB_BENCH_REPEAT_BELOW_S; then every row's cost is the median of its
 * rounds. Back-to-back repeats of one configuration share the machine's
 * state of that moment; rounds spread over the whole bench put a slow
 * phase of the machine into one round of many rows instead of every round of
 * a few (two frontier runs 26 minutes apart had the same rows' cost ratios
 * differ by up to 1.9 times with back-to-back repeats). progress gets the
 * fraction from `from` to 1. */
static fb_status retime(fb_bench_row *rows, double from,
                        void (*progress)(double fraction, void *user), void *user,
                        fb_diag *diag) {
  int todo = 0;
  for (int i = 0; i < timings.n; i++) {
    const bench_timing *t = &timings.t[i];
    todo += t->walls[0][0] + t->walls[1][0] <= FB_BENCH_REPEAT_BELOW_S;
  }
  int done = 0;
  for (int round = 1; round < FB_BENCH_ROUNDS; round++)
    for (int i = 0; i < timings.n; i++) {
      bench_timing *t = &timings.t[i];
      if (t->reps != round || t->walls[0][0] + t->walls[1][0] > FB_BENCH_REPEAT_BELOW_S) continue;
      static fb_run r;
      double walls[2][3], setups[2][3], stepping[2][3];
      int reps;
      fb_status st = timed_runs(&r, &t->k, t->timed, 1, walls, setups, stepping, &reps, diag);
      if (st != FB_OK) return st;
      fb_run_free(&r);
      for (int q = 0; q < t->timed; q++) {
        t->walls[q][round] = walls[q][0];
        t->setups[q][round] = setups[q][0];
        t->stepping[q][round] = stepping[q][0];
      }
      t->reps = round + 1;
      if (progress && todo > 0)
        progress(from + (1.0 - from) * (double)++done / ((FB_BENCH_ROUNDS - 1) * todo), user);
    }
  for (int i = 0; i < timings.n; i++) timing_apply(rows, &timings.t[i]);
  return FB_OK;
}

static fb_status bench_grids(fb_bench_row *rows, int *n, const fb_case *c, int grids,
                             void (*progress)(double fraction, void *user), void *user,
                             fb_diag *diag);

fb_status fb_bench_run(fb_bench_row *rows, int *n, const fb_case *c, int grids,
                       void (*progress)(double fraction, void *user), void *user, fb_diag *diag) {
  timings.n = 0;
  fb_status st = bench_grids(rows, n, c, grids, progress, user, diag);
  if (st == FB_OK) st = retime(rows, FB_BENCH_FIRST_PASS_SHARE, progress, user, diag);
  free(timings.t);
  memset(&timings, 0, sizeof timings);
  if (st == FB_OK) fb_bench_mark_pareto(rows, *n);
  return st;
}

/* the progress of the grids' first pass, scaled into [0, share) */
typedef struct {
  void (*progress)(double fraction, void *user);
  void *user;
} first_pass;

static void first_pass_progress(double fraction, void *user) {
  const first_pass *f = user;
  f->progress(FB_BENCH_FIRST_PASS_SHARE * fraction, f->user);
}

static fb_status bench_grids(fb_bench_row *rows, int *n, const fb_case *c, int grids,
                             void (*progress_all)(double fraction, void *user), void *user_all,
                             fb_diag *diag) {
  first_pass fp = {progress_all, user_all};
  void (*progress)(double fraction, void *user) = progress_all ? first_pass_progress : NULL;
  void *user = &fp;
  const double hs[FB_BENCH_STEPS] = {1e-3, 1e-4, 1e-5, 1e-6, 0.0}; /* 0: auto */
  const int iters[4] = {0, 10, 20, 50}; /* 0: dWorldStep */
  const double erp[2] = {0.2, 0.8}, cfm[2] = {1e-10, 1e-8};
  const int solvers = (grids & FB_BENCH_SOLVERS) != 0;
  const int frontier = !solvers && (grids & FB_BENCH_FRONTIER) != 0; /* solvers holds it */
  const int mujoco = solvers && fb_engine_available(FB_ENGINE_MUJOCO);
  const int bullet_only = grids == FB_BENCH_BULLET;
  const int bullet = (solvers || bullet_only) && fb_engine_available(FB_ENGINE_BULLET);
  const int mj_frontier = frontier && fb_engine_available(FB_ENGINE_MUJOCO);
  const int extra = solvers || frontier; /* the tuned ideal and adaptive rows */
  const int colliders = (grids & FB_BENCH_COLLIDERS) && c->clearance.mask == (1 << FB_JOINT_B);
  const int dflt = (grids & FB_BENCH_DEFAULT) != 0;
  const int total = (dflt ? DEFAULT_POINTS : 0) + (solvers ? 4 * FB_BENCH_STEPS * FB_MAPPING_COUNT * 2 : 0) +
                    (extra ? FB_BENCH_IDEAL_TUNED + FB_BENCH_ADAPTIVE + FB_BENCH_ADAPTIVE_ROCKING : 0) +
                    (frontier ? FB_BENCH_FRONTIER_STEPS + 1 : 0) +
                    (mj_frontier ? FB_BENCH_FRONTIER_STEPS + FB_BENCH_ADAPTIVE : 0) +
                    (mujoco ? 3 * FB_BENCH_MUJOCO_STEPS + FB_BENCH_ADAPTIVE : 0) +
                    (bullet ? FB_BENCH_BULLET_SOLVERS * FB_BENCH_BULLET_STEPS : 0) + bullet_only +
                    (colliders ? 2 * COLLIDER_RINGS : 0);
  int done = 0;
  *n = 0;
  if (dflt) {
    fb_status st = default_grid(rows, n, c, progress, user, &done, total, diag);
    if (st != FB_OK) return st;
  }
  if (grids & FB_BENCH_SIMBODY) {
    /* alone (--grid simbody): with ODE's dWorldStep rows for the comparison */
    fb_status st = fb_engine_available(FB_ENGINE_SIMBODY)
                       ? simbody_grid(rows, n, c, !solvers, progress, user, diag)
                       : FB_OK;
    if (st != FB_OK) return st;
  }
  for (int si = 0; si < (solvers ? 4 : 0); si++)
    for (int hi = 0; hi < FB_BENCH_STEPS; hi++)
      for (int mi = 0; mi < FB_MAPPING_COUNT; mi++)
        for (int ei = 0; ei < 2; ei++) {
          fb_case k;
          bench_case(&k, c, hs[hi], FB_ENGINE_ODE);
          k.solver.stepper = iters[si] ? FB_STEPPER_QUICK : FB_STEPPER_WORLD;
          k.solver.quick_iterations = iters[si] ? iters[si] : 20;
          k.solver.world_erp = erp[ei];
          k.solver.world_cfm = cfm[ei];
          k.clearance.mapping = mi;
          char stepper[32];
          if (iters[si]) snprintf(stepper, sizeof stepper, "quick-%d", iters[si]);
          else snprintf(stepper, sizeof stepper, "world");
          /* the mapping does not touch the ideal model: one row for it */
          fb_status st = bench_point(rows, n, &k, "ode", stepper, mi, mi == 0, diag);
          if (st != FB_OK) return st;
          if (progress) progress((double)++done / total, user);
        }
  /* the ideal model at its cheapest setting for 1e-5 (issue 29): world
   * ERP 1 (the whole joint error corrected each step) lets the step double */
  /* the frontier (--grid frontier): the case's stepper, world ERP/CFM and
   * mapping at the fixed steps of FB_BENCH_FRONTIER_STEPS and auto, the
   * ideal model at ERP 0.8, CFM 1e-8, h = 1e-5 s; MuJoCo with the case's
   * integrators at the fixed steps */
  const double fh[FB_BENCH_FRONTIER_STEPS] = {1e-5, 3e-6, 1e-6, 0.0}; /* 0: auto */
  for (int hi = 0; hi < (frontier ? FB_BENCH_FRONTIER_STEPS : 0); hi++) {
    fb_case k;
    bench_case(&k, c, fh[hi], FB_ENGINE_ODE);
    fb_status st = bench_point(rows, n, &k, "ode", k.solver.stepper == FB_STEPPER_WORLD ? "world" : "quick",
                               k.clearance.mapping, 1, diag);
    if (st != FB_OK) return st;
    if (progress) progress((double)++done / total, user);
  }
  if (frontier) {
    fb_case k;
    bench_case(&k, c, 1e-5, FB_ENGINE_ODE);
    k.model_count = 1;
    k.solver.stepper = FB_STEPPER_WORLD;
    k.solver.world_erp = 0.8;
    k.solver.world_cfm = 1e-8;
    fb_status st = bench_point(rows, n, &k, "ode", "world", 0, 1, diag);
    if (st != FB_OK) return st;
    if (progress) progress((double)++done / total, user);
  }
  for (int hi = 0; hi < (mj_frontier ? FB_BENCH_FRONTIER_STEPS - 1 : 0); hi++) {
    fb_case k;
    bench_case(&k, c, fh[hi], FB_ENGINE_MUJOCO);
    fb_status st = bench_point(rows, n, &k, "mujoco", fb_mujoco_integrator_name(k.mujoco.integrator),
                               -1, 1, diag);
    if (st != FB_OK) return st;
    if (progress) progress((double)++done / total, user);
  }
  for (int ti = 0; ti < (extra ? FB_BENCH_IDEAL_TUNED : 0); ti++) {
    const double tuned[FB_BENCH_IDEAL_TUNED][3] = {{1.5e-5, 1.0, 1e-10}, {2e-5, 1.0, 1e-10}};
    fb_case k;
    bench_case(&k, c, tuned[ti][0], FB_ENGINE_ODE);
    k.model_count = 1;
    k.solver.stepper = FB_STEPPER_WORLD;
    k.solver.world_erp = tuned[ti][1];
    k.solver.world_cfm = tuned[ti][2];
    fb_status st = bench_point(rows, n, &k, "ode", "world", 0, 1, diag);
    if (st != FB_OK) return st;
    if (progress) progress((double)++done / total, user);
  }
  /* ODE with [solver] h_s = adaptive (step_control.h) at two accuracies */
  for (int ai = 0; ai < (extra ? FB_BENCH_ADAPTIVE : 0); ai++) {
    const double accuracy[FB_BENCH_ADAPTIVE] = {0.3, 0.1};
    fb_case k;
    bench_case(&k, c, 0.0, FB_ENGINE_ODE);
    k.solver.h_mode = FB_STEP_ADAPTIVE;
    k.solver.h = k.solver.h_min;
    k.solver.accuracy = accuracy[ai];
    k.solver.stepper = FB_STEPPER_WORLD;
    char stepper[32];
    snprintf(stepper, sizeof stepper, "world-a%g", accuracy[ai]);
    const int mapping = k.clearance.mapping == FB_MAPPING_MATCHED ? FB_MAPPING_MATCHED_STATIC
                                                                  : k.clearance.mapping;
    fb_status st = bench_point(rows, n, &k, "ode", stepper, mapping, 1, diag);
    if (st != FB_OK) return st;
    if (progress) progress((double)++done / total, user);
  }
  /* ODE's adaptive row with the rocking bound (bench.h) */
  for (int ri = 0; ri < (extra ? FB_BENCH_ADAPTIVE_ROCKING : 0); ri++) {
    fb_case k;
    bench_case(&k, c, 0.0, FB_ENGINE_ODE);
    k.solver.h_mode = FB_STEP_ADAPTIVE;
    k.solver.h = k.solver.h_min;
    k.solver.accuracy = 0.3;
    k.solver.rocking_h_omega = FB_BENCH_ROCKING_H_OMEGA;
    k.solver.stepper = FB_STEPPER_WORLD;
    char stepper[32];
    snprintf(stepper, sizeof stepper, "world-a0.3-r%g", FB_BENCH_ROCKING_H_OMEGA);
    const int mapping = k.clearance.mapping == FB_MAPPING_MATCHED ? FB_MAPPING_MATCHED_STATIC
                                                                  : k.clearance.mapping;
    fb_status st = bench_point(rows, n, &k, "ode", stepper, mapping, 1, diag);
    if (st != FB_OK) return st;
    if (progress) progress((double)++done / total, user);
  }
  /* MuJoCo with [solver] h_s = adaptive, the case's integrators */
  for (int ai = 0; ai < (mujoco || mj_frontier ? FB_BENCH_ADAPTIVE : 0); ai++) {
    const double accuracy[FB_BENCH_ADAPTIVE] = {0.3, 0.1};
    fb_case k;
    bench_case(&k, c, 0.0, FB_ENGINE_MUJOCO);
    k.solver.h_mode = FB_STEP_ADAPTIVE;
    k.solver.h = k.solver.h_min;
    k.solver.accuracy = accuracy[ai];
    char stepper[32];
    snprintf(stepper, sizeof stepper, "%s-a%g", fb_mujoco_integrator_name(k.mujoco.integrator),
             accuracy[ai]);
    fb_status st = bench_point(rows, n, &k, "mujoco", stepper, -1, 1, diag);
    if (st != FB_OK) return st;
    if (progress) progress((double)++done / total, user);
  }
  /* MuJoCo: integrator x step, with the case's loop closure and drive */
  if (mujoco) {
    const double mh[FB_BENCH_MUJOCO_STEPS] = {1e-3, 3e-4, 1e-4, 3e-5, 1e-5, 3e-6, 1e-6};
    const int integ[3] = {FB_MUJOCO_EULER, FB_MUJOCO_IMPLICIT, FB_MUJOCO_RK4};
    for (int ii = 0; ii < 3; ii++)
      for (int hi = 0; hi < FB_BENCH_MUJOCO_STEPS; hi++) {
        fb_case k;
        bench_case(&k, c, mh[hi], FB_ENGINE_MUJOCO);
        k.mujoco.integrator = integ[ii];
        fb_status st = bench_point(rows, n, &k, "mujoco", fb_mujoco_integrator_name(integ[ii]),
                                   -1, 1, diag);
        if (st != FB_OK) return st;
        if (progress) progress((double)++done / total, user);
      }
  }
  if (bullet_only) {
    /* ODE at the case's own settings, measured in the same run */
    fb_case k;
    bench_case(&k, c, c->solver.h_mode == FB_STEP_FIXED ? c->solver.h : 0.0, FB_ENGINE_ODE);
    char stepper[32];
    if (c->solver.stepper == FB_STEPPER_QUICK)
      snprintf(stepper, sizeof stepper, "quick-%d", c->solver.quick_iterations);
    else
      snprintf(stepper, sizeof stepper, "world");
    fb_status st = bench_point(rows, n, &k, "ode", stepper, k.clearance.mapping, 1, diag);
    if (st != FB_OK) return st;
    if (progress) progress((double)++done / total, user);
  }
  if (bullet) {
    fb_status st = bullet_grid(rows, n, c, progress, user, &done, total, diag);
    if (st != FB_OK) return st;
  }
  for (int hi = 0; hi < (colliders ? 2 : 0); hi++)
    for (int ri = 0; ri < COLLIDER_RINGS; ri++) {
      fb_status st = collider_run(rows, n, c, collider_hs[hi], collider_rings[ri], diag);
      if (st != FB_OK) return st;
      if (progress) progress((double)++done / total, user);
    }
  return FB_OK;
}

void fb_bench_mark_pareto(fb_bench_row *rows, int n) {
  int *nn = &n;
  for (int i = 0; i < *nn; i++) {
    fb_bench_row *a = &rows[i];
    if (!isfinite(a->error)) continue;
    a->pareto = 1;
    for (int j = 0; j < *nn && a->pareto; j++) {
      const fb_bench_row *b = &rows[j];
      if (j == i || a->row != b->row || !isfinite(b->error)) continue;
      if (b->error <= a->error && b->wall_per_rev <= a->wall_per_rev &&
          (b->error < a->error || b->wall_per_rev < a->wall_per_rev))
        a->pareto = 0;
    }
  }
}

int fb_bench_cheapest(const fb_bench_row *rows, int n, const fb_model *model, double target) {
  int best = -1;
  for (int i = 0; i < n; i++)
    if (rows[i].row == model && isfinite(rows[i].error) && rows[i].error <= target &&
        (best < 0 || rows[i].wall_per_rev < rows[best].wall_per_rev))
      best = i;
  return best;
}
