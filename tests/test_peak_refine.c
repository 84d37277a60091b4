/* The references' peak refinement (peak_refine.h) on a motion whose extremes
 * are known in closed form: an undamped oscillator x'' = -omega^2 x,
 * x(t) = A sin(omega t + phi), sampled at t = k h with a period of 6
 * samples, a pulse as short against the samples as an impact's (the Watt
 * six-bar's first impact lasts 2.6 samples at its 5e-6 s). Sampling alone
 * misses an extreme by up to A (1 - cos(pi / 6)) = 13 %; refined, every
 * local extreme is the oscillator's amplitude. And what the refinement
 * costs, as a count of the right-hand side's evaluations, not time. */
#include <gsl/gsl_errno.h>
#include <math.h>

#include "fb_test.h"
#include "peak_refine.h"

#define AMPLITUDE 2.5
#define H_S 1e-3
#define OMEGA (2.0 * M_PI / (6.0 * H_S))
#define PHASE 0.3 /* rad: the extremes fall between the samples, at varying offsets */
#define SAMPLES 400
#define RK8PD_TOL 1e-12 /* the references' own (reference.h FB_REFERENCE_TOL) */

/* A refined extreme against the amplitude. The bound is the search's: the
 * extreme lies in Brent's final bracket, at most FB_PEAK_REFINE_SEARCH_TOL
 * of a grid spacing (2 h / (2 FB_REFERENCE_REFINE)) wide, so the best
 * point found is within delta of it and reads at most A (omega delta)^2 / 2
 * low: 1.34e-8 relative here. Measured 5.9e-15 (Brent's parabolic steps
 * land on a smooth extreme); a sample read unrefined misses by up to
 * 1 - cos(pi / 6) = 0.13 (2.5e-2 at this phase). */
#define PEAK_REL_TOL 1.4e-8

/* The right-hand side's evaluations per refined sample (an rk8pd step is
 * 13): measured 413, with 4 stops over the two sample intervals and each
 * search evaluation integrated from the latest exact state before it;
 * from the stops alone it took 671, and with a stop every sixteenth of a
 * sample and the search closed to 1e-4 of a spacing 528 (both measured).
 * The bound fails a return to either. */
#define RHS_PER_REFINED_MAX 480

typedef struct {
  long rhs; /* right-hand side evaluations */
} oscillator;

static int rhs(double t, const double y[], double dydt[], void *p) {
  (void)t;
  ((oscillator *)p)->rhs++;
  dydt[0] = y[1];
  dydt[1] = -OMEGA * OMEGA * y[0];
  return GSL_SUCCESS;
}

/* quantity 0: x (its maxima), quantity 1: -x (x's minima) */
static void eval(double *q, double *dydt, double t, const double *y, void *p) {
  (void)t, (void)p;
  q[0] = y[0];
  q[1] = -y[0];
  dydt[0] = y[1];
  dydt[1] = -OMEGA * OMEGA * y[0];
}

/* the exact state at sample k */
static double start(double *y, size_t k, void *p) {
  (void)p;
  const double t = (double)k * H_S;
  y[0] = AMPLITUDE * sin(OMEGA * t + PHASE);
  y[1] = AMPLITUDE * OMEGA * cos(OMEGA * t + PHASE);
  return t;
}

static void test_every_extreme_is_the_amplitude(void **state) {
  (void)state;
  static double t[SAMPLES], x[SAMPLES], sampled[SAMPLES];
  for (size_t k = 0; k < SAMPLES; k++) {
    double y[2];
    t[k] = start(y, k, NULL);
    x[k] = sampled[k] = y[0];
  }
  oscillator o = {0};
  const fb_peak_refine_ode ode = {2, 2, rhs, eval, start, &o, H_S, RK8PD_TOL, 0};
  fb_peak_refine_column col = {x, 0, 1, 1};
  /* t_split past the run: one part, every local extreme refined */
  assert_int_equal(fb_peak_refine(&col, 1, t, SAMPLES, 2.0 * SAMPLES * H_S, &ode), 1);
  int refined = 0;
  double worst = 0.0, worst_sampled = 0.0;
  for (size_t k = 1; k + 1 < SAMPLES; k++) {
    const int top = sampled[k] > sampled[k - 1] && sampled[k] > sampled[k + 1];
    const int bottom = sampled[k] < sampled[k - 1] && sampled[k] < sampled[k + 1];
    if (!top && !bottom) {
      assert_true(x[k] == sampled[k]); /* not a spike: left as sampled */
      continue;
    }
    refined++;
    const double want = top ? AMPLITUDE : -AMPLITUDE;
    worst = fmax(worst, fabs(x[k] - want) / AMPLITUDE);
    worst_sampled = fmax(worst_sampled, fabs(sampled[k] - want) / AMPLITUDE);
  }
  report_residual("refined extreme against the amplitude", worst, PEAK_REL_TOL);
  report_residual("sampled extreme against the amplitude", worst_sampled, PEAK_REL_TOL);
  report_residual("rhs evaluations per refined sample", (double)o.rhs / refined,
                  RHS_PER_REFINED_MAX);
  /* two extremes a period of 6 samples */
  assert_true(refined >= SAMPLES / 3 - 2);
  assert_true(worst_sampled > 0.01); /* the samples do miss the extremes */
  assert_true(worst <= PEAK_REL_TOL);
  assert_true((double)o.rhs <= (double)RHS_PER_REFINED_MAX * refined);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_every_extreme_is_the_amplitude),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
