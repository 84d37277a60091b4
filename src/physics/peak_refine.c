/* Refinement of a reference's sampled peaks (peak_refine.h). */
#include "peak_refine.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_min.h>
#include <gsl/gsl_odeiv2.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "series.h"

enum { N = 2 * FB_REFERENCE_REFINE, STRIDE = FB_REFERENCE_REFINE_STRIDE, STOPS = N / STRIDE };
/* the search's exact states an interval keeps, each a start for a later
 * evaluation beyond it (the oldest replaced) */
enum { KEPT = 2 * FB_PEAK_REFINE_SEARCH };

/* the workspace of one interval's refinement */
typedef struct {
  const fb_peak_refine_ode *ode;
  double *stop_y, *stop_f; /* the stops' states and rates ((STOPS + 1) x dim) */
  double *y, *yi, *di;     /* a state, an interpolated state and its rates (dim each) */
  gsl_min_fminimizer *min; /* Brent's method */
  double *kept_y;          /* the search's exact states (KEPT x dim) */
  double kept_t[KEPT];     /* their times [s] */
  int nkept, next;         /* states kept; the slot the next one takes */
} work;

static double *row(double *a, const work *w, int j) { return a + (size_t)j * w->ode->dim; }

/* the exact value of every quantity at time tt of the interval starting at
 * t0 (q: nquant): integrated from the latest exact state at or before it, a
 * stop or an earlier evaluation of the interval's search (Brent's points
 * close in on the extreme: each then one short rk8pd step from the last,
 * not several from a stop), the first step tried the whole way; the state
 * reached is kept for the evaluations after it */
static int exact_at(double *q, work *w, gsl_odeiv2_driver *drv, double t0, double tt) {
  const fb_peak_refine_ode *o = w->ode;
  const size_t dim = o->dim;
  const double dt = 2.0 * o->h * STRIDE / N;
  int j = (int)floor((tt - t0) / dt);
  j = j < 0 ? 0 : j >= STOPS ? STOPS - 1 : j;
  double t = t0 + dt * j;
  const double *from = row(w->stop_y, w, j);
  for (int e = 0; e < w->nkept; e++)
    if (w->kept_t[e] > t && w->kept_t[e] <= tt) t = w->kept_t[e], from = w->kept_y + e * dim;
  memcpy(w->y, from, dim * sizeof *w->y);
  if (tt > t) {
    gsl_odeiv2_driver_reset_hstart(drv, tt - t);
    if (gsl_odeiv2_driver_apply(drv, &t, tt, w->y) != GSL_SUCCESS) return 0;
    memcpy(w->kept_y + w->next * dim, w->y, dim * sizeof *w->y);
    w->kept_t[w->next] = tt;
    w->next = (w->next + 1) % KEPT;
    if (w->nkept < KEPT) w->nkept++;
  }
  o->eval(q, w->di, tt, w->y, o->ctx);
  return 1;
}

/* Brent's view of one quantity: its negated exact value at a time */
typedef struct {
  work *w;
  gsl_odeiv2_driver *drv;
  double t0;   /* the interval's start [s] */
  int m;       /* the quantity */
  double *q;   /* scratch (nquant) */
  int ok;      /* 0 once an integration failed */
  double *best; /* the quantity's best exact value so far, raised by each evaluation */
} search;

static double negated(double tt, void *p) {
  search *s = p;
  if (!s->ok || !(s->ok = exact_at(s->q, s->w, s->drv, s->t0, tt))) return HUGE_VAL;
  *s->best = fmax(*s->best, s->q[s->m]);
  return -s->q[s->m];
}

/* The extremes (best, each quantity as a maximum) over (t_{k-1}, t_{k+1})
 * of a fresh integration of sample k - 1's state: of the quantities with
 * want[m] set, the extreme itself (below); of the others, the largest at
 * the stops. Every STRIDE-th evaluation point is a stop of the integration
 * and exact; the points between are ranked on the cubic Hermite
 * interpolant of the stops' states and rates. A wanted quantity's extreme
 * is then searched on the exact integration (FB_PEAK_REFINE_SEARCH),
 * not taken at the grid's nearest point: a contact's force peaks where its
 * damper saturates, within a fraction of a grid spacing (the Watt
 * six-bar's second impact: 75.02 N, 2.5e-3 above the grid's best point).
 * Every value kept is an exact evaluation, so the search only ever raises
 * the stops' result. Returns 0 when the integration fails. */
