#include "numfmt.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

/* exact powers of ten: every 10^k with 0 <= k <= 22 is a double */
static const double pow10_exact[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                       1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                       1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

/* 10^k for -10 <= k <= 12 (index k + 10), for the exponent estimate */
static const double pow10_range[23] = {1e-10, 1e-9, 1e-8, 1e-7, 1e-6, 1e-5, 1e-4, 1e-3,
                                       1e-2,  1e-1, 1e0,  1e1,  1e2,  1e3,  1e4,  1e5,
                                       1e6,   1e7,  1e8,  1e9,  1e10, 1e11, 1e12};

/* 10^k as an integer, 0 <= k <= 12 */
static const uint64_t pow10_int[13] = {1ULL,         10ULL,         100ULL,         1000ULL,
                                       10000ULL,     100000ULL,     1000000ULL,     10000000ULL,
                                       100000000ULL, 1000000000ULL, 10000000000ULL, 100000000000ULL,
                                       1000000000000ULL};

/* the product x 10^k (or quotient) has one rounding error of at most half
 * an ulp: below 2^40 (12 digits) that is 2^-13 < 1.3e-4, so a fractional
 * part farther than this from 1/2 rounds the same way as the exact value */
#define FB_NUMFMT_TIE_MARGIN 1e-3

static size_t slow(char *buf, double x, int digits) {
  const int n = snprintf(buf, FB_NUMFMT_G12_SIZE, "%.*g", digits, x);
  return n > 0 ? (size_t)n : 0;
}

/* `digits` significant digits of a = |x| as m in [10^(digits-1), 10^digits)
 * with a ~ m 10^(e-digits+1); 0 when the product is too close to a tie to
 * decide without printf */
static int scaled(double a, int e, int digits, uint64_t *m) {
  const int k = digits - 1 - e;
  double y;
  if (k >= 0) {
    if (k > 22) return 0;
    y = a * pow10_exact[k];
  } else {
    if (-k > 22) return 0;
    y = a / pow10_exact[-k];
  }
  const double f = floor(y);
  const double frac = y - f;
  if (fabs(frac - 0.5) < FB_NUMFMT_TIE_MARGIN) return 0;
  *m = (uint64_t)f + (frac > 0.5);
  return 1;
}

/* floor(log10(a)) for a normal double, or one less next to a power of
 * ten (the caller corrects it): the binary exponent times log10(2) */
static int decimal_exponent(double a) {
  uint64_t bits;
  memcpy(&bits, &a, sizeof bits);
  const int e2 = (int)((bits >> 52) & 0x7ff) - 1023;
  /* 78913 / 2^18 = 0.30102920532 ~ log10(2); the arithmetic shift floors */
  int e = (e2 * 78913) >> 18;
  if (e + 1 >= -10 && e + 1 <= 12 && a >= pow10_range[e + 1 + 10]) e++;
  return e;
}

size_t fb_numfmt_g12(char *buf, double x) { return fb_numfmt_g(buf, x, 12); }

size_t fb_numfmt_g(char *buf, double x, int digits) {
  if (digits < 1 || digits > FB_NUMFMT_DIGITS_MAX) return slow(buf, x, digits < 1 ? 1 : FB_NUMFMT_DIGITS_MAX);
  if (x == 0.0) { /* the free-flight contact columns: many zeros */
    if (signbit(x)) {
      memcpy(buf, "-0", 3);
      return 2;
    }
    memcpy(buf, "0", 2);
    return 1;
  }
  const double a = fabs(x);
  if (!(a >= 1e-10 && a < 1e12)) return slow(buf, x, digits); /* tiny, huge, inf, nan */
  const uint64_t lo = pow10_int[digits - 1], hi = pow10_int[digits];
  int e = decimal_exponent(a);
  uint64_t m;
  if (!scaled(a, e, digits, &m)) return slow(buf, x, digits);
  /* log10 can be one off next to a power of ten; rounding can carry to 10^digits */
  if (m < lo) {
    e--;
    if (!scaled(a, e, digits, &m)) return slow(buf, x, digits);
  }
  if (m >= hi) {
    if (m == hi) {
      m = lo;
      e++;
    } else {
      e++;
      if (!scaled(a, e, digits, &m)) return slow(buf, x, digits);
      if (m >= hi) {
        m = lo;
        e++;
      }
    }
  }
  if (m < lo || m >= hi) return slow(buf, x, digits);
  char d[FB_NUMFMT_DIGITS_MAX];
  for (int i = digits - 1; i >= 0; i--) {
    d[i] = (char)('0' + m % 10);
    m /= 10;
  }
  int nd = digits; /* significant digits kept: trailing zeros removed (%g) */
  while (nd > 1 && d[nd - 1] == '0') nd--;
  char *p = buf;
  if (x < 0) *p++ = '-';
  if (e >= -4 && e < digits) {
    if (e >= 0) {
      for (int i = 0; i <= e; i++) *p++ = d[i];
      if (nd > e + 1) {
        *p++ = '.';
        for (int i = e + 1; i < nd; i++) *p++ = d[i];
      }
    } else {
      *p++ = '0';
      *p++ = '.';
      for (int i = 0; i < -e - 1; i++) *p++ = '0';
      for (int i = 0; i < nd; i++) *p++ = d[i];
    }
  } else {
    *p++ = d[0];
    if (nd > 1) {
      *p++ = '.';
      for (int i = 1; i < nd; i++) *p++ = d[i];
    }
    *p++ = 'e';
    *p++ = e < 0 ? '-' : '+';
    const int ae = e < 0 ? -e : e;
    if (ae >= 100) *p++ = (char)('0' + ae / 100);
    *p++ = (char)('0' + ae / 10 % 10);
    *p++ = (char)('0' + ae % 10);
  }
  *p = '\0';
  return (size_t)(p - buf);
}

const char *fb_num_text(char *buf, size_t size, const char *fmt, double x, const char *none) {
  if (isfinite(x)) snprintf(buf, size, fmt, x);
  else snprintf(buf, size, "%s", none);
  return buf;
}
