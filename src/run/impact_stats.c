#include "impact_stats.h"

#include "metrics.h"

#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

/* the output bodies' values: the array and the four-bar's names share storage */
_Static_assert(offsetof(fb_impact_stats, alpha_follower) ==
                   offsetof(fb_impact_stats, alpha) + (FB_MECH_MAX_OUTPUTS - 1) * sizeof(fb_dist),
               "fb_impact_stats: the four-bar's names alias alpha[]");
_Static_assert(offsetof(fb_impact_values, alpha_follower) ==
                   offsetof(fb_impact_values, alpha) + (FB_MECH_MAX_OUTPUTS - 1) * sizeof(double *),
               "fb_impact_values: the four-bar's names alias alpha[]");

/* room for one more impact in every column of v; 0: out of memory (v unchanged but for the
 * columns already grown, each still holding v->n values) */
static int grow(fb_impact_values *v) {
  if (v->n < v->cap) return 1;
  const size_t cap = v->cap ? 2 * v->cap : 64;
  double *f = realloc(v->force, cap * sizeof *f);
  if (!f) return 0;
  v->force = f;
  for (int k = 0; k < FB_MECH_MAX_OUTPUTS; k++) {
    double *a = realloc(v->alpha[k], cap * sizeof *a);
    if (!a) return 0;
    v->alpha[k] = a;
  }
  v->cap = cap;
  return 1;
}

fb_status fb_impact_values_push(fb_impact_values *v, double force,
                                const double alpha[FB_MECH_MAX_OUTPUTS], fb_diag *diag) {
  if (!grow(v)) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for impact statistics");
  v->force[v->n] = force;
  for (int k = 0; k < FB_MECH_MAX_OUTPUTS; k++) v->alpha[k][v->n] = alpha[k];
  v->n++;
  return FB_OK;
}

fb_status fb_impact_values_add(fb_impact_values *v, const fb_series *s, int j, double t_from,
                               fb_diag *diag) {
  if (j < 0 || j >= FB_MECH_MAX_JOINTS || !(s->contact_mask & (1 << j)))
    return fb_diag_set(diag, FB_ERR_ARG, "no contact columns at joint %d for impact statistics", j);
  const double *f = s->contact[j][FB_C_FORCE];
  const int outputs = fb_series_output_count(s);
  size_t i = 0, a, e;
  for (; fb_metrics_next_impact(s, j, i, &a, &e); i = e + 1) {
    if (s->t[a] < t_from) continue;
    double fm = 0.0, am[FB_MECH_MAX_OUTPUTS] = {0.0};
    for (size_t q = a; q <= e; q++) fm = fmax(fm, f[q]);
    /* each output body's largest over the episode's samples and the one after it */
    for (int k = 0; k < outputs; k++)
      for (size_t q = a; q <= e + 1 && q < s->n; q++)
        am[k] = fmax(am[k], fabs(s->body[k][FB_Q_ACC][q]));
    const fb_status st = fb_impact_values_push(v, fm, am, diag);
    if (st != FB_OK) return st;
  }
  return FB_OK;
}

void fb_impact_values_free(fb_impact_values *v) {
  free(v->force);
  for (int k = 0; k < FB_MECH_MAX_OUTPUTS; k++) free(v->alpha[k]);
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
  /* the force, then each output body's alpha */
  for (int q = 0; q <= FB_MECH_MAX_OUTPUTS; q++) {
    if (n) memcpy(x, q ? v->alpha[q - 1] : v->force, n * sizeof *x);
    dist_of(q ? &out->alpha[q - 1] : &out->force, x, n);
  }
  free(x);
  return FB_OK;
}
