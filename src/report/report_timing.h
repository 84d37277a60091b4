/* timing.json: where a run's wall time went, and the line fourbar run ends
 * with. docs/outputs.md gives the keys. */
#ifndef FB_REPORT_TIMING_H
#define FB_REPORT_TIMING_H

#include <stddef.h>

#include "report_common.h"
#include "run.h"

/* What writing a run's set cost: its writers fill it (fb_report_write_run
 * the series and summary.json, the command the figures and reports). */
typedef struct {
  double series_s;     /* the time series (CSV or HDF5), wall [s] */
  double series_cpu_s; /* the same, CPU time of the process [s] */
  double series_bytes; /* bytes of the series written [-] */
  double summary_s;    /* summary.json [s] */
  double figures_s;    /* the figures (gnuplot) [s] */
  double report_s;     /* report.html and report.md [s] */
  int series_async;     /* 1: the series written by a worker process beside the others */
  double series_part_s; /* then the writer's own time on them: starting it, waiting [s] */
} fb_write_costs;

/* One part of a run's wall time. */
typedef struct {
  char name[FB_NAME_SIZE + 16]; /* "<model>.stepping", "ensemble", ... */
  double s;                     /* [s] */
} fb_time_part;

/* parts of a run: four per model and at most this many others */
#define FB_TIME_PARTS_MAX (4 * FB_MAX_MODELS + 16)

/* The parts of run r's wall time run_wall_s [s] (measured from the
 * process's start, clock.h): "start" (the process up to the run: the
 * program's loading, the case file, the preflight of the case and its
 * variants, the output folder), "scene" (run.h scene_s), per model in the
 * case's order "<model>.setup", ".stepping", ".sampling" (its wall time
 * less the two) and ".check" (a reference's check integration; 0 for
 * others), "metrics", "h_auto_redo", "ensemble" (the members beyond the
 * first), "variants", "series", "figures", "report" (summary.json,
 * report.html, report.md; w may be NULL: none written yet) and "other",
 * run_wall_s less the sum of the rest (verdicts, tables, whatever no part
 * names): the parts sum to run_wall_s. Returns the count (<= max). */
int fb_report_time_parts(fb_time_part *out, int max, const fb_run *r, const fb_write_costs *w,
                         double run_wall_s);

/* timing.json (new reference): {"case", "run_wall_s", "parts": {name: s,
 * ...} (fb_report_time_parts), "models": [{"name", "steps", "wall_s",
 * "setup_s", "time_per_step_us", "stepping_s", "samples", "cpu_s",
 * "check_cpu_s"}], "ensemble": {...}, "estimate": {"wall_s",
 * "models_wall_s", "models_cpu_s", "bytes", "max_rss_bytes"} (run.h
 * fb_run_estimate against fb_run_estimated_work and the peak resident
 * memory), "series_write_s", "series_write_cpu_s", "series_bytes"}
 * (docs/outputs.md). */
json_t *fb_report_timing_json(const fb_run *r, const fb_write_costs *w, double run_wall_s);

/* The line fourbar run ends with: the run's wall time and its largest
 * parts, e.g. "time 2.71 s: reference.stepping 0.52 s, series 0.28 s, ...
 * (every part: timing.json)". */
void fb_report_timing_line(char *buf, size_t size, const fb_run *r, const fb_write_costs *w,
                           double run_wall_s);

#endif
