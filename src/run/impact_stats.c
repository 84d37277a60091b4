#include "impact_stats.h"

#include "metrics.h"

#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static int grow(fb_impact_values *v) {
  if (v->n < v->cap) return 1;
  const size_t cap = v->cap ? 2 * v->cap : 64;
  double *f = realloc(v->force, cap * sizeof *f);
  if (!f) return 0;
  v->force = f;
  double *c = realloc(v->alpha_coupler, cap * sizeof *c);
  if (!c) return 0;
  v->alpha_coupler = c;
  double *w = realloc(v->alpha_follower, cap * sizeof *w);
  if (!w) return 0;
  v->alpha_follower = w;
  v->cap = cap;
  return 1;
}

fb_status fb_impact_values_add(fb_impact_values *v, const fb_series *s, int j, double t_from,
                               fb_diag *diag) {
  if (j < 0 || j > 3 || !(s->contact_mask & (1 << j)))
    return fb_diag_set(diag, FB_ERR_ARG, "no contact columns at joint %d for impact statistics", j);
  const double *f = s->contact[j][FB_C_FORCE];
  size_t i = 0, a, e;
  for (; fb_metrics_next_impact(s, j, i, &a, &e); i = e + 1) {
    if (s->t[a] < t_from) continue;
    double fm = 0.0, ac = 0.0, af = 0.0;
    for (size_t q = a; q <= e; q++) fm = fmax(fm, f[q]);
    /* the episode's samples and the one after it */
    for (size_t q = a; q <= e + 1 && q < s->n; q++) {
      ac = fmax(ac, fabs(s->coupler_alpha[q]));
      af = fmax(af, fabs(s->follower_alpha[q]));
    }
    if (!grow(v)) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for impact statistics");
    v->force[v->n] = fm;
    v->alpha_coupler[v->n] = ac;
    v->alpha_follower[v->n] = af;
    v->n++;
  }
  return FB_OK;
}

void fb_impact_values_free(fb_impact_values *v) {
  free(v->force);
  free(v->alpha_coupler);
  free(v->alpha_follower);
  memset(v, 0, sizeof *v);
}

static void dist_of(fb_dist *d, double *x, size_t n) {
  d->n = (int)n;
  if (n == 0) {
    d->mean = d->p50 = d->p90 = d->max = NAN;
    return;
  }
  gsl_sort(x, 1, n);
  d->mean = gsl_stats_mean(x, 1, n);
  d->p50 = gsl_stats_quantile_from_sorted_data(x, 1, n, 0.5);
  d->p90 = gsl_stats_quantile_from_sorted_data(x, 1, n, 0.9);
  d->max = x[n - 1];
}

fb_status fb_impact_stats_of(fb_impact_stats *out, const fb_impact_values *v, fb_diag *diag) {
  const size_t n = v->n;
  double *x = malloc((n ? n : 1) * sizeof *x);
  if (!x) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for impact statistics");
  const double *src[3] = {v->force, v->alpha_coupler, v->alpha_follower};
  fb_dist *dst[3] = {&out->force, &out->alpha_coupler, &out->alpha_follower};
  for (int q = 0; q < 3; q++) {
    if (n) memcpy(x, src[q], n * sizeof *x);
    dist_of(dst[q], x, n);
  }
  free(x);
  return FB_OK;
}
