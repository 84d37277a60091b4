#include "iso2768.h"

#include <math.h>
#include <stdio.h>

#define N_RANGES 8
static const double upper_mm[N_RANGES] = {3, 6, 30, 120, 400, 1000, 2000, 4000};
static const double lower_mm[N_RANGES] = {0.5, 3, 6, 30, 120, 400, 1000, 2000};
/* ISO 2768-1 Table 1 [mm]; NAN where the standard gives no value */
static const double table[4][N_RANGES] = {
    {0.05, 0.05, 0.1, 0.15, 0.2, 0.3, 0.5, NAN}, /* f */
    {0.1, 0.1, 0.2, 0.3, 0.5, 0.8, 1.2, 2},      /* m */
    {0.2, 0.3, 0.5, 0.8, 1.2, 2, 3, 4},          /* c */
    {NAN, 0.5, 1, 1.5, 2.5, 4, 6, 8},            /* v */
};
static const char classes[4] = {'f', 'm', 'c', 'v'};

fb_status fb_iso2768_linear(double *plus_minus, char cls, double size, char *clause,
                            size_t clause_size, fb_diag *diag) {
  int c = -1;
  for (int i = 0; i < 4; i++)
    if (classes[i] == cls) c = i;
  if (c < 0)
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "general tolerance class '%c': ISO 2768-1 classes are f, m, c, v", cls);
  const double mm = size * 1e3;
  char num[32];
  if (!(mm >= 0.5 * (1 - 1e-12)) || mm > 4000.0 * (1 + 1e-12))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "size %s mm: ISO 2768-1 linear tolerances cover 0.5 to 4000 mm",
                       fb_diag_number(num, sizeof num, mm));
  int r = 0;
  while (r < N_RANGES - 1 && mm > upper_mm[r] * (1 + 1e-12)) r++;
  if (isnan(table[c][r]))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "size %s mm, class %c: ISO 2768-1 gives no value here (class %c covers "
                       "%s)",
                       fb_diag_number(num, sizeof num, mm), cls, cls, cls == 'v' ? "over 3 up to 4000 mm" : "0.5 up to 2000 mm");
  *plus_minus = table[c][r] * 1e-3;
  if (clause)
    snprintf(clause, clause_size, "ISO 2768-1 class %c, %s %g up to %g mm", cls,
             r == 0 ? "from" : "over", lower_mm[r], upper_mm[r]);
  return FB_OK;
}
