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

/* one configuration: runs case k (its models: an ideal stack-up model, and
 * with clearance at B the clearance impact model and the reference) up to 3
 * times, and appends one row per engine model (the ideal one only when
 * with_ideal) */
static fb_status bench_point(fb_bench_row *rows, int *n, fb_case *k, const char *engine,
                             const char *stepper, int mapping, int with_ideal, fb_diag *diag) {
  const int with_clearance = k->model_count > 1;
  double walls[2][3], setups[2][3];
  int reps = 0;
  static fb_run r;
  for (int rep = 0; rep < 3; rep++) {
    fb_status st = fb_run_case(&r, k, NULL, NULL, diag);
    if (st != FB_OK) return st;
    /* steady-state cost: the engine's setup (MuJoCo compiles its model,
     * 5-45 ms here) is kept apart */
    for (int q = 0; q < 2; q++) {
      const fb_model_run *mr = &r.model[q].run;
      const int has = q == 0 || with_clearance;
      walls[q][rep] = has ? mr->wall_s - mr->setup_s : 0.0;
      setups[q][rep] = has ? mr->setup_s : 0.0;
    }
    reps++;
    const int last = rep == 2 || walls[0][rep] + walls[1][rep] > 1.0;
    if (!last) {
      fb_run_free(&r);
      continue;
    }
    for (int q = 0; q < (with_clearance ? 2 : 1); q++) {
      if (q == 0 && !with_ideal) continue;
      if (*n == FB_BENCH_MAX_ROWS) break;
      fb_bench_row *b = &rows[(*n)++];
      const fb_model_result *m = &r.model[q];
      memset(b, 0, sizeof *b);
      b->row = m->run.model;
      snprintf(b->model, sizeof b->model, "%s", m->run.name);
      snprintf(b->engine, sizeof b->engine, "%s", engine);
      snprintf(b->stepper, sizeof b->stepper, "%s", stepper);
      b->h = k->solver.h;
      b->mapping = q == 0 ? -1 : mapping;
      b->world_erp = mapping >= 0 ? k->solver.world_erp : NAN;
      b->world_cfm = mapping >= 0 ? k->solver.world_cfm : NAN;
      snprintf(b->status, sizeof b->status, "%s", m->run.status);
      b->error = NAN;
      if (strcmp(m->run.status, "ok") == 0) {
        if (q == 0 && m->has_error) b->error = omega_peak_error(&m->error);
        if (q == 1 && m->has_ref_error)
          b->error = fmax(fabs(m->ref_error.force_max_rel), fabs(m->ref_error.penetration_max_rel));
      }
      qsort(walls[q], (size_t)reps, sizeof(double), cmp_double);
      qsort(setups[q], (size_t)reps, sizeof(double), cmp_double);
      b->setup_s = setups[q][reps / 2];
      /* per revolution actually simulated: a run that stopped early covered
       * less; one that stopped within its first step has no cost per
       * revolution (NaN, printed "-") */
      const double simulated = (double)m->run.steps * m->run.h * k->crank_speed / (2.0 * M_PI);
      b->wall_per_rev = m->run.steps > 1 && simulated > 0.0 ? walls[q][reps / 2] / simulated : NAN;
      b->repeats = reps;
    }
    fb_run_free(&r);
    break;
  }
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
  k->solver.h = h;
  const fb_model *models[3];
  fb_bench_models(engine, &models[0], &models[1]);
  models[2] = fb_model_reference_of(models[1]);
  k->model_count = k->clearance.mask == (1 << FB_JOINT_B) ? 3 : 1;
  for (int q = 0; q < k->model_count; q++)
    snprintf(k->models[q], FB_NAME_SIZE, "%s", models[q]->name);
}

fb_status fb_bench_run(fb_bench_row *rows, int *n, const fb_case *c,
                       void (*progress)(double fraction, void *user), void *user, fb_diag *diag) {
  const double hs[4] = {1e-3, 1e-4, 1e-5, 1e-6};
  const int iters[4] = {0, 10, 20, 50}; /* 0: dWorldStep */
  const double erp[2] = {0.2, 0.8}, cfm[2] = {1e-10, 1e-8};
  const int mujoco = fb_engine_available(FB_ENGINE_MUJOCO);
  const int total = 4 * 4 * 2 * 2 + (mujoco ? 3 * FB_BENCH_MUJOCO_STEPS : 0);
  int done = 0;
  *n = 0;
  for (int si = 0; si < 4; si++)
    for (int hi = 0; hi < 4; hi++)
      for (int mi = 0; mi < 2; mi++)
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
  fb_bench_mark_pareto(rows, *n);
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
