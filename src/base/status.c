#include "status.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

fb_status fb_diag_set(fb_diag *diag, fb_status s, const char *fmt, ...) {
  if (diag) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(diag->msg, sizeof diag->msg, fmt, ap);
    va_end(ap);
  }
  return s;
}

void fb_diag_clear(fb_diag *diag) {
  if (diag) diag->msg[0] = '\0';
}

/* the fewest significant digits, at most max, that read back as x; no
 * exponent for a whole part %g would shorten (10 is "10", not "1e+01") */
static const char *shortest(char *buf, size_t size, double x, int max) {
  for (int p = 1; p <= max; p++) {
    snprintf(buf, size, "%.*g", p, x);
    if (strchr(buf, 'e') && fabs(x) >= 1.0 && fabs(x) < 1e15) continue;
    if (strtod(buf, NULL) == x) return buf;
  }
  snprintf(buf, size, "%.*g", max, x);
  return buf;
}

const char *fb_diag_number(char *buf, size_t size, double x) {
  /* 500.0001 stays 500.0001 where %g would print 500, and 279.4 stays
   * 279.4; at most 15 digits, which also hides the last-bit noise of a unit
   * conversion (4000.0001 mm through metres is 4000.0001000000002) */
  return shortest(buf, size, x, 15);
}

const char *fb_diag_exact(char *buf, size_t size, double x) {
  if (!isfinite(x)) { /* a computed value, never a typed one: said in words */
    snprintf(buf, size, "%s", x != x ? "not a number" : x > 0 ? "beyond the largest double"
                                                               : "below the lowest double");
    return buf;
  }
  return shortest(buf, size, x, 17); /* 17 digits read back every double */
}
