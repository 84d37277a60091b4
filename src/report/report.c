/* A run's output folder (report.h): the series in the case's format
 * (series_write.h, CSV or HDF5), summary.json (report_summary.h) and
 * timing.json (report_timing.h), each written atomically. */
#include "report.h"

#include <jansson.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <time.h>

#include "clock.h"
#include "fileio.h"
#include "series_write.h"

/* bytes of the file at path (0 when it cannot be read) */
static double file_bytes(const char *path) {
  struct stat sb;
  return stat(path, &sb) == 0 ? (double)sb.st_size : 0.0;
}

/* CPU time of this process [s] (the writer's cost without the waits of a
 * busy machine or of the disk) */
static double cpu_s(void) {
  struct timespec ts;
  return clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts) == 0 ? (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec
                                                           : 0.0;
}

/* the time series in the case's format ([run] series, series_every); its
 * wall time goes to *write_s, its CPU time to *cpu and the bytes written
 * to *bytes */
static fb_status write_series(const char *dir, const fb_run *r, const char *case_path,
                              double *write_s, double *cpu, double *bytes, fb_diag *diag) {
  char path[4096];
  const fb_case *c = &r->c;
  *write_s = 0.0;
  *cpu = 0.0;
  *bytes = 0.0;
  if (c->series == FB_SERIES_NONE) return FB_OK;
  const double t0 = fb_clock_s(), c0 = cpu_s();
  unsigned char *keep[FB_MAX_MODELS] = {0};
  fb_status st = FB_OK;
  if (c->series_every > 1)
    for (int i = 0; i < r->n && st == FB_OK; i++) {
      const fb_series *s = &r->model[i].run.series;
      keep[i] = malloc(s->n ? s->n : 1);
      if (!keep[i]) st = fb_diag_set(diag, FB_ERR_NOMEM, "series selection: out of memory");
      else fb_series_keep(s, c->series_every, keep[i]);
    }
  if (st == FB_OK && c->series == FB_SERIES_HDF5) {
    snprintf(path, sizeof path, "%s/series.h5", dir);
    json_t *j = fb_report_summary_json(r, case_path);
    char *text = json_dumps(j, JSON_INDENT(2) | JSON_REAL_PRECISION(12));
    json_decref(j);
    st = fb_series_write_hdf5(path, r, keep, text, diag);
    free(text);
    *bytes = file_bytes(path);
  }
  if (c->series == FB_SERIES_CSV)
    for (int i = 0; i < r->n && st == FB_OK; i++) {
      snprintf(path, sizeof path, "%s/%s.csv", dir, r->model[i].run.name);
      st = fb_series_write_csv(path, &r->model[i].run.series, keep[i], diag);
      *bytes += file_bytes(path);
    }
  for (int i = 0; i < r->n; i++) free(keep[i]);
  *write_s = fb_clock_s() - t0;
  *cpu = cpu_s() - c0;
  return st;
}

fb_status fb_report_write_run(const char *dir, const fb_run *r, const char *case_path,
                              fb_write_costs *w, fb_diag *diag) {
  char path[4096];
  fb_status st = write_series(dir, r, case_path, &w->series_s, &w->series_cpu_s,
                              &w->series_bytes, diag);
  if (st != FB_OK) return st;
  const double t0 = fb_clock_s();
  snprintf(path, sizeof path, "%s/summary.json", dir);
  json_t *j = fb_report_summary_json(r, case_path);
  st = fb_report_write_json(path, j, diag);
  json_decref(j);
  w->summary_s = fb_clock_s() - t0;
  return st;
}

fb_status fb_report_write_timing(const char *dir, const fb_run *r, const fb_write_costs *w,
                                 double *run_wall_s, fb_diag *diag) {
  char path[4096];
  snprintf(path, sizeof path, "%s/timing.json", dir);
  *run_wall_s = fb_clock_s() - fb_clock_process_start_s();
  json_t *j = fb_report_timing_json(r, w, *run_wall_s);
  fb_status st = fb_report_write_json(path, j, diag);
  json_decref(j);
  return st;
}
