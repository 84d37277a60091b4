/* Tolerance stack-up of a mechanism's outputs: worst case over the 2^n
 * corners of its n length tolerances (the four-bar's 4 links, 16 corners;
 * the slider-crank's crank, coupler and guide offset, 8 corners), RSS from
 * exact sensitivities, and Monte Carlo with GSL's Mersenne Twister
 * (gsl_rng_mt19937). The case's [linkage] type chooses (fb_case.mechanism).
 *
 * Outputs (FB_TOL_NOUT, both mechanisms): the four-bar's eight peaks of
 * coupler and follower angular velocity [rad/s] and acceleration [rad/s^2]
 * over a revolution, and the transmission angle's minimum and maximum
 * [rad]; the slider-crank's four peaks of the rod (coupler) as the
 * four-bar's, the slider's velocity [m/s] and acceleration [m/s^2] peaks in
 * the follower's slots, the smallest transmission angle [rad] and the
 * stroke [m] (fb_tol_output_name_of).
 * Sensitivities dOutput/dLength are exact: for a peak, the envelope theorem
 * gives the partial derivative at the crank angle of the peak
 * (fb_linkage_sensitivity, fb_slider_crank_sensitivity); for the four-bar's
 * transmission angle, the derivative of mu = acos((b^2 + c^2 - f^2) /
 * (2 b c)) with f = g -+ a at theta2 = 0, pi; for the slider-crank's, of
 * acos((crank + |offset|) / coupler), and its stroke's, of
 * sqrt((coupler + crank)^2 - offset^2) - sqrt((coupler - crank)^2 -
 * offset^2) (slider_crank.h fb_slider_crank_limits).
 * RSS: nominal +- sqrt(sum_k (S_k t_k)^2), each tolerance t_k taken as 3
 * sigma, so the band is the 3-sigma band of the linearised output.
 * Monte Carlo: each length nominal + t_k x, x ~ N(0, 1/3) ("normal": 3 sigma
 * at the tolerance limit) or U(-1, 1) ("uniform"); quantiles at 0.135 %,
 * 50 % and 99.865 % (GSL gsl_stats_quantile_from_sorted_data), each with a
 * distribution-free confidence interval from order statistics
 * (fb_tol_quantile_ranks). The samples are drawn in order from one stream
 * and may be evaluated by several threads: the numbers depend only on the
 * seed and the sample count. */
#ifndef FB_TOLERANCE_H
#define FB_TOLERANCE_H

#include <stddef.h>

#include "analytic.h"
#include "case.h"

#define FB_TOL_NOUT 10

/* The four-bar's output names with SI unit suffix, e.g.
 * "coupler_omega_max_rad_s", "transmission_angle_min_rad". This and the
 * other four-bar functions below (fb_tol_output_parse, fb_tol_outputs,
 * fb_tol_outputs_from_peaks, fb_tol_sensitivities) are defined with its
 * closed forms (closed_form_fourbar.c); the _of functions look the
 * mechanism's up in its table (closed_form.h). */
const char *fb_tol_output_name(int i);

/* Index of an output name (with or without its unit suffix), -1 if none. */
int fb_tol_output_parse(const char *name);

/* The output names of mechanism t: the four-bar's fb_tol_output_name; the
 * slider-crank's "coupler_omega_max_rad_s" .. "coupler_alpha_min_rad_s2",
 * "slider_velocity_max_m_s", "slider_velocity_min_m_s",
 * "slider_acceleration_max_m_s2", "slider_acceleration_min_m_s2" (as
 * summary.json's models[].slider, fb_mech_output_key),
 * "transmission_angle_min_rad", "stroke_m"; "?" out of range. */
const char *fb_tol_output_name_of(fb_mech_type t, int i);

/* The unit of output i of mechanism t, from its name's suffix: "rad/s^2",
 * "rad/s", "rad", "m/s^2", "m/s", "m". */
const char *fb_tol_output_unit_of(fb_mech_type t, int i);

/* Evaluates the four-bar's outputs for lengths lk. Errors: those of
 * fb_analytic_peaks. */
fb_status fb_tol_outputs(double out[FB_TOL_NOUT], const fb_linkage *lk, fb_branch branch,
                         double omega2, fb_diag *diag);

