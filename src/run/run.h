/* The run pipeline: case -> models -> metrics. Runs every model a case asks
 * for, then measures each: peaks over the revolutions after the first, and,
 * for ODE models, the error against the analytic solution of the same link
 * lengths. Writers (report.h) take the result from here. The ensemble
 * (ensemble.h) sits above this file and fb_run_case (run_case.h) above
 * both: nothing here calls the ensemble. */
#ifndef FB_RUN_H
#define FB_RUN_H

#include "ensemble.h"
#include "metrics.h"
#include "model_run.h"
#include "scene.h"
#include "variants.h"
#include "verdict.h"
#include "verdict_stats.h"

/* Warnings a model run can carry. */
#define FB_RUN_WARNINGS 6

/* `fourbar run` runs the sequential test by itself (ensemble.h,
 * fb_ensemble_sequential; verdict_stats.h: FB_SEQ_FIRST up to FB_SEQ_CAP
 * members) when the case does not set [run] ensemble and a model is
 * unsettled (verdict.h: a clearance model left its reference, or a
 * reference parted from its check integration); case ensemble_auto holds
 * this flag [-]. */
#define FB_ENSEMBLE_AUTO 1

/* A crank that lags its prescribed angle by more than this has had its drive
 * saturate (ODE: [solver] drive_torque_max_n_m; MuJoCo: the flywheel's
 * [mujoco] drive_armature_kg_m2): the crank tip then trails by
 * 1e-4 x 0.108 m = 11 um in the paper's case, most of a radial clearance, so
 * the contact no longer sees the prescribed motion [rad]. */
#define FB_DRIVE_LAG_WARN_RAD 1e-4

/* An ideal model (no clearance) of an engine, measured against the analytic
 * solution of the same lengths, carries the warning "peak error against the
 * analytic solution" (FB_WARN_ERROR_BOUND) when the largest |relative error|
 * of its coupler and follower omega and alpha peaks passes this bound: 5 %,
 * about 3000 times ODE's error at the paper's step (1.7e-5 on alpha) and 5
 * times dWorldQuickStep's at 20 iterations (< 1e-2, test_scene.c), so only a
 * lost solution passes it (a crank angle of 1e20 deg gave 1.5, a coupler of
 * 1e300 kg 5e4, both once reported "ok") [-]. */
#define FB_IDEAL_PEAK_ERROR_BOUND 0.05

/* A reference whose window peaks (force, coupler and follower alpha) move
 * by more than this when its integration is repeated at a tighter tolerance
 * (reference.h, FB_REFERENCE_CHECK_FACTOR) has unconverged peaks: they are
 * printed marked and with fewer digits. The paper case's reference moves
 * them by < 1e-6; a rattling pin's by tens of percent (its impact sequence
 * is chaotic) [-]. */
#define FB_UNCONVERGED_REL 1e-3

/* h_s = auto re-chooses its step when the run met a contact stiffer than
 * its estimate (h omega_c above FB_H_OMEGA_C_BOUND): the step is scaled by
 * bound / measured h omega_c times this margin and the run redone, because
 * the new step reaches the stiffer states a little more often [-]. */
#define FB_H_AUTO_MARGIN 0.9
/* and at most this many times (the margin has converged in one on every
 * case measured, docs/chaos.md) [-]. */
#define FB_H_AUTO_RETRIES 3

/* fb_model_result.matched_error: the matched impacts miss the bound while the
 * model keeps the reference's trajectory, or before it leaves it. */
#define FB_MATCHED_ERROR_KEPT 1
#define FB_MATCHED_ERROR_THEN_DIVERGENT 2

