/* Fast decimal formatting of doubles for the series writers: the exact
 * bytes of printf's "%.12g" (C11 7.21.6.1, the g conversion with precision
 * 12; fb_numfmt_g: any precision up to 12), without printf's
 * arbitrary-precision path for the common case. */
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

/* The most significant digits fb_numfmt_g takes: the scaled integer stays
 * below 2^40, where one rounding is far from a tie (numfmt.c) */
#define FB_NUMFMT_DIGITS_MAX 12

/* fb_numfmt_g12 for any precision: x into buf (FB_NUMFMT_G12_SIZE bytes)
 * exactly as snprintf(buf, size, "%.*g", digits, x) does in the C locale,
 * digits in [1, FB_NUMFMT_DIGITS_MAX] (outside it, clamped to that range);
 * returns the length. report-data.js's series use 10 digits. */
size_t fb_numfmt_g(char *buf, double x, int digits);

/* The one rule for a number that could not be measured (NaN or an
 * infinity) in a text output (docs/outputs.md, "Values that could not be
 * measured"): x printed with fmt (one double conversion) when finite, else
 * none: FB_NUM_NONE_TABLE in printed tables and report.md,
 * FB_NUM_NONE_CSV in a CSV (JSON writes null). Returns buf. */
const char *fb_num_text(char *buf, size_t size, const char *fmt, double x, const char *none);

#define FB_NUM_NONE_TABLE "-"
#define FB_NUM_NONE_CSV ""

/* fb_num_text in a buffer of its own (32 bytes) for a printf argument; the
 * buffer lives until the end of the enclosing block (C11 6.5.2.5). */
#define FB_NUM_CELL(fmt, x, none) fb_num_text((char[32]){0}, 32, (fmt), (x), (none))

#endif
