/* The HDF5 series writer (series_write.h): the only file that includes
 * HDF5 headers; built when meson finds libhdf5 (FB_HAVE_HDF5). */
#include <errno.h>
#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fb_config.h"
#include "fileio.h"
#include "model_table.h"
#include "series_write.h"

/* samples per chunk: 64 KiB of float64, large enough for deflate to work on
 * and small enough that a reader of one impact reads little else */
#define FB_H5_CHUNK 8192
/* deflate level 1 after the shuffle filter: the paper case's file is 37.4 MB
 * (37.0 MB at level 4, in twice the time; without shuffle 48.1 MB in 1.7
 * times the time; chunks of 4096 or 16384 samples no faster; docs/series.md) */
#define FB_H5_DEFLATE 1
/* the in-memory file grows in steps of this many bytes (H5Pset_fapl_core) */
#define FB_H5_CORE_INCREMENT (4 << 20)

/* a variable-length UTF-8 string attribute: h5py reads it as str, pandas
 * and MATLAB (h5readatt) as text */
static int attr_string(hid_t obj, const char *name, const char *value) {
  hid_t type = H5Tcopy(H5T_C_S1);
  if (type < 0) return -1;
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  hid_t space = H5Screate(H5S_SCALAR);
  hid_t a = H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  int rc = a < 0 ? -1 : H5Awrite(a, type, &value);
  if (a >= 0) H5Aclose(a);
  H5Sclose(space);
  H5Tclose(type);
  return rc < 0 ? -1 : 0;
}

static int attr_double(hid_t obj, const char *name, double value) {
  hid_t space = H5Screate(H5S_SCALAR);
  hid_t a = H5Acreate2(obj, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT);
  int rc = a < 0 ? -1 : H5Awrite(a, H5T_NATIVE_DOUBLE, &value);
  if (a >= 0) H5Aclose(a);
  H5Sclose(space);
  return rc < 0 ? -1 : 0;
}

static int attr_long(hid_t obj, const char *name, long long value) {
  hid_t space = H5Screate(H5S_SCALAR);
  hid_t a = H5Acreate2(obj, name, H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT);
  int rc = a < 0 ? -1 : H5Awrite(a, H5T_NATIVE_LLONG, &value);
  if (a >= 0) H5Aclose(a);
  H5Sclose(space);
  return rc < 0 ? -1 : 0;
}

/* the SI unit a column name ends in ("time_s" -> "s"); "1" for the state */
static const char *unit_of(const char *name) {
  static const struct {
    const char *suffix, *unit;
  } u[] = {{"_rad_s2", "rad/s^2"}, {"_rad_s", "rad/s"}, {"_rad", "rad"}, {"_n_m", "N m"},
           {"_n", "N"},            {"_m", "m"},         {"_s", "s"},     {"_state", "1"}};
  const size_t n = strlen(name);
  for (size_t k = 0; k < sizeof u / sizeof u[0]; k++) {
    const size_t m = strlen(u[k].suffix);
    if (n > m && strcmp(name + n - m, u[k].suffix) == 0) return u[k].unit;
  }
  return "1";
}

