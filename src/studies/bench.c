#include "bench.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "engine.h"
#include "model_table.h"
#include "pilot.h"
#include "run.h"

static double repeat_below = FB_BENCH_REPEAT_BELOW_S;

double fb_bench_repeat_below_s(void) { return repeat_below; }

void fb_bench_repeat_below(double seconds) { repeat_below = seconds; }

/* The estimate pass (fb_bench_estimate): the grids walked as the bench
 * walks them, every run replaced by its case's pilot (pilot.h), whose
 * extrapolated CPU time is counted as often as the bench would run it
 * (its repeats by the same rule, read from the extrapolated wall times);
 * no row is made. */
static struct {
  int on;
  double cpu;   /* the runs' CPU time, extrapolated [s] */
  double pilot; /* what the pilots cost [s] */
} plan;

/* the CPU time of the last planned configuration's timed models alone
 * (timed_runs): what each later round of its timing costs [s] */
static double plan_timed_cpu;

/* case k's cost into *p, counted reps times */
static fb_status plan_run(fb_pilot *p, const fb_case *k, int reps, fb_diag *diag) {
  fb_status st = fb_pilot_case(p, k, diag);
  if (st != FB_OK) return st;
  plan.cpu += reps * p->cpu_s;
  plan.pilot += p->pilot_cpu_s;
  return FB_OK;
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* the largest omega peak error of the nout output bodies (fmax from NaN:
 * a NaN part counts as absent, as fmax has it) */
static double omega_peak_error(const fb_error *e, int nout) {
  double worst = NAN;
  for (int k = 0; k < nout; k++)
    worst = fmax(worst, fmax(fabs(e->body[k].omega_max_rel), fabs(e->body[k].omega_min_rel)));
  return worst;
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

/* the peaks a row's error compares, per output body k in the description's
 * order (fb_series_output_count of the model's series): clearance (q = 1)
 * force, penetration and each body's alpha spike (FB_BENCH_PART_ALPHA_COUPLER
 * + k); ideal (q = 0) each body's omega max and min (2k, 2k + 1). Returns
 * the parts filled (the rest NaN), 0 when the model did not reach its window */
static int row_peaks(double out[FB_BENCH_PARTS], const fb_model_result *m, int q) {
  if (m->run.stop.kind != FB_STOP_NONE || !m->has_peaks) return 0;
  if (q == 1 && !m->has_spikes) return 0;
  const int nout = fb_series_output_count(&m->run.series);
  for (int p = 0; p < FB_BENCH_PARTS; p++) out[p] = NAN;
  if (q == 0) {
    for (int k = 0; k < nout; k++) {
      out[2 * k] = m->peaks.body[k].omega_max;
      out[2 * k + 1] = m->peaks.body[k].omega_min;
    }
    return 2 * nout;
  }
  out[FB_BENCH_PART_FORCE] = m->spikes.force_max;
  out[FB_BENCH_PART_PENETRATION] = m->spikes.penetration_max;
  for (int k = 0; k < nout; k++)
    out[FB_BENCH_PART_ALPHA_COUPLER + k] = fb_bench_alpha_spike(&m->peaks.body[k]);
  return FB_BENCH_PART_ALPHA_COUPLER + nout;
}

/* row m's clearance peaks against those of ref into part (FB_BENCH_PARTS;
 * left as they are when either did not reach its window, or they differ
 * in count); returns the largest relative error, NaN then */
static double clearance_error(double part[FB_BENCH_PARTS], const fb_model_result *m,
                              const fb_model_result *ref) {
  double mine[FB_BENCH_PARTS], theirs[FB_BENCH_PARTS];
  const int np = row_peaks(mine, m, 1);
  if (!np || row_peaks(theirs, ref, 1) != np) return NAN;
  return fb_bench_rel_parts(part, mine, theirs, np);
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
  if (plan.on) {
    fb_pilot p;
    return plan_run(&p, &k2, 1, diag);
  }
  static fb_run r2;
  fb_status st = fb_run_case(&r2, &k2, NULL, NULL, diag);
  if (st != FB_OK) return st;
  for (int i = 0; i < nrows; i++) {
    fb_bench_row *b = &rows[i];
    double at_h[FB_BENCH_PARTS], at_h2[FB_BENCH_PARTS], rel[FB_BENCH_PARTS];
    for (int p = 0; p < FB_BENCH_PARTS; p++) at_h[p] = b->halving_part[p];
    for (int p = 0; p < FB_BENCH_PARTS; p++) b->halving_part[p] = NAN;
    const int np = isfinite(at_h[0]) ? row_peaks(at_h2, &r2.model[idx[i]], kind[i]) : 0;
    if (!np) continue;
    b->halving = fb_bench_rel_parts(rel, at_h, at_h2, np);
    if (kind[i])
      for (int p = 0; p < np; p++) b->halving_part[p] = rel[p];
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
  if (plan.on) { /* its pilot, counted as often as the repeat rule would run it */
    fb_pilot p;
    fb_status st = fb_pilot_case(&p, k, diag);
    if (st != FB_OK) return st;
    double first = 0.0;
    for (int q = 0; q < 2; q++) {
      walls[q][0] = q < timed && q < p.n ? p.model_s[q] : 0.0;
      setups[q][0] = q < timed && q < p.n ? p.setup_s[q] : 0.0;
      stepping[q][0] = walls[q][0];
      first += walls[q][0];
    }
    *reps = 1;
    plan.cpu += (first > repeat_below ? 1 : max_reps) * p.cpu_s;
    plan.pilot += p.pilot_cpu_s;
    /* the later rounds (retime) run the timed models alone: their share */
    double all = 0.0, mine = 0.0;
    for (int q = 0; q < p.n; q++) {
      all += p.model_s[q] + p.setup_s[q];
      if (q < timed) mine += p.model_s[q] + p.setup_s[q];
    }
    plan_timed_cpu = all > 0.0 ? p.cpu_s * mine / all : p.cpu_s;
    return FB_OK;
  }
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
    if (rep == max_reps - 1 || walls[0][rep] + walls[1][rep] > repeat_below) break;
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
  double plan_cpu;       /* the estimate pass: a later round's CPU time [s] */
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
  if (plan.on) { /* its later rounds and its step-halving run, counted */
    tm.k = *k;
    tm.k.model_count = tm.timed;
    tm.plan_cpu = plan_timed_cpu;
    st0 = timing_add(&tm, diag);
    if (st0 == FB_OK && k->solver.h_mode == FB_STEP_FIXED) st0 = halving(NULL, 0, NULL, NULL, k, diag);
    return st0;
  }
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
      if (q == 0 && m->has_error)
        b->error = omega_peak_error(&m->error, fb_series_output_count(&m->run.series));
    }
    for (int p = 0; p < FB_BENCH_PARTS; p++) b->part[p] = b->halving_part[p] = NAN;
    b->halving = NAN;
    b->ecc_direction_rms = m->has_ref_error && m->run.stop.kind == FB_STOP_NONE
                               ? m->ref_error.ecc_direction_rms
                               : NAN;
    double mine[FB_BENCH_PARTS];
    if (q == 1 && m->has_ref_error) b->error = clearance_error(b->part, m, &r.model[2]);
    /* this row's peaks, for the halving run below */
    if (!b->h_auto && row_peaks(mine, m, q))
      for (int p = 0; p < FB_BENCH_PARTS; p++) b->halving_part[p] = mine[p];
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
  /* an engine without the impact law (Siconos: rigid, Newton's law) is
   * benched with its first stack-up clearance model, against its reference */
  for (int q = 0; !*clearance && q < fb_model_count; q++)
    if (fb_models[q].engine == e && fb_models[q].lengths == FB_LENGTHS_STACKUP &&
        fb_models[q].joints == FB_JOINTS_CLEARANCE && fb_models[q].reference)
      *clearance = &fb_models[q];
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
  k->model_count = k->clearance.mask == (1 << fb_case_mech(k)->reference_joint) ? 3 : 1;
  for (int q = 0; q < k->model_count; q++)
    snprintf(k->models[q], FB_NAME_SIZE, "%s", models[q]->name);
}

/* the collider axis: segments of the ccd rings; 0 stands for the faceted
 * model with the case's ring */
static const int collider_rings[] = {16, 64, 256, 1024, 0};
#define COLLIDER_RINGS ((int)(sizeof collider_rings / sizeof collider_rings[0]))

static double rel(double a, double b) { return b != 0.0 ? (a - b) / fabs(b) : NAN; }

/* the collider axis' models of engine e: its clearance impact model with
 * the exact collider (*exact) and with the ccd collider (ring > 0) or the
 * faceted one (ring 0) (*model); 0 when the engine lacks one */
static int collider_models(fb_engine_id e, int ring, const fb_model **exact,
                           const fb_model **model) {
  *exact = fb_model_match(e, FB_LENGTHS_STACKUP, FB_JOINTS_CLEARANCE, FB_MODEL_LAW_IMPACT,
                          FB_COLLIDER_EXACT);
  *model = fb_model_match(e, FB_LENGTHS_STACKUP, FB_JOINTS_CLEARANCE, FB_MODEL_LAW_IMPACT,
                          ring > 0 ? FB_COLLIDER_CCD : FB_COLLIDER_FACETED);
  return *exact && *model && fb_model_reference_of(*exact);
}

/* one run of the collider axis at the configuration kp of engine eng (id
 * e; its point pt of FB_BENCH_SET_COLLIDERS): its exact collider, the model
 * of ring ring, the reference; rows for the model (and, with the first
 * ring, the exact collider) */
static fb_status collider_run(fb_bench_row *rows, int *n, fb_engine_id e, const fb_engine *eng,
                              const fb_case *kp, const fb_bench_point *pt, int ring,
                              fb_diag *diag) {
  fb_case k = *kp;
  const double h = k.solver.h;
  k.clearance.collider = FB_CASE_COLLIDER_EXACT;
  if (ring > 0) {
    k.clearance.segments = ring;
    k.clearance.segments_given = 0; /* the faceted ring stays the case's */
  }
  const fb_model *exact, *model;
  if (!collider_models(e, ring, &exact, &model)) return FB_OK;
  const fb_model *models[3] = {exact, model, fb_model_reference_of(exact)};
  k.model_count = 3;
  for (int q = 0; q < 3; q++) snprintf(k.models[q], FB_NAME_SIZE, "%s", models[q]->name);
  double walls[2][3], setups[2][3], stepping[2][3];
  int reps;
  static fb_run r;
  fb_status st = timed_runs(&r, &k, 2, 3, walls, setups, stepping, &reps, diag);
  if (st != FB_OK) return st;
  if (plan.on) { /* its step-halving run, counted */
    k.model_count = 2;
    return halving(NULL, 0, NULL, NULL, &k, diag);
  }
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
    snprintf(b->engine, sizeof b->engine, "%s", eng->name);
    snprintf(b->stepper, sizeof b->stepper, "%s", pt->stepper);
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
    double mine[FB_BENCH_PARTS];
    if (row_peaks(mine, m, 1))
      for (int p = 0; p < FB_BENCH_PARTS; p++) b->halving_part[p] = mine[p];
    if (m->run.stop.kind != FB_STOP_NONE || !m->has_spikes || !ex->has_spikes) continue;
    /* against the reference (the faceted row names none: compared here) */
    fb_reference_error re;
    fb_diag inner;
    if (ref->has_peaks && fb_metrics_vs_reference(&re, &m->run.series, &ref->run.series,
                                                  r.t_window, fb_case_mech(&r.c)->reference_joint, &inner) == FB_OK)
      b->error = clearance_error(b->part, m, ref);
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

/* the bench's copy of case c for engine e (bench_case, at the case's auto
 * step) set to point i of the engine's rows of set s (fb_engine_bench.point);
 * 0 when the set has no point i */
static int engine_point(const fb_engine *eng, fb_engine_id e, fb_bench_set s, int i,
                        const fb_case *c, fb_case *k, fb_bench_point *p) {
  bench_case(k, c, 0.0, e);
  memset(p, 0, sizeof *p);
  p->mapping = -1;
  return eng->bench->point(s, i, c, k, p);
}

int fb_bench_builds(fb_engine_id e, const fb_case *c) {
  const fb_model *m[2]; /* every model builds some mechanisms (fb_model_builds) */
  fb_bench_models(e, &m[0], &m[1]);
  for (int k = 0; k < 2; k++)
    if (m[k] && !fb_model_builds(m[k], c->mechanism)) return 0;
  return 1;
}

/* the engine of id e when this build has it, it gives bench rows and its
 * bench models build the case's mechanism, else NULL */
static const fb_engine *bench_engine(fb_engine_id e, const fb_case *c) {
  const fb_engine *eng = fb_engine_available(e) ? fb_engine_get(e, NULL) : NULL;
  return eng && eng->bench && fb_bench_builds(e, c) ? eng : NULL;
}

/* the points of engine e's rows of set s on case c (0: none, or no such engine) */
static int set_points(fb_engine_id e, fb_bench_set s, const fb_case *c) {
  const fb_engine *eng = bench_engine(e, c);
  if (!eng || s == FB_BENCH_SET_NONE) return 0;
  static fb_case k;
  fb_bench_point p;
  int count = 0;
  while (engine_point(eng, e, s, count, c, &k, &p)) count++;
  return count;
}

/* the points of set s of every engine */
static int all_points(fb_bench_set s, const fb_case *c) {
  int count = 0;
  for (int e = 0; e < FB_ENGINE_COUNT; e++) count += set_points((fb_engine_id)e, s, c);
  return count;
}

/* a grid's pass: rows, case, progress over the configurations of the pass */
typedef struct {
  fb_bench_row *rows;
  int *n;
  const fb_case *c;
  void (*progress)(double fraction, void *user);
  void *user;
  int done, total;
} bench_pass;

static void pass_step(bench_pass *x) {
  if (x->progress && x->total > 0) x->progress((double)++x->done / x->total, x->user);
}

/* engine e's rows of set s: one bench_point per point */
static fb_status run_set(bench_pass *x, fb_engine_id e, fb_bench_set s, fb_diag *diag) {
  const fb_engine *eng = bench_engine(e, x->c);
  if (!eng || s == FB_BENCH_SET_NONE) return FB_OK;
  for (int i = 0;; i++) {
    fb_case k;
    fb_bench_point p;
    if (!engine_point(eng, e, s, i, x->c, &k, &p)) return FB_OK;
    const int first = *x->n;
    fb_status st = bench_point(x->rows, x->n, &k, eng->name, p.stepper, p.mapping,
                               !p.no_ideal_row, diag);
    if (st != FB_OK) return st;
    if (p.hard_pins)
      for (int j = first; j < *x->n; j++) x->rows[j].world_cfm = 0.0;
    pass_step(x);
  }
}

/* the rows of set s of every engine, in the order of their ids */
static fb_status run_all(bench_pass *x, fb_bench_set s, fb_diag *diag) {
  for (int e = 0; e < FB_ENGINE_COUNT; e++) {
    fb_status st = run_set(x, (fb_engine_id)e, s, diag);
    if (st != FB_OK) return st;
  }
  return FB_OK;
}

/* 1 when grids run engine e's own grid: its bit is in grids, and not with
 * the solver grids when its solver rows stand for it; *alone: without the
 * solver grids (then with the rows it wants beside it) */
static int runs_own(fb_engine_id e, int grids, const fb_case *c, int *alone) {
  const fb_engine *eng = bench_engine(e, c);
  if (!eng || !eng->bench->own_grid || !(grids & eng->bench->own_grid)) return 0;
  const int solvers = (grids & FB_BENCH_SOLVERS) != 0;
  *alone = !solvers;
  return !solvers || set_points(e, FB_BENCH_SET_SOLVERS, c) == 0;
}

/* the collider axis of every engine with rows of FB_BENCH_SET_COLLIDERS:
 * each of its points with each ring */
static fb_status run_colliders(bench_pass *x, fb_diag *diag) {
  for (int e = 0; e < FB_ENGINE_COUNT; e++) {
    const fb_engine *eng = bench_engine((fb_engine_id)e, x->c);
    for (int i = 0; eng; i++) {
      fb_case k;
      fb_bench_point p;
      if (!engine_point(eng, (fb_engine_id)e, FB_BENCH_SET_COLLIDERS, i, x->c, &k, &p)) break;
      for (int ri = 0; ri < COLLIDER_RINGS; ri++) {
        fb_status st = collider_run(x->rows, x->n, (fb_engine_id)e, eng, &k, &p, collider_rings[ri],
                                    diag);
        if (st != FB_OK) return st;
        pass_step(x);
      }
    }
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
    todo += t->walls[0][0] + t->walls[1][0] <= repeat_below;
  }
  int done = 0;
  for (int round = 1; round < FB_BENCH_ROUNDS; round++)
    for (int i = 0; i < timings.n; i++) {
      bench_timing *t = &timings.t[i];
      if (t->reps != round || t->walls[0][0] + t->walls[1][0] > repeat_below) continue;
      if (plan.on) {
        plan.cpu += t->plan_cpu;
        t->reps = round + 1;
        continue;
      }
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

fb_status fb_bench_estimate(double *cpu_s, double *pilot_s, const fb_case *c, int grids,
                            fb_diag *diag) {
  static fb_bench_row rows[FB_BENCH_MAX_ROWS];
  int n = 0;
  plan.on = 1;
  plan.cpu = plan.pilot = 0.0;
  timings.n = 0;
  fb_status st = bench_grids(rows, &n, c, grids, NULL, NULL, diag);
  if (st == FB_OK) st = retime(rows, 1.0, NULL, NULL, diag);
  free(timings.t);
  memset(&timings, 0, sizeof timings);
  plan.on = 0;
  *cpu_s = plan.cpu;
  if (pilot_s) *pilot_s = plan.pilot;
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
  bench_pass x = {rows, n, c, progress_all ? first_pass_progress : NULL, &fp, 0, 0};
  const int solvers = (grids & FB_BENCH_SOLVERS) != 0;
  const int frontier = !solvers && (grids & FB_BENCH_FRONTIER) != 0; /* solvers holds it */
  const int colliders = (grids & FB_BENCH_COLLIDERS) && c->clearance.mask == (1 << fb_case_mech(c)->reference_joint);
  const int dflt = (grids & FB_BENCH_DEFAULT) != 0;
  /* the configurations of the first pass, for its progress */
  if (dflt) x.total += all_points(FB_BENCH_SET_DEFAULT, c) + all_points(FB_BENCH_SET_DEFAULT_LAST, c);
  for (int e = 0; e < FB_ENGINE_COUNT; e++) {
    int alone;
    if (!runs_own((fb_engine_id)e, grids, c, &alone)) continue;
    const fb_engine_bench *b = bench_engine((fb_engine_id)e, c)->bench;
    x.total += set_points((fb_engine_id)e, FB_BENCH_SET_OWN, c);
    if (alone) x.total += all_points(b->alone_before, c) + all_points(b->alone_after, c);
  }
  if (solvers) x.total += all_points(FB_BENCH_SET_SOLVERS, c);
  if (frontier)
    x.total += all_points(FB_BENCH_SET_FRONTIER, c) + all_points(FB_BENCH_SET_FRONTIER_LAST, c);
  if (colliders) x.total += all_points(FB_BENCH_SET_COLLIDERS, c) * COLLIDER_RINGS;
  *n = 0;
  fb_status st = FB_OK;
  /* the default grid: every engine at its recommended settings, then the rows
   * that come last (ODE's tuned ideal rows) */
  if (dflt && (st = run_all(&x, FB_BENCH_SET_DEFAULT, diag)) == FB_OK)
    st = run_all(&x, FB_BENCH_SET_DEFAULT_LAST, diag);
  /* the engines' own grids (--grid simbody, bullet; Simbody's with solvers
   * and all), alone with the rows they want beside them */
  for (int e = 0; e < FB_ENGINE_COUNT && st == FB_OK; e++) {
    int alone;
    if (!runs_own((fb_engine_id)e, grids, c, &alone)) continue;
    const fb_engine_bench *b = bench_engine((fb_engine_id)e, c)->bench;
    if (alone) st = run_all(&x, b->alone_before, diag);
    if (st == FB_OK) st = run_set(&x, (fb_engine_id)e, FB_BENCH_SET_OWN, diag);
    if (st == FB_OK && alone) st = run_all(&x, b->alone_after, diag);
  }
  /* the solver grids: every engine's settings x steps (with ODE's tuned and
   * adaptive rows, MuJoCo's adaptive rows) */
  if (st == FB_OK && solvers) st = run_all(&x, FB_BENCH_SET_SOLVERS, diag);
  /* the frontier (--grid frontier): every engine's frontier, then its tuned
   * and adaptive rows (docs/step-size.md) */
  if (st == FB_OK && frontier && (st = run_all(&x, FB_BENCH_SET_FRONTIER, diag)) == FB_OK)
    st = run_all(&x, FB_BENCH_SET_FRONTIER_LAST, diag);
  if (st == FB_OK && colliders) st = run_colliders(&x, diag);
  return st;
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

int fb_bench_cheapest_of(const fb_bench_row *rows, int n, const fb_model *model, double target,
                         const unsigned char *eligible) {
  int best = -1;
  for (int i = 0; i < n; i++)
    if (rows[i].row == model && (!eligible || eligible[i]) && isfinite(rows[i].error) &&
        rows[i].error <= target && (best < 0 || rows[i].wall_per_rev < rows[best].wall_per_rev))
      best = i;
  return best;
}

int fb_bench_cheapest(const fb_bench_row *rows, int n, const fb_model *model, double target) {
  return fb_bench_cheapest_of(rows, n, model, target, NULL);
}
