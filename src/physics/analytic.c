#include "analytic.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_min.h>
#include <math.h>

/* the eight quantities whose extremes are sought, as signed selectors */
typedef struct {
  const fb_linkage *lk;
  fb_branch branch;
  double omega2;
  int which; /* 0..3 coupler omega, alpha; follower omega, alpha (x2 for sign) */
  double sign;
} peak_ctx;

static double quantity(const fb_linkage_state *s, int which) {
  switch (which) {
    case 0: return s->coupler_omega;
    case 1: return s->coupler_alpha;
    case 2: return s->follower_omega;
    default: return s->follower_alpha;
  }
}

/* objective for GSL: minimise sign * quantity (sign -1 finds a maximum) */
static double objective(double theta2, void *p) {
  const peak_ctx *c = p;
  fb_linkage_state s;
  if (fb_linkage_solve(&s, c->lk, c->branch, theta2, c->omega2, 0.0, NULL) != FB_OK)
    return GSL_POSINF;
  return c->sign * quantity(&s, c->which);
}

/* refines a bracketed minimum of the objective; returns the objective value
 * and its location in *at */
static double refine(peak_ctx *c, double lo, double mid, double hi, double fmid, double *at) {
  gsl_min_fminimizer *m = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
  *at = mid;
  if (!m) return fmid;
  gsl_function F = {objective, c};
  double best = fmid;
  *at = mid;
  if (gsl_min_fminimizer_set_with_values(m, &F, mid, fmid, lo, objective(lo, c), hi,
                                         objective(hi, c)) == GSL_SUCCESS) {
    for (int it = 0; it < 100; it++) {
      if (gsl_min_fminimizer_iterate(m) != GSL_SUCCESS) break;
      double a = gsl_min_fminimizer_x_lower(m), b = gsl_min_fminimizer_x_upper(m);
      if (gsl_min_test_interval(a, b, 1e-12, 0.0) == GSL_SUCCESS) break;
    }
    double f = gsl_min_fminimizer_f_minimum(m);
    if (f < best) {
      best = f;
      *at = gsl_min_fminimizer_x_minimum(m);
    }
  }
  gsl_min_fminimizer_free(m);
  return best;
}

fb_status fb_analytic_peaks(fb_peaks *out, const fb_linkage *lk, fb_branch branch,
                            double omega2, fb_diag *diag) {
  return fb_analytic_peaks_where(out, NULL, lk, branch, omega2, diag);
}

fb_status fb_analytic_peaks_where(fb_peaks *out, double where[8], const fb_linkage *lk,
                                  fb_branch branch, double omega2, fb_diag *diag) {
  double lo, hi;
  int full;
  fb_status st = fb_linkage_crank_range(lk, &lo, &hi, &full, diag);
  if (st != FB_OK) return st;
  if (!full)
    return fb_diag_set(diag, FB_ERR_ASSEMBLY,
                       "the crank cannot turn fully: the linkage assembles only for "
                       "crank angles with |theta2| in [%.4f, %.4f] deg",
                       lo * 180.0 / M_PI, hi * 180.0 / M_PI);
  /* bracket: best sample of each of the 8 extremes on a uniform grid */
  enum { N = FB_ANALYTIC_PEAK_SAMPLES };
  const double step = 2.0 * M_PI / N;
  double best_val[4][2];
  double best_th[4][2];
  for (int k = 0; k < N; k++) {
    fb_linkage_state s;
    double th = step * k;
    st = fb_linkage_solve(&s, lk, branch, th, omega2, 0.0, diag);
    if (st != FB_OK) return st;
    for (int w = 0; w < 4; w++) {
      double v = quantity(&s, w);
      if (k == 0 || v > best_val[w][0]) best_val[w][0] = v, best_th[w][0] = th;
      if (k == 0 || v < best_val[w][1]) best_val[w][1] = v, best_th[w][1] = th;
    }
  }
  /* refine each bracket [th - step, th + step] */
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  double res[4][2]; /* [which][0 = max, 1 = min] */
  for (int w = 0; w < 4; w++) {
    for (int m = 0; m < 2; m++) {
      double sign = m == 0 ? -1.0 : 1.0;
      peak_ctx c = {lk, branch, omega2, w, sign};
      double th = best_th[w][m];
      double at;
      res[w][m] = sign * refine(&c, th - step, th, th + step, sign * best_val[w][m], &at);
      if (where) where[(w / 2) * 4 + (w % 2) * 2 + m] = at;
    }
  }
  gsl_set_error_handler(old);
  out->coupler = (fb_body_peaks){res[0][0], res[0][1], res[1][0], res[1][1]};
  out->follower = (fb_body_peaks){res[2][0], res[2][1], res[3][0], res[3][1]};
  return FB_OK;
}

void fb_analytic_to_sample(fb_sample *x, double t, const fb_linkage_state *st) {
  x->t = t;
  x->crank_angle = st->crank_angle;
  x->coupler_angle = st->coupler_angle;
  x->coupler_omega = st->coupler_omega;
  x->coupler_alpha = st->coupler_alpha;
  x->follower_angle = st->follower_angle;
  x->follower_omega = st->follower_omega;
  x->follower_alpha = st->follower_alpha;
}

fb_status fb_analytic_sample(fb_series *out, const fb_linkage *lk, fb_branch branch,
                             double theta0, double omega2, double h, size_t n,
                             fb_diag *diag) {
  if (fb_series_init(out, n) != FB_OK)
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for %zu samples", n);
  for (size_t k = 0; k < n; k++) {
    double t = (double)k * h;
    fb_linkage_state s;
    fb_status st = fb_linkage_solve(&s, lk, branch, theta0 + omega2 * t, omega2, 0.0, diag);
    if (st != FB_OK) {
      fb_series_free(out);
      return st;
    }
    fb_sample x;
    fb_analytic_to_sample(&x, t, &s);
    x.crank_angle = theta0 + omega2 * t; /* unwrapped, as the ODE series */
    fb_series_push(out, &x);
  }
  return FB_OK;
}
