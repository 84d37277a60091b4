#include "decimate.h"

#include <math.h>

/* the pixel column of x on [x0, x1] over columns, clamped */
static long column_of(double x, double x0, double x1, int columns) {
  const double c = floor((x - x0) / (x1 - x0) * (double)columns);
  return c < 0.0 ? 0 : c >= (double)columns ? (long)columns - 1 : (long)c;
}

size_t fb_decimate_minmax(const double *x, const double *y, size_t n, double x0, double x1,
                          int columns, size_t *keep) {
  size_t m = 0;
  size_t i = 0;
  while (i < n && (isnan(x[i]) || isnan(y[i]))) i++;
  while (i < n) {
    /* one run: consecutive samples in the column of sample i */
    const long c = column_of(x[i], x0, x1, columns);
    size_t lo = i, hi = i, j = i + 1;
    for (; j < n; j++) {
      if (isnan(x[j]) || isnan(y[j])) continue;
      if (column_of(x[j], x0, x1, columns) != c) break;
      if (y[j] < y[lo]) lo = j;
      if (y[j] > y[hi]) hi = j;
    }
    if (lo == hi) {
      keep[m++] = lo;
    } else {
      keep[m++] = lo < hi ? lo : hi;
      keep[m++] = lo < hi ? hi : lo;
    }
    i = j;
  }
  return m;
}

size_t fb_decimate_path(const double *x, const double *y, const double *mark, size_t n,
                        double cell, size_t *keep) {
  size_t m = 0;
  double cx = 0.0, cy = 0.0;
  for (size_t i = 0; i < n; i++) {
    const double px = floor(x[i] / cell), py = floor(y[i] / cell);
    const int changes = i > 0 && mark && mark[i] != mark[i - 1];
    if (i == 0 || i + 1 == n || changes || px != cx || py != cy) {
      keep[m++] = i;
      cx = px;
      cy = py;
    }
  }
  return m;
}