static int refine_interval(double *best, const unsigned char *want, work *w, size_t k) {
  const fb_peak_refine_ode *o = w->ode;
  const size_t dim = o->dim;
  const int nq = o->nquant;
  const double h = o->h, dx = 2.0 * h / N; /* the grid's spacing [s] */
  double *y = w->y;
  const double t0 = o->start(y, k - 1, o->ctx);
  double t = t0;
  w->nkept = w->next = 0; /* the search's states are this interval's */
  gsl_odeiv2_system sys = {o->rhs, NULL, dim, o->ctx};
  /* the first step tried is the way to the first stop (the control shrinks
   * it where the tolerance asks): from 1e-3 h, GSL's standard control
   * (at most fivefold a step) took about four steps to grow to a stop's
   * spacing, in every interval */
  gsl_odeiv2_driver *drv =
      gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, dx * STRIDE, o->tol, o->tol);
  if (!drv) return 0;
  gsl_odeiv2_driver_set_nmax(drv, 0);
  double q[FB_PEAK_REFINE_MAX_QUANTITIES], between[FB_PEAK_REFINE_MAX_QUANTITIES];
  double stop_q[(STOPS + 1) * FB_PEAK_REFINE_MAX_QUANTITIES]; /* each stop's quantities */
  int best_at[FB_PEAK_REFINE_MAX_QUANTITIES];
  for (int m = 0; m < nq; m++) between[m] = -INFINITY, best_at[m] = -1;
  memcpy(row(w->stop_y, w, 0), y, dim * sizeof *y);
  o->eval(stop_q, row(w->stop_f, w, 0), t0, y, o->ctx);
  for (int m = 0; m < nq; m++) best[m] = stop_q[m];
  int ok = 1;
  for (int j = 1; j <= STOPS && ok; j++) {
    const double ta = t, tb = t0 + dx * (j * STRIDE), hh = tb - ta;
    ok = gsl_odeiv2_driver_apply(drv, &t, tb, y) == GSL_SUCCESS;
    const double *ya = row(w->stop_y, w, j - 1), *fa = row(w->stop_f, w, j - 1);
    double *fb = row(w->stop_f, w, j);
    memcpy(row(w->stop_y, w, j), y, dim * sizeof *y);
    /* the stop's quantities and rates fb, which the interpolant reads */
    o->eval(stop_q + j * nq, fb, tb, y, o->ctx);
    for (int m = 0; m < nq; m++) best[m] = fmax(best[m], stop_q[j * nq + m]);
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
  /* each wanted quantity's extreme, exactly: Brent's method (GSL) between
   * the stops beside its best stop, where that is a strict local maximum
   * of the stops (the interpolant ranks the points between but cannot
   * place a sharp peak: a penetration is |e| - c, the difference of two
   * lengths a hundred times larger, and its interpolant's best point lay 4
   * points off the six-bar's first impact's); else the interpolant's best
   * point, exactly, where it beats the stops */
  for (int m = 0; m < nq && ok; m++) {
    if (!want[m]) continue;
    int j = 1;
    for (int i = 2; i < STOPS; i++)
      if (stop_q[i * nq + m] > stop_q[j * nq + m]) j = i;
    const double top = stop_q[j * nq + m], fa = stop_q[(j - 1) * nq + m],
                 fb = stop_q[(j + 1) * nq + m], ds = dx * STRIDE;
    search s = {w, drv, t0, m, q, 1, best + m};
    gsl_function f = {negated, &s};
    if (top > fa && top > fb &&
        gsl_min_fminimizer_set_with_values(w->min, &f, t0 + ds * j, -top, t0 + ds * (j - 1), -fa,
                                           t0 + ds * (j + 1), -fb) == GSL_SUCCESS) {
      for (int it = 0; it < FB_PEAK_REFINE_SEARCH && s.ok; it++)
        if (gsl_min_fminimizer_iterate(w->min) != GSL_SUCCESS ||
            gsl_min_test_interval(gsl_min_fminimizer_x_lower(w->min),
                                  gsl_min_fminimizer_x_upper(w->min),
                                  dx * FB_PEAK_REFINE_SEARCH_TOL, 0.0) == GSL_SUCCESS)
          break;
    } else if (between[m] > best[m])
      negated(t0 + dx * best_at[m], &s);
    ok = s.ok;
  }
  gsl_odeiv2_driver_free(drv);
  return ok;
}

int fb_peak_refine(fb_peak_refine_column *cols, int ncols, const double *t, size_t n,
                   double t_split, const fb_peak_refine_ode *ode) {
  if (n < 3 || ncols < 1) return 1;
  const size_t dim = ode->dim;
  double *big = malloc(2 * (size_t)ncols * sizeof *big);
  double *ws = malloc((2 * (STOPS + 1) + 3 + KEPT) * dim * sizeof *ws);
  unsigned char *spike = malloc(2 * (size_t)ncols);
  gsl_min_fminimizer *min = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
  if (!big || !ws || !spike || !min || ode->nquant > FB_PEAK_REFINE_MAX_QUANTITIES) {
    free(big), free(ws), free(spike);
    if (min) gsl_min_fminimizer_free(min);
    return 0;
  }
  work w = {ode, ws, ws + (STOPS + 1) * dim, ws + 2 * (STOPS + 1) * dim, NULL, NULL, min,
            NULL, {0}, 0, 0};
  w.yi = w.y + dim;
  w.di = w.yi + dim;
  w.kept_y = w.di + dim;
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
      const double fraction = cols[c].every ? 0.0 : FB_REFERENCE_REFINE_FRACTION;
      spike[2 * c] = cols[c].qmax >= 0 && fb_series_is_spike(cols[c].v, k, 1, fraction, b);
      spike[2 * c + 1] = cols[c].qmin >= 0 && fb_series_is_spike(cols[c].v, k, -1, fraction, b);
      any |= spike[2 * c] | spike[2 * c + 1];
    }
    unsigned char want[FB_PEAK_REFINE_MAX_QUANTITIES] = {0};
    for (int c = 0; c < ncols; c++) {
      if (spike[2 * c]) want[cols[c].qmax] = 1;
      if (spike[2 * c + 1]) want[cols[c].qmin] = 1;
    }
    if (!any || !refine_interval(best, want, &w, k)) continue;
    for (int c = 0; c < ncols; c++) {
      double *v = cols[c].v;
      if (spike[2 * c]) v[k] = fmax(v[k], best[cols[c].qmax]);
      if (spike[2 * c + 1]) v[k] = fmin(v[k], -best[cols[c].qmin]);
    }
  }
  gsl_set_error_handler(old);
  free(big), free(ws), free(spike);
  gsl_min_fminimizer_free(min);
  return 1;
}
