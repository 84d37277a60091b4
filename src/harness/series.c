#include "series.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "case.h"

static const char *const column_names[] = {
#define FB_SERIES_NAME(name, col) col,
    FB_SERIES_COLUMNS(FB_SERIES_NAME)
#undef FB_SERIES_NAME
};

#define FB_NCOLUMNS (sizeof column_names / sizeof column_names[0])

static double **columns(fb_series *s, double **cols) {
  size_t k = 0;
#define FB_SERIES_PTR(name, col) cols[k++] = s->name;
  FB_SERIES_COLUMNS(FB_SERIES_PTR)
#undef FB_SERIES_PTR
  return cols;
}

fb_status fb_series_init(fb_series *s, size_t cap) {
  memset(s, 0, sizeof *s);
  if (cap == 0) cap = 16;
#define FB_SERIES_ALLOC(name, col)                   \
  s->name = malloc(cap * sizeof(double));            \
  if (!s->name) {                                    \
    fb_series_free(s);                               \
    return FB_ERR_NOMEM;                             \
  }
  FB_SERIES_COLUMNS(FB_SERIES_ALLOC)
#undef FB_SERIES_ALLOC
  s->cap = cap;
  return FB_OK;
}

static const char *const contact_suffix[FB_CONTACT_COLS] = {"force_n", "penetration_m",
                                                            "ecc_x_m", "ecc_y_m", "state"};

fb_status fb_series_enable_contact(fb_series *s, int mask) {
  for (int j = 0; j < 4; j++) {
    if (!(mask & (1 << j))) continue;
    for (int q = 0; q < FB_CONTACT_COLS; q++) {
      s->contact[j][q] = calloc(s->cap ? s->cap : 1, sizeof(double));
      if (!s->contact[j][q]) return FB_ERR_NOMEM;
    }
    s->contact_mask |= 1 << j;
  }
  return FB_OK;
}

/* the load arrays, drive torque first (1 + 4 x 2) */
static int load_arrays(fb_series *s, double ***out) {
  out[0] = &s->drive_torque;
  for (int j = 0; j < 4; j++)
    for (int c = 0; c < 2; c++) out[1 + 2 * j + c] = &s->reaction[j][c];
  return 9;
}

fb_status fb_series_enable_loads(fb_series *s) {
  double **a[9];
  const int n = load_arrays(s, a);
  for (int k = 0; k < n; k++) {
    *a[k] = calloc(s->cap ? s->cap : 1, sizeof(double));
    if (!*a[k]) return FB_ERR_NOMEM;
  }
  s->has_loads = 1;
  return FB_OK;
}

fb_status fb_series_push(fb_series *s, const fb_sample *x) {
  if (s->n == s->cap) {
    size_t cap = s->cap ? 2 * s->cap : 16;
    if (s->has_loads) {
      double **a[9];
      const int na = load_arrays(s, a);
      for (int k = 0; k < na; k++) {
        double *p = realloc(*a[k], cap * sizeof(double));
        if (!p) return FB_ERR_NOMEM;
        *a[k] = p;
      }
    }
    for (int j = 0; j < 4; j++)
      for (int q = 0; q < FB_CONTACT_COLS && (s->contact_mask & (1 << j)); q++) {
        double *p = realloc(s->contact[j][q], cap * sizeof(double));
        if (!p) return FB_ERR_NOMEM;
        s->contact[j][q] = p;
      }
#define FB_SERIES_GROW(name, col)                          \
  {                                                        \
    double *p = realloc(s->name, cap * sizeof(double));    \
    if (!p) return FB_ERR_NOMEM;                           \
    s->name = p;                                           \
  }
    FB_SERIES_COLUMNS(FB_SERIES_GROW)
#undef FB_SERIES_GROW
    s->cap = cap;
  }
#define FB_SERIES_SET(name, col) s->name[s->n] = x->name;
  FB_SERIES_COLUMNS(FB_SERIES_SET)
#undef FB_SERIES_SET
  for (int j = 0; j < 4; j++)
    if (s->contact_mask & (1 << j))
      for (int q = 0; q < FB_CONTACT_COLS; q++) s->contact[j][q][s->n] = x->contact[j][q];
  if (s->has_loads) {
    s->drive_torque[s->n] = x->drive_torque;
    for (int j = 0; j < 4; j++)
      for (int c = 0; c < 2; c++) s->reaction[j][c][s->n] = x->reaction[j][c];
  }
  s->n++;
  return FB_OK;
}

