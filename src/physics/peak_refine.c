/* Refinement of a reference's sampled peaks (peak_refine.h). */
#include "peak_refine.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "series.h"

enum { N = 2 * FB_REFERENCE_REFINE, STRIDE = FB_REFERENCE_REFINE_STRIDE, STOPS = N / STRIDE };

/* the workspace of one interval's refinement */
typedef struct {
  const fb_peak_refine_ode *ode;
  double *stop_y, *stop_f; /* the stops' states and rates ((STOPS + 1) x dim) */
  double *y, *yi, *di;     /* a state, an interpolated state and its rates (dim each) */
} work;

static double *row(double *a, const work *w, int j) { return a + (size_t)j * w->ode->dim; }

/* The extremes (best, each quantity as a maximum) over (t_{k-1}, t_{k+1})
 * of a fresh integration of sample k - 1's state. Every STRIDE-th
 * evaluation point is a stop of the integration and exact; the points
 * between are ranked on the cubic Hermite interpolant of the stops' states
 * and rates, and each quantity's best of them, where it beats the stops,
 * is then integrated to and evaluated exactly: the extremes are those of
 * the exact evaluation at every point (the points' spacing, not the
 * interpolant, bounds their error). Returns 0 when the integration fails. */
static int refine_interval(double *best, work *w, size_t k) {
  const fb_peak_refine_ode *o = w->ode;
  const size_t dim = o->dim;
  const int nq = o->nquant;
  const double h = o->h;
  double *y = w->y;
  const double t0 = o->start(y, k - 1, o->ctx);
  double t = t0;
  gsl_odeiv2_system sys = {o->rhs, NULL, dim, o->ctx};
  gsl_odeiv2_driver *drv =
      gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, h * 1e-3, o->tol, o->tol);
  if (!drv) return 0;
  gsl_odeiv2_driver_set_nmax(drv, 0);
  double q[FB_PEAK_REFINE_MAX_QUANTITIES], at_stops[FB_PEAK_REFINE_MAX_QUANTITIES];
  double between[FB_PEAK_REFINE_MAX_QUANTITIES];
  int best_at[FB_PEAK_REFINE_MAX_QUANTITIES];
  for (int m = 0; m < nq; m++) at_stops[m] = between[m] = -INFINITY, best_at[m] = -1;
  memcpy(row(w->stop_y, w, 0), y, dim * sizeof *y);
  o->eval(q, row(w->stop_f, w, 0), t0, y, o->ctx);
  int ok = 1;
  for (int j = 1; j <= STOPS && ok; j++) {
    const double ta = t, tb = t0 + 2.0 * h * (j * STRIDE) / N, hh = tb - ta;
    ok = gsl_odeiv2_driver_apply(drv, &t, tb, y) == GSL_SUCCESS;
    const double *ya = row(w->stop_y, w, j - 1), *fa = row(w->stop_f, w, j - 1);
    double *fb = row(w->stop_f, w, j);
    memcpy(row(w->stop_y, w, j), y, dim * sizeof *y);
    o->eval(q, fb, tb, y, o->ctx);
    for (int m = 0; m < nq; m++) at_stops[m] = fmax(at_stops[m], q[m]);
    for (int i = 1; i < STRIDE; i++) {
      const double u = (double)i / STRIDE;
      const double h00 = (1 + 2 * u) * (1 - u) * (1 - u), h10 = u * (1 - u) * (1 - u);
      const double h01 = u * u * (3 - 2 * u), h11 = u * u * (u - 1);
      for (size_t c = 0; c < dim; c++)
        w->yi[c] = h00 * ya[c] + h10 * hh * fa[c] + h01 * y[c] + h11 * hh * fb[c];
      o->eval(q, w->di, ta + u * hh, w->yi, o->ctx);
      for (int m = 0; m < nq; m++)
        if (q[m] > between[m]) between[m] = q[m], best_at[m] = (j - 1) * STRIDE + i;
    }
  }
  /* each quantity's best point between the stops, exactly */
  memcpy(best, at_stops, (size_t)nq * sizeof *best);
  for (int m = 0; m < nq && ok; m++) {
    if (!(between[m] > at_stops[m])) continue;
    const int i = best_at[m], j = i / STRIDE;
    memcpy(y, row(w->stop_y, w, j), dim * sizeof *y);
    t = t0 + 2.0 * h * (j * STRIDE) / N;
    gsl_odeiv2_driver_reset(drv);
    ok = gsl_odeiv2_driver_apply(drv, &t, t0 + 2.0 * h * i / N, y) == GSL_SUCCESS;
    o->eval(q, w->di, t, y, o->ctx);
    for (int p = m; p < nq; p++) /* the others found here too, once */
      if (best_at[p] == i && between[p] > at_stops[p]) {
        best[p] = fmax(best[p], q[p]);
        between[p] = -INFINITY;
      }
  }
  gsl_odeiv2_driver_free(drv);
  return ok;
}

int fb_peak_refine(fb_peak_refine_column *cols, int ncols, const double *t, size_t n,
                   double t_split, const fb_peak_refine_ode *ode) {
  if (n < 3 || ncols < 1) return 1;
  const size_t dim = ode->dim;
  double *big = malloc(2 * (size_t)ncols * sizeof *big);
  double *ws = malloc((2 * (STOPS + 1) + 3) * dim * sizeof *ws);
  unsigned char *spike = malloc(2 * (size_t)ncols);
  if (!big || !ws || !spike || ode->nquant > FB_PEAK_REFINE_MAX_QUANTITIES) {
    free(big), free(ws), free(spike);
    return 0;
  }
  work w = {ode, ws, ws + (STOPS + 1) * dim, ws + 2 * (STOPS + 1) * dim, NULL, NULL};
  w.yi = w.y + dim;
  w.di = w.yi + dim;
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  /* each spike against the largest of its own part of the run, the
   * start-up or the peak window (series.h fb_largest_abs_split) */
  size_t split = n;
  for (int c = 0; c < ncols; c++) fb_largest_abs_split(big + 2 * c, &split, t, n, cols[c].v, t_split);
  double best[FB_PEAK_REFINE_MAX_QUANTITIES];
  for (size_t k = ode->window ? (split > 1 ? split : 1) : 1; k + 1 < n; k++) {
    const int part = k >= split;
    int any = 0;
    for (int c = 0; c < ncols; c++) {
      const double b = big[2 * c + part];
      spike[2 * c] = cols[c].qmax >= 0 &&
                     fb_series_is_spike(cols[c].v, k, 1, FB_REFERENCE_REFINE_FRACTION, b);
      spike[2 * c + 1] = cols[c].qmin >= 0 &&
                         fb_series_is_spike(cols[c].v, k, -1, FB_REFERENCE_REFINE_FRACTION, b);
      any |= spike[2 * c] | spike[2 * c + 1];
    }
    if (!any || !refine_interval(best, &w, k)) continue;
    for (int c = 0; c < ncols; c++) {
      double *v = cols[c].v;
      if (spike[2 * c]) v[k] = fmax(v[k], best[cols[c].qmax]);
      if (spike[2 * c + 1]) v[k] = fmin(v[k], -best[cols[c].qmin]);
    }
  }
  gsl_set_error_handler(old);
  free(big), free(ws), free(spike);
  return 1;
}
