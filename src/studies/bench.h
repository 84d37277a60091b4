/* Speed against error: a grid of every engine's configurations on one case,
 * each measured against the exact yardstick (the analytic solution for the
 * ideal stack-up model, the reference dynamics for the clearance impact
 * model), with its cost as wall time per simulated revolution (median of
 * repeats).
 *
 * The configurations are the engines' own (engine_bench.h: each engine's
 * table gives its rows of each row set); a grid runs its sets over every
 * engine of the build in the order of their ids (fb_bench_run), so a new
 * engine joins every grid it gives rows for. Today's rows:
 *
 * Grid: stepper (dWorldStep; dWorldQuickStep at 10, 20, 50 iterations) x
 * step size h (1e-3, 1e-4, 1e-5, 1e-6 s and auto: resolution.h) x mapping
 * (secant, tangent, matched; the clearance model only) x world ERP/CFM of the ideal joints ((0.2, 1e-10),
 * (0.8, 1e-8)); and, in builds with MuJoCo, MuJoCo's integrator (euler,
 * implicit, rk4) x h (1e-3, 3e-4, 1e-4, 3e-5, 1e-5, 3e-6, 1e-6 s) with the
 * case's loop closure and drive (models mujoco-ideal-stackup and
 * mujoco-clearance-impact); and, in builds with Bullet, Bullet's solver
 * (sequential impulse at 10, 50 and 100 iterations, "si-N"; mlcp-dantzig,
 * "mlcp") x h (1e-4, 1e-5, 1e-6 s and auto) with the case's mapping (models
 * bullet-ideal-stackup and bullet-clearance-impact). Error of the ideal model: largest |relative error| of the
 * four angular-velocity peaks; of the clearance model: the largest of the
 * |relative errors| of peak force, max penetration and the coupler and
 * follower alpha spikes (peak |alpha|) against the reference, each part kept
 * in the row. Every fixed-step row also has a step-halving consistency
 * figure: the same case run once more at h/2 (no reference), the largest
 * relative change of the same peaks, an error estimate where no reference
 * exists.
 * A row is on the Pareto front of its model (so of its engine) when no other
 * row of that model is both cheaper and at least as accurate.
 *
 * Collider axis (docs/colliders.md): the impact law through each ODE
 * collider, dWorldStep, the case's mapping, world ERP/CFM (0.2, 1e-10),
 * h = 1e-5 and 1e-6 s: ode-clearance-ccd with rings of 16, 64, 256 and 1024
 * segments and ode-clearance-faceted with the case's box ring, each run
 * beside ode-clearance-impact (the exact collider) and the reference; a row
 * holds its error against the reference as above, its differences from the
 * exact collider of the same run (peak force, peak penetration, impacts,
 * coupler spike ratio) and its cost per step, also relative to the exact
 * collider's. */
#ifndef FB_BENCH_H
#define FB_BENCH_H

#include "analytic.h"
#include "case.h"
#include "engine_bench.h"
#include "model_table.h"
#include "outcome.h"