void fb_series_get(const fb_series *s, size_t i, fb_sample *x) {
#define FB_SERIES_GET(name, col) x->name = s->name[i];
  FB_SERIES_COLUMNS(FB_SERIES_GET)
#undef FB_SERIES_GET
  for (int j = 0; j < 4; j++)
    for (int q = 0; q < FB_CONTACT_COLS; q++)
      x->contact[j][q] = (s->contact_mask & (1 << j)) ? s->contact[j][q][i] : 0.0;
  x->drive_torque = s->has_loads ? s->drive_torque[i] : 0.0;
  for (int j = 0; j < 4; j++)
    for (int c = 0; c < 2; c++) x->reaction[j][c] = s->has_loads ? s->reaction[j][c][i] : 0.0;
}

void fb_series_free(fb_series *s) {
  double **a[9];
  const int na = load_arrays(s, a);
  for (int k = 0; k < na; k++) free(*a[k]);
  for (int j = 0; j < 4; j++)
    for (int q = 0; q < FB_CONTACT_COLS; q++) free(s->contact[j][q]);
#define FB_SERIES_FREE(name, col) free(s->name);
  FB_SERIES_COLUMNS(FB_SERIES_FREE)
#undef FB_SERIES_FREE
  memset(s, 0, sizeof *s);
}

static int enabled_count(const fb_series *s) {
  int n = 0;
  for (int j = 0; j < 4; j++) n += (s->contact_mask >> j) & 1;
  return n;
}

/* joint and contact column of extra column x (0-based after the kinematic ones) */
static void contact_column(const fb_series *s, size_t x, int *joint, int *col) {
  int seen = 0;
  for (int j = 0; j < 4; j++) {
    if (!(s->contact_mask & (1 << j))) continue;
    if (x < (size_t)(seen + 1) * FB_CONTACT_COLS) {
      *joint = j;
      *col = (int)(x - (size_t)seen * FB_CONTACT_COLS);
      return;
    }
    seen++;
  }
  *joint = -1;
  *col = -1;
}

/* columns: the kinematic ones, the contact columns of enabled joints, then
 * the load columns when held */
static size_t contact_columns(const fb_series *s) { return (size_t)enabled_count(s) * FB_CONTACT_COLS; }

size_t fb_series_column_count(const fb_series *s) {
  return FB_NCOLUMNS + contact_columns(s) + (s->has_loads ? FB_LOAD_COLS : 0);
}

static const char *joint_word(int j, char *buf, size_t size) {
  snprintf(buf, size, "%s", fb_joint_name(j));
  for (char *p = buf; *p; p++)
    if (*p == '-') *p = '_';
  return buf;
}

const char *fb_series_column_name(const fb_series *s, size_t k, char *buf, size_t size) {
  if (k < FB_NCOLUMNS) {
    snprintf(buf, size, "%s", column_names[k]);
    return buf;
  }
  char joint[32];
  if (k >= FB_NCOLUMNS + contact_columns(s)) {
    const size_t q = k - FB_NCOLUMNS - contact_columns(s);
    if (!s->has_loads || q >= FB_LOAD_COLS) return NULL;
    static const char *const part[3] = {"reaction_x_n", "reaction_y_n", "reaction_n"};
    if (q == 0) snprintf(buf, size, "drive_torque_n_m");
    else snprintf(buf, size, "%s_%s", joint_word((int)(q - 1) / 3, joint, sizeof joint), part[(q - 1) % 3]);
    return buf;
  }
  int j, q;
  contact_column(s, k - FB_NCOLUMNS, &j, &q);
  if (j < 0) return NULL;
  snprintf(buf, size, "%s_%s", joint_word(j, joint, sizeof joint), contact_suffix[q]);
  return buf;
}

