/* Sampled time series of one model on its time grid: the data every model
 * produces and every metric and writer consumes (column-major arrays). */
#ifndef FB_SERIES_H
#define FB_SERIES_H

#include <stddef.h>

#include "status.h"

/* Columns of a series, in CSV order; names carry their SI unit. */
#define FB_SERIES_COLUMNS(X)             \
  X(t, "time_s")                         \
  X(crank_angle, "crank_angle_rad")      \
  X(coupler_angle, "coupler_angle_rad")  \
  X(coupler_omega, "coupler_omega_rad_s") \
  X(coupler_alpha, "coupler_alpha_rad_s2") \
  X(follower_angle, "follower_angle_rad") \
  X(follower_omega, "follower_omega_rad_s") \
  X(follower_alpha, "follower_alpha_rad_s2")

typedef struct {
  size_t n;   /* samples held */
  size_t cap; /* samples allocated */
#define FB_SERIES_FIELD(name, col) double *name; /* (n) */
  FB_SERIES_COLUMNS(FB_SERIES_FIELD)
#undef FB_SERIES_FIELD
} fb_series;

/* One sample: the values of every column at one instant (SI units). */
typedef struct {
#define FB_SAMPLE_FIELD(name, col) double name;
  FB_SERIES_COLUMNS(FB_SAMPLE_FIELD)
#undef FB_SAMPLE_FIELD
} fb_sample;

/* Allocates room for cap samples. Errors: FB_ERR_NOMEM. */
fb_status fb_series_init(fb_series *s, size_t cap);

/* Appends one sample, growing the arrays when full. Errors: FB_ERR_NOMEM. */
fb_status fb_series_push(fb_series *s, const fb_sample *x);

/* Reads sample i (i < n) into *x. */
void fb_series_get(const fb_series *s, size_t i, fb_sample *x);

/* Frees the arrays; s is left empty and may be re-initialised. */
void fb_series_free(fb_series *s);

/* Number of columns and the CSV name of column k (k < count). */
size_t fb_series_column_count(void);
const char *fb_series_column_name(size_t k);
/* Value of column k at sample i. */
double fb_series_value(const fb_series *s, size_t k, size_t i);

#endif
