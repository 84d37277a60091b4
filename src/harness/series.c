#include "series.h"

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

fb_status fb_series_push(fb_series *s, const fb_sample *x) {
  if (s->n == s->cap) {
    size_t cap = s->cap ? 2 * s->cap : 16;
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
}

void fb_series_free(fb_series *s) {
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

size_t fb_series_column_count(const fb_series *s) {
  return FB_NCOLUMNS + (size_t)enabled_count(s) * FB_CONTACT_COLS;
}

const char *fb_series_column_name(const fb_series *s, size_t k, char *buf, size_t size) {
  if (k < FB_NCOLUMNS) {
    snprintf(buf, size, "%s", column_names[k]);
    return buf;
  }
  int j, q;
  contact_column(s, k - FB_NCOLUMNS, &j, &q);
  if (j < 0) return NULL;
  char joint[32];
  snprintf(joint, sizeof joint, "%s", fb_joint_name(j));
  for (char *p = joint; *p; p++)
    if (*p == '-') *p = '_';
  snprintf(buf, size, "%s_%s", joint, contact_suffix[q]);
  return buf;
}

double fb_series_value(const fb_series *s, size_t k, size_t i) {
  if (k < FB_NCOLUMNS) {
    double *cols[FB_NCOLUMNS];
    columns((fb_series *)s, cols);
    return cols[k][i];
  }
  int j, q;
  contact_column(s, k - FB_NCOLUMNS, &j, &q);
  return j < 0 ? 0.0 : s->contact[j][q][i];
}
