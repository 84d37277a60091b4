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
 * this fraction of the radial clearance, along the direction k x the golden
 * angle (2.39996 rad) from +x, so that members are distinct however many
 * the test asks for (member 0 is the run itself) [-]. Where the pin sits in
 * its clearance at t = 0 is what nobody knows; 1 % of the gap is far less
 * than that, and spreads a chaotic reference's members (measured, 16
 * members, docs/verdicts.md "Members"): the Flores slider-crank's parted
 * from the run itself at 2.6 to 6.8 ms (its first revolution is 12 ms),
 * where 1e-6 of the gap left all 16 on the run's own trajectory (its
 * members' force max with no spread) and 1e-4 parted 10 of 15 at 16 to
 * 17 ms, inside the window; the untuned crank-rocker's at 6.8 to 73 ms
 * (median 9 ms; window from 75 ms). The paper case's regular sequence
 * does not part (its members' force mean within 1.6e-4). */
#define FB_ENSEMBLE_ECC_FRACTION 1e-2
/* The golden angle, pi (3 - sqrt 5) [rad]: member k's direction */
#define FB_ENSEMBLE_GOLDEN_ANGLE 2.39996322972865332
/* A pooled statistic's rel and sigmas (fb_stats_compare) are printed for a
 * reader; a model's verdict rests on the per-member test (verdict_stats.h).
 * A reference's check integration against its members still uses this
 * many normal standard deviations, as Student's t on N - 1 degrees of
 * freedom (fb_ensemble_compare_one) [-]. */
#define FB_ENSEMBLE_AGREE_SIGMAS 3.0
#define FB_ENSEMBLE_MAX 64

/* One member's statistics of one model, the unit of replication of the
 * verdict's test (verdict_stats.h): impacts within one run are correlated,
 * members are independent draws once they part. */
typedef struct {
  int k;                /* the member: 0 the run itself, k >= 1 its start moved [-] */
  int impacts;          /* impacts in the window (metrics.h, fb_metrics_next_impact) [-] */
  double revolutions;   /* crank revolutions of its window [-] */
  double rate;          /* impacts per revolution of the window [1/rev] */
  double force_mean;    /* mean peak force of its impacts [N]; NaN without impacts */
  double force_p90;     /* 90th percentile of the same [N]; NaN without impacts */
  double omega_dev;     /* largest |omega - omega_exact| of the rotating output bodies over the
                           window (fb_spikes.omega_dev_max) [rad/s] */
  double t_part;        /* when its trajectory leaves member 0's (metrics.h, fb_divergence's
                           criterion) [s]; INFINITY: it never does; NaN for member 0 */
} fb_member;

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
  fb_member member[FB_ENSEMBLE_MAX]; /* per member, in member order (members of them) */
} fb_ensemble;

/* Statistics against a yardstick's (a model's pooled ones against its
 * reference's, for the reader; a reference's check integration against its
 * members, fb_ensemble_compare_one). */
typedef struct {
  fb_impact_stats rel;       /* (model - reference) / reference of each pooled statistic [-] */
  fb_impact_stats sigmas;    /* |model - reference| / sqrt(s_model^2 + s_ref^2) [-]
                                (NaN with one member or no spread) */
  int agree;                 /* fb_ensemble_compare_one: 1 every statistic within agree_sigmas
                                sd or FB_MATCHED_IMPACT_ERROR_BOUND relative; -1: not measured
                                (one member); a model's: -1 (its test decides) */
  double agree_sigmas;       /* the bound on sigmas: Student's t for one run against an
                                ensemble (fb_ensemble_compare_one) [-] */
} fb_stats_compare;

/* One run that is not a member (a reference's check integration at a
 * tighter tolerance, run.h) against an ensemble e: is it one more sample of
 * the members' distribution? Each statistic a verdict tests
 * (verdict_stats.h: the impact rate, force mean and force p90 of one run)
 * against the members' mean, within the prediction interval of one more
 * sample of a normal spread known from N members: sd_member x sqrt(1 + 1 /
 * N) times agree_sigmas, Student's t on N - 1 degrees of freedom at the
 * two-sided level FB_VERDICT_ALPHA / 3 (Bonferroni over the three: 2.7 for
 * 16 members); or within FB_MATCHED_IMPACT_ERROR_BOUND relative (a regular
 * sequence has almost no spread). rel and sigmas hold every pooled
 * statistic's for a reader (against the members' mean; sigmas in units of
 * sd_member sqrt(1 + 1 / N)). agree is -1 for an ensemble of one member. */
void fb_ensemble_compare_one(fb_stats_compare *out, const fb_impact_stats *one,
                             const fb_ensemble *e);

/* Fills each clearance model's impact statistics of the run r (models that
 * reached their peak window) and, with r->c.ensemble > 1, runs the other
 * members of every clearance model and reference (r->c.jobs worker
 * processes; the result does not depend on the count) and pools them;
 * then tests each clearance model that has a reference against it at the
 * full level (one look, verdict_stats.h), and compares each reference's
 * check integration with the reference's members (run.h, check_compare).
 * progress (may be NULL) is called as "ensemble" with the fraction of
 * members done. Errors: FB_ERR_NOMEM; those of fb_run_models (run.h) for
 * a member; FB_ERR_IO when a worker fails. */
fb_status fb_ensemble_measure(struct fb_run_s *r, fb_progress_fn progress, void *user,
                              fb_diag *diag);

/* The sequential test (verdict_stats.h, docs/verdicts.md): for every
 * clearance model whose verdict is unsettled (verdict.h), and every
 * reference unsettled against its check, members are added in looks of
 * FB_SEQ_FIRST, 2 x, 4 x, ... up to FB_SEQ_CAP members (the run itself
 * the first), each look running only the models still undecided and their
 * references, in r->c.jobs worker processes; after each look each
 * undecided model is tested at FB_VERDICT_ALPHA / FB_SEQ_LOOKS and stops
 * when decided. Stops early, leaving the rest undecided, when the next
 * look's estimate (the models' first run, times the members it adds, over
 * the workers) would pass [run] max_wall_s since t_start [s]. r->seq_*
 * record the looks and members; the caller (run_case.c) times them into
 * r->ensemble_wall_s. Errors: as fb_ensemble_measure. */
fb_status fb_ensemble_sequential(struct fb_run_s *r, double t_start, fb_progress_fn progress,
                                 void *user, fb_diag *diag);

/* The worker processes an ensemble gets when the command names none
 * (`fourbar run` without --jobs): the processors online
 * (sysconf(_SC_NPROCESSORS_ONLN)), at least 1, at most FB_ENSEMBLE_MAX;
 * a look never starts more workers than it adds members. The numbers do
 * not depend on it (each member's values come back in member order). */
int fb_ensemble_default_jobs(void);

#endif
