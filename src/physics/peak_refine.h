/* Refinement of a reference's sampled peaks: the rule both references
 * (reference.c's closed forms and the planar core's, run/planar_ref_model.c)
 * apply to their samples, written once here.
 *
 * A reference integrates an ODE and samples it at t = k h; a spike lasting a
 * few samples is missed there by up to ~20 % (the paper four-bar's coupler
 * acceleration spike at h = 1e-5 s: 17.5 %). Every sample that is a local
 * extreme of a contact's column (each impact's force and penetration
 * peaks), and of another column one at least
 * FB_REFERENCE_REFINE_FRACTION of that column's largest magnitude in its
 * part of the run (the start-up, or the peak window from t_split: a
 * window's spike is refined even where the start-up's first impact is five
 * times harder) is re-integrated from the sample before it over two sample
 * intervals, evaluated FB_REFERENCE_REFINE times per interval, the
 * refined quantity's extreme then searched on the exact integration
 * (FB_PEAK_REFINE_SEARCH below), and holds the extreme found there instead
 * of its instantaneous value: peak metrics then see the true spike. The
 * grid alone reads a smooth pulse of duration T within (pi h / (T N))^2 / 8
 * of its extreme (3e-5 for the shortest contacts, T ~ 5 h, at N = 64), a
 * sharper peak by more; the search to the integration's own accuracy. */
#ifndef FB_PEAK_REFINE_H
#define FB_PEAK_REFINE_H

#include <stddef.h>

#define FB_REFERENCE_REFINE 64
#define FB_REFERENCE_REFINE_FRACTION 0.2
/* Of those evaluation points, every FB_REFERENCE_REFINE_STRIDE-th is a stop
 * of the integration (4 stops over the two intervals, one every half
 * sample); the others are ranked on the cubic Hermite interpolant of the
 * stops' states and rates. A refined quantity's extreme is searched on the
 * exact integration between the stops beside its best stop (below), so the
 * stops need only bracket it: every stop forces an rk8pd step, and at 16
 * stops (a stride of 8) the stops' integration cost more than the
 * reference's own (paper case, 2 revolutions: refinement 702 M of the
 * reference's 1,301 M instructions). At a stride of 32 the refined peaks
 * of both references of the paper case, rattling_pin, slider_crank_flores,
 * speed_3000rpm, restitution_0_3 and engines_restitution, and the six-bar's
 * impacts 1 to 3, are those of a stride of 8 to 4e-10 (summary.json), the
 * integrator's own spread between two step sequences. The stride sits
 * between two regimes: where the step resolves the contact (the paper
 * case) rk8pd's own steps span samples and each stop forces one; where a
 * pulse lasts a few samples (the oscillator of tests/test_peak_refine.c,
 * 6 samples a period) the searches' evaluations take several steps each.
 * Measured at strides 16, 32 and 64: the paper case's reference 1,046 M,
 * 995 M and 972 M; the oscillator 343, 413 and 556 right-hand side
 * evaluations a refined sample. */
#define FB_REFERENCE_REFINE_STRIDE 32

/* The search for a refined quantity's extreme: Brent's method (GSL's
 * gsl_min) on the exact integration between the two stops beside its best
 * stop, at most FB_PEAK_REFINE_SEARCH evaluations, to a bracket of
 * FB_PEAK_REFINE_SEARCH_TOL of a grid spacing (2 h / (2
 * FB_REFERENCE_REFINE)); each evaluation integrates from the latest exact
 * state before it (a stop, or an earlier evaluation: Brent's points close
 * in, so each is then one short step), its first step the whole way there
 * (an oscillator of 6 samples a period, tests/test_peak_refine.c: 413
 * right-hand side evaluations a refined sample, 671 from the stops
 * alone). The grid's best point read the Watt six-bar's second impact
 * 2.5e-3 low (a force peak where the damper's ramp saturates, sharper than
 * the grid) and its first impact's penetration 1.7e-3 low (the
 * interpolant placed it 4 points off); the search finds impacts 1 to 3 to 1.5e-9 of an independent model
 * (tests/test_sixbar_independent.py). Brent's parabolic steps reach the
 * extreme's value long before the bracket closes (paper case, 2,322
 * searches: within 1e-11 after 2.3 evaluations on average, where closing
 * a bracket of 1e-4 of a spacing took 11.8): at 1e-2 a search takes 7.0,
 * and the paper case's refined columns move by at most 7e-11. */
#define FB_PEAK_REFINE_SEARCH 20
#define FB_PEAK_REFINE_SEARCH_TOL 1e-2

/* Most quantities one refinement ranks. */
#define FB_PEAK_REFINE_MAX_QUANTITIES 64

/* The reference's ODE as the refinement re-integrates it. */
typedef struct {
  size_t dim;   /* state dimension (>= 1) */
  int nquant;   /* quantities eval ranks, each as a maximum (1 .. MAX_QUANTITIES) */
  /* the right-hand side, in the form of GSL's gsl_odeiv2_system function */
  int (*rhs)(double t, const double y[], double dydt[], void *ctx);
  /* the quantities (nquant) and the rates dydt (dim) at time t, state y */
  void (*eval)(double *quant, double *dydt, double t, const double *y, void *ctx);
  /* the state at sample k into y (dim); returns the time [s] of that state
   * on the right-hand side's clock */
  double (*start)(double *y, size_t k, void *ctx);
  void *ctx;
  double h;     /* sample spacing [s] > 0 */
  double tol;   /* rk8pd relative and absolute tolerance, as the reference's own */
  int window;   /* 1: only the samples from t_split (a check integration, whose window
                   peaks alone are read: its start-up's spikes need no refinement) */
} fb_peak_refine_ode;

/* One refined column: a spike maximum of v takes quantity qmax's largest
 * value, a spike minimum the negative of quantity qmin's largest (-1: that
 * sign is not refined). A column of a contact's force or penetration
 * refines every local extreme (every = 1): each impact is a spike of its
 * own, whatever its size against the run's hardest (the Watt six-bar's
 * third impact, 20.7 N beside the first's 221 N, was read at a raw sample,
 * 5.6 % low against an independent model); a body's alpha only those of
 * at least FB_REFERENCE_REFINE_FRACTION of its largest. */
typedef struct {
  double *v;  /* the column (n), refined in place */
  int qmax;
  int qmin;
  int every;  /* 1: every local extreme (a contact's column), 0: the large ones */
} fb_peak_refine_column;

/* Replaces each spike sample of the columns (n samples at times t [s]) with
 * the extreme of its quantity over (t_{k-1}, t_{k+1}), from an rk8pd
 * integration of ode from sample k - 1 (above); a column's spike is one
 * against the largest |v| of its own part of the run, before or from
 * t_split [s] (fb_largest_abs_split). An interval whose integration fails
 * keeps its samples. Allocates its workspace; out of memory: nothing
 * refined, returns 0 (else 1). */
int fb_peak_refine(fb_peak_refine_column *cols, int ncols, const double *t, size_t n,
                   double t_split, const fb_peak_refine_ode *ode);

#endif
