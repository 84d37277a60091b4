/* The reference integration of a planar description with clearance joints
 * (planar_dynamics.h): GSL's rk8pd (gsl_odeiv2_step_rk8pd) at relative and
 * absolute tolerance tol, as reference.h, on the index-1 DAE in absolute
 * coordinates, with the state projected back onto the constraints at every
 * output sample.
 *
 * The choice (docs/planar.md): the augmented (index-1) system is general
 * and needs no Newton solve inside the right-hand side, where coordinate
 * partitioning would solve the dependent coordinates at every one of
 * rk8pd's 13 evaluations per step and switch partitions near singular
 * positions. Its cost is drift: the position and velocity constraints are
 * not integrated, only their second derivative, so they drift at the
 * integrator's error. Projection (mass-weighted least squares,
 * fb_planar_cmass_project) at each output sample removes it without
 * changing the dynamics between samples, as a Baumgarte term would (whose
 * gains depend on the step). tests/test_planar_dynamics.c measures the
 * drift with and without the projection and the agreement with the
 * closed-form references (reference.h, slider_crank_dynamics.h). */
#ifndef FB_PLANAR_REFERENCE_H
#define FB_PLANAR_REFERENCE_H

#include <stddef.h>

#include "planar_dynamics.h"

/* Accepted rk8pd steps allowed per output sample on average
 * (FB_REFERENCE_STEPS_PER_SAMPLE's reason, reference.h). */
#define FB_PLANAR_REF_STEPS_PER_SAMPLE 200

/* What a run measured. */
typedef struct {
  size_t steps;   /* accepted integrator steps */
  size_t evals;   /* right-hand side evaluations */
  double drift_q; /* largest |Phi| of the joints' length rows at a sample, before its
                     projection [m] */
  double drift_v; /* largest |G q' - nu| of those rows at a sample, before its projection [m/s] */
} fb_planar_ref_stats;

/* Integrates d from y0 (2 nq, at t = 0) and samples at t = k h,
 * k = 0 .. n - 1: y (n x 2 nq: q, q'), acc (n x nq: q''; may be NULL) and
 * contact (n x njoints; may be NULL). project: 1 projects the state onto
 * the constraints at every sample (the reference), 0 only measures how far
 * it is (the drift without projection). stats (may be NULL).
 * Errors: FB_ERR_RANGE for tol outside [1e-13, 1e-3], h <= 0 or n < 1;
 * FB_ERR_NUMERIC when the integrator fails, the step budget runs out or
 * the constraint set turns singular (message names the time; the samples
 * before are kept); FB_ERR_NOMEM. */
fb_status fb_planar_ref_run(double *y, double *acc, fb_planar_contact *contact, size_t n,
                            double h, const double *y0, fb_planar_dyn *d, double tol,
                            int project, fb_planar_ref_stats *stats, fb_diag *diag);

#endif
