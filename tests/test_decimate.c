/* Decimation for drawing (decimate.h): min/max per pixel column keeps every
 * spike that stands out of its column, with its value, and no more than two
 * samples per column; the path decimation keeps every pixel the path
 * crosses and every change of state. */
#include <math.h>
#include <stdlib.h>

#include "decimate.h"
#include "fb_test.h"

/* a long series against the columns of one figure panel: the paper case's
 * revolution at its automatic step is 18,000 samples, a revolution at
 * h = 1e-7 s 600,000 */
#define N 600000
#define COLUMNS 650
/* spikes of one sample, each far beyond what the smooth curve moves in one
 * pixel column (100 sin(3 x): at most 2.9 per column of 650 over 360 deg) */
#define SPIKE 50.0

static double x[N], y[N];
static size_t keep[N];

static int kept(const size_t *k, size_t m, size_t i) {
  for (size_t q = 0; q < m; q++)
    if (k[q] == i) return 1;
  return 0;
}

static void smooth(int wrap_laps) {
  for (size_t i = 0; i < N; i++) {
    const double deg = 360.0 * (double)wrap_laps * (double)i / (double)N;
    /* one lap over [0, 360), or a cw crank running backwards over several */
    x[i] = wrap_laps == 1 ? deg : fmod(360.0 - fmod(deg, 360.0), 360.0);
    y[i] = 100.0 * sin(3.0 * deg * M_PI / 180.0);
  }
}

static void test_spikes_survive(void **state) {
  (void)state;
  smooth(1);
  /* up and down, in a rise and in a fall, on a column's first sample, at
   * the ends of the series */
  const size_t at[] = {0, 12345, 54321, 99999, 150000, 300000, 451234, N - 1};
  const double sign[] = {1, 1, -1, 1, -1, -1, 1, -1};
  const int ns = (int)(sizeof at / sizeof at[0]);
  for (int k = 0; k < ns; k++) y[at[k]] += sign[k] * SPIKE;
  const size_t m = fb_decimate_minmax(x, y, N, 0.0, 360.0, COLUMNS, keep);
  report_residual("kept of 600000", (double)m, 2.0 * COLUMNS);
  assert_true(m <= 2 * COLUMNS);
  assert_true(m >= COLUMNS); /* a column holding samples keeps at least one */
  for (size_t q = 1; q < m; q++) assert_true(keep[q] > keep[q - 1]);
  for (int k = 0; k < ns; k++) {
    if (!kept(keep, m, at[k])) fail_msg("spike at sample %zu (%+g) was decimated away", at[k], sign[k] * SPIKE);
  }
  /* every column's extremes: the envelope drawn is the series' */
  double lo = INFINITY, hi = -INFINITY, klo = INFINITY, khi = -INFINITY;
  for (size_t i = 0; i < N; i++) lo = fmin(lo, y[i]), hi = fmax(hi, y[i]);
  for (size_t q = 0; q < m; q++) klo = fmin(klo, y[keep[q]]), khi = fmax(khi, y[keep[q]]);
  assert_true(lo == klo && hi == khi);
}

/* a clockwise crank: the angle runs backwards and wraps every turn; a run
 * ends wherever the column changes, so the wrap starts a new one */
static void test_spikes_survive_wrapping_angle(void **state) {
  (void)state;
  smooth(3);
  const size_t at[] = {7, 200000, 200001 + N / 3, 599990};
  const double sign[] = {-1, 1, 1, -1};
  for (int k = 0; k < 4; k++) y[at[k]] += sign[k] * SPIKE;
  const size_t m = fb_decimate_minmax(x, y, N, 0.0, 360.0, COLUMNS, keep);
  assert_true(m <= 2 * (3 * COLUMNS + 3));
  for (int k = 0; k < 4; k++)
    if (!kept(keep, m, at[k])) fail_msg("spike at sample %zu lost across the wrap", at[k]);
}

/* a sample that is not a number is left out, and does not end a run */
static void test_nan_skipped(void **state) {
  (void)state;
  const double xs[6] = {0.0, 0.1, 0.2, 0.3, NAN, 0.5};
  const double ys[6] = {1.0, NAN, 5.0, -2.0, 9.0, 3.0};
  size_t k[6];
  const size_t m = fb_decimate_minmax(xs, ys, 6, 0.0, 1.0, 1, k);
  assert_int_equal(m, 2); /* one column: its minimum and maximum, in order */
  assert_int_equal(k[0], 2);
  assert_int_equal(k[1], 3);
}

/* a pin's orbit: noisy circles, thousands of samples per pixel; every
 * pixel the path crosses and every change of state is kept */
static void test_path_keeps_pixels_and_states(void **state) {
  (void)state;
  const size_t n = 200000;
  double *px = malloc(n * sizeof *px), *py = malloc(n * sizeof *py), *mark = malloc(n * sizeof *mark);
  assert_non_null(px);
  assert_non_null(py);
  assert_non_null(mark);
  for (size_t i = 0; i < n; i++) {
    const double a = 20.0 * M_PI * (double)i / (double)n;
    const double r = 14.5 + 0.3 * sin(37.0 * a);
    px[i] = r * cos(a);
    py[i] = r * sin(a);
    mark[i] = (i / 7919) % 3; /* a change of state every 7919 samples */
  }
  const double cell = 0.05; /* um */
  const size_t m = fb_decimate_path(px, py, mark, n, cell, keep);
  assert_true(m < n / 4);
  assert_int_equal(keep[0], 0);
  assert_int_equal(keep[m - 1], n - 1);
  for (size_t i = 1; i < n; i++)
    if (mark[i] != mark[i - 1] && !kept(keep, m, i)) fail_msg("change of state at %zu not kept", i);
  /* each sample lies in the pixel of the last sample kept at or before it */
  size_t q = 0;
  for (size_t i = 0; i < n; i++) {
    while (q + 1 < m && keep[q + 1] <= i) q++;
    const size_t k = keep[q];
    assert_true(floor(px[i] / cell) == floor(px[k] / cell) && floor(py[i] / cell) == floor(py[k] / cell));
  }
  free(px);
  free(py);
  free(mark);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_spikes_survive),
      cmocka_unit_test(test_spikes_survive_wrapping_angle),
      cmocka_unit_test(test_nan_skipped),
      cmocka_unit_test(test_path_keeps_pixels_and_states),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
