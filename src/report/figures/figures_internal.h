/* What the figure files share, inside src/report/figures/ only: the
 * gnuplot plumbing (figures_gnuplot.c), a run's series as datablocks and
 * the manifest's entries (figures_series.c), the models' styles
 * (figures_style.c), the study CSV reader (figures_csv.c), and the figure
 * families that fb_figures_run draws (one file each). */
#ifndef FB_FIGURES_INTERNAL_H
#define FB_FIGURES_INTERNAL_H

#include <jansson.h>
#include <stdio.h>

#include "figures.h"

/* ---- the gnuplot plumbing (figures_gnuplot.c) ------------------------------ */

typedef struct {
  FILE *p;         /* the figure's gnuplot script, written to a file in dir */
  int columns;     /* the figure's width [px]: the buckets of min/max decimation */
  char dir[4096];  /* output folder; gnuplot runs in it */
  char path[4400]; /* final name */
  char tmp[4400];  /* written by gnuplot (a fixed-form name in dir), renamed on success */
  char script[4400]; /* the script (a fixed-form name in dir), removed when drawn */
  char log[4400];
} plot;

/* "png" or "svg" */
const char *fig_ext(fb_figure_format f);

/* Text for the inside of a gnuplot single-quoted string (quotes doubled,
 * control characters '?'; with enhanced = 1 the enhanced-text markup
 * characters backslash-escaped too), truncated to size; returns out. */
const char *fig_gp_text(const char *in, int enhanced, char *out, size_t size);

/* fig_gp_text for gnuplot's enhanced mode: underscores would become subscripts */
const char *fig_esc(const char *in, char *out, size_t size);

/* Opens figure dir/name.<ext> of width x height pixels: its script file in
 * dir, started with the terminal and the temporary output name.
 * Errors: FB_ERR_IO when the script cannot be written. */
fb_status fig_plot_open(plot *pl, const char *dir, const char *name, fb_figure_format fmt,
                        int width, int height, fb_diag *diag);

/* Ends the figure's script; inside a batch keeps it for fig_batch_end,
 * else draws it with one gnuplot and puts the figure into place.
 * Errors: FB_ERR_IO naming the figure (gnuplot's messages in dir/.gnuplot.log). */
fb_status fig_plot_close(plot *pl, fb_diag *diag);

/* A batch (a run's figures): between fig_batch_begin and fig_batch_start,
 * fig_plot_close keeps the scripts; fig_batch_start starts them side by
 * side, one gnuplot per processor, and returns while they draw;
 * fig_batch_end (starting them first if fig_batch_start did not) waits for
 * every gnuplot started and puts every figure into place. Errors (of
 * fig_batch_end, the first one, a failure to start included) as
 * fig_plot_close. */
void fig_batch_begin(void);
void fig_batch_start(void);
fb_status fig_batch_end(fb_diag *diag);

/* Ends a run's batch (fig_batch_end) and, when it and st are FB_OK, writes
 * dir/figures.json of figs (taken either way); returns st, else the
 * batch's or the write's error. */
fb_status fig_batch_finish(fb_status st, json_t *figs, const char *dir, fb_diag *diag);

/* "dir/name.ext" -> dir, name (no extension); "name.ext" -> ".", name */
void fig_split_path(const char *path, char *dir, size_t dsize, char *name, size_t nsize);

/* ---- a run's series in a figure (figures_series.c) ------------------------- */

/* the symlog transform of alpha.svg: linear within +-C, logarithmic beyond */
#define SYMLOG_C 1000.0

/* crank angle in degrees in [0, 360) */
double fig_crank_deg(double th);

/* Writes datablock $name of (crank deg, y) over [t0, t1], min/max-decimated
 * per pixel column of the figure; returns the points written and their
 * extremes in *ymin, *ymax. fig_datablock_x: x the crank angle (x_time = 0)
 * or the time [ms] (x_time = 1, log-time pixel columns). */
int fig_datablock(const plot *pl, const char *name, const fb_series *s, const double *y,
                  double t0, double t1, double *ymin, double *ymax);
int fig_datablock_x(const plot *pl, const char *name, const fb_series *s, const double *y,
                    double t0, double t1, int x_time, double *ymin, double *ymax);

/* yardsticks (analytic, reference) first: the run's model indices in the
 * order they are drawn, into order; returns their number */
int fig_draw_order(const fb_run *r, int order[]);

/* the decade at or above |y| * headroom, at least SYMLOG_C */
double fig_decade_above(double y, double headroom);

/* Writes the symlog y axis of a panel whose data span [lo, hi] (lo <= 0 <=
 * hi) to the figure's script: linear within +-SYMLOG_C, logarithmic beyond,
 * the range to the decade above the data with 15 % headroom, every decade
 * labelled. With axis not NULL, records y_min, y_max and y_tics in it. */
void fig_symlog_axis(const plot *pl, double lo, double hi, json_t *axis);

/* appends {file, title, curves} to the manifest's figures (takes curves) */
void fig_manifest_add(json_t *figs, const char *file, const char *title, json_t *curves);

/* a manifest curve: model, column, csv, points, and when ymin is finite its
 * extremes and time window [s] */
json_t *fig_curve(const char *model, const char *column, const char *csv, int points,
                  double ymin, double ymax, double t0, double t1);

/* ---- the run's bodies and joints (figures_series.c) ------------------------ */

