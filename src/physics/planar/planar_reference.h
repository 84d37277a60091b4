/* The reference integration of a planar description with clearance joints
 * (planar_relative.h): GSL's rk8pd (gsl_odeiv2_step_rk8pd) at relative and
 * absolute tolerance tol, as reference.h, on the clearance joints'
 * relative coordinates (and an undriven description's free coordinate),
 * sampled every h.
 *
 * The state is what the contact law reads (the pins' eccentricities, a
 * slider's tilt and offset), in metres and radians of the clearance's
 * size: the step control sees the contact's motion at its own scale, with
 * no rounding of the mechanism's size in it, and the joints that hold are
 * solved at every evaluation, so positions and velocities keep them to
 * the rounding level with no projection. tests/test_planar_relative.c
 * measures both and the agreement with the closed-form references
 * (reference.h, slider_crank_dynamics.h). */
#ifndef FB_PLANAR_REFERENCE_H
#define FB_PLANAR_REFERENCE_H

#include <stddef.h>

#include "planar_relative.h"

/* Accepted rk8pd steps allowed per output sample on average
 * (FB_REFERENCE_STEPS_PER_SAMPLE's reason, reference.h). */
#define FB_PLANAR_REF_STEPS_PER_SAMPLE 200

/* What a run measured. */
typedef struct {
  size_t samples; /* samples written (n, or those before the integration stopped) */
  size_t steps;   /* accepted integrator steps */
  int budget;     /* 1: the integration stopped on its step budget */
  size_t evals;   /* right-hand side evaluations */
  double closure; /* largest |Phi| of the joints that hold at a sample, lengths only [m] */
} fb_planar_ref_stats;

/* Integrates d from its steady start (fb_planar_rel_steady, t = 0) and
 * samples at t = k h, k = 0 .. n - 1: y (n x 2 nq: q, q'), acc (n x nq:
 * q''; may be NULL), contact (n x njoints; may be NULL) and z (n x dim:
 * the state; may be NULL). stats (may be NULL).
 * Errors: FB_ERR_RANGE for tol outside [1e-13, 1e-3], h <= 0 or n < 1;
 * FB_ERR_NUMERIC when the integrator fails, the step budget runs out or
 * the positions cannot be solved (message names the time; the samples
 * before are kept); those of fb_planar_rel_steady; FB_ERR_NOMEM. */
fb_status fb_planar_ref_run(double *y, double *acc, fb_planar_contact *contact, double *z,
                            size_t n, double h, fb_planar_rel *d, double tol,
                            fb_planar_ref_stats *stats, fb_diag *diag);

/* fb_planar_ref_run from the steady start with every pin moved off its
 * hole's centre by offset [m] (fb_planar_rel_steady_offset; NULL: none). */
fb_status fb_planar_ref_run_offset(double *y, double *acc, fb_planar_contact *contact, double *z,
                                   size_t n, double h, fb_planar_rel *d, double tol,
                                   const double *offset, fb_planar_ref_stats *stats,
                                   fb_diag *diag);

/* The columns of a sampled reference its refinement rewrites
 * (fb_planar_ref_refine). */
typedef struct {
  const double *t;       /* sample times [s] (n) */
  double *const *alpha;  /* per moving body (the description's body b at b - 1): its angular
                            acceleration [rad/s^2] (n), or NULL: not refined */
  int njoints;           /* clearance joints refined */
  const int *joint;      /* their indices in the description (njoints) */
  double *const *force;  /* each one's contact force [N] (njoints x n) */
  double *const *pen;    /* each one's penetration [m] (njoints x n) */
} fb_planar_ref_columns;

/* The samples at spikes of each clearance joint's force and penetration
 * and every refined body's alpha (the driven body's is the drive's, zero:
 * never) replaced by their extremes between the neighbouring samples
 * (peak_refine.h, the closed-form reference's rule), re-integrating d
 * from the run's samples: y (n x 2 nq: q, q') and z (n x dim: the
 * states) as fb_planar_ref_run wrote them, n samples h [s] apart, at
 * tolerance tol; spikes are measured in their part of the run, before or
 * from t_split [s]; window 1 refines the samples from t_split alone (a
 * check integration's). Out of memory: nothing refined. */
void fb_planar_ref_refine(const fb_planar_ref_columns *col, size_t n, double h, fb_planar_rel *d,
                          const double *y, const double *z, double tol, double t_split,
                          int window);

#endif