/* Outputs 0..7 from peaks p: per output body (the four-bar's coupler and
 * follower; another member's in its description's output order) omega max,
 * min, alpha max, min; slots 8 and 9 untouched. */
void fb_tol_outputs_from_peaks(double out[FB_TOL_NOUT], const fb_peaks *p);

/* The four-bar's exact sensitivities [output unit per m] (FB_TOL_NOUT x 4). */
fb_status fb_tol_sensitivities(double out[FB_TOL_NOUT][FB_LINK_COUNT], const fb_linkage *lk,
                               fb_branch branch, double omega2, fb_diag *diag);

/* The outputs of mechanism t for lengths lk (a slider-crank's crank,
 * coupler and offset, mechanism.h FB_LENGTH_OFFSET; branch is the
 * four-bar's alone). Errors: those of fb_tol_outputs, or for the
 * slider-crank of fb_slider_crank_limit_positions (the crank cannot turn
 * fully) and fb_mech_peaks. */
fb_status fb_tol_outputs_of(double out[FB_TOL_NOUT], fb_mech_type t, const fb_linkage *lk,
                            fb_branch branch, double omega2, fb_diag *diag);

/* The exact sensitivities of mechanism t [output unit per m], per length
 * slot of lk (FB_TOL_NOUT x 4): the slider-crank's columns crank, coupler,
 * offset, and 0 in the fourth. At offset 0 the slider-crank's smallest
 * transmission angle has a corner (it depends on |offset|, and either sign
 * lowers it): its offset entry is then the one-sided derivative toward
 * +offset, -1 / (coupler sin mu_min), so that the RSS band is as wide as
 * the offset makes it (on the low side; the corners and Monte Carlo show
 * the one-sidedness). A peak that two crank angles tie for has a corner
 * too (the zero-offset slider-crank's slider acceleration maximum when
 * crank / coupler > 1/4: two maxima mirrored about the inner dead centre;
 * measured: d/d offset = +98560 and -98560 (m/s^2)/m on either side for
 * cases/slider_crank_flores.ini): its sensitivity is the derivative at the
 * first of them on the search's grid, one side's. Errors: those of
 * fb_tol_outputs_of and fb_slider_crank_sensitivity. */
fb_status fb_tol_sensitivities_of(double out[FB_TOL_NOUT][FB_LINK_COUNT], fb_mech_type t,
                                  const fb_linkage *lk, fb_branch branch, double omega2,
                                  fb_diag *diag);

typedef enum { FB_DIST_NORMAL = 0, FB_DIST_UNIFORM = 1 } fb_distribution;

/* Result of a stack-up analysis; fields of methods not run are 0. */
typedef struct {
  double nominal[FB_TOL_NOUT];
  double sens[FB_TOL_NOUT][FB_LINK_COUNT];
  double corner_min[FB_TOL_NOUT], corner_max[FB_TOL_NOUT];
  int corner_of_max[FB_TOL_NOUT][FB_LINK_COUNT]; /* corner giving the largest |output|
                                                    (0 in a slot the mechanism has not) */
  double rss_half[FB_TOL_NOUT];                  /* half-width of the RSS band */
  double q[FB_TOL_NOUT][3];                      /* Monte Carlo 0.135 %, 50 %, 99.865 % */
  double mc_mean[FB_TOL_NOUT], mc_std[FB_TOL_NOUT];
  double q_ci[FB_TOL_NOUT][3][2];                /* confidence interval of each quantile
                                                    (lo, hi); -inf / +inf when the sample is
                                                    too small to bound that side */
  size_t q_rank[3][2];                           /* 1-based order statistics of those bounds
                                                    (0: none) */
  double ci_level;                               /* their confidence level (FB_TOL_CI_LEVEL) */
  size_t samples;                                /* Monte Carlo samples used */
  int jobs;                                      /* threads that evaluated them */
  double mc_wall_s;                              /* Monte Carlo wall time [s] */
} fb_stackup_result;

/* Two-sided confidence level of the quantile intervals. */
#define FB_TOL_CI_LEVEL 0.95
/* Most threads fb_tol_analyse_jobs will start. */
#define FB_TOL_MAX_JOBS 256

