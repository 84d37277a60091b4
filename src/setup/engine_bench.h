/* What an engine gives `fourbar bench` (studies/bench.c): its rows of each
 * of the bench's row sets, one configuration (a "point") at a time. The
 * bench decides which sets a grid runs and in which order (every engine of
 * the build with rows in a set, in the order of their ids: bench.h); each
 * engine decides its own configurations: its step sizes, its solver
 * settings, the words of its stepper column. So a new engine appears in
 * every grid it gives rows for without a line in src/studies/.
 *
 * Also the grids fourbar bench runs (FB_BENCH_*, the bits of --grid) and the
 * axes the engines' rows share (the frontier's steps, the adaptive rows). */
#ifndef FB_ENGINE_BENCH_H
#define FB_ENGINE_BENCH_H

#include "case.h"

/* Which grids fb_bench_run runs (bench.h). */
enum {
  FB_BENCH_SOLVERS = 1,  /* every engine's solver settings x step sizes (FB_BENCH_SET_SOLVERS) */
  FB_BENCH_COLLIDERS = 2, /* the collider axis (FB_BENCH_SET_COLLIDERS) */
  FB_BENCH_BULLET = 4,    /* Bullet's grid alone (its rows of FB_BENCH_SOLVERS), beside ODE at the
                             case's own settings (one configuration, the same run's yardstick) */
  FB_BENCH_SIMBODY = 8,   /* Simbody's integrator x accuracy (its own grid); alone, with ODE's
                             dWorldStep rows at the matched mapping */
  FB_BENCH_FRONTIER = 16, /* the step-size frontier alone (a subset of FB_BENCH_SOLVERS'
                             rows): fixed h = 1e-5, 3e-6, 1e-6 s and auto with the case's
                             settings, the tuned ideal rows and the adaptive rows */
  FB_BENCH_PEERS = 32,    /* each engine's bare program beside the harness's model
                             (peers.h; run by the CLI, not by fb_bench_run) */
  FB_BENCH_DEFAULT = 64,  /* the default grid: each engine at its recommended settings
                             (FB_BENCH_SET_DEFAULT), a few minutes on 2 cores */
  FB_BENCH_SCALING = 128  /* how a run's cost grows (scaling.h; run by the CLI's study, not
                             by fb_bench_run) */
};

/* The row sets an engine gives rows for. A grid runs a set for every engine
 * of the build in the order of their ids (bench.h, fb_bench_run). */
typedef enum {
  FB_BENCH_SET_NONE = 0,
  FB_BENCH_SET_DEFAULT,       /* --grid default: the engine at the settings its section of
                                 docs/engines.md recommends for this stiff closed loop */
  FB_BENCH_SET_DEFAULT_LAST,  /* the default grid's last rows, after every engine's
                                 (ODE: its ideal rows at world ERP 1) */
  FB_BENCH_SET_SOLVERS,       /* --grid solvers and all: the engine's solver settings x step
                                 sizes, with its adaptive and tuned rows */
  FB_BENCH_SET_FRONTIER,      /* --grid frontier: the case's settings at the frontier's steps
                                 (FB_BENCH_FRONTIER_STEPS) */
  FB_BENCH_SET_FRONTIER_LAST, /* the frontier's last rows, after every engine's frontier: its
                                 tuned and adaptive rows */
  FB_BENCH_SET_OWN,           /* the engine's own grid (fb_engine_bench.own_grid) */
  FB_BENCH_SET_CASE_ROW,      /* one row at the case's own settings: the yardstick run before
                                 another engine's own grid run alone (--grid bullet) */
  FB_BENCH_SET_STEP_ROWS,     /* rows at fixed steps and auto with the matched mapping, run
                                 after another engine's own grid run alone (--grid simbody) */
  FB_BENCH_SET_COLLIDERS,     /* the collider axis: the steps and settings at which the bench
                                 runs each of the engine's clearance impact models beside its
                                 exact collider (the engine's models with the faceted and the
                                 ccd collider, rings of several segment counts) */
  FB_BENCH_SETS
} fb_bench_set;

/* The columns of one point's rows the engine says (the bench measures the
 * rest). The bench sets stepper "", mapping -1, no_ideal_row 0 and
 * hard_pins 0 before it asks. */
typedef struct {
  char stepper[32]; /* the stepper column: ODE "world", "quick-20", "world-a0.3"; MuJoCo its
                       integrator; Bullet "si-10", "mlcp"; Simbody "rkmerson 1e-06" */
  int mapping;      /* the mapping column of its clearance row (fb_mapping), -1 where the
                       engine takes none (its ideal row has none either way) */
  int no_ideal_row; /* 1: the ideal model runs (timing, step halving) without a row of its
                       own: a point that varies only the clearance contact */
  int hard_pins;    /* 1: the rows' world_cfm column is 0: the engine's ideal joints are hard
                       rows whatever the case's world CFM (Bullet) */
} fb_bench_point;

