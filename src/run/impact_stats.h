/* Statistics of a run's impacts: the distribution of the per-impact peak
 * contact force and of each output body's |alpha| spike (the four-bar's
 * coupler and follower) each impact raises, for comparing two impact
 * sequences that are equally valid but different (a chaotic sequence: the
 * model and its reference part after a few impacts, metrics.h
 * fb_divergence) by their distributions rather than peak by peak. */
#ifndef FB_IMPACT_STATS_H
#define FB_IMPACT_STATS_H

#include "series.h"
#include "status.h"

/* Distribution of one per-impact quantity (unit of the quantity). */
typedef struct {
  int n;        /* impacts [-] */
  double mean;  /* arithmetic mean */
  double p50;   /* median (GSL's quantile of the sorted values, linear interpolation) */
  double p90;   /* 90th percentile, same */
  double max;   /* largest */
} fb_dist;

/* The statistics of one run's impacts in its window. */
typedef struct {
  fb_dist force; /* peak contact force of each impact [N] */
  union {
    fb_dist alpha[FB_MECH_MAX_OUTPUTS]; /* per output body (mechanism.h, in the description's
                                            output order): its largest |alpha| over each impact
                                            [rad/s^2] (a translating body's |acceleration|
                                            [m/s^2]) */
    __extension__ struct {              /* the four-bar's names for them (their output keys,
                                            FB_IMPACT_STATS_KEYS) */
      fb_dist alpha_coupler;
      fb_dist alpha_follower;
    };
  };
} fb_impact_stats;

/* Per-impact values of one run, owned (fb_impact_values_free). */
typedef struct {
  size_t n, cap;
  double *force; /* n [N] */
  union {
    double *alpha[FB_MECH_MAX_OUTPUTS]; /* n each, per output body as fb_impact_stats.alpha */
    __extension__ struct {
      double *alpha_coupler, *alpha_follower; /* the four-bar's names for them */
    };
  };
} fb_impact_values;

/* Appends one impact to v: its peak force [N] and each output body's
 * largest |alpha| (FB_MECH_MAX_OUTPUTS; units as fb_impact_stats.alpha).
 * Errors: FB_ERR_NOMEM (v keeps the impacts it held). */
fb_status fb_impact_values_push(fb_impact_values *v, double force,
                                const double alpha[FB_MECH_MAX_OUTPUTS], fb_diag *diag);

/* Appends the impacts of series s at clearance joint j whose onset lies at
 * t >= t_from [s] to v: an impact as every count defines it (metrics.h,
 * fb_metrics_next_impact: an unbroken run of samples whose force exceeds
 * the series' impact floor); its force is the largest over the episode and
 * its alpha spikes the largest |alpha| over it and the sample after (the
 * acceleration a contact force raises shows at the step that applies it).
 * Errors: FB_ERR_ARG without contact columns at j; FB_ERR_NOMEM. */
fb_status fb_impact_values_add(fb_impact_values *v, const fb_series *s, int j, double t_from,
                               fb_diag *diag);

void fb_impact_values_free(fb_impact_values *v);

/* The distributions of the values in v (pooled, when v holds several runs).
 * An empty v gives n = 0 and NaN statistics. Errors: FB_ERR_NOMEM. */
fb_status fb_impact_stats_of(fb_impact_stats *out, const fb_impact_values *v, fb_diag *diag);

/* The output keys of a distribution, in order, X(field, key): summary.json
 * (report.c) and the checked metrics (check.c) spell them from here. */
#define FB_DIST_KEYS(X) \
  X(mean, "mean")       \
  X(p50, "p50")         \
  X(p90, "p90")         \
  X(max, "max")
/* The distributions of fb_impact_stats with their key prefixes. */
#define FB_IMPACT_STATS_KEYS(X)                       \
  X(force, "impact_force", "n")                       \
  X(alpha_coupler, "impact_alpha_coupler", "rad_s2")  \
  X(alpha_follower, "impact_alpha_follower", "rad_s2")

#endif
