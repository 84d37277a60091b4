/* Long work, said before it starts and bounded up front: every command that
 * can run long (fourbar run, stackup, bench) estimates its cost from the
 * case's own cost per evaluation (measured on a few evaluations of this
 * case, then extrapolated), says the estimate on stderr before the work,
 * refuses work estimated beyond [run] max_wall_s with the option that runs
 * it anyway or the cheaper method, and draws one progress line on a
 * terminal. The rule that keeps it honest: an estimate is a count of
 * evaluations times a cost measured on this case, never a constant
 * measured on another. */
#ifndef FB_WORK_H
#define FB_WORK_H

#include "status.h"

/* Work estimated above this is said on stderr before it starts [s]: a
 * pause a user notices (shorter work starts without a word). */
#define FB_WORK_NOTE_S 2.0

/* A probe of the cost per evaluation evaluates until it has spent this much
 * CPU time [s], FB_WORK_PROBE_MIN evaluations at least, FB_WORK_PROBE_MAX at
 * most: 10 ms holds the clock's resolution (1 us) to 1e-4 of the figure and
 * the probe to a few per cent of the shortest work it announces. */
#define FB_WORK_PROBE_S 0.01
#define FB_WORK_PROBE_MIN 1
#define FB_WORK_PROBE_MAX 100000
/* Work the first window estimates above FB_WORK_NOTE_S is probed further,
 * in windows of FB_WORK_PROBE_S, for this share of its estimate (2 %: the
 * probe a small part of the work it times) ... */
#define FB_WORK_PROBE_SHARE 0.02
/* ... and at most this much CPU time [s]: a process's first few tenths of
 * a second can run at half speed (measured on the development machine, a
 * virtual one: the paper case's evaluation 30 us in a process's first
 * 0.2 s, 15 us after 0.3 s of other work), so the long probe outlasts
 * that and keeps its fastest window. */
#define FB_WORK_PROBE_LONG_S 0.5

/* CPU time of this process, every thread, not its children [s]
 * (CLOCK_PROCESS_CPUTIME_ID: nanoseconds): differences time a probe. */
double fb_work_cpu_s(void);

/* One evaluation of some work's unit (a corner, a sample), for a probe. */
typedef fb_status (*fb_work_eval)(void *ctx, fb_diag *diag);

/* The CPU time of one evaluation [s] into *s_per_eval: eval called until
 * the probe has spent FB_WORK_PROBE_S of CPU (FB_WORK_PROBE_MIN to
 * FB_WORK_PROBE_MAX calls), the mean; when units (the evaluations the work
 * will make; 0: not known) times that exceeds FB_WORK_NOTE_S, more windows
 * of FB_WORK_PROBE_S each, until the probe has spent FB_WORK_PROBE_SHARE of
 * the estimate (FB_WORK_PROBE_LONG_S at most), and the fastest window's
 * mean: whatever slows an evaluation (the process's start, other load)
 * slows a window, never speeds it. *evals (may be NULL) the calls.
 * Errors: eval's, at once. */
fb_status fb_work_probe(double *s_per_eval, int *evals, double units, fb_work_eval eval,
                        void *ctx, fb_diag *diag);

/* Seconds as a person reads them: "0.8 s", "46 s", "12 min", "3.4 h",
 * "2.1 days", "24 years" (beyond a year the figure stays in years). */
const char *fb_work_duration(char *buf, size_t size, double seconds);

/* The estimate said on stderr when it passes FB_WORK_NOTE_S (always with
 * force): "fourbar <command>: <what>: an estimated <duration> of CPU
 * (<basis>)<after>"; basis says what it was measured on. */
void fb_work_note(const char *command, const char *what, double cpu_s, const char *basis,
                  const char *after, int force);

/* A basis of fb_work_note: "<each> each, measured on this case" ("14.1 us
 * each, ..."). Returns buf. */
const char *fb_work_each(char *buf, size_t size, double each_s);

/* Refuses work estimated at wall_s [s] of wall time beyond max_wall_s [s]
 * ([run] max_wall_s): FB_ERR_RANGE with "<what>: an estimated <duration>,
 * more than [run] max_wall_s = <max> s: <instead>, or raise the limit
 * (--set run.max_wall_s=<wall_s rounded up>)"; an infinite estimate (more
 * corners than a count holds) names no limit. FB_OK when it fits. */
fb_status fb_work_bound(double wall_s, double max_wall_s, const char *what, const char *instead,
                        fb_diag *diag);

/* One progress line on stderr, fourbar run's: drawn only on a terminal
 * and with text output (on: isatty(2) and not --json), redrawn at most
 * every FB_WORK_REDRAW_S: "  <label>  42 %  17 s, about 23 s left". A new
 * label starts its own clock; a fraction of 1 ends the line. */
#define FB_WORK_REDRAW_S 0.1
typedef struct {
  int on;          /* draw */
  char label[64];  /* the work drawn */
  double t0;       /* its start [s] (fb_clock_s) */
  double last;     /* last redraw [s] */
} fb_progress;

/* A progress line for a command printing JSON (json 1) or text. */
void fb_progress_init(fb_progress *p, int json);

/* Draws label at fraction (0 .. 1) done. */
void fb_progress_draw(fb_progress *p, const char *label, double fraction);

#endif
