/* `[run] ensemble = N`: the clearance models and their references run N
 * times, each run with the pins' initial eccentricity moved by a tiny,
 * stated amount in another direction, and their impact statistics
 * (impact_stats.h) pooled, with the spread over the runs. A model that
 * parts from a chaotic reference (metrics.h, fb_divergence) is compared
 * with it by these statistics, not peak by peak (docs/chaos.md).
 *
 * Why the pin eccentricity and not the crank angle: the crank is driven at
 * a prescribed speed from a state on the ideal motion, so moving its start
 * angle by d only shifts the whole solution in time by d / omega (the
 * equations do not depend on t); it perturbs the integration grid, not the
 * motion. The pin's start inside its clearance is what nobody knows. */
#ifndef FB_ENSEMBLE_H
#define FB_ENSEMBLE_H

#include "impact_stats.h"
#include "metrics.h"

struct fb_run_s;

/* Member k >= 1 starts with every clearance joint's eccentricity moved by
 * this fraction of the radial clearance, along the direction at
 * 2 pi (k - 1) / (N - 1) from +x (member 0 is the run itself): 1e-6 x
 * 14.5 um = 15 pm in the own four-bar template, a millionth of the gap, far
 * below anything measurable, yet a chaotic sequence amplifies it into a
 * different impact history within a revolution (docs/chaos.md), while the
 * paper case's regular sequence moves its peaks by ~1e-6 [-]. */
#define FB_ENSEMBLE_ECC_FRACTION 1e-6
/* A model agrees with its reference's distribution when each pooled
 * statistic differs from the reference's by at most this many standard
 * deviations of the two ensembles' member statistics combined
 * (sqrt(s_model^2 + s_ref^2)): 3, the usual two-sided 99.7 % band of a
 * normal spread; or by at most FB_MATCHED_IMPACT_ERROR_BOUND of the
 * reference's value (a regular sequence has almost no spread, and is held
 * to the bound of its matched impacts) [-]. */
#define FB_ENSEMBLE_AGREE_SIGMAS 3.0
#define FB_ENSEMBLE_MAX 64

/* One model's ensemble. */
typedef struct {
  int members;               /* runs pooled (the run itself included) [-] */
  int impacts_min;           /* fewest impacts of a member in the window [-] */
  int impacts_max;           /* most [-] */
  fb_impact_stats pooled;    /* over every member's impacts */
  fb_impact_stats spread;    /* sample standard deviation over the members of each
                                member's statistic (n: of the impact counts); 0 for
                                one member (unit of the statistic) */
} fb_ensemble;

/* A model's statistics against its reference's. */
typedef struct {
  fb_impact_stats rel;       /* (model - reference) / reference of each pooled statistic [-] */
  fb_impact_stats sigmas;    /* |model - reference| / sqrt(s_model^2 + s_ref^2) [-]
                                (NaN with one member or no spread) */
  int agree;                 /* 1: every statistic within FB_ENSEMBLE_AGREE_SIGMAS sd or
                                FB_MATCHED_IMPACT_ERROR_BOUND relative; -1: not measured
                                (one member) */
} fb_stats_compare;

/* Fills each clearance model's impact statistics of the run r (models that
 * reached their peak window) and, with r->c.ensemble > 1, runs the other
 * members (r->c.jobs worker processes; the result does not depend on the
 * count) and pools them; then compares each clearance model that has a
 * reference with it. Errors: FB_ERR_NOMEM; those of fb_run_case for a
 * member; FB_ERR_IO when a worker fails. */
fb_status fb_ensemble_measure(struct fb_run_s *r, fb_diag *diag);

#endif