/* One model with its metrics. */
typedef struct {
  fb_model_run run;        /* series, cost and status */
  int has_peaks;           /* 1 when the peak window was reached */
  fb_peaks peaks;          /* analytic: exact (GSL-refined); ode: over samples [rad/s, rad/s^2] */
  fb_peaks exact;          /* analytic peaks of the same lengths */
  int has_error;           /* 1 for ode models that reached the window */
  fb_error error;          /* against the analytic solution of the same lengths */
  fb_peaks delta_vs_nominal; /* (peak - analytic nominal peak) / |analytic nominal peak| [-] */
  int has_spikes;          /* 1 for clearance models that reached the window */
  fb_spikes spikes;
  char spikes_reference[FB_NAME_SIZE]; /* model whose peak |alpha| the ratios divide by */
  fb_peaks_at peaks_at;    /* time and crank angle of each peak of the window */
  int has_startup;         /* 1 when the run has a sample in revolution 1 */
  fb_peaks startup;        /* peaks over revolution 1 alone, t < t_startup_end (analytic: exact) */
  fb_peaks_at startup_at;  /* time and crank angle of each start-up peak */
  double startup_force_max;       /* largest contact force in revolution 1 [N] (clearance models) */
  double startup_penetration_max; /* largest penetration in revolution 1 [m] */
  int first_impact_joint;  /* clearance joint of first_impact (the lowest of the mask), or -1 */
  fb_first_impact first_impact; /* first impact of the run at that joint */
  double penetration_max_run; /* largest penetration over the whole run [m] */
  int warning_count;       /* entries used in warnings */
  fb_warning warnings[FB_RUN_WARNINGS]; /* typed warnings (outcome.h; writers render them) */
  int has_ref_error;       /* 1 for a clearance model run beside its reference */
  fb_reference_error ref_error;
  char ref_name[FB_NAME_SIZE]; /* the reference model compared against */
  int has_divergence;      /* 1 for a clearance model run beside its reference */
  fb_divergence divergence; /* where it leaves the reference, impacts matched before */
  int has_ref_estimate;    /* 1 for a reference model that ran to its end and whose check
                              integration did (reference.h, FB_REFERENCE_CHECK_FACTOR) */
  fb_reference_error ref_estimate; /* this reference against its check integration */
  double ref_tol;          /* the reference's tolerance [-] */
  double ref_check_tol;    /* the check integration's tolerance [-] */
  size_t ref_check_steps;  /* the check integration's accepted steps [-] */
  double check_s;          /* wall time of the check integration and its comparison [s]
                              (0: none; timing.json's <model>.check) */
  double check_cpu_s;      /* its CPU time [s] */
  int has_ensemble;        /* 1 for a clearance model that reached its window (ensemble.h) */
  fb_ensemble ensemble;    /* its impact statistics, pooled over [run] ensemble members */
  int has_stats_compare;   /* 1 when its reference has an ensemble too */
  fb_stats_compare stats_compare; /* its pooled statistics against the reference's (printed) */
  fb_impact_values member_impacts[FB_ENSEMBLE_MAX]; /* each member's impacts (ensemble.members of
                                                       them; owned, freed by fb_run_free) */
  int has_test;            /* 1: a clearance model tested against its reference's members */
  fb_stat_test test;       /* that test (verdict_stats.h): what a verdict on statistics rests on */
  int has_first_check;     /* 1: a clearance model whose first impacts were compared */
  fb_first_check first_check; /* its first impacts against its reference's, one to one */
  int matched_error;       /* matched-impact peak errors beyond FB_MATCHED_IMPACT_ERROR_BOUND:
                              0 none; FB_MATCHED_ERROR_KEPT while the trajectory stays with the
                              reference (status "error"); FB_MATCHED_ERROR_THEN_DIVERGENT
                              before it leaves it (status "divergent"; report_chaos.h) */
  int peaks_unconverged;   /* 1: its window peaks are not to be read as converged numbers
                              (divergent from its reference, or a reference whose own check
                              integration moves them, FB_UNCONVERGED_REL): printed marked */
  /* a reference's check integration beyond its peaks (has_ref_estimate): */
  int has_check_divergence; /* 1 when check_divergence was measured */
  fb_divergence check_divergence; /* where this reference leaves its check integration (the
                              check in the reference's place), impacts matched before */
  int has_check_stats;     /* 1 when the check integration had impacts in the window */
  fb_impact_stats check_stats; /* its impact statistics over the window */
  int has_check_compare;   /* 1 when this reference has an ensemble to compare them with */
  fb_stats_compare check_compare; /* check_stats against the ensemble's members (ensemble.h,
                              fb_ensemble_compare_one) */
  fb_verdict_word verdict; /* the printed word, and what it rests on (verdict.h) */
  fb_verdict_basis basis;
} fb_model_result;

