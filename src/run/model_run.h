/* Running one model of a case on its engine (engine.h), on the case's time
 * grid, with its cost (steps, wall time) and a typed stop reason (outcome.h) for a run
 * stopped early. The model is a row of the model table (model_table.h); the
 * scene is the case resolved once (scene.h). */
#ifndef FB_MODEL_RUN_H
#define FB_MODEL_RUN_H

#include <stddef.h>

#include "engine.h"
#include "model_table.h"
#include "outcome.h"
#include "scene.h"
#include "series.h"

/* Steps between two readings of the clock against the run's wall-time
 * deadline (fb_case.wall_deadline): a reading costs ~25 ns, the cheapest
 * step ~2 us, so the check costs under 0.1 %, and a model overruns its
 * deadline by at most 16 steps. */
#define FB_WALL_CHECK_STEPS 16

/* What a model run produced. */
typedef struct {
  char name[FB_NAME_SIZE]; /* model name (the row's) */
  const fb_model *model;   /* the row of the model table */
  fb_stop stop;            /* why the run stopped early (kind FB_STOP_NONE: it did not);
                              writers render it (outcome_text.h) */
  fb_linkage lengths;      /* link lengths the model used [m] */
  double h;                /* step size (ode) or sampling interval (analytic) [s] */
  size_t steps;            /* steps taken (ode), samples computed (analytic), accepted
                              integrator steps (reference) */
  double wall_s;           /* wall-clock time of the run [s] */
  double cpu_s;            /* its CPU time (fb_clock_cpu_s) [s] */
  double setup_s;          /* of which set-up [s]: the engine's create (MuJoCo: the MJCF
                              compile) and mapping the series' storage (fb_series_touch);
                              an engine that computes its series in create
                              (computes_in_create: analytic, reference) books create as
                              stepping_s instead */
  double stepping_s;       /* of which the engine's stepping [s]: its step() calls (or the
                              share of them its stepping_s op names); the rest of wall_s -
                              setup_s is the harness's sampling (sample, reactions, checks,
                              the series) */
  fb_series series;        /* samples at t = k h */
  double joint_drift_max;  /* ode: largest hinge anchor separation seen [m] */
  int clearance_mask;      /* bit j: joint j had clearance in this model */
  const char *builder;     /* who built an engine's model ([solver] builder): "kit" (its
                              engine-kit binding) or "hand" (the engine's own world); NULL for
                              the analytic and reference models */
  fb_collider collider;    /* collider of its clearance joints (FB_COLLIDER_NONE without) */
  int segments;            /* faceted boxes or ccd segments of the ring [-]; 0 for the others */
  double bore_ovality;     /* ccd: the ellipse bore's diameter excess [m]; 0: circle */
  int has_step_stats;      /* 1 for a model that followed [solver] h_s = adaptive */
  fb_step_stats step_stats; /* its steps: count, shortest and longest h and their counts */
  int has_provenance;      /* 1 when the engine kept provenance[] */
  fb_contact_provenance provenance[FB_MECH_MAX_JOINTS]; /* per clearance joint, at the end
                                                           of the run */
} fb_model_run;

/* Called during long runs with the model name and the fraction done [0, 1]. */
typedef void (*fb_progress_fn)(const char *model, double fraction, void *user);

/* Runs model m on scene def into *out (out->series is initialised here;
 * release with fb_model_run_free), through the interface of the model's
 * engine: create, then step and sample def->steps times. A numerical failure
 * (NaN or infinity in the state, penetration beyond def->penetration_limit
 * on a guarded engine, the reference integrator giving up) is not an error:
 * the run stops, stop names the reason, time, step and joint, and the samples
 * so far are kept (all finite).
 * Errors: FB_ERR_ARG (engine not built, model needs what the scene lacks);
 * FB_ERR_ASSEMBLY, FB_ERR_RANGE (scene check), FB_ERR_NOMEM. */
fb_status fb_model_run_one(fb_model_run *out, const fb_scene *def, const fb_model *m,
                           fb_progress_fn progress, void *user, fb_diag *diag);

void fb_model_run_free(fb_model_run *r);

/* The length [m] among r's lengths of case c's first output body (mechanism.h
 * fb_mech_outputs; a body's index is its index in the per-link lengths: the
 * four-bar's and the slider-crank's coupler), the body whose angle
 * fb_metrics_divergence compares: its angle tolerance is the clearance over
 * this length. NAN for a mechanism without output bodies. */
double fb_model_run_output_length(const fb_model_run *r, const fb_case *c);

#endif
