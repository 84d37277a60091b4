/* Parameter studies: a base case plus axes, each a list or range of values
 * for a case key (--set syntax) or a Monte Carlo sample of the case's link
 * tolerances. The grid is the Cartesian product of the axes in file order
 * (the first axis varies slowest); point i has fixed overrides, so any
 * subset of points (a shard, a worker's share, a resumed remainder) gives
 * the same row for the same i. A row is one JSON line:
 *   {"study", "index", "of", "axes": {key: value}, "status", "metrics": {name: value}}
 * with metric names as in fourbar check. Rows hold no wall time, so the same
 * study run any way gives byte-identical rows.
 *
 * Study file (INI):
 *   [study] name, case (relative to the study file, else a shipped case
 *           name: fb_study_load_with_cases), set (fixed overrides
 *           separated by ';'), metrics (comma list; a trailing * matches a
 *           prefix; default all), plot (up to 8 metric names to draw in
 *           study.svg; default the first four), heatmap (yes: a heat map over
 *           the first two axes instead of curves)
 *   [axis.<name>] key + values (comma list) or range (FROM:TO:STEP), or
 *           montecarlo = N samples with seed = S (lengths drawn from the
 *           case's tolerances and distribution, one seed per point). */
#ifndef FB_STUDY_H
#define FB_STUDY_H

#include <stddef.h>

#include "case.h"

#define FB_STUDY_MAX_AXES 8
#define FB_STUDY_MAX_VALUES 1024
#define FB_STUDY_MAX_SETS 32
#define FB_STUDY_MAX_METRICS 64
#define FB_STUDY_MAX_POINTS 10000000 /* grid points of one study (rows read back are checked too) */

typedef struct {
  char name[64];
  char key[128];                         /* section.key, or "montecarlo" */
  int montecarlo;                        /* 1: samples of the link tolerances */
  unsigned long seed;                    /* Monte Carlo seed */
  int n;                                 /* number of values */
  char value[FB_STUDY_MAX_VALUES][32];   /* values as text (--set syntax) */
} fb_axis;

typedef struct fb_study_s {
  char path[4096];                        /* study file */
  char name[64];
  char case_path[4096];                   /* resolved case file */
  int nsets;
  char sets[FB_STUDY_MAX_SETS][256];      /* fixed overrides */
  int nmetrics;                           /* 0: all */
  char metrics[FB_STUDY_MAX_METRICS][128];
  int nplot;                              /* metrics to draw (0: the first four) */
  char plot[8][128];
  int heatmap;                            /* 1: draw a heat map over the first two axes */
  int naxes;
  fb_axis axis[FB_STUDY_MAX_AXES];
  size_t points;                          /* product of the axis sizes */
} fb_study;

/* Reads and checks a study file: the case loads with the fixed overrides and
 * with the first and last value of every axis.
 * Errors: FB_ERR_IO, FB_ERR_PARSE, FB_ERR_RANGE naming file:line and key. */
fb_status fb_study_load(fb_study *s, const char *path, fb_diag *diag);

/* fb_study_load with the shipped cases' folder (NULL: none): a [study] case
 * not found from the study file's folder is then the shipped case of that
 * name (<cases_dir>/<case> or <case>.ini), as `fourbar run NAME` finds it.
 * Errors as fb_study_load; a case found in neither place: FB_ERR_IO naming
 * both paths it tried. */
fb_status fb_study_load_with_cases(fb_study *s, const char *path, const char *cases_dir,
                                   fb_diag *diag);

/* jansson's object type, declared here so that includers do not get jansson
 * (C11 allows the same typedef again where <jansson.h> is included too) */
typedef struct json_t json_t;

/* What a study's rows are computed from (issue 13): {"study_file",
 * "study_file_fnv1a64" (its bytes), "resolved_study_fnv1a64" (name, case
 * path, sets, metrics, every axis's key, seed and values), "case_files":
 * [{"path", "fnv1a64"}] (the case file and every base it reads), "points",
 * "fourbar_build_fnv1a64" (the running executable's bytes: the build),
 * "environment": {every FOURBAR_* variable set: its value}}. The caller adds
 * "fourbar_version". Hashes are FNV-1a 64 bit in hex: they detect a changed
 * input, they do not authenticate one. A sweep stores it beside its rows and
 * refuses to resume rows computed from anything else; merge refuses shards
 * whose provenance differs. */
json_t *fb_study_provenance(const fb_study *s);

/* 1 when rows of provenance old and now cannot stand in one table (another
 * version or build of fourbar, another resolved study, FOURBAR_* environment
 * or case file bytes), with what differs in what (size bytes); else 0. */
int fb_study_provenance_differs(const json_t *old, const json_t *now, char *what, size_t size);

/* Runs point i (< s->points) and returns its row as a malloc'ed JSON line
 * ending in '\n' (caller frees). A case that does not load or run gives a row
 * whose status says why. Errors: FB_ERR_NOMEM only. */
fb_status fb_study_point(const fb_study *s, size_t i, char **line, fb_diag *diag);

/* Checks a row read back from disk, field by field: "study" a string, "of"
 * an integer from 1 to FB_STUDY_MAX_POINTS, "index" from 0 to of - 1,
 * "axes" an object of strings, "status" a string, "metrics" an object of
 * finite numbers. Returns 1 and sets *index and *of, or 0 with the first
 * broken rule in why (why_size bytes; why may be NULL). */
int fb_study_row_parse(const char *line, long *index, size_t *of, char *why, size_t why_size);

/* Index of a row line, or -1 when the line is not a valid row
 * (fb_study_row_parse). */
long fb_study_row_index(const char *line, size_t *of);

/* Writes rows (JSON lines, any order, one per index) as CSV sorted by index:
 * index, the axis keys, status, every metric seen, then warnings ("; "-joined).
 * Errors: FB_ERR_IO. */
fb_status fb_study_write_csv(const char *path, char **rows, size_t n, fb_diag *diag);

/* The error line of a study command (sweep, merge, check), as the command
 * line prints its own: "fourbar <cmd>: <message>" on standard error.
 * Returns status (2 bad input, 1 failed) for `return fb_study_fail(...)`. */
int fb_study_fail(const char *cmd, int status, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Writes j to the file at path, whole or not at all (report.h's
 * fb_report_write_json, a floor above, given by the command line).
 * Errors: FB_ERR_IO. */
typedef fb_status (*fb_study_json_writer)(const char *path, const json_t *j, fb_diag *diag);

/* Draws DIR/study.svg from DIR/points.csv (figures.h's fb_figures_study, a
 * floor above, given by the command line). Errors: those of gnuplot. */
typedef fb_status (*fb_study_drawer)(const fb_study *s, const char *dir, fb_diag *diag);

/* Counts the rows (JSON lines as fb_study_point writes them) whose status is
 * not "ok" (*stopped) and those with at least one warning (*warned); a row
 * that does not parse counts as neither. */
void fb_study_tally(char **rows, size_t n, size_t *stopped, size_t *warned);

#endif