/* Every body name, symbol, unit, column and joint name a figure writes is
 * read from the case's mechanism description (mechanism.h), so that a
 * slider-crank's figures name its slider and its coupler-slider joint. The
 * four-bar's words are those its figures always wrote: coupler and follower,
 * omega and alpha in rad/s and rad/s^2. q is FB_Q_POS, FB_Q_VEL or FB_Q_ACC;
 * k an output body (0 .. fig_outputs - 1, the series' body[k]). */

/* the number of output bodies of the run's mechanism */
int fig_outputs(const fb_run *r);

/* output body k's name ("coupler", "follower", "slider") */
const char *fig_body(const fb_run *r, int k);

/* its symbol and unit of quantity q ("omega", "rad/s"; the slider's "v", "m/s") */
const char *fig_symbol(const fb_run *r, int k, int q);
const char *fig_unit(const fb_run *r, int k, int q);

/* its quantity q in words: "angular velocity", "angular acceleration" for a
 * rotating or planar body; "velocity", "acceleration" for a translating one */
const char *fig_quantity(const fb_run *r, int k, int q);

/* the quantity q of every output body in words into out (returned): the
 * shared words when every body has the same ("angular velocity"), else each
 * body's ("coupler angular velocity and slider velocity") */
const char *fig_quantity_all(const fb_run *r, int q, char *out, size_t size);

/* the symbol of quantity q shared by every output body ("alpha"), else the
 * quantity's plain word ("velocity", "acceleration") */
const char *fig_symbol_all(const fb_run *r, int q);

/* 1 when every output body has the unit of quantity q that body 0 has */
int fig_same_unit(const fb_run *r, int q);

/* output body k's CSV column of quantity q (fb_mech_body_column:
 * "coupler_omega_rad_s", "slider_v_m_s") into out (returned); with word
 * not NULL, "_<word>" after the symbol ("coupler_omega_residual_rad_s") */
const char *fig_column(const fb_run *r, int k, int q, const char *word, char *out, size_t size);

/* joint j's name in the run's mechanism ("crank-coupler", "coupler-slider") */
const char *fig_joint(const fb_run *r, int j);

/* joint j's name as a CSV column prefix, '-' as '_' ("coupler_slider"),
 * into out (returned) */
const char *fig_joint_column(const fb_run *r, int j, char *out, size_t size);

/* ---- one style per model (figures_style.c) --------------------------------- */

typedef struct {
  const char *name;  /* model name */
  const char *color; /* '#rrggbb' */
  int dash;          /* gnuplot dash type: 1 solid, 2 dashed, 3 dotted, 4 dash-dot */
  double width;      /* line width */
} model_style;

/* the style of the model named name from the model table alone (the
 * bench's figures, which hold no run) */
model_style fig_style_of(const char *name);

/* its style in run r (NULL: fig_style_of): a simulated model's colour from
 * the run's palette by its rank among the run's simulated models, so that
 * a run's models differ in hue; the same in every figure of the run */
model_style fig_style_in(const fb_run *r, const char *name);

/* "lc rgb '#rrggbb' dt N lw W" of a model in run r, into out (returned) */
const char *fig_style_spec(const fb_run *r, const char *model, char *out, size_t size);

/* records a curve's style (color, dash) in run r in the manifest */
void fig_curve_style(json_t *c, const fb_run *r, const char *model);

/* ---- the figure families of a run (fb_figures_run) ------------------------- */

/* omega.<ext> (alpha = 0) or alpha.<ext> (alpha = 1), figures_omega_alpha.c */
fb_status fig_omega_alpha(const fb_run *r, const char *dir, fb_figure_format fmt, int alpha,
                          json_t *figs, fb_diag *diag);

/* every contact figure of the window (startup 0) or of the start-up (1),
 * each file name appended to names (up to max), figures_contact.c */
fb_status fig_contact_figures(const fb_run *r, const char *dir, fb_figure_format fmt,
                              int startup, json_t *figs, char names[][128], int max, int *n,
                              fb_diag *diag);

/* spikes.<ext>, *drawn = 0 for a run without a clearance model, figures_spikes.c */
fb_status fig_spikes(const fb_run *r, const char *dir, fb_figure_format fmt, json_t *figs,
                     int *drawn, fb_diag *diag);

/* startup.<ext>, figures_startup.c */
/* verdict_<model>.<ext> for each model judged on statistics (verdict.h):
 * its members' impact peak forces against the reference's (empirical
 * distributions), their impact rates per revolution, its first impacts'
 * errors against their bounds, and the test's figures in its title; the
 * files' names appended to names (at most max, *n counting) */
fb_status fig_verdicts(const fb_run *r, const char *dir, fb_figure_format fmt, json_t *figs,
                       char names[][128], int max, int *n, fb_diag *diag);

fb_status fig_startup(const fb_run *r, const char *dir, fb_figure_format fmt, json_t *figs,
                      fb_diag *diag);

/* ---- the study CSV reader (figures_csv.c) ---------------------------------- */

/* points.csv as text cells: header names, then rows (status unquoted) */
typedef struct {
  int ncol;
  char **head;     /* (ncol) */
  size_t nrow;
  char ***cell;    /* (nrow x ncol) */
  int status_col;  /* index of "status" */
} study_csv;

/* Reads the CSV at path into t (at most its first 200,000 rows); 1 when it
 * has a header with a "status" column, else 0. fig_csv_free it either way. */
int fig_csv_read(study_csv *t, const char *path);
void fig_csv_free(study_csv *t);

/* the index of column name, or -1 */
int fig_csv_col(const study_csv *t, const char *name);

/* a cell's number, NaN when it is not wholly a finite number */
double fig_cell_num(const char *text);

#endif
