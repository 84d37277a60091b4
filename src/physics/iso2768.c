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

/* the row of class cls in the tables, or -1 with diag filled */
static int class_row(char cls, fb_diag *diag) {
  for (int i = 0; i < 4; i++)
    if (classes[i] == cls) return i;
  fb_diag_set(diag, FB_ERR_RANGE, "general tolerance class '%c': ISO 2768-1 classes are f, m, c, "
              "v", cls);
  return -1;
}

fb_status fb_iso2768_linear(double *plus_minus, char cls, double size, char *clause,
                            size_t clause_size, fb_diag *diag) {
  const int c = class_row(cls, diag);
  if (c < 0) return FB_ERR_RANGE;
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

#define N_LEGS 5
/* ISO 2768-1 Table 3's shorter-leg ranges [mm] (the last open above) */
static const double leg_upper_mm[N_LEGS - 1] = {10, 50, 120, 400};
/* ISO 2768-1 Table 3 [minutes of arc] */
static const double angular_min[4][N_LEGS] = {
    {60, 30, 20, 10, 5},  /* f */
    {60, 30, 20, 10, 5},  /* m */
    {90, 60, 30, 15, 10}, /* c */
    {180, 120, 60, 30, 20}, /* v */
};

fb_status fb_iso2768_angular(double *plus_minus, char cls, double leg, char *clause,
                             size_t clause_size, fb_diag *diag) {
  const int c = class_row(cls, diag);
  if (c < 0) return FB_ERR_RANGE;
  char num[32];
  if (!(leg > 0.0) || !isfinite(leg))
    return fb_diag_set(diag, FB_ERR_RANGE, "shorter leg %s mm: an angle's leg must be positive "
                       "and finite", fb_diag_number(num, sizeof num, leg * 1e3));
  const double mm = leg * 1e3;
  int r = 0;
  while (r < N_LEGS - 1 && mm > leg_upper_mm[r] * (1 + 1e-12)) r++;
  *plus_minus = angular_min[c][r] / 60.0 * M_PI / 180.0;
  if (clause) {
    if (r == 0)
      snprintf(clause, clause_size, "ISO 2768-1 Table 3 class %c, shorter leg up to 10 mm", cls);
    else if (r == N_LEGS - 1)
      snprintf(clause, clause_size, "ISO 2768-1 Table 3 class %c, shorter leg over 400 mm", cls);
    else
      snprintf(clause, clause_size, "ISO 2768-1 Table 3 class %c, shorter leg over %g up to %g mm",
               cls, leg_upper_mm[r - 1], leg_upper_mm[r]);
  }
  return FB_OK;
}