/* An engine's bench rows (fb_engine.bench). */
typedef struct {
  /* Point i (0, 1, ...) of the engine's rows of set s on case c: sets k, the
   * bench's copy of c (two revolutions; the engine's ideal stack-up model,
   * and with clearance at the crank-coupler joint alone also its clearance
   * impact model and their reference, fb_bench_models; the case's step with
   * [solver] h_s = auto), to the point's configuration (its step:
   * fb_bench_fixed_step, fb_bench_adaptive_step or the case's own; its
   * solver settings; k->model_count = 1 for the ideal model alone), and p
   * to its columns. Returns 0 when set s has no point i (k and p then
   * unused). Never fails. */
  int (*point)(fb_bench_set s, int i, const fb_case *c, fb_case *k, fb_bench_point *p);
  int own_grid;             /* the FB_BENCH_* grid that runs the engine's FB_BENCH_SET_OWN
                               rows (0: none): after the default grid, before the solver
                               grids; not with FB_BENCH_SOLVERS when the engine has rows of
                               FB_BENCH_SET_SOLVERS (they stand for it) */
  fb_bench_set alone_before; /* with its own grid run without FB_BENCH_SOLVERS: the set of
                               every engine's rows run before it (FB_BENCH_SET_NONE: none) */
  fb_bench_set alone_after; /* ... and after it */
  int names_world_erp;      /* 1: a configuration of the engine includes the world ERP and CFM
                               of the ideal joints ([solver] world_erp, world_cfm), which the
                               bench's cheapest lines name */
} fb_engine_bench;

/* k at the fixed step h [s]; h = 0 leaves the case's [solver] h_s = auto. */
static inline void fb_bench_fixed_step(fb_case *k, double h) {
  if (h > 0.0) {
    k->solver.h = h;
    k->solver.h_mode = FB_STEP_FIXED;
  }
}

/* k with [solver] h_s = adaptive at accuracy [-] on the output grid
 * [solver] h_min_s. */
static inline void fb_bench_adaptive_step(fb_case *k, double accuracy) {
  k->solver.h_mode = FB_STEP_ADAPTIVE;
  k->solver.h = k->solver.h_min;
  k->solver.accuracy = accuracy;
}

/* The axes of the engines' rows, shared with the tests. */
/* ODE step sizes of the grid: 1e-3, 1e-4, 1e-5, 1e-6 s and auto. */
#define FB_BENCH_STEPS 5
/* ODE ideal rows beyond the grid: dWorldStep, world ERP 1, CFM 1e-10 at
 * h = 1.5e-5 and 2e-5 s (the 1e-5 error target at half the 1e-5 s cost). */
#define FB_BENCH_IDEAL_TUNED 2
/* Rows with [solver] h_s = adaptive: accuracy 0.3 and 0.1
 * (FB_BENCH_ADAPTIVE_ACCURACY); ODE with dWorldStep, the case's world
 * ERP/CFM and mapping (stepper "world-a<accuracy>"), MuJoCo with the case's
 * integrator ("<integrator>-a<accuracy>"). */
#define FB_BENCH_ADAPTIVE 2
#define FB_BENCH_ADAPTIVE_ACCURACY(i) ((i) == 0 ? 0.3 : 0.1)
/* ODE's adaptive row with the rocking bound (step_control.h, [solver]
 * rocking_h_omega): accuracy 0.3, rocking_h_omega FB_BENCH_ROCKING_H_OMEGA
 * (stepper "world-a0.3-r<bound>"); one row, beside the ODE rows above. */
#define FB_BENCH_ADAPTIVE_ROCKING 1
/* The bound of that row [-]: on the paper case 0.08, 0.1 and 0.12 put the
 * peak force 1.2e-3, 1.6e-3 and 2.0e-3 off at 30,674, 23,869 and 20,431
 * steps over 2 revolutions (docs/step-size.md); 0.1 is the loosest within
 * 2e-3 with a margin. */
#define FB_BENCH_ROCKING_H_OMEGA 0.1
/* Steps of the frontier grid: 1e-5, 3e-6, 1e-6 s and auto
 * (FB_BENCH_FRONTIER_H; ODE all four, MuJoCo the three fixed ones). */
#define FB_BENCH_FRONTIER_STEPS 4
#define FB_BENCH_FRONTIER_H(i) ((i) == 0 ? 1e-5 : (i) == 1 ? 3e-6 : (i) == 2 ? 1e-6 : 0.0)
#define FB_BENCH_MUJOCO_STEPS 7 /* step sizes of the MuJoCo grid */
#define FB_BENCH_BULLET_STEPS 4 /* step sizes of the Bullet grid: 1e-4, 1e-5, 1e-6 s and auto */
#define FB_BENCH_BULLET_SOLVERS 4 /* sequential impulse at 10, 50, 100 iterations; mlcp-dantzig */

#endif