/* one model's group: a dataset per column of the kept samples */
static int write_group(hid_t file, const fb_series_table *t, const unsigned char *keep,
                       int every, double *buf) {
  hid_t g = H5Gcreate2(file, t->model, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (g < 0) return -1;
  size_t kept = 0;
  for (size_t i = 0; i < t->n; i++) kept += !keep || keep[i];
  int rc = 0;
  rc |= attr_string(g, "engine", t->engine);
  rc |= attr_string(g, "model_summary", t->summary);
  rc |= attr_double(g, "h_s", t->h);
  rc |= attr_long(g, "samples_run", (long long)t->n);
  rc |= attr_long(g, "samples_written", (long long)kept);
  rc |= attr_long(g, "series_every", every);
  const hsize_t dims[1] = {kept};
  hsize_t chunk[1] = {kept < FB_H5_CHUNK ? (kept ? kept : 1) : FB_H5_CHUNK};
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  rc |= H5Pset_chunk(dcpl, 1, chunk) < 0;
  rc |= H5Pset_shuffle(dcpl) < 0;
  rc |= H5Pset_deflate(dcpl, FB_H5_DEFLATE) < 0;
  hid_t space = H5Screate_simple(1, dims, NULL);
  for (size_t k = 0; k < t->ncols && !rc; k++) {
    char name[96];
    t->name(t, k, name, sizeof name);
    const double *col = t->column ? t->column(t, k) : NULL;
    size_t w = 0;
    for (size_t i = 0; i < t->n; i++)
      if (!keep || keep[i]) buf[w++] = col ? col[i] : t->value(t, k, i);
    hid_t d = H5Dcreate2(g, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    if (d < 0) {
      rc = -1;
      break;
    }
    if (kept > 0) rc |= H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) < 0;
    rc |= attr_string(d, "unit", unit_of(name));
    H5Dclose(d);
  }
  H5Sclose(space);
  H5Pclose(dcpl);
  H5Gclose(g);
  return rc ? -1 : 0;
}

fb_status fb_series_write_hdf5_tables(const char *path, const char *case_name, int every,
                                      const char *rule, const fb_series_table *t, int n,
                                      unsigned char *const *keep, const char *summary_json,
                                      fb_diag *diag) {
  size_t most = 1;
  for (int i = 0; i < n; i++)
    if (t[i].n > most) most = t[i].n;
  double *buf = malloc(most * sizeof *buf);
  if (!buf) return fb_diag_set(diag, FB_ERR_NOMEM, "%s: out of memory", path);
  fb_outfile out;
  fb_status st = fb_outfile_open(&out, path, diag);
  if (st != FB_OK) {
    free(buf);
    return st;
  }
  /* HDF5 prints its error stack to stderr by default: the diagnostic
   * below says what failed instead */
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  /* the file is built in memory (HDF5's core driver without a backing
   * store) and written here: a full disk is then this program's write
   * error with its cause (No space left on device, as for a CSV), and
   * HDF5 never holds a file whose close failed (its clean-up at exit
   * crashes on one: SIGSEGV in H5F__close_cb, HDF5 1.10.8) */
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  int rc = fapl < 0 || H5Pset_fapl_core(fapl, FB_H5_CORE_INCREMENT, 0) < 0;
  hid_t file = rc ? -1 : H5Fcreate(out.tmp, H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  rc |= file < 0;
  if (!rc) {
    rc |= attr_string(file, "fourbar_version", FB_PROJECT_VERSION);
    rc |= attr_string(file, "case", case_name);
    rc |= attr_long(file, "series_every", every);
    rc |= attr_string(file, "series_rule", rule);
    rc |= attr_string(file, "layout",
                      "one group per model; one float64 dataset per column, named as the "
                      "columns of <model>.csv, attribute unit (SI)");
    if (summary_json) rc |= attr_string(file, "summary_json", summary_json);
    for (int i = 0; i < n && !rc; i++)
      rc |= write_group(file, &t[i], keep ? keep[i] : NULL, every, buf);
  }
  /* the finished file's bytes (H5Fget_file_image), then closed in memory */
  void *image = NULL;
  ssize_t size = -1;
  if (!rc) rc |= H5Fflush(file, H5F_SCOPE_GLOBAL) < 0;
  if (!rc) size = H5Fget_file_image(file, NULL, 0);
  if (!rc && size > 0 && (image = malloc((size_t)size)) != NULL)
    rc |= H5Fget_file_image(file, image, (size_t)size) != size;
  else
    rc = 1;
  if (file >= 0) rc |= H5Fclose(file) < 0;
  if (fapl >= 0) H5Pclose(fapl);
  free(buf);
  if (rc) {
    free(image);
    fb_outfile_abort(&out);
    return fb_diag_set(diag, FB_ERR_IO, "%s: HDF5 could not build the file (%s)", path,
                       size > 0 && !image ? "out of memory" : "an HDF5 library error");
  }
  errno = 0;
  const int written = fwrite(image, 1, (size_t)size, out.f) == (size_t)size && fflush(out.f) == 0;
  const int e = errno;
  free(image);
  if (!written) {
    fb_outfile_abort(&out);
    return fb_diag_set(diag, FB_ERR_IO, "%s: write failed: %s", path, strerror(e ? e : EIO));
  }
  return fb_outfile_commit(&out, diag);
}

/* a run's model as a table: its series' columns (fb_series_column_name) */
static void series_name(const fb_series_table *t, size_t k, char *buf, size_t size) {
  fb_series_column_name(t->self, k, buf, size);
}

static double series_value(const fb_series_table *t, size_t k, size_t i) {
  return fb_series_value(t->self, k, i);
}

static const double *series_column(const fb_series_table *t, size_t k) {
  return fb_series_column(t->self, k);
}

fb_status fb_series_write_hdf5(const char *path, const fb_run *r, unsigned char *const *keep,
                               const char *summary_json, fb_diag *diag) {
  fb_series_table *t = calloc((size_t)(r->n > 0 ? r->n : 1), sizeof *t);
  if (!t) return fb_diag_set(diag, FB_ERR_NOMEM, "%s: out of memory", path);
  for (int i = 0; i < r->n; i++) {
    const fb_model_run *run = &r->model[i].run;
    t[i] = (fb_series_table){run->name, fb_engine_name(run->model->engine), run->model->summary,
                             run->h, run->series.n, fb_series_column_count(&run->series),
                             &run->series, series_name, series_value, series_column};
  }
  const fb_status st = fb_series_write_hdf5_tables(path, r->c.name, r->c.series_every,
                                                   FB_SERIES_KEEP_RULE, t, r->n, keep,
                                                   summary_json, diag);
  free(t);
  return st;
}
