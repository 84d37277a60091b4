/* A run's cost estimated from the case itself: two short runs of the case
 * (its models, settings and step as they are, the simulated time cut to
 * d1 and 2 d1) give each cost's fixed part and its part per simulated
 * second, and the line through them gives the cost of the whole duration.
 * The long commands that run a case many times (fourbar bench) or once at
 * length (a planar case's fourbar run) estimate from it (work.h's rule: a
 * count times a cost measured on this case). d1 is FB_PILOT_FRACTION of
 * the duration, FB_PILOT_STEPS output steps at least; a run too short for
 * that is run whole (d1 half of it), so the estimate is the run itself.
 * The process's first pilot runs d1 once more before it: what a process
 * sets up once goes there, not into the slope. */
#ifndef FB_PILOT_H
#define FB_PILOT_H

#include "case.h"
#include "status.h"

/* The first pilot's share of the duration: 1/64, so that the two pilots
 * cost 3/64 (5 %) of the run they estimate, beyond its fixed costs twice. */
#define FB_PILOT_FRACTION (1.0 / 64.0)
/* The fewest output steps a pilot simulates: 50, so that a run's costs
 * per step show beside its set-up. */
#define FB_PILOT_STEPS 50.0

/* What a run of a case costs, extrapolated from its pilots. */
typedef struct {
  double cpu_s;                    /* the run's CPU time, its worker processes' included [s] */
  double wall_s;                   /* its wall time [s] */
  int n;                           /* models */
  double model_s[FB_MAX_MODELS];   /* each model's wall time, its set-up excluded [s] (what the
                                      bench's repeat rule reads) */
  double setup_s[FB_MAX_MODELS];   /* each model's set-up [s] */
  double pilot_cpu_s;              /* what the pilots cost [s] */
} fb_pilot;

/* The cost of running case c (a four-bar or slider-crank: fb_run_case; a
 * planar case: fb_planar_run_case) for its whole duration, from two pilots
 * over [run] peaks = all. Errors: those of the run (a case that does not
 * run fails its pilot as it would fail its run). */
fb_status fb_pilot_case(fb_pilot *p, const fb_case *c, fb_diag *diag);

#endif
