/* Writers of the per-model time series ([run] series): CSV, one file per
 * model, and HDF5, one file per run (docs/series.md). Both write the same
 * columns, named as fb_series_column_name gives them (SI unit in the name),
 * and the same samples: every N-th and every sample of an impact episode
 * (fb_series_keep). */
#ifndef FB_SERIES_WRITE_H
#define FB_SERIES_WRITE_H

#include <stddef.h>

#include "run.h"
#include "series.h"
#include "status.h"

/* The sample selection rule, in words (written into series.h5 and
 * summary.json's "series" object). */
#define FB_SERIES_KEEP_RULE                                                                \
  "every N-th sample (i mod N = 0), the last sample, and every sample of an impact "      \
  "episode (contact state impact, 1, in any clearance joint: its compression and "        \
  "restitution) with one sample either side; free flight and continuous contact are kept " \
  "every N-th sample"

/* Marks in keep (s->n bytes, 1 kept, 0 dropped) the samples written with
 * series_every = every (>= 1; 1 keeps all), by FB_SERIES_KEEP_RULE.
 * Returns the number kept. */
size_t fb_series_keep(const fb_series *s, int every, unsigned char *keep);

/* Writes s as CSV to path (atomically, fileio.h): a header of column names,
 * then one row per kept sample (keep NULL: every sample), each value as
 * "%.12g" would print it (numfmt.h). Errors: FB_ERR_IO naming the file,
 * FB_ERR_NOMEM. */
fb_status fb_series_write_csv(const char *path, const fb_series *s, const unsigned char *keep,
                              fb_diag *diag);

/* One model's columns as a writer reads them, whatever holds them: n
 * samples of ncols columns, column k named name(k) (the CSV's column
 * names, SI unit in the name) with value(k, i) at sample i. */
typedef struct fb_series_table {
  const char *model;   /* the model's name: the HDF5 group */
  const char *engine;  /* its engine's name (group attribute "engine") */
  const char *summary; /* one line on the model (group attribute "model_summary") */
  double h;            /* its step [s] */
  size_t n;            /* samples run */
  size_t ncols;        /* columns */
  const void *self;    /* what name and value read */
  void (*name)(const struct fb_series_table *t, size_t k, char *buf, size_t size);
  double (*value)(const struct fb_series_table *t, size_t k, size_t i);
  const double *(*column)(const struct fb_series_table *t, size_t k); /* optional: column k's
                          n values in a row, or NULL where it has none (value reads it) */
} fb_series_table;

/* Writes tables t[0..n) into one HDF5 file at path (atomically), as
 * fb_series_write_hdf5 lays it out: the root's attributes "case" (case),
 * "series_every" (every), "series_rule" (rule), "summary_json" (summary_json,
 * NULL: none); keep[i] the samples of table i written (NULL, or a NULL
 * entry: every sample). Errors: FB_ERR_IO naming the file, FB_ERR_NOMEM;
 * FB_ERR_ARG in a build without HDF5 (FB_HAVE_HDF5 0). */
fb_status fb_series_write_hdf5_tables(const char *path, const char *case_name, int every,
                                      const char *rule, const fb_series_table *t, int n,
                                      unsigned char *const *keep, const char *summary_json,
                                      fb_diag *diag);

/* Writes every model of r into one HDF5 file at path (atomically): a group
 * /<model name> per model holding one 1-D float64 dataset per column, named
 * as the CSV column, chunked and deflate-compressed, with attributes "unit"
 * (SI) on each dataset; "engine", "model_summary", "h_s", "samples_run" and
 * "samples_written" on each group; and on the root "fourbar_version",
 * "case", "case_file", "series_every", "series_rule" and "summary_json" (the
 * run's summary.json as text: its provenance). keep[i] as fb_series_keep
 * for model i (NULL entries: every sample). Errors: FB_ERR_IO naming the
 * file; FB_ERR_ARG in a build without HDF5 (FB_HAVE_HDF5 0). */
fb_status fb_series_write_hdf5(const char *path, const fb_run *r, unsigned char *const *keep,
                               const char *summary_json, fb_diag *diag);

#endif