typedef struct fb_bench_row_s {
  const fb_model *row;     /* the model (rows compare by it) */
  char model[FB_NAME_SIZE]; /* its name, for the writers */
  char engine[16];         /* "ode" or "mujoco" */
  char stepper[32];        /* ode: "world" or "quick-<iterations>"; mujoco: its integrator */
  double h;                /* [s] */
  int h_auto;              /* 1: h came from [solver] h_s = auto */
  int h_adaptive;          /* 1: [solver] h_s = adaptive; h is the output grid (h_min_s) */
  double steps_taken;      /* engine steps of the run [-] (adaptive: its own steps) */
  int mapping;             /* fb_mapping; -1 where none applies (ideal, mujoco) */
  double world_erp, world_cfm; /* ode's ideal joints; NaN for mujoco */
  fb_stop stop;            /* why the model's run stopped (FB_STOP_NONE: it did not) */
  double error;            /* NaN when the run stopped */
  double wall_per_rev;     /* median wall time per simulated revolution, the engine's setup
                              excluded [s] */
  double setup_s;          /* median wall time of the set-up (the engine's create, the
                              series' storage mapped) [s] */
  double stepping_per_rev; /* of wall_per_rev, the engine's stepping (model_run.h stepping_s;
                              Simbody: its integrator's steps) [s]; the median of the rounds */
  double sampling_per_rev; /* the rest: the harness's sampling of the output grid (reading,
                              checking and storing each sample; Simbody: also its
                              interpolation and exact samples) [s] */
  double samples_per_rev;  /* output samples per revolution (the grid it samples) [-] */
  int repeats;
  int pareto;
  char collider[32];       /* "-" (ideal), "exact", "faceted", "ccd" or "native" */
  int segments;            /* ring of the faceted and ccd colliders [-]; 0 for the others */
  double us_per_step;      /* median wall time per step [us] */
  int collider_axis;       /* 1: a row of the collider axis */
  int has_vs_exact;        /* collider axis row that ran: the fields below are set */
  double force_vs_exact;   /* (peak force - exact collider's) / exact's [-] */
  double pen_vs_exact;     /* the same for the peak penetration [-] */
  double alpha_vs_exact;   /* the same for the coupler spike ratio alpha_peak_ratio_coupler [-] */
  int impacts;             /* impacts counted over the peak window [-] */
  int impacts_exact;       /* by the exact collider [-] */
  double cost_vs_exact;    /* us_per_step / the exact collider's [-] */
  double part[4];          /* clearance rows beside the reference: the parts of error, signed
                              (model - reference) / |reference| of peak force, max penetration,
                              coupler and follower alpha spike (FB_BENCH_PART_*) [-]; NaN else */
  double halving;          /* step-halving consistency of a fixed-step row: largest |relative
                              change| of the peaks its error compares (ideal: the four omega
                              peaks; clearance: the four parts) from h to h/2 [-]; NaN for
                              auto rows and when either run stopped */
  double halving_part[4];  /* clearance rows: each part's change from h to h/2, signed
                              (peak at h - peak at h/2) / |peak at h/2| [-]; NaN else */
  double ecc_direction_rms; /* clearance rows beside the reference: the eccentricity
                              direction's RMS error in continuous contact (metrics.h,
                              fb_reference_error.ecc_direction_rms) [rad]; NaN else */
} fb_bench_row;

/* The parts of a clearance row's error, in order (fb_bench_row.part). */
enum {
  FB_BENCH_PART_FORCE = 0,          /* peak contact force */
  FB_BENCH_PART_PENETRATION = 1,    /* max penetration depth */
  FB_BENCH_PART_ALPHA_COUPLER = 2,  /* coupler alpha spike: peak |alpha| */
  FB_BENCH_PART_ALPHA_FOLLOWER = 3, /* follower alpha spike */
  FB_BENCH_PARTS = 4
};

/* A body's alpha spike: max(|alpha_max|, |alpha_min|) over the peak window
 * [rad/s^2]. */
double fb_bench_alpha_spike(const fb_body_peaks *p);

/* rel[i] = (a[i] - b[i]) / |b[i]| for i < n (signed relative difference of
 * peak a from peak b); returns the largest |rel[i]|, the combined error
 * (NaN when any is not finite, b[i] = 0 included). A clearance row's error
 * is this over FB_BENCH_PARTS peaks against the reference's; its halving
 * figure the same with a = peaks at h, b = peaks at h/2. */
double fb_bench_rel_parts(double *rel, const double *a, const double *b, int n);

/* Rows one bench run may hold: every engine's grid (ODE 320 rows, MuJoCo,
 * Bullet, Simbody, the adaptive and tuned rows and the collider axis come to
 * about 500); a run that would pass it stops with an error, never a silent cut. */
#define FB_BENCH_MAX_ROWS 1024

/* Timing: a configuration is run once for its errors, then again, its timed
 * models only, in FB_BENCH_ROUNDS - 1 further rounds over the whole grid
 * when its first run took at most FB_BENCH_REPEAT_BELOW_S (timed models
 * together); a row's cost is the median of its rounds. A round visits every
 * configuration once, so repeats of one configuration lie far apart in time
 * and a slow phase of the machine lands in one round of many rows, not in
 * every repeat of a few. The collider axis keeps back-to-back repeats (its
 * costs compare with the exact collider's of the same runs). */
