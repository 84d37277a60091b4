/* fourbar bench as a whole (bench.h holds the grid): the grids and the
 * peers (peers.h) run on one case, then DIR/bench.csv (one line per row),
 * DIR/bench.json (the rows, the cheapest configuration per engine and
 * across engines for error targets 1e-2, 1e-3 and 1e-4, the peers) and
 * DIR/bench.svg written, and the tables printed. The command line
 * (cmd_bench.c) parses the flags and calls fb_bench_study. */
#ifndef FB_BENCH_STUDY_H
#define FB_BENCH_STUDY_H

#include "bench.h"
#include "peers.h"
#include "study.h"

/* The error targets the cheapest configurations are named for. */
#define FB_BENCH_TARGETS 3

/* What bench.svg marks beside the rows: each error target's cheapest
 * configuration across engines, per kind of model, and the peers. */
typedef struct fb_bench_marks_s {
  double target[FB_BENCH_TARGETS];        /* the error targets [-] (1e-2, 1e-3, 1e-4) */
  int cheapest[2][FB_BENCH_TARGETS];      /* row index per kind (ideal, clearance impact) and
                                             target, across engines; -1: none meets it */
  const fb_peer_row *peers;               /* each engine's bare program beside the harness */
  int npeers;                             /* (0: the grid ran no peers) */
} fb_bench_marks;

/* Draws bench.svg at path from rows[0..n) of case case_name, with marks
 * (figures.h's fb_figures_bench, a floor above, given by the command line). */
typedef fb_status (*fb_bench_drawer)(const char *path, const char *case_name,
                                     const fb_bench_row *rows, int n,
                                     const fb_bench_marks *marks, fb_diag *diag);

/* What to bench (the flags of fourbar bench). */
typedef struct {
  const fb_case *c;       /* the case */
  const char *dir;        /* output folder (created) */
  int grids;              /* FB_BENCH_* bits (FB_BENCH_PEERS: the peers too) */
  const char *grid_name;  /* --grid as given, recorded in bench.json */
  int json;               /* 1: print bench.json instead of the tables */
  fb_study_json_writer write_json; /* writes bench.json */
  fb_bench_drawer draw;   /* draws bench.svg (a failure is a warning) */
} fb_bench_opts;

/* The bench o asks for, said before it starts and bounded (work.h): its
 * CPU time cpu_s [s] (fb_bench_estimate, fb_peers_estimate,
 * fb_scaling_estimate, or the planar bench's: pilots of this case's own
 * runs), pilot_s what estimating it cost [s], on stderr when long; refused
 * beyond the case's [run] max_wall_s with instead (the cheaper grids, or
 * NULL). Returns 0 or the exit status (2: beyond the limit), said. */
int fb_bench_work(const fb_bench_opts *o, double cpu_s, double pilot_s, const char *instead);

/* Writes bench.json (j, through o->write_json; on failure j is freed)
 * and bench.svg (o->draw of rows[0..n) with marks; a failure is a
 * warning on stderr) into o->dir. Returns the exit status: 0 ok, 1
 * bench.json could not be written (said on stderr). */
int fb_bench_write_json_svg(const fb_bench_opts *o, json_t *j, const fb_bench_row *rows, int n,
                            const fb_bench_marks *marks);

/* Runs the bench o asks for (on a terminal with a progress bar and the
 * time left on stderr), writes its files and prints its tables (or, with
 * o->json, bench.json) on stdout. Returns the exit status: 0 ok, 1
 * failed, having said why on stderr ("fourbar bench: ..."). */
int fb_bench_study(const fb_bench_opts *o);

#endif
