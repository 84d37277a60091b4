/* How a run's cost grows with what a case asks for (`fourbar bench --grid
 * scaling`, docs/performance.md): the case run in this process at each
 * value of one setting at a time, each run's CPU time (user + sys, its
 * ensemble's worker processes included: fb_clock_cpu_s), wall time and
 * up-front estimate (fb_run_estimate; fb_tol_estimate for a Monte Carlo),
 * and the reference's accepted steps per revolution with its check's.
 * CPU time and step counts are the measures: the wall time of a machine
 * others load grows with their load. */
#ifndef FB_SCALING_H
#define FB_SCALING_H

#include "case.h"
#include "status.h"

/* Rows of one plan at most. */
#define FB_SCALING_MAX_ROWS 32

/* What to vary, each list over the case as given (lists may be empty). */
typedef struct {
  const double *revolutions; /* [run] revolutions, with the reference model alone, run.ensemble
                                1 and run.peaks all (the measurement) */
  int nrevolutions;
  const double *stiffness;   /* [clearance] stiffness_scale, with the case's models, ensemble 1 */
  int nstiffness;
  const int *members;        /* [run] ensemble, with the case's models ... */
  const int *jobs;           /* ... on this many worker processes (--jobs) */
  int nensemble;
  const double *samples;     /* Monte Carlo samples of fourbar stackup, 1 thread */
  int nsamples;
} fb_scaling_plan;

/* The plan of `fourbar bench --grid scaling`: revolutions 1, 2, 4, 8, 16;
 * stiffness x1, x10, x100; an ensemble of 1 and of 4 members at 1 and 2
 * jobs; 1e4 and 1e5 Monte Carlo samples (about 20 s of CPU on the paper
 * case). */
extern const fb_scaling_plan fb_scaling_default;

typedef struct {
  char vary[24];          /* "revolutions", "stiffness_scale", "ensemble", "montecarlo_samples" */
  double value;           /* its value [-] */
  int jobs;               /* worker processes (ensemble), threads (Monte Carlo), else 1 */
  int ran;                /* 1: it ran; else why in status */
  char status[256];       /* "ok" or the run's error */
  double cpu_s;           /* CPU time of the run [s] */
  double wall_s;          /* its wall time [s] */
  double estimate_s;      /* the up-front estimate of the models (run.h) or the Monte Carlo [s] */
  double reference_steps_per_rev; /* the reference model's accepted steps per revolution
                                     (NaN: no model named reference ran) [1/rev] */
  double check_steps_per_rev;     /* its check integration's (NaN: none) [1/rev] */
} fb_scaling_row;

/* Runs plan p on case c into rows (FB_SCALING_MAX_ROWS): revolutions, then
 * stiffness, then the ensembles, then the Monte Carlo, *n rows. A run that
 * fails is a row with ran = 0 and its error. Errors: FB_ERR_ARG when the
 * plan has more rows than FB_SCALING_MAX_ROWS. */
fb_status fb_scaling_run(fb_scaling_row *rows, int *n, const fb_case *c, const fb_scaling_plan *p,
                         fb_diag *diag);

/* The CPU time [s] fb_scaling_run(c, p) would take, estimated before it
 * runs: each run's case by its pilot (pilot.h), each Monte Carlo row by
 * this case's cost per sample (fb_tol_eval_cost); *pilot_s (may be NULL)
 * what the pilots cost. Errors: those of fb_run_case. */
fb_status fb_scaling_estimate(double *cpu_s, double *pilot_s, const fb_case *c,
                              const fb_scaling_plan *p, fb_diag *diag);

#endif