#define FB_BENCH_ROUNDS 3
#define FB_BENCH_REPEAT_BELOW_S 1.0
/* The threshold the grids repeat below [s]: FB_BENCH_REPEAT_BELOW_S unless
 * fb_bench_repeat_below set another (a test sets INFINITY, so that which
 * rows repeat, and its verdict, does not hang on how long a run took on a
 * machine others load). */
double fb_bench_repeat_below_s(void);
void fb_bench_repeat_below(double seconds);
/* The share of the progress fraction the first pass reports (the rounds
 * time the timed models alone, without the reference or the step-halving
 * runs). */
#define FB_BENCH_FIRST_PASS_SHARE 0.6

/* Runs the grids named in grids (FB_BENCH_* bits, engine_bench.h) on case c
 * (2 revolutions per run; timing above), each a sequence of row sets run
 * over every engine of the build with rows in the set, in the order of
 * their ids: the default grid FB_BENCH_SET_DEFAULT then
 * FB_BENCH_SET_DEFAULT_LAST; the engines' own grids (FB_BENCH_SET_OWN of an
 * engine whose fb_engine_bench.own_grid bit is in grids; without
 * FB_BENCH_SOLVERS with the sets it asks beside it); FB_BENCH_SOLVERS:
 * FB_BENCH_SET_SOLVERS; FB_BENCH_FRONTIER (not with FB_BENCH_SOLVERS):
 * FB_BENCH_SET_FRONTIER then FB_BENCH_SET_FRONTIER_LAST; FB_BENCH_COLLIDERS:
 * each point of FB_BENCH_SET_COLLIDERS with each ring. rows gets *n rows.
 * progress (may be NULL) gets the fraction done. The collider axis needs a
 * case whose only clearance joint is the crank-coupler one (else it adds no
 * row). Errors: those of fb_run_case. */
fb_status fb_bench_run(fb_bench_row *rows, int *n, const fb_case *c, int grids,
                       void (*progress)(double fraction, void *user), void *user, fb_diag *diag);

/* The CPU time [s] fb_bench_run(c, grids) would take, estimated before it
 * runs: the same grids walked, each run replaced by its case's pilot
 * (pilot.h: two short runs of it, extrapolated) and counted as often as
 * the bench would run it (its step-halving run, its repeats by the repeat
 * rule read from the extrapolated wall times, the later rounds' timed
 * models); *pilot_s (may be NULL) what the pilots cost. The peers and the
 * scaling grid are not in it (fb_peers_estimate, fb_scaling_estimate).
 * Errors: those of fb_run_case (a configuration that does not run). */
fb_status fb_bench_estimate(double *cpu_s, double *pilot_s, const fb_case *c, int grids,
                            fb_diag *diag);

/* Marks rows on the Pareto front of their model: no other row of the same
 * model with a finite error is at least as cheap and as accurate, and
 * strictly better in one. Rows with a non-finite error are never on it. */
void fb_bench_mark_pareto(fb_bench_row *rows, int n);

/* Index of the cheapest row of model meeting error <= target, -1 if none. */
int fb_bench_cheapest(const fb_bench_row *rows, int n, const fb_model *model, double target);

/* As fb_bench_cheapest, among the rows i with eligible[i] != 0 only (n
 * entries; NULL: every row): a planar case's clearance row whose first
 * impact is beyond fourbar run's verdict bound is not eligible, so that
 * the configuration bench names reads ok in run. */
int fb_bench_cheapest_of(const fb_bench_row *rows, int n, const fb_model *model, double target,
                         const unsigned char *eligible);

/* The models a bench of engine e measures: its ideal stack-up model
 * (*ideal) and its clearance impact model with the exact collider
 * (*clearance; for an engine without one, its first stack-up clearance
 * model with a reference: siconos-clearance-newton); NULL where the table
 * has none. */
void fb_bench_models(fb_engine_id e, const fb_model **ideal, const fb_model **clearance);

/* 1 when engine e's bench models (fb_bench_models) build case c's
 * mechanism (model_table.h mechanisms); the grids leave out an engine's
 * rows when they do not (fourbar bench names it). */
int fb_bench_builds(fb_engine_id e, const fb_case *c);

#endif
