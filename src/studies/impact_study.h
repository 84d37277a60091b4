/* fourbar impact below the command: one body's single impact in ODE (and
 * a second engine beside it) against the engine-free reference and closed
 * form (impact.h). Every engine is reached through its engine table's
 * impact op (engine.h, fb_engine_impact), never by its own function. */
#ifndef FB_IMPACT_STUDY_H
#define FB_IMPACT_STUDY_H

#include "engine.h"
#include "impact.h"
#include "status.h"

/* What the user asks for. */
typedef struct {
  fb_impact_def d;      /* the impact; d.h is ignored (see h) */
  double h;             /* the engines' step [s]; 0: the estimated contact duration / 200;
                           < 0 is refused (--h-s) */
  fb_impact_opts opts;  /* the engines' own settings (Bullet's solver and iterations) */
  const char *engine;   /* a second engine run beside ODE, by name ("bullet"); NULL: none */
} fb_impact_request;

/* One engine's single impact of the law. */
typedef struct {
  const char *engine;       /* its name ("ode", "bullet") */
  fb_status status;         /* FB_OK, or why it failed (msg) */
  char msg[FB_DIAG_SIZE];
  fb_impact_result r;       /* valid when status is FB_OK */
} fb_impact_run;

#define FB_IMPACT_RUNS_MAX 2

typedef struct {
  fb_impact_def d;          /* as run: h resolved */
  fb_impact_opts opts;      /* as asked */
  double h_omega;           /* h omega_c, omega_c = pi / the reference's contact duration [-] */
  fb_impact_result ref;     /* the reference integration */
  int has_closed_form;      /* 1: closed_form holds the law's closed form */
  fb_impact_result closed_form;
  int n_runs;               /* runs[0] is ODE; runs[1] the second engine, if asked */
  fb_impact_run runs[FB_IMPACT_RUNS_MAX];
  int bad_input;            /* 1: the error fb_impact_study_run returned is bad input */
} fb_impact_study;

/* Runs q: checks the second engine is in this build (and has a single
 * impact of a law), the impact (fb_impact_check, with the step then
 * resolved and checked again), integrates the reference, then each
 * engine's impact (an engine's failure is recorded in its run, not
 * returned) and the closed form. Errors, with out->bad_input 1: FB_ERR_ARG
 * (an engine not in this build, with how to get it), those of
 * fb_impact_check, FB_ERR_RANGE (a negative step); with out->bad_input 0:
 * those of fb_impact_reference (the reference could not be integrated). */
fb_status fb_impact_study_run(fb_impact_study *out, const fb_impact_request *q, fb_diag *diag);

/* (x - ref) / |ref|, or x - ref when ref is 0: the relative errors of
 * fourbar impact [-]. */
double fb_impact_rel(double x, double ref);

#endif
