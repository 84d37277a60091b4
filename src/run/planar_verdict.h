/* What an engine's model of a planar case is judged on (issue 58): the
 * verdict words and bases of verdict.h, reached by the four-bar's rules
 * (docs/verdicts.md) as far as a planar run measures them, without its
 * ensembles (planar_verdict.c; fb_planar_verdicts in planar_run.h sets them).
 *
 * An ideal model: every moving body's omega and alpha window peaks against
 * the analytic model's, each error relative to the larger magnitude of that
 * body's two analytic extremes of the quantity (a peak near zero has no
 * relative error of its own), a quantity whose analytic extremes are below
 * FB_PLANAR_PEAK_FLOOR_REL of the largest over the bodies left out (the
 * driven crank's alpha: rounding); beyond FB_IDEAL_PEAK_ERROR_BOUND (run.h)
 * warn, else ok (basis pointwise).
 *
 * A clearance model: against the reference of the same law in the run
 * (model_table.h, fb_model_reference_of). Its impacts and the reference's
 * are the contact episodes of their clearance joint (unbroken runs of
 * positive penetration; a touch whose peak force is below
 * FB_MATCHED_GRAZING_SHARE of the reference's largest is left out, as
 * metrics.h leaves it out of the matched bound). The model parts from its
 * reference at the first sample where a body's angle differs from the
 * reference's by more than FB_DIVERGE_ANGLE_FRACTION x c / the body's size
 * (the largest distance between two of its joints: the rotation that moves
 * its far joint by that share of the radial clearance c, metrics.h's
 * coupler rule for every body). Before that, impacts are paired in order
 * by onset within FB_IMPACT_MATCH_REV_FRACTION of a revolution, an onset
 * without a partner left unpaired (an extra touch does not shift every
 * later pair); a pair's peaks are each run's largest over the two episodes'
 * span together, the engine's refined by the parabola through its largest
 * sample and the two beside it (series.h's rule for an engine's spikes;
 * the reference's samples hold their extremes, peak_refine.h).
 *   1. The first impact, one to one: unpaired, or its peak force or peak
 *      penetration off the reference's by more than
 *      FB_FAITHFUL_PENETRATION_TOL (impact.h): error, pointwise.
 *   2. A reference that did not converge (its check integration), or a
 *      model that parts: warn, unsettled (the four-bar's ensemble would
 *      decide on statistics; a planar run has none yet).
 *   3. Kept one to one to the end: every matched impact within
 *      FB_MATCHED_IMPACT_ERROR_BOUND (metrics.h) ok, else error, pointwise.
 * A stopped model, or a failed reference, warn without a basis; no
 * yardstick in the run: unchecked. */
#ifndef FB_PLANAR_VERDICT_H
#define FB_PLANAR_VERDICT_H

#include "verdict.h"

/* An analytic extreme below this share of the largest of its quantity over
 * the moving bodies is not compared: the driven crank turns at constant
 * speed, its analytic alpha is rounding (1e-10 rad/s^2 beside 3e4 on the
 * six-bar) and an engine's the solver's residual (1e-8) [-]. */
#define FB_PLANAR_PEAK_FLOOR_REL 1e-6

/* An engine model's verdict and what it measured (NaN where not measured). */
typedef struct {
  int judged;                 /* 1: an engine's model (the fields below are set) */
  fb_verdict_word word;
  fb_verdict_basis basis;
  char reason[400];
  int impacts;                /* the model's impacts over the run (grazing touches left out) */
  int impacts_reference;      /* the reference's */
  int matched;                /* paired one to one from t = 0 before it parts */
  double parts_s;             /* onset where it parts [s]; INFINITY: it does not */
  double first_t_error_s;     /* the first impact's onset minus the reference's [s] */
  double first_force_rel;     /* its peak force against the reference's [-] */
  double first_penetration_rel; /* its peak penetration against the reference's [-] */
  int sampled;                /* 1: its impacts compared with the reference's samples at the
                                 same instants (planar_verdict.c compare), 0: with the
                                 reference's continuous extremes */
  double first_resolution_force_rel; /* sampled: the reference's first-impact peak force at
                                 the model's instants against its continuous extreme, what the
                                 step resolves of the impact (<= 0) [-]; NaN otherwise */
  double first_resolution_penetration_rel; /* the same for the penetration [-] */
  double matched_force_rel_max; /* largest |force error| of the matched impacts [-] */
  double matched_penetration_rel_max; /* same for the penetration [-] */
  double peak_rel_max;        /* an ideal model's largest window-peak error [-] */
  int rigid;                  /* 1: a rigid (impulsive) model: its force and penetration are
                                 not compared; its first impact's rebound ratio against the
                                 law's cr is */
  double first_rebound_ratio; /* a rigid model's first rebound: the rate of |e| out of the
                                 wall over the rate into it [-]; NaN: not measured */
  double first_impulse_n_s;   /* a rigid model's first impact's impulse, its force over the
                                 steps of the impact [N s] */
  double restitution;         /* a rigid model: the law's cr its rebound is held to [-] */
} fb_planar_verdict;

#endif
