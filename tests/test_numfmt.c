/* The series writers' number formatter (numfmt.h) against its definition:
 * fb_numfmt_g12(x) must give exactly the bytes of snprintf("%.12g", x), the
 * format the CSV files have always had. Oracle: glibc's printf, on edge
 * values (powers of ten, ties, both ends of the fast range, the switches
 * between fixed and exponent notation) and on random doubles of every
 * magnitude the series hold. */
#include <string.h>

#include "numfmt.h"
#include "fb_test.h"

/* random doubles drawn: enough to hit the tie fallback thousands of times */
#define RANDOM_SAMPLES 2000000

static void expect_same(double x) {
  char mine[FB_NUMFMT_G12_SIZE], ref[64];
  const size_t n = fb_numfmt_g12(mine, x);
  snprintf(ref, sizeof ref, "%.12g", x);
  if (strcmp(mine, ref) != 0 || n != strlen(ref))
    fail_msg("x = %a: fb_numfmt_g12 gives '%s' (%zu), printf '%s'", x, mine, n, ref);
}

/* fb_numfmt_g(x, digits) against snprintf("%.*g", digits, x) */
static void expect_same_g(double x, int digits) {
  char mine[FB_NUMFMT_G12_SIZE], ref[64];
  const size_t n = fb_numfmt_g(mine, x, digits);
  snprintf(ref, sizeof ref, "%.*g", digits, x);
  if (strcmp(mine, ref) != 0 || n != strlen(ref))
    fail_msg("x = %a, %d digits: fb_numfmt_g gives '%s' (%zu), printf '%s'", x, digits, mine, n, ref);
}

static void test_edges(void **state) {
  (void)state;
  const double fixed[] = {0.0,     -0.0,    1.0,       -1.0,      0.5,        0.1,
                          1e-4,    9.99999999999e-5, 1e-5, 1e-10,  9.9999999999e-11,
                          1e11,    1e12,    999999999999.0, 999999999999.5, 99999999999.95,
                          123456789012.0,  0.000123456789012345, 3.3e-6, 2.5e-12,
                          1.0000000000005, 1.00000000000049, 9.9999999999995, 9.99999999999949,
                          0.1234567890125, 5e-324, 1.7976931348623157e308, INFINITY, -INFINITY,
                          NAN,     2.0,     4.0,     1e22,      1e-22,     12345.678,
                          -0.00021, 6.283185307179586, 3.141592653589793, 1e100, 1e-100};
  for (size_t k = 0; k < sizeof fixed / sizeof fixed[0]; k++) expect_same(fixed[k]);
  /* every power of ten, its neighbours and the tie values just around it */
  for (int e = -30; e <= 30; e++) {
    const double p = pow(10.0, e);
    expect_same(p);
    expect_same(nextafter(p, 0.0));
    expect_same(nextafter(p, INFINITY));
    expect_same(p * (1.0 - 5e-13));
    expect_same(p * (1.0 + 5e-13));
    expect_same(-p * 9.999999999995);
  }
}

/* the next random double of the xorshift state *z: a mantissa in [1, 10)
 * and an exponent over the range the series use (1e-14 m .. 1e13 rad/s^2),
 * a quarter of them rounded to `decimals` decimals like a time grid's */
static double random_value(uint64_t *z, double decimals) {
  *z ^= *z << 13;
  *z ^= *z >> 7;
  *z ^= *z << 17;
  const double mant = 1.0 + 9.0 * (double)(*z >> 11) / 9007199254740992.0;
  const int e = (int)((*z >> 3) % 28) - 14;
  double x = mant * pow(10.0, e);
  if (*z & 1) x = -x;
  if ((*z >> 1) % 4 == 0) x = round(x * decimals) / decimals;
  return x;
}

static void test_random(void **state) {
  (void)state;
  uint64_t z = 0x9e3779b97f4a7c15ULL;
  for (long i = 0; i < RANDOM_SAMPLES; i++) expect_same(random_value(&z, 1e6));
}

/* every precision (report-data.js uses 10) on the edges and on random
 * doubles: the switch to exponent notation moves with the precision */
static void test_precisions(void **state) {
  (void)state;
  uint64_t z = 0x2545f4914f6cdd1dULL;
  for (int digits = 1; digits <= FB_NUMFMT_DIGITS_MAX; digits++) {
    for (int e = -12; e <= 13; e++) {
      const double p = pow(10.0, e);
      expect_same_g(p, digits);
      expect_same_g(-nextafter(p, 0.0), digits);
      expect_same_g(nextafter(p, INFINITY), digits);
      expect_same_g(p * (1.0 - 0.5 * pow(10.0, -digits)), digits);
      expect_same_g(p * 9.5, digits);
    }
    for (long i = 0; i < RANDOM_SAMPLES / 10; i++) expect_same_g(random_value(&z, 1e4), digits);
  }
  expect_same_g(NAN, 10);
  expect_same_g(-0.0, 10);
  expect_same_g(0.0, 10);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_edges),
      cmocka_unit_test(test_random),
      cmocka_unit_test(test_precisions),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
