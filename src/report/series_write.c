#include "series_write.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fb_config.h"
#include "fileio.h"
#include "numfmt.h"

size_t fb_series_keep(const fb_series *s, int every, unsigned char *keep) {
  const size_t n = s->n;
  if (every < 1) every = 1;
  for (size_t i = 0; i < n; i++) keep[i] = (unsigned char)(i % (size_t)every == 0);
  if (n > 0) keep[n - 1] = 1;
  for (int j = 0; j < 4; j++) {
    if (!(s->contact_mask & (1 << j))) continue;
    const double *state = s->contact[j][FB_C_STATE];
    for (size_t i = 0; i < n; i++) {
      if (state[i] != FB_STATE_IMPACT) continue;
      keep[i] = 1;
      if (i > 0) keep[i - 1] = 1;
      if (i + 1 < n) keep[i + 1] = 1;
    }
  }
  size_t kept = 0;
  for (size_t i = 0; i < n; i++) kept += keep[i];
  return kept;
}

/* bytes of text gathered before one fwrite */
#define FB_CSV_BUFFER (1u << 20)

fb_status fb_series_write_csv(const char *path, const fb_series *s, const unsigned char *keep,
                              fb_diag *diag) {
  const size_t nc = fb_series_column_count(s);
  /* every column's values as one array (the reaction magnitudes computed
   * once, by fb_series_value) */
  const double **col = malloc(nc * sizeof *col);
  double **owned = calloc(nc, sizeof *owned);
  char *buf = malloc(FB_CSV_BUFFER);
  if (!col || !owned || !buf) {
    free(col);
    free(owned);
    free(buf);
    return fb_diag_set(diag, FB_ERR_NOMEM, "%s: out of memory", path);
  }
  fb_status st = FB_OK;
  for (size_t k = 0; k < nc && st == FB_OK; k++) {
    /* a column held as an array is used in place; a derived one (a
     * reaction magnitude) is computed once */
    col[k] = fb_series_column(s, k);
    if (col[k]) continue;
    owned[k] = malloc((s->n ? s->n : 1) * sizeof(double));
    if (!owned[k]) {
      st = fb_diag_set(diag, FB_ERR_NOMEM, "%s: out of memory", path);
      break;
    }
    for (size_t i = 0; i < s->n; i++) owned[k][i] = fb_series_value(s, k, i);
    col[k] = owned[k];
  }
  fb_outfile out;
  if (st == FB_OK) st = fb_outfile_open(&out, path, diag);
  if (st == FB_OK) {
    char name[96];
    size_t used = 0;
    for (size_t k = 0; k < nc; k++)
      used += (size_t)snprintf(buf + used, FB_CSV_BUFFER - used, "%s%s", k ? "," : "",
                               fb_series_column_name(s, k, name, sizeof name));
    buf[used++] = '\n';
    const size_t row_max = nc * (FB_NUMFMT_G12_SIZE + 1) + 1;
    for (size_t i = 0; i < s->n; i++) {
      if (keep && !keep[i]) continue;
      if (used + row_max > FB_CSV_BUFFER) {
        fwrite(buf, 1, used, out.f);
        used = 0;
      }
      for (size_t k = 0; k < nc; k++) {
        if (k) buf[used++] = ',';
        used += fb_numfmt_g12(buf + used, col[k][i]);
      }
      buf[used++] = '\n';
    }
    fwrite(buf, 1, used, out.f);
    st = fb_outfile_commit(&out, diag);
  }
  for (size_t k = 0; k < nc; k++) free(owned[k]);
  free(owned);
  free(col);
  free(buf);
  return st;
}

#if !FB_HAVE_HDF5
fb_status fb_series_write_hdf5_tables(const char *path, const char *case_name, int every,
                                      const char *rule, const fb_series_table *t, int n,
                                      unsigned char *const *keep, const char *summary_json,
                                      fb_diag *diag) {
  (void)case_name;
  (void)every;
  (void)rule;
  (void)t;
  (void)n;
  (void)keep;
  (void)summary_json;
  return fb_diag_set(diag, FB_ERR_ARG,
                     "%s: this fourbar was built without HDF5; install libhdf5-dev (Debian) "
                     "and rebuild (meson setup --reconfigure build -Dhdf5=enabled)",
                     path);
}

fb_status fb_series_write_hdf5(const char *path, const fb_run *r, unsigned char *const *keep,
                               const char *summary_json, fb_diag *diag) {
  (void)r;
  return fb_series_write_hdf5_tables(path, NULL, 1, NULL, NULL, 0, keep, summary_json, diag);
}
#endif
