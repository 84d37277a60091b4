#include "bench.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "run.h"

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double omega_peak_error(const fb_error *e) {
  return fmax(fmax(fabs(e->coupler.omega_max_rel), fabs(e->coupler.omega_min_rel)),
              fmax(fabs(e->follower.omega_max_rel), fabs(e->follower.omega_min_rel)));
}

fb_status fb_bench_run(fb_bench_row *rows, int *n, const fb_case *c,
                       void (*progress)(double fraction, void *user), void *user, fb_diag *diag) {
  const double hs[4] = {1e-3, 1e-4, 1e-5, 1e-6};
  const int iters[4] = {0, 10, 20, 50}; /* 0: dWorldStep */
  const double erp[2] = {0.2, 0.8}, cfm[2] = {1e-10, 1e-8};
  const int total = 4 * 4 * 2 * 2;
  int done = 0;
  *n = 0;
  for (int si = 0; si < 4; si++)
    for (int hi = 0; hi < 4; hi++)
      for (int mi = 0; mi < 2; mi++)
        for (int ei = 0; ei < 2; ei++) {
          fb_case k = *c;
          k.revolutions = 2;
          k.solver.h = hs[hi];
          k.solver.stepper = iters[si] ? FB_STEPPER_QUICK : FB_STEPPER_WORLD;
          k.solver.quick_iterations = iters[si] ? iters[si] : 20;
          k.solver.world_erp = erp[ei];
          k.solver.world_cfm = cfm[ei];
          k.clearance.mapping = mi;
          const char *models[3] = {"ode-ideal-stackup", "ode-clearance-impact", "reference"};
          const int with_clearance = k.clearance.mask == (1 << FB_JOINT_B);
          k.model_count = with_clearance ? 3 : 1;
          for (int q = 0; q < k.model_count; q++) snprintf(k.models[q], FB_NAME_SIZE, "%s", models[q]);
          double walls[2][3];
          int reps = 0;
          static fb_run r;
          for (int rep = 0; rep < 3; rep++) {
            fb_status st = fb_run_case(&r, &k, NULL, NULL, diag);
            if (st != FB_OK) return st;
            walls[0][rep] = r.model[0].run.wall_s;
            walls[1][rep] = with_clearance ? r.model[1].run.wall_s : 0.0;
            reps++;
            const int last = rep == 2 || r.model[0].run.wall_s + walls[1][rep] > 1.0;
            if (!last) {
              fb_run_free(&r);
              continue;
            }
            for (int q = 0; q < (with_clearance ? 2 : 1); q++) {
              /* the mapping does not touch the ideal model: one row for it */
              if (q == 0 && mi == 1) continue;
              if (*n == FB_BENCH_MAX_ROWS) break;
              fb_bench_row *b = &rows[(*n)++];
              const fb_model_result *m = &r.model[q];
              memset(b, 0, sizeof *b);
              snprintf(b->model, sizeof b->model, "%s", m->run.name);
              if (iters[si]) snprintf(b->stepper, sizeof b->stepper, "quick-%d", iters[si]);
              else snprintf(b->stepper, sizeof b->stepper, "world");
              b->h = hs[hi];
              b->mapping = mi;
              b->world_erp = erp[ei];
              b->world_cfm = cfm[ei];
              snprintf(b->status, sizeof b->status, "%s", m->run.status);
              b->error = NAN;
              if (strcmp(m->run.status, "ok") == 0) {
                if (q == 0 && m->has_error) b->error = omega_peak_error(&m->error);
                if (q == 1 && m->has_ref_error)
                  b->error = fmax(fabs(m->ref_error.force_max_rel), fabs(m->ref_error.penetration_max_rel));
              }
              qsort(walls[q], (size_t)reps, sizeof(double), cmp_double);
              /* per revolution actually simulated: a run that stopped early
               * covered less; one that stopped within its first step has
               * no cost per revolution (NaN, printed "-") */
              const double simulated = (double)m->run.steps * m->run.h * k.crank_speed / (2.0 * M_PI);
              b->wall_per_rev = m->run.steps > 1 && simulated > 0.0 ? walls[q][reps / 2] / simulated : NAN;
              b->repeats = reps;
            }
            fb_run_free(&r);
            break;
          }
          if (progress) progress((double)++done / total, user);
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
      if (j == i || strcmp(a->model, b->model) != 0 || !isfinite(b->error)) continue;
      if (b->error <= a->error && b->wall_per_rev <= a->wall_per_rev &&
          (b->error < a->error || b->wall_per_rev < a->wall_per_rev))
        a->pareto = 0;
    }
  }
}

int fb_bench_cheapest(const fb_bench_row *rows, int n, const char *model, double target) {
  int best = -1;
  for (int i = 0; i < n; i++)
    if (strcmp(rows[i].model, model) == 0 && isfinite(rows[i].error) && rows[i].error <= target &&
        (best < 0 || rows[i].wall_per_rev < rows[best].wall_per_rev))
      best = i;
  return best;
}