/* The step a run took, verified as `fourbar contact-params --case` verifies
 * a contact (studies/contact_params.h): the restitution law's single impact
 * in ODE's matched row, at each clearance joint's effective masses and every
 * onset phase within a step, against the continuous law (impact.h,
 * FB_FAITHFUL_*). `fourbar run` fills it when a restitution-law model ran;
 * the step line states the error the run accepts when it is not faithful. */
typedef struct {
  int checked;            /* 1: verified */
  int joint;              /* the clearance joint of the worst figures */
  int faithful;           /* 1: every joint within both bounds */
  double restitution_rel; /* worst relative error of the restitution [-] */
  double penetration_rel; /* worst relative error of the peak penetration [-] */
  double largest_step;    /* the smallest over the joints of the largest faithful step [s]; NaN:
                             none found */
} fb_step_check;

typedef struct fb_run_s {
  fb_case c;                              /* the case as run (worst corner resolved) */
  fb_scene scene;                     /* the case resolved once; every model's scene */
  double t_window;                        /* peaks and errors use t >= t_window [s] */
  double t_startup_end;                   /* revolution 1 is t < t_startup_end [s] */
  int n;                                  /* models run */
  fb_model_result model[FB_MAX_MODELS];   /* in the case's order */
  fb_peaks analytic_nominal;              /* exact peaks of the nominal linkage */
  int h_auto;                             /* 1: the step came from [solver] h_s = auto */
  double h_auto_estimate;                 /* auto's step from the contact estimate [s] */
  int h_rechosen;                         /* times the run was redone at a smaller step because
                                             a contact passed FB_H_OMEGA_C_BOUND [-] */
  double h_omega_c_max;                   /* largest h omega_c over the clearance models'
                                             contact steps (0: none measured) [-] */
  int ensemble_auto;                      /* members the run's own sequential test reached
                                             because a model was unsettled (case ensemble_auto;
                                             0: none ran) */
  int seq_looks;                          /* looks it took (verdict_stats.h) [-] */
  int seq_wall_cut;                       /* 1: it stopped before a look whose estimate passed
                                             [run] max_wall_s */
  int ensemble_auto_skipped;              /* 1: it would have run, but its first look's estimate
                                             passed [run] max_wall_s */
  double ensemble_estimate_s;             /* the estimate of the look it did not run [s] */
  double ensemble_wall_s;                 /* wall time of the members beyond the first [s] */
  double models_wall_s;                   /* wall time of the ensemble's models' first run [s] */
  /* where the run's wall time went, beside each model's own (timing.json's parts) */
  double t_run_start;                     /* fb_clock_s() when fb_run_case began [s] */
  double scene_s;                         /* the up-front cost check, the scene stage and
                                             the nominal peaks [s] */
  double metrics_s;                       /* measuring the models: peaks, errors, spikes,
                                             comparisons with the references [s] */
  double redo_s;                          /* the runs h_s = auto redid at a smaller step
                                             (FB_H_AUTO_RETRIES), all but the last [s] */
  double variants_s;                      /* the case's variants (fb_run_variants) [s] */
  double ensemble_cpu_s;                  /* CPU time of the members beyond the first, their
                                             worker processes' included [s] */
  double estimate_s;                      /* the up-front estimate of the models' wall time
                                             (fb_run_estimate, before any h_s = auto redo) [s] */
  double estimate_bytes;                  /* and of their samples' memory [bytes] */
  fb_step_check step_check;               /* the step's single impact, as contact-params
                                             verifies it (fourbar run only) */
  int variant_count;                      /* variants run (fb_run_variants; 0: none) */
  fb_variant_result variant[FB_MAX_VARIANTS]; /* their models' peaks, in c.variant order */
} fb_run;

