#include "series.h"

#include <stdlib.h>
#include <string.h>

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

fb_status fb_series_push(fb_series *s, const fb_sample *x) {
  if (s->n == s->cap) {
    size_t cap = s->cap ? 2 * s->cap : 16;
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
  s->n++;
  return FB_OK;
}

void fb_series_get(const fb_series *s, size_t i, fb_sample *x) {
#define FB_SERIES_GET(name, col) x->name = s->name[i];
  FB_SERIES_COLUMNS(FB_SERIES_GET)
#undef FB_SERIES_GET
}

void fb_series_free(fb_series *s) {
#define FB_SERIES_FREE(name, col) free(s->name);
  FB_SERIES_COLUMNS(FB_SERIES_FREE)
#undef FB_SERIES_FREE
  memset(s, 0, sizeof *s);
}

size_t fb_series_column_count(void) { return FB_NCOLUMNS; }

const char *fb_series_column_name(size_t k) {
  return k < FB_NCOLUMNS ? column_names[k] : NULL;
}

double fb_series_value(const fb_series *s, size_t k, size_t i) {
  double *cols[FB_NCOLUMNS];
  columns((fb_series *)s, cols);
  return cols[k][i];
}
