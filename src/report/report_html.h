/* report.html: the run's interactive page, opened from the file system with
 * no server and no network (docs/report.md).
 *
 * The folder gets four files beside the other results, each written
 * atomically (fileio.h): report.html (the page: static markup and script,
 * no run data), report-data.js (the run's data as one JSON value assigned to
 * window.FOURBAR_DATA, encoded by jansson with every non-ASCII character and
 * '/' escaped, so no text of the run can end the script or run as code), and
 * the charting library uPlot (npm package uplot, copied: uPlot.iife.min.js,
 * uPlot.min.css) so the folder opens alone.
 *
 * Data: each model's samples decimated to min/max buckets
 * (FB_REPORT_BUCKETS over the run, the extremes of every plotted column
 * kept), plus every sample of each impact episode and FB_REPORT_IMPACT_PAD
 * samples either side (a long episode: its ends, and min/max buckets of
 * FB_REPORT_CONTACT_BUCKET inside); the page decimates again per zoom level. The summary
 * is summary.json's value itself (same JSON encoding, same 12 digits). */
#ifndef FB_REPORT_HTML_H
#define FB_REPORT_HTML_H

#include "report.h" /* json_t */
#include "run.h"

/* Buckets of the whole-run level of each model's data: 4000 buckets keep
 * each plotted column's minimum and maximum every 1/4000 of the run (15 us
 * of the paper case's 3 revolutions = 4.5 steps), about 2 pixels of a
 * full-screen chart, so the whole-run view loses no extreme [-]. */
#define FB_REPORT_BUCKETS 4000

/* Samples kept at full resolution before and after each impact episode:
 * 200 steps of the paper case (0.66 ms) hold the approach and the rebound
 * seen in a click's zoom around the impact [-]. */
#define FB_REPORT_IMPACT_PAD 200

/* An impact episode longer than 2 FB_REPORT_IMPACT_PAD + this (a phase of
 * continuous contact: three of about 17 000 steps each a run on the paper
 * case's clearance models) keeps every sample only FB_REPORT_IMPACT_PAD
 * steps into it from each end (the impact's onset and spike, the
 * separation); inside, each plotted column's minimum and maximum every
 * FB_REPORT_CONTACT_BUCKET samples (32 steps of the paper case: 0.1 ms, a
 * pixel of a 50 ms window), so no extreme and no change of contact state is
 * lost [-]. */
#define FB_REPORT_CONTACT_BUCKET 32

/* Impacts listed per model and joint (the rest are counted) [-]. */
#define FB_REPORT_MAX_IMPACTS 500

/* Where the charting library's files are: $FOURBAR_UPLOT_DIR when set, else
 * the uplot package that the quick start installs with npm into the source
 * tree's node_modules (meson.build: FB_UPLOT_DIR). Writes the folder into
 * out (size bytes) and returns 1 when it holds uPlot.iife.min.js and
 * uPlot.min.css, else 0. */
int fb_report_html_library(char *out, size_t size);

/* Writes report.html, report-data.js and, when the library is found, its
 * two files into dir. summary is summary.json's value (the page's tables
 * show its numbers). *charts is set to 1 when the library was copied, 0
 * when the page was written without charts (it then says how to get them).
 * Errors: FB_ERR_IO naming the file; FB_ERR_NOMEM. */
fb_status fb_report_html_write(const char *dir, const fb_run *r, const json_t *summary, int *charts,
                               fb_diag *diag);

/* As fb_report_html_write for data built by another writer (a planar
 * run's, report_html_planar.h): the library copied when found (*charts),
 * data's "charts" set, report-data.js (data, taken, then summary) and
 * report.html written. Errors as fb_report_html_write. */
fb_status fb_report_html_write_data(const char *dir, json_t *data, const json_t *summary,
                                    int *charts, fb_diag *diag);

#endif
