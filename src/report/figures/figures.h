/* Figures of a run, drawn by gnuplot (gnuplot 5.4, Debian's gnuplot-nox)
 * from a script file per figure written into the output folder (started
 * with posix_spawn and an argument vector in that folder, no shell; every
 * text entering the script is escaped for a single-quoted gnuplot string,
 * and the script names no user path); a run's figures are drawn side by
 * side, one gnuplot per processor. SVG by default, PNG (pngcairo) on
 * request. Each figure is written to a temporary name and renamed into
 * place. Curves are decimated to the figure's pixel columns, keeping each
 * column's minimum and maximum (decimate.h), so spikes survive; a pin's
 * orbit to the pixels it crosses. A manifest figures.json lists every figure
 * with the number of points of each curve and the CSV it was drawn from. */
#ifndef FB_FIGURES_H
#define FB_FIGURES_H

#include "planar_run.h"
#include "run.h"

typedef enum { FB_FIGURE_SVG = 0, FB_FIGURE_PNG = 1 } fb_figure_format;

/* The colour ('#rrggbb') and gnuplot dash type model name is drawn with in
 * every figure of run r (the run's palette by its rank among the run's
 * simulated models, or the model table's colour for a yardstick;
 * docs/figures.md), so that report.html draws it alike. */
const char *fb_figure_model_color(const fb_run *r, const char *name);
int fb_figure_model_dash(const fb_run *r, const char *name);

/* Draws the run's figures into dir: omega.<ext> (the output bodies'
 * velocity against crank angle over the revolution after the first, every
 * model overlaid on the analytic curve: the four-bar's coupler and follower
 * omega, the slider-crank's coupler omega and slider v), alpha.<ext> (the
 * same for the acceleration, symlog axis with a linear band of +-1000 in
 * each body's unit), spikes.<ext>, startup.<ext>, and for each clearance
 * model and joint contact_<model>_<joint>.<ext> (pin centre orbit inside the
 * clearance circle coloured by contact state, and the contact force against
 * crank angle), plus figures.json. Body names, symbols, units, CSV columns
 * and joint names are the case's mechanism's (docs/figures.md). names
 * receives the file names written (up to max), *n their count.
 * Errors: FB_ERR_IO when gnuplot cannot be started or fails (its messages are
 * in dir/.gnuplot.log), naming the figure. */
fb_status fb_figures_run(const fb_run *r, const char *dir, fb_figure_format fmt, char names[][128],
                         int max, int *n, fb_diag *diag);

/* Draws a planar case's run r (planar_run.h) into dir, by the
 * description's names: omega.<ext> and alpha.<ext> (every moving body's
 * angular velocity and acceleration, one panel each, every model overlaid,
 * against the drive angle over the revolution from the peak window's start,
 * the run's first when it ends before; alpha on a symlog axis), for each
 * reference contact_<model>_<joint>.<ext> (its clearance joint's contact
 * force and penetration; '-' in the joint's name as '_'), and
 * figures.json. An undriven case (a free start) has no drive angle: no
 * figure, figures.json's list empty. names, max, n and errors as
 * fb_figures_run. */
fb_status fb_figures_planar(const fb_planar_run *r, const char *dir, fb_figure_format fmt,
                            char names[][128], int max, int *n, fb_diag *diag);

/* fb_figures_run in two halves, so that the caller writes its other files
 * while gnuplot draws (one gnuplot per processor, separate processes):
 * fb_figures_start writes the scripts and starts the gnuplots (names, *n as
 * above); fb_figures_finish waits for them, puts the figures into place and
 * writes figures.json. Every fb_figures_start must be followed by one
 * fb_figures_finish (also after an error, which it returns then: the
 * gnuplots started are waited for, their files removed). Errors as
 * fb_figures_run, from fb_figures_finish; fb_figures_start returns the
 * failure met before the gnuplots started, if any, early. */
fb_status fb_figures_start(const fb_run *r, const char *dir, fb_figure_format fmt, char names[][128],
                           int max, int *n, fb_diag *diag);
fb_status fb_figures_finish(fb_diag *diag);

/* Checks, before any work, that gnuplot can be started (an executable
 * gnuplot on PATH). Errors: FB_ERR_IO saying how to install it or to pass
 * --no-figures. */
fb_status fb_figures_check_gnuplot(fb_diag *diag);

/* Draws penalty.<ext>: force, contact stiffness, penalty and approach against
 * the drive's speed (speed: its name on the axis, "crank speed" or "drive
 * speed") for every joint (the paper's Figures 2 to 4), from columns of
 * equal length n: speed rpm [rpm], then per joint j < njoints force[j] [N],
 * stiffness[j] [N/m], penalty[j] (the mode's unit: N mm^0.5 in paper
 * mode, N m^0.5 otherwise), approach_um[j] [um]; joint[j] their names
 * ("crank-coupler", "coupler-follower", a planar case's joint names).
 * Errors as fb_figures_run. */
fb_status fb_figures_penalty(const char *path, fb_figure_format fmt, const char *mode,
                             const char *speed, int n, const double *rpm, int njoints, const double *const *force,
                             const double *const *stiffness, const double *const *penalty,
                             const double *const *approach_um, const char *const *joint,
                             fb_diag *diag);

/* Draws the ERP map over log10 stiffness x log10 step (heat map) with the
 * h omega = 1 contour and the ERP = 0.1 and 0.99 contours, to path. erp and
 * h_omega are (nk x nh), row-major by stiffness. Errors as fb_figures_run. */
fb_status fb_figures_mapping(const char *path, fb_figure_format fmt, const char *title, int nk,
                             const double *k, int nh, const double *h, const double *erp,
                             const double *h_omega, fb_diag *diag);

struct fb_study_s;

/* Draws DIR/study.svg from DIR/points.csv: one panel per plotted metric
 * ([study] plot, default the first four metric columns), the metric against
 * the first axis (or the row index for a Monte Carlo axis) with one series per
 * combination of the other axes' values, or a heat map over the first two
 * axes ([study] heatmap = yes). Errors as fb_figures_run. */
fb_status fb_figures_study(const struct fb_study_s *s, const char *dir, fb_diag *diag);

struct fb_bench_row_s;
struct fb_bench_marks_s;

/* Draws error against wall time per revolution (log-log), one colour per
 * model, Pareto front joined, to path, titled with the engines the rows
 * ran on; marks (bench_study.h; may be NULL): each error target's cheapest
 * configuration across engines ringed and named, the peers' harness/bare
 * ratios written beside the chart. rows as from fb_bench_run. */
fb_status fb_figures_bench(const char *path, fb_figure_format fmt, const char *case_name,
                           const void *rows, int n, const struct fb_bench_marks_s *marks,
                           fb_diag *diag);

#endif
