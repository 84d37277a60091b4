#include "impact_stats.h"

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
  const double *st = s->contact[j][FB_C_STATE], *f = s->contact[j][FB_C_FORCE];
  int open = 0; /* 1 inside an impact that counts */
  for (size_t i = 0; i < s->n; i++) {
    const int in = (int)st[i] == FB_STATE_IMPACT && f[i] > 0.0;
    const int onset = in && (i == 0 || (int)st[i - 1] != FB_STATE_IMPACT || !(f[i - 1] > 0.0));
    if (onset) {
      open = s->t[i] >= t_from;
      if (open) {
        if (!grow(v)) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for impact statistics");
        v->force[v->n] = v->alpha_coupler[v->n] = v->alpha_follower[v->n] = 0.0;
        v->n++;
      }
    }
    if (!open) continue;
    const size_t k = v->n - 1;
    if (in) v->force[k] = fmax(v->force[k], f[i]);
    /* the episode's samples and the one after it */
    if (in || (i > 0 && (int)st[i - 1] == FB_STATE_IMPACT && f[i - 1] > 0.0)) {
      v->alpha_coupler[k] = fmax(v->alpha_coupler[k], fabs(s->coupler_alpha[i]));
      v->alpha_follower[k] = fmax(v->alpha_follower[k], fabs(s->follower_alpha[i]));
    }
    if (!in) open = 0;
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
