#include "equivalence.h"

#include <gsl/gsl_cdf.h>
#include <math.h>
#include <string.h>

/* mean and sample standard deviation of the finite values of v */
static void mean_sd(const double *v, int n, double *mean, double *sd, int *used, int *skipped) {
  double s = 0.0;
  int k = 0;
  for (int i = 0; i < n; i++)
    if (isfinite(v[i])) s += v[i], k++;
  *used = k;
  *skipped = n - k;
  *mean = k ? s / k : NAN;
  double q = 0.0;
  for (int i = 0; i < n; i++)
    if (isfinite(v[i])) q += (v[i] - *mean) * (v[i] - *mean);
  *sd = k > 1 ? sqrt(q / (k - 1)) : NAN;
}

/* Welch-Satterthwaite degrees of freedom of a + b, a and b the squared
 * standard errors of two means from na and nb values (equivalence.h) */
static double welch_df(double a, double b, int na, int nb) {
  if (a == 0.0 && b == 0.0) return INFINITY;
  const double den = a * a / (na - 1) + b * b / (nb - 1);
  return (a + b) * (a + b) / den;
}

/* Student's t distribution's lower tail at t on df degrees of freedom, with
 * the limits of an exact (spread-free) comparison */
static double t_lower(double t, double df) {
  if (t == INFINITY) return 1.0;
  if (t == -INFINITY) return 0.0;
  return isinf(df) ? gsl_cdf_ugaussian_P(t) : gsl_cdf_tdist_P(t, df);
}

/* the statistic D = xbar - theta ybar over its standard error, and its
 * degrees of freedom */
static double t_at(const fb_equiv *e, double theta, double *df) {
  const double a = e->sd_x * e->sd_x / e->nx, b = theta * theta * e->sd_y * e->sd_y / e->ny;
  const double d = e->mean_x - theta * e->mean_y, v = a + b;
  *df = welch_df(a, b, e->nx, e->ny);
  if (v == 0.0) return d > 0.0 ? INFINITY : d < 0.0 ? -INFINITY : 0.0;
  return d / sqrt(v);
}

/* Fieller's (1 - 2 alpha) interval of mean_x / mean_y */
static void fieller(fb_equiv *e, double alpha) {
  const double a = e->sd_x * e->sd_x / e->nx, b = e->sd_y * e->sd_y / e->ny;
  e->df = welch_df(a, b * e->ratio * e->ratio, e->nx, e->ny);
  if (a == 0.0 && b == 0.0) {
    e->lo = e->hi = e->ratio;
    return;
  }
  const double t = isinf(e->df) ? gsl_cdf_ugaussian_Pinv(1.0 - alpha)
                                 : gsl_cdf_tdist_Pinv(1.0 - alpha, e->df);
  const double x = e->mean_x, y = e->mean_y;
  const double lead = y * y - t * t * b;
  if (!(lead > 0.0)) { /* the reference's mean not clear of zero: unbounded */
    e->lo = -INFINITY;
    e->hi = INFINITY;
    return;
  }
  const double root = t * sqrt(fmax(0.0, a * y * y + b * x * x - t * t * a * b));
  e->lo = (x * y - root) / lead;
  e->hi = (x * y + root) / lead;
}

void fb_equiv_ratio(fb_equiv *out, const double *x, int nx, const double *y, int ny,
                    double theta, double alpha) {
  memset(out, 0, sizeof *out);
  fb_equiv *e = out;
  e->margin = theta;
  mean_sd(x, nx, &e->mean_x, &e->sd_x, &e->nx, &e->skipped_x);
  mean_sd(y, ny, &e->mean_y, &e->sd_y, &e->ny, &e->skipped_y);
  e->ratio = e->lo = e->hi = e->df = NAN;
  e->p_equivalent = e->p_different = NAN;
  e->decision = FB_EQUIV_UNDEFINED;
  if (e->nx < 2 || e->ny < 2 || !(e->mean_y >= 0.0) || !(e->mean_x >= 0.0)) return;
  if (e->mean_y == 0.0) { /* nothing on the reference's side */
    const int none = e->mean_x == 0.0;
    e->ratio = none ? NAN : INFINITY;
    e->p_equivalent = none ? 0.0 : 1.0;
    e->p_different = none ? 1.0 : 0.0;
    e->decision = none ? FB_EQUIV_EQUIVALENT : FB_EQUIV_DIFFERENT;
    return;
  }
  e->ratio = e->mean_x / e->mean_y;
  const double lo = 1.0 / theta, hi = theta;
  double df_lo, df_hi;
  const double t_lo = t_at(e, lo, &df_lo), t_hi = t_at(e, hi, &df_hi);
  /* inside: above the lower margin and below the upper one */
  const double p_l = 1.0 - t_lower(t_lo, df_lo), p_u = t_lower(t_hi, df_hi);
  e->p_equivalent = fmax(p_l, p_u);
  /* outside: below the lower margin, or above the upper one, each at alpha / 2 */
  const double p_below = t_lower(t_lo, df_lo), p_above = 1.0 - t_lower(t_hi, df_hi);
  e->p_different = fmin(1.0, 2.0 * fmin(p_below, p_above));
  fieller(e, alpha);
  e->decision = e->p_equivalent <= alpha  ? FB_EQUIV_EQUIVALENT
                : e->p_different <= alpha ? FB_EQUIV_DIFFERENT
                                          : FB_EQUIV_UNDECIDED;
}

int fb_holm(const double *p, int m, double alpha, int *reject) {
  int order[64];
  int n = 0;
  for (int i = 0; i < m && i < 64; i++) {
    reject[i] = 0;
    if (isfinite(p[i])) order[n++] = i;
  }
  /* insertion sort by p (m is a handful of statistics) */
  for (int i = 1; i < n; i++)
    for (int k = i; k > 0 && p[order[k]] < p[order[k - 1]]; k--) {
      const int t = order[k];
      order[k] = order[k - 1];
      order[k - 1] = t;
    }
  int rejected = 0;
  for (int k = 0; k < n; k++) {
    if (!(p[order[k]] <= alpha / (double)(m - k))) break;
    reject[order[k]] = 1;
    rejected++;
  }
  return rejected;
}