/* Up-front cost of running case c's models, its step resolved (auto and
 * adaptive: fb_scene_from_case; an adaptive run samples every h_min_s): per
 * model, the samples its series holds (duration / h + 1) times the bytes of
 * one sample of the columns it keeps (and the copies beside it: run.c),
 * over the program's own FB_COST_PROGRAM_BYTES; and the samples times the
 * model's cost per sample, FB_COST_LOAD_FACTOR times over; an ensemble's
 * members (ensemble.h) add its clearance models and references once per
 * member, in rounds of --jobs workers. Sums over the case's models. The
 * cost per sample of a model is its engine's (fb_engine.cost_per_sample,
 * engine.h: CPU time measured over the shipped cases and rounded up),
 * FB_COST_DEFAULT_S for an engine that gives none. What it stands for is
 * timing.json's estimate.models_wall_s (the models, their check
 * integrations, the ensemble's members): measured on the 22 shipped cases
 * whose models run to their end, the estimate is 1.20 to 1.90 times their CPU
 * time (docs/performance.md), FB_COST_LOAD_FACTOR being the margin for a
 * machine others share. */
#define FB_COST_LOAD_FACTOR 1.25
#define FB_COST_DEFAULT_S 5e-6
/* the program's own resident memory, libraries loaded, before any series:
 * measured 31.1 MB (fourbar run, the analytic model alone at h = 1e-3 s) */
#define FB_COST_PROGRAM_BYTES 32e6
/* at most this fraction of the machine's physical memory may be reserved */
#define FB_COST_MEMORY_FRACTION 0.5
void fb_run_estimate(const fb_case *c, double *bytes, double *seconds);
/* What fb_run_estimate's seconds stand for, measured on run r: the wall
 * and CPU time [s] of its models, their check integrations and the case's
 * own ensemble members (their worker processes' CPU included; not an
 * ensemble the run added by itself, not the runs h_s = auto redid). */
void fb_run_estimated_work(const fb_run *r, double *wall_s, double *cpu_s);

/* Checks case c as fb_run_case would before its first model runs: the scene
 * resolves (the step chosen, the corner found; its errors are the case's)
 * and the estimated cost fits (fb_run_estimate against memory and [run]
 * max_wall_s; *over_cost = 1 when that refused it). For the CLI, which
 * checks a case and every variant before any simulation. Errors: those of
 * fb_scene_from_case; FB_ERR_RANGE with the estimate. */
fb_status fb_run_preflight(const fb_case *c, int *over_cost, fb_diag *diag);

/* Runs case c's models and measures each, without the ensemble: what
 * fb_run_case (run_case.h) runs first, and all it runs for an ensemble's
 * member (c->member). A model that stops on numerical trouble keeps its
 * status and the others still run; with h_s = auto a run whose contact
 * passed FB_H_OMEGA_C_BOUND is redone at a smaller step (at most
 * FB_H_AUTO_RETRIES times). Refused before any model runs (FB_ERR_RANGE,
 * with the estimate) when the estimated memory exceeds
 * FB_COST_MEMORY_FRACTION of physical memory or the estimated wall time
 * exceeds [run] max_wall_s; a model still running [run] max_wall_s after
 * the start (a member: after its run's start, c->wall_deadline) stops
 * there with FB_STOP_WALL_TIME. Errors: FB_ERR_ASSEMBLY, FB_ERR_NOMEM,
 * FB_ERR_ARG, FB_ERR_RANGE; on error *r holds nothing that needs freeing. */
fb_status fb_run_models(fb_run *r, const fb_case *c, fb_progress_fn progress, void *user,
                        fb_diag *diag);

void fb_run_free(fb_run *r);

/* fb_run_case, the pipeline's entry (the models, then the ensemble above
 * them), for the callers that include this header */
#include "run_case.h"

#endif