/* Ranks (1-based) of the order statistics X_(lo) <= X_(hi) of n samples that
 * bound the p-quantile with probability at least `level`, whatever the
 * distribution (the number B of samples below the quantile is Binomial(n, p),
 * so [X_(lo), X_(hi)] covers it with probability P(lo <= B < hi); the
 * classical order-statistic interval, evaluated with GSL gsl_cdf_binomial_P/Q): lo is the largest rank with P(B < lo) <= (1-level)/2,
 * hi the smallest with P(B >= hi) <= (1-level)/2. A side that no rank can
 * bound at that level (too few samples in the tail) is 0. */
void fb_tol_quantile_ranks(size_t n, double p, double level, size_t *lo, size_t *hi);

/* Methods to run (bit mask). */
#define FB_TOL_CORNERS 1
#define FB_TOL_RSS 2
#define FB_TOL_MONTECARLO 4

/* Runs the methods in mask for the case's nominal lengths and tolerances,
 * for the case's mechanism (corners over its lengths; the Monte Carlo draws
 * its lengths only, in their order, per sample).
 * progress (may be NULL) gets the Monte Carlo fraction done.
 * Errors: FB_ERR_ASSEMBLY when a corner or sample cannot turn its crank
 * fully (message names the lengths); FB_ERR_NOMEM. */
fb_status fb_tol_analyse(fb_stackup_result *out, const fb_case *c, int mask, size_t samples,
                         unsigned long seed, fb_distribution dist,
                         void (*progress)(double fraction, void *user), void *user,
                         fb_diag *diag);

/* As fb_tol_analyse, with the Monte Carlo samples evaluated by `jobs`
 * threads (1 .. FB_TOL_MAX_JOBS): the same numbers for every jobs. progress
 * is called from the calling thread. Errors: those of fb_tol_analyse (the
 * lowest failing sample is the one named); FB_ERR_ARG for jobs out of range. */
/* The program's own resident memory before any sample: measured 29.2 MB
 * (fourbar stackup --method montecarlo --samples 100), and 6 MB beyond the
 * samples' own at 1e6 (147.3 MB peak: 29.2 + 112 + 6); rounded up. */
#define FB_TOL_PROGRAM_BYTES 40e6
/* Share of the machine's memory a Monte Carlo run may reserve. */
#define FB_TOL_MEMORY_FRACTION 0.5

/* CPU time [s] of one evaluation of case c's stack-up outputs (what each
 * corner and each Monte Carlo sample evaluates: its closed form's outputs
 * and their peaks at the nominal lengths), measured on c itself by the
 * probe of work.h (fb_work_probe, for work of units evaluations; 0: not
 * known); *evals (may be NULL) the evaluations it made. Errors: those of
 * the outputs (fb_tol_outputs_of). */
fb_status fb_tol_eval_cost(double *s_per_eval, int *evals, double units, const fb_case *c,
                           fb_diag *diag);

/* Estimated memory [bytes] and wall time [s] of a Monte Carlo analysis of
 * samples samples, each s_per_sample [s] of CPU (fb_tol_eval_cost), on jobs
 * threads (the samples and their outputs are kept for the quantiles, over
 * the program's own memory). */
void fb_tol_estimate(double s_per_sample, size_t samples, int jobs, double *bytes, double *seconds);

/* Refuses, before anything is reserved, a Monte Carlo analysis whose memory
 * estimate passes FB_TOL_MEMORY_FRACTION of this machine's memory.
 * Errors: FB_ERR_RANGE naming the samples, the estimate and what to lower. */
fb_status fb_tol_check_cost(double s_per_sample, size_t samples, int jobs, fb_diag *diag);

fb_status fb_tol_analyse_jobs(fb_stackup_result *out, const fb_case *c, int mask, size_t samples,
                              unsigned long seed, fb_distribution dist, int jobs,
                              void (*progress)(double fraction, void *user), void *user,
                              fb_diag *diag);

/* Resolves a "worst" stack-up: sets c->stackup.corner to the corner that
 * maximises |output c->stackup.worst_output| and clears the worst flag.
 * Does nothing for other choices. Errors: those of fb_tol_outputs. */
fb_status fb_tol_resolve_worst(fb_case *c, fb_diag *diag);

#endif
