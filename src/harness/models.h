/* Running one model of a case: the analytic solution or an ODE variant, on
 * the case's time grid, with its cost (steps, wall time) and a status that
 * names why a run stopped early. */
#ifndef FB_MODELS_H
#define FB_MODELS_H

#include <stddef.h>

#include "case.h"
#include "series.h"

typedef enum { FB_KIND_ANALYTIC = 0, FB_KIND_ODE = 1, FB_KIND_REFERENCE = 2 } fb_model_kind;

/* "analytic", "ode" or "reference" (reference.h: minimal coordinates, GSL rk8pd). */
const char *fb_model_kind_name(fb_model_kind k);

/* What a model run produced. */
typedef struct {
  char name[FB_NAME_SIZE]; /* model name from the case */
  fb_model_kind kind;
  char status[256];        /* "ok", or the reason and time the run stopped */
  fb_linkage lengths;      /* link lengths the model used [m] */
  double h;                /* step size (ode) or sampling interval (analytic) [s] */
  size_t steps;            /* steps taken (ode) or samples computed (analytic) */
  double wall_s;           /* wall-clock time of the run [s] */
  fb_series series;        /* samples at t = k h */
  double joint_drift_max;  /* ode: largest hinge anchor separation seen [m] */
  int clearance_mask;      /* bit j: joint j had clearance in this model */
} fb_model_run;

/* Called during long runs with the model name and the fraction done [0, 1]. */
typedef void (*fb_progress_fn)(const char *model, double fraction, void *user);

/* Runs model `name` of case c into *out (out->series is initialised here;
 * release with fb_model_run_free). A numerical failure (NaN or infinity in
 * the state) is not an error: the run stops, the status names the reason and
 * the time, and the samples so far are kept (all finite).
 * Errors: FB_ERR_ARG for an unknown model; FB_ERR_ASSEMBLY, FB_ERR_NOMEM. */
fb_status fb_model_run_one(fb_model_run *out, const fb_case *c, const char *name,
                           fb_progress_fn progress, void *user, fb_diag *diag);

void fb_model_run_free(fb_model_run *r);

/* Lengths a model name implies: nominal, or the case's stack-up corner for
 * names ending in "-stackup" and for the ode-clearance-* and reference models
 * (the paper's clearance cases use the stack-up lengths). */
void fb_model_lengths(const fb_case *c, const char *name, fb_linkage *out);

#endif
