/* A run's cost from two short runs of its case (pilot.h). */
#include "pilot.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "clock.h"
#include "planar_run.h"
#include "run.h"

/* one pilot over d [s]: the CPU and wall time of the whole run, each
 * model's wall time (set-up excluded) and set-up */
typedef struct {
  double cpu, wall;
  int n;
  double model[FB_MAX_MODELS], setup[FB_MAX_MODELS];
} one_pilot;

static fb_status run_for(one_pilot *o, const fb_case *c, double d, fb_diag *diag) {
  fb_case *k = malloc(sizeof *k);
  if (!k) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  *k = *c;
  k->duration_s = d;
  k->peaks = FB_PEAKS_ALL; /* a window from t = 0: a pilot is shorter than a revolution */
  memset(o, 0, sizeof *o);
  const double c0 = fb_clock_cpu_s(), w0 = fb_clock_s();
  fb_status st;
  if (c->planar.on) {
    static fb_planar_run r;
    st = fb_planar_run_case(&r, k, diag);
    if (st == FB_OK) {
      o->n = r.n;
      for (int q = 0; q < r.n; q++) {
        o->model[q] = r.model[q].wall_s - r.model[q].setup_s;
        o->setup[q] = r.model[q].setup_s;
      }
      fb_planar_run_free(&r);
    }
  } else {
    static fb_run r;
    st = fb_run_case(&r, k, NULL, NULL, diag);
    if (st == FB_OK) {
      o->n = r.n;
      for (int q = 0; q < r.n; q++) {
        o->model[q] = r.model[q].run.wall_s - r.model[q].run.setup_s;
        o->setup[q] = r.model[q].run.setup_s;
      }
      fb_run_free(&r);
    }
  }
  o->cpu = fb_clock_cpu_s() - c0;
  o->wall = fb_clock_s() - w0;
  free(k);
  return st;
}

/* a cost at duration D from its values a at d1 and b at d2 > d1: the line
 * through them, its slope no less than 0 (a fixed cost read twice) */
static double at(double a, double b, double d1, double d2, double D) {
  if (!(b > a)) return fmax(a, b);
  return a + (b - a) / (d2 - d1) * (D - d1);
}

fb_status fb_pilot_case(fb_pilot *p, const fb_case *c, fb_diag *diag) {
  memset(p, 0, sizeof *p);
  const double D = fb_case_duration(c);
  const double h = c->planar.on ? fb_planar_run_step(c)
                   : c->solver.h_mode == FB_STEP_ADAPTIVE ? c->solver.h_min
                                                          : c->solver.h;
  double d1 = fmax(D * FB_PILOT_FRACTION, FB_PILOT_STEPS * h);
  if (!(2.0 * d1 < D)) d1 = 0.5 * D; /* short: the second pilot is the run itself */
  const double d2 = fmin(2.0 * d1, D);
  one_pilot a, b;
  /* the process's first run pays what is set up once (libraries, tables):
   * a run at d1 before the first pilot takes it, never the slope */
  static int warm;
  fb_status st = warm ? FB_OK : run_for(&a, c, d1, diag);
  warm = 1;
  if (st == FB_OK) st = run_for(&a, c, d1, diag);
  if (st == FB_OK) st = run_for(&b, c, d2, diag);
  if (st != FB_OK) return st;
  p->cpu_s = at(a.cpu, b.cpu, d1, d2, D);
  p->wall_s = at(a.wall, b.wall, d1, d2, D);
  p->n = a.n < b.n ? a.n : b.n;
  for (int q = 0; q < p->n; q++) {
    p->model_s[q] = at(a.model[q], b.model[q], d1, d2, D);
    p->setup_s[q] = fmax(a.setup[q], b.setup[q]);
  }
  p->pilot_cpu_s = a.cpu + b.cpu;
  return FB_OK;
}
