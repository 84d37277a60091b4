/* Writers of a run's results: its output folder (below), summary.json and
 * timing.json (report_summary.h), the printed summary table
 * (report_table.h), report.md (report_markdown.h) and the cells they share
 * (report_common.h), all included here for the writers' callers. Keys and
 * column names carry their SI unit; NaN and infinity are never written
 * (JSON null stands for "not measured"). */
#ifndef FB_REPORT_H
#define FB_REPORT_H

#include "report_common.h"
#include "report_markdown.h"
#include "report_summary.h"
#include "report_table.h"
#include "report_timing.h"
#include "run.h"

/* Writes DIR/<model>.csv for every model (or DIR/series.h5, or no series,
 * as the case's [run] series says) and DIR/summary.json, each atomically,
 * and what they cost into w's series and summary fields.
 * Errors: FB_ERR_IO naming the file. */
fb_status fb_report_write_run(const char *dir, const fb_run *r, const char *case_path,
                              fb_write_costs *w, fb_diag *diag);

/* fb_report_write_run in parts, so that the caller writes its other files
 * while the series are written: fb_report_series_start forks a worker
 * process (worker.h: it dies with the caller and holds none of its locks;
 * outdir.h: killed before a staging folder is removed on a signal) that
 * writes the series as fb_report_write_run does, and returns at once (when
 * no process can be started it writes them itself); fb_report_series_finish
 * waits for it and fills w's series fields (series_s and series_cpu_s: the
 * worker's own wall and CPU time) and series_part_s (what starting and
 * waiting cost the caller, timing.json's "series" part);
 * fb_report_write_summary writes summary.json (summary_s). Every start is
 * followed by one finish. Errors: as fb_report_write_run, from
 * fb_report_series_finish (FB_ERR_IO also when the worker dies). */
void fb_report_series_start(const char *dir, const fb_run *r, const char *case_path, fb_write_costs *w);
fb_status fb_report_series_finish(fb_write_costs *w, fb_diag *diag);
fb_status fb_report_write_summary(const char *dir, const fb_run *r, const char *case_path,
                                  fb_write_costs *w, fb_diag *diag);

/* Writes DIR/timing.json (report_timing.h) with the run's wall time up to
 * now, which *run_wall_s receives [s]: the last file of a set, so that it
 * counts the others (w: what writing them cost). Errors: FB_ERR_IO. */
fb_status fb_report_write_timing(const char *dir, const fb_run *r, const fb_write_costs *w,
                                 double *run_wall_s, fb_diag *diag);

#endif
