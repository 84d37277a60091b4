/* ISO 2768-1:1989 general tolerances for linear dimensions (Table 1) and
 * angular dimensions (Table 3, below). Table 1: classes f (fine), m
 * (medium), c (coarse), v (very coarse), size ranges with the upper limit
 * inclusive: 0.5..3, over 3..6, 6..30, 30..120, 120..400,
 * 400..1000, 1000..2000, 2000..4000 mm. Class v has no value up to 3 mm and
 * class f none over 2000 mm: the standard gives none, and neither do we. The
 * paper cites it (and IS 2102) for its link tolerances. */
#ifndef FB_ISO2768_H
#define FB_ISO2768_H

#include "status.h"

/* Permissible deviation +- [m] for nominal size [m] and class 'f', 'm', 'c'
 * or 'v'. Errors: FB_ERR_RANGE for an unknown class, a size outside
 * [0.5, 4000] mm, or a cell the standard leaves empty; the message names the
 * class's valid range. *clause, if not NULL, receives a short source text
 * such as "ISO 2768-1 class m, over 30 up to 120 mm". */
fb_status fb_iso2768_linear(double *plus_minus, char cls, double size, char *clause,
                            size_t clause_size, fb_diag *diag);

/* ISO 2768-1:1989 Table 3, general tolerances for angular dimensions: the
 * permissible deviation +- [rad] of an angle whose shorter leg is leg [m]
 * long, for class 'f', 'm', 'c' or 'v'. Ranges of the shorter leg, the
 * upper limit inclusive: up to 10, over 10 up to 50, 50..120, 120..400,
 * over 400 mm; f and m share one row (1 deg, 30', 20', 10', 5'), c
 * (1 deg 30', 1 deg, 30', 15', 10'), v (3 deg, 2 deg, 1 deg, 30', 20').
 * Errors: FB_ERR_RANGE for an unknown class or a leg not positive and
 * finite. *clause, if not NULL, receives a short source text such as
 * "ISO 2768-1 Table 3 class m, shorter leg over 50 up to 120 mm". */
fb_status fb_iso2768_angular(double *plus_minus, char cls, double leg, char *clause,
                             size_t clause_size, fb_diag *diag);

#endif
