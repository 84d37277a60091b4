/* Fast decimal formatting of doubles for the series writers: the exact
 * bytes of printf's "%.12g" (C11 7.21.6.1, the g conversion with precision
 * 12), without printf's arbitrary-precision path for the common case. */
#ifndef FB_NUMFMT_H
#define FB_NUMFMT_H

#include <stddef.h>

/* Longest text fb_numfmt_g12 writes, with its terminating NUL
 * ("-1.23456789012e-308" is 19 characters; "-nan" and "-inf" are shorter). */
#define FB_NUMFMT_G12_SIZE 24

/* Writes x into buf (FB_NUMFMT_G12_SIZE bytes) exactly as
 * snprintf(buf, size, "%.12g", x) does in the C locale and returns the
 * length (no NUL counted). Method: x is scaled by an exact power of ten
 * (10^k, |k| <= 22) to a 12-digit integer in one correctly rounded
 * operation; when that product lies within 1e-3 of a rounding tie, or x is
 * outside [1e-10, 1e12) in magnitude, zero, or not finite, snprintf does
 * the work, so every output equals printf's. */
size_t fb_numfmt_g12(char *buf, double x);

#endif