double fb_series_value(const fb_series *s, size_t k, size_t i) {
  if (k < FB_NCOLUMNS) {
    double *cols[FB_NCOLUMNS];
    columns((fb_series *)s, cols);
    return cols[k][i];
  }
  if (k >= FB_NCOLUMNS + contact_columns(s)) {
    const size_t q = k - FB_NCOLUMNS - contact_columns(s);
    if (!s->has_loads || q >= FB_LOAD_COLS) return 0.0;
    if (q == 0) return s->drive_torque[i];
    const int j = (int)(q - 1) / 3, c = (int)(q - 1) % 3;
    return c < 2 ? s->reaction[j][c][i] : hypot(s->reaction[j][0][i], s->reaction[j][1][i]);
  }
  int j, q;
  contact_column(s, k - FB_NCOLUMNS, &j, &q);
  return j < 0 ? 0.0 : s->contact[j][q][i];
}

const double *fb_series_column(const fb_series *s, size_t k) {
  if (k < FB_NCOLUMNS) {
    double *cols[FB_NCOLUMNS];
    columns((fb_series *)s, cols);
    return cols[k];
  }
  if (k >= FB_NCOLUMNS + contact_columns(s)) {
    const size_t q = k - FB_NCOLUMNS - contact_columns(s);
    if (!s->has_loads || q >= FB_LOAD_COLS) return NULL;
    if (q == 0) return s->drive_torque;
    const int j = (int)(q - 1) / 3, c = (int)(q - 1) % 3;
    return c < 2 ? s->reaction[j][c] : NULL;
  }
  int j, q;
  contact_column(s, k - FB_NCOLUMNS, &j, &q);
  return j < 0 ? NULL : s->contact[j][q];
}

int fb_series_is_spike(const double *v, size_t k, int sign, double fraction, double big) {
  const double a = sign * v[k];
  return a > 0.0 && a >= sign * v[k - 1] && a >= sign * v[k + 1] && a >= fraction * big;
}

double fb_series_largest_abs(const double *v, size_t n) {
  double m = 0.0;
  for (size_t i = 0; i < n; i++) m = fmax(m, fabs(v[i]));
  return m;
}

/* vertex of the parabola through (-1, ym), (0, y0), (1, yp), for the
 * extreme of sign `sign` at y0 */
static double vertex(double ym, double y0, double yp, int sign) {
  const double den = ym - 2.0 * y0 + yp;
  if (!(sign * den < 0.0) || !(sign * ym > 0.0) || !(sign * yp > 0.0)) return y0;
  return y0 - 0.125 * (yp - ym) * (yp - ym) / den;
}

static void refine_column(double *v, size_t n, double fraction) {
  if (!v || n < 3) return;
  const double big = fb_series_largest_abs(v, n);
  if (!(big > 0.0)) return;
  /* vertices from the original samples: a refined value must not feed its
   * neighbour's parabola */
  double prev = v[0];
  for (size_t k = 1; k + 1 < n; k++) {
    const double here = v[k];
    const double vk[3] = {prev, here, v[k + 1]};
    for (int sign = -1; sign <= 1; sign += 2)
      if (fb_series_is_spike(vk, 1, sign, fraction, big)) v[k] = vertex(prev, here, v[k + 1], sign);
    prev = here;
  }
}

void fb_series_refine_peaks(fb_series *s, double fraction) {
  refine_column(s->coupler_alpha, s->n, fraction);
  refine_column(s->follower_alpha, s->n, fraction);
  for (int j = 0; j < 4; j++) {
    if (!(s->contact_mask & (1 << j))) continue;
    refine_column(s->contact[j][FB_C_FORCE], s->n, fraction);
    refine_column(s->contact[j][FB_C_PEN], s->n, fraction);
  }
}

void fb_series_attribute_to_step_start(fb_series *s) {
  if (s->n < 2) return;
  double *cols[2 + 2 * 4];
  int nc = 0;
  cols[nc++] = s->coupler_alpha;
  cols[nc++] = s->follower_alpha;
  for (int j = 0; j < 4; j++)
    if (s->contact_mask & (1 << j)) {
      cols[nc++] = s->contact[j][FB_C_FORCE];
      cols[nc++] = s->contact[j][FB_C_STATE];
    }
  for (int q = 0; q < nc; q++) {
    memmove(cols[q], cols[q] + 1, (s->n - 1) * sizeof(double));
    /* the last sample's step was never taken: hold the last value */
    cols[q][s->n - 1] = cols[q][s->n - 2];
  }
}
