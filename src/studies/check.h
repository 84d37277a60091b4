/* Regression of spike magnitudes: the metrics of a run, baselines with
 * measured tolerances, and the comparison.
 *
 * Metrics: for every model, the eight peaks (<model>.coupler.omega_max_rad_s
 * ...) and, for clearance models, the spike metrics (<model>.spikes.force_max_n
 * ...). Tolerances are measured, not guessed (fb_check_calibrate): the case is
 * rerun with what should not matter perturbed (h 1 % smaller, the initial
 * crank angle moved by 1e-12 rad, and the same run repeated), each metric's
 * spread is the largest change seen, and its tolerance is
 * max(floor_abs, floor_rel |value|, safety_factor * spread). A metric whose
 * spread exceeds 5 % of its value is marked chaotic (impact counts and crank
 * angles of spikes usually are): it is still compared by value, with its wide
 * measured tolerance.
 *
 * A case with [run] ensemble = N > 1 adds, for every clearance model, the
 * pooled impact statistics (<model>.stats.impact_force_p90_n, ...; mean,
 * p50, p90, max of the per-impact peak force and coupler and follower alpha
 * spikes, and the impact count), with a tolerance of
 * FB_CHECK_ENSEMBLE_SIGMAS x its ensemble_sd; and a model
 * whose window peaks are not converged (divergent from its reference, or a
 * reference whose check integration moves them: run.h, peaks_unconverged)
 * is checked by these statistics alone, not by its peaks and spikes. */
#ifndef FB_CHECK_H
#define FB_CHECK_H

#include "planar_run.h"
#include "run.h"

#define FB_CHECK_MAX_METRICS 256
#define FB_CHECK_SAFETY_FACTOR 3.0   /* tolerance over the measured spread */
#define FB_CHECK_FLOOR_REL 1e-9      /* relative floor: bit-level changes of a recompile */
#define FB_CHECK_FLOOR_ABS 1e-12     /* absolute floor for values at or near zero */
#define FB_CHECK_CHAOTIC_REL 0.05    /* spread above this share of the value: chaotic */
#define FB_CHECK_H_FACTOR 0.99       /* the "a little smaller" step */
#define FB_CHECK_ANGLE_NUDGE_RAD 1e-12
/* a planar case's drive speed, times 1 + this: a description starts at its
 * assembly, so its start cannot be turned; over a run of a few revolutions
 * the drive's angle moves by about 1e-11 rad, the built-ins' nudge's order
 * [-] */
#define FB_CHECK_SPEED_NUDGE_REL 1e-12

/* A statistics metric's tolerance is this many times its ensemble_sd: the
 * standard deviation of the difference of the pooled statistic between two
 * ensembles that differ in roundoff alone (a rebuild, another machine),
 * which a chaotic sequence turns into two independent samples:
 * sd_member sqrt(2 / N) for N members (sd_count sqrt(2 N) for the pooled
 * impact count). 4 of them: a normal difference passes it once in ~16000
 * per metric, while a spike distribution that doubles fails (the rattling
 * pin's force mean: tolerance 0.56 of its value with 5 members over 2
 * revolutions; more members or revolutions narrow it). The calibration's
 * perturbed runs are reported as spread but not used for these metrics:
 * a 1 % smaller step is itself another ensemble sample of a chaotic
 * sequence [-]. */
#define FB_CHECK_ENSEMBLE_SIGMAS 4.0

typedef struct {
  char name[128];
  double value;
  double ensemble_sd; /* statistics metrics: sd of its difference between two ensembles
                         (FB_CHECK_ENSEMBLE_SIGMAS); else 0 */
} fb_metric;

/* Collects the metrics of run r into out (at most max); returns the count:
 * each model's peaks, a clearance model's spikes, an ensemble's statistics
 * (the metrics the baselines of results/baselines hold). */
int fb_check_metrics(const fb_run *r, fb_metric *out, int max);

/* fb_check_metrics and, for each clearance model whose pin touched the
 * wall, its first impact (<model>.first_impact.<key>, FB_FIRST_IMPACT_KEYS):
 * the metrics a study's row holds (study.c). The baselines were calibrated
 * before the first impact's metrics existed, so fourbar check leaves them
 * out rather than find them missing from every baseline. */
int fb_study_metrics(const fb_run *r, fb_metric *out, int max);

/* Collects the metrics of planar run r (planar_run.h) into out (at most
 * max); returns the count: each model's peaks of every moving body, named
 * <model>.<body>.<key> by the description's body names (summary.json's
 * models[].bodies), and each model with a clearance joint's contact (a
 * reference of its law, an engine's clearance model) as
 * <model>.spikes.force_max_n and <model>.spikes.penetration_max_m (its
 * largest contact force [N] and penetration [m] in the window). A model
 * that stopped gives none. */
int fb_check_planar_metrics(const fb_planar_run *r, fb_metric *out, int max);

/* Runs case c (a planar one by fourbar run's planar pipeline, else
 * fb_run_case with progress and user) and collects its metrics into out
 * (FB_CHECK_MAX_METRICS at most, the count into *n): fb_check_metrics or
 * fb_check_planar_metrics. h_used (may be NULL) gets the step the run ran
 * at [s]. Errors: those of fb_run_case and fb_planar_run_case. */
fb_status fb_check_case_metrics(fb_metric *out, int *n, const fb_case *c,
                                fb_progress_fn progress, void *user, double *h_used,
                                fb_diag *diag);

/* 1 when name is a metric a run of mechanism mech can give (<model>.<group>.
 * <key>, the names fb_study_metrics writes, in mech's names: a
 * slider-crank's slider.velocity_max_m_s, never follower.*, for a model
 * that builds mech; or <model>.stats.<key>), or, ending in '*', a prefix of
 * one; else 0 with, in known (size bytes; may be NULL), the nearest such
 * name ("did you mean ...? ") and mech's groups and keys. */
int fb_check_metric_name_ok(const char *name, const fb_mech_desc *mech, char *known, size_t size);

/* As fb_check_metric_name_ok for a planar case of description m: 1 when
 * name is a metric fb_check_planar_metrics can give for a model that runs
 * a planar case (<model>.<body>.<key> by m's moving bodies' names,
 * <model>.spikes.force_max_n or penetration_max_m), or, ending in '*', a
 * prefix of one; else 0 with, in known (size bytes; may be NULL), the
 * nearest name and the groups and keys. */
int fb_check_planar_metric_name_ok(const char *name, const fb_planar *m, char *known,
                                   size_t size);

/* One baseline metric. */
typedef struct {
  char name[128];
  double value;     /* baseline value */
  double tolerance; /* absolute */
  double spread;    /* measured by calibration */
  double ensemble_sd; /* statistics metrics: as in fb_metric; else 0 */
  int chaotic;
} fb_baseline_metric;

/* Measures metrics and tolerances for case c (its own file and overrides
 * already applied): a base run and three perturbed runs (h times
 * FB_CHECK_H_FACTOR; the crank's start moved by FB_CHECK_ANGLE_NUDGE_RAD,
 * a planar case's drive speed by FB_CHECK_SPEED_NUDGE_REL, none on an
 * undriven planar case; the run repeated). out gets n metrics.
 * *nondeterministic is set when the repeated run differs from the base.
 * Errors: those of fb_check_case_metrics. */
fb_status fb_check_calibrate(fb_baseline_metric *out, int *n, int *nondeterministic,
                             const fb_case *c, fb_diag *diag);

#endif
