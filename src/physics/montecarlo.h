/* Monte Carlo stack-up over n toleranced lengths, any mechanism: the one
 * sampling, quantile and interval rule that the four-bar's and
 * slider-crank's stack-up (tolerance.c) and a planar case's
 * (studies/planar_tools.c) both call.
 *
 * Sampling: each sample draws its n lengths in order from one GSL
 * mt19937 stream seeded with `seed`, length k = nominal_k + t_k x with
 * x ~ N(0, 1/3) ("normal": 3 sigma at the tolerance limit,
 * gsl_ran_gaussian) or U(-1, 1) ("uniform", gsl_ran_flat); every sample is
 * drawn before any is evaluated, so the sequence depends on the seed
 * alone. The evaluation callback then gives the sample's outputs, on
 * `jobs` threads taking blocks of samples from a shared counter; each
 * output lands in its sample's slot, so every statistic is the same for
 * any number of jobs.
 * Statistics per output: mean, standard deviation (gsl_stats_mean,
 * gsl_stats_sd), quantiles at 0.135 %, 50 % and 99.865 %
 * (gsl_stats_quantile_from_sorted_data), each with the distribution-free
 * confidence interval [X_(lo), X_(hi)] at FB_TOL_CI_LEVEL from order
 * statistics (fb_tol_quantile_ranks). */
#ifndef FB_MONTECARLO_H
#define FB_MONTECARLO_H

#include <stddef.h>

#include "tolerance.h"

/* The quantiles' probabilities: 0.135 %, 50 %, 99.865 % (3 sigma of a
 * normal output on either side, and the median). */
#define FB_MC_NQ 3
extern const double fb_mc_quantile_p[FB_MC_NQ];

/* Outputs out (nout) of one sample's lengths len (nlengths) [m], in the
 * problem's draw order. Called from several threads at once when jobs > 1:
 * it must not write shared state. Returns FB_OK or an error with diag. */
typedef fb_status (*fb_mc_eval)(double *out, const double *len, void *ctx, fb_diag *diag);

/* What to sample. */
typedef struct {
  int nlengths;             /* lengths drawn per sample (>= 1) */
  const double *nominal;    /* nominal lengths, in draw order [m] (nlengths) */
  const double *plus_minus; /* symmetric tolerances t_k [m] (nlengths) */
  int nout;                 /* outputs per sample (>= 1) */
  fb_mc_eval eval;          /* the outputs of one sample */
  void *ctx;                /* passed to eval */
  size_t block;             /* samples per block a thread takes; 0: 256 (about 1 ms of
                               the four-bar's closed form); 1 for a costly evaluation, so
                               that the progress moves and the threads share evenly */
  int count_unassembled;    /* 1: a sample whose evaluation returns FB_ERR_ASSEMBLY (a
                               mechanism its lengths cannot assemble or turn) is counted
                               (fb_mc_result.unassembled) and left out of the statistics,
                               which are over the others; 0: it stops the run as any error */
} fb_mc_problem;

/* One output's statistics. */
typedef struct {
  double q[FB_MC_NQ];       /* quantiles at fb_mc_quantile_p [output unit] */
  double q_ci[FB_MC_NQ][2]; /* their intervals (lo, hi); -inf / +inf when the sample is
                               too small to bound that side */
  double mean, std;         /* [output unit] */
} fb_mc_output;

/* A Monte Carlo result. */
typedef struct {
  fb_mc_output *out;            /* (nout), the caller's */
  size_t q_rank[FB_MC_NQ][2];   /* 1-based order statistics of the interval bounds (0: none) */
  double ci_level;              /* FB_TOL_CI_LEVEL */
  size_t samples;               /* samples evaluated */
  int jobs;                     /* threads that evaluated them (jobs asked, at most one per
                                   block) */
  double wall_s;                /* wall time, drawing to statistics [s] */
  size_t failed_at;             /* the lowest failing sample (0-based), SIZE_MAX if none */
  double *failed_len;           /* NULL, or the caller's (nlengths): that sample's lengths */
  size_t unassembled;           /* with count_unassembled: samples left out (samples counts
                                   the others) */
  size_t unassembled_first;     /* the lowest of them (0-based), SIZE_MAX if none */
  char unassembled_msg[FB_DIAG_SIZE]; /* its evaluation's message ("" if none) */
} fb_mc_result;

/* Runs p over `samples` samples (>= 1) from `seed` with distribution dist
 * on jobs threads (1 .. FB_TOL_MAX_JOBS). r->out and r->failed_len are the
 * caller's; the rest is filled. progress (may be NULL) gets the fraction
 * done, from the calling thread. Errors: the evaluation's, of the lowest
 * failing sample (diag holds its message alone; r->failed_at and
 * r->failed_len say which), FB_ERR_NOMEM. */
fb_status fb_mc_run(fb_mc_result *r, const fb_mc_problem *p, size_t samples, unsigned long seed,
                    fb_distribution dist, int jobs,
                    void (*progress)(double fraction, void *user), void *user, fb_diag *diag);

/* Estimated memory [bytes] (FB_TOL_PROGRAM_BYTES and the samples' lengths
 * and outputs, kept for the quantiles) and wall time [s] (samples x
 * s_per_sample / jobs) of a run with nout outputs and nlengths lengths. */
void fb_mc_estimate(double s_per_sample, int nout, int nlengths, size_t samples, int jobs,
                    double *bytes, double *seconds);

/* Refuses, before anything is reserved, a run whose memory estimate bytes
 * passes FB_TOL_MEMORY_FRACTION of this machine's memory. Errors:
 * FB_ERR_RANGE naming the samples, the estimate (and wall time seconds) and
 * what to lower. */
fb_status fb_mc_check_cost(size_t samples, double bytes, double seconds, fb_diag *diag);

#endif
