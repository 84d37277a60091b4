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
#include "model_run.h"

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
  fb_impact_stats member_mean; /* mean over the members of each member's statistic (n: 0);
                                  what one more run is compared with (fb_ensemble_compare_one) */
} fb_ensemble;

/* A model's statistics against its reference's. */
typedef struct {
  fb_impact_stats rel;       /* (model - reference) / reference of each pooled statistic [-] */
  fb_impact_stats sigmas;    /* |model - reference| / sqrt(s_model^2 + s_ref^2) [-]
                                (NaN with one member or no spread) */
  int agree;                 /* 1: every statistic within agree_sigmas sd or
                                FB_MATCHED_IMPACT_ERROR_BOUND relative; -1: not measured
                                (one member) */
  double agree_sigmas;       /* the bound on sigmas: FB_ENSEMBLE_AGREE_SIGMAS, or Student's t
                                for one run against an ensemble (fb_ensemble_compare_one) [-] */
} fb_stats_compare;

/* One run that is not a member (a reference's check integration at a
 * tighter tolerance, run.h) against an ensemble e: each of its statistics
 * against the mean of the members' (not the pooled value, whose p90 and
 * max cover N runs' impacts), agreeing within the prediction interval of
 * one more sample of a normal spread known from N members: sigmas in units
 * of sd_member x sqrt(1 + 1 / N), within agree_sigmas = Student's t on
 * N - 1 degrees of freedom at the two-sided level of
 * FB_ENSEMBLE_AGREE_SIGMAS normal standard deviations (6.6 for 5 members,
 * 3.6 for 16); or FB_MATCHED_IMPACT_ERROR_BOUND relative. A
 * chaotic sequence's member statistics spread widely and 5 members
 * estimate the spread poorly: on the untuned crank-rocker
 * (cases/untuned_crank_rocker.ini) the force p50's sd was 17 N over 5
 * members and 21 N (tolerance 1e-12) and 38 N (1e-13) over 16, so a plain
 * 3 sd would fail a sample the larger ensembles hold typical. agree is -1
 * for an ensemble of one member. */
void fb_ensemble_compare_one(fb_stats_compare *out, const fb_impact_stats *one,
                             const fb_ensemble *e);

/* Fills each clearance model's impact statistics of the run r (models that
 * reached their peak window) and, with r->c.ensemble > 1, runs the other
 * members (r->c.jobs worker processes; the result does not depend on the
 * count) and pools them; then compares each clearance model that has a
 * reference with it, and each reference's check integration with the
 * reference's ensemble (run.h, check_compare). progress (may be NULL) is
 * called as "ensemble" with the fraction of members done. Errors:
 * FB_ERR_NOMEM; those of fb_run_models (run.h) for a member; FB_ERR_IO
 * when a worker fails. */
fb_status fb_ensemble_measure(struct fb_run_s *r, fb_progress_fn progress, void *user,
                              fb_diag *diag);

#endif
