/* fourbar bench: argument parsing and dispatch only; the bench, its files and
 * tables are bench_study.c's, the grid bench.c's. */
#include <getopt.h>
#include <stdio.h>
#include <string.h>

#include "bench_study.h"
#include "cli.h"
#include "fileio.h"
#include "figures.h"
#include "peers.h"
#include "planar_bench.h"
#include "report.h"

static const char bench_help[] =
    "usage: fourbar bench [CASE] [--out DIR [--overwrite]] [--json]\n"
    "                     [--set section.key=value]...\n"
    "                     [--grid default|peers|all|solvers|colliders|bullet|\n"
    "                             simbody|frontier|scaling]\n"
    "\n"
    "Default grid (--grid default; about 30 s of CPU on the paper case, 29 s\n"
    "measured with its estimate; longer while others load the machine): each\n"
    "engine at its recommended settings (ODE dWorldStep at h = 1e-5 s, auto and\n"
    "adaptive; MuJoCo at 1e-5 s, 3e-6 s and adaptive; Bullet's MLCP at 1e-5 s and\n"
    "auto; Simbody rkmerson at accuracy 1e-4 and 1e-6 and cpodes at 1e-6 on the\n"
    "case's output grid; Siconos at auto; DART's World::step with PGS at 1e-5 s\n"
    "and auto; ODE's ideal rows at world ERP 1), each row's cost split into\n"
    "the engine's stepping and the harness's sampling of its output grid, then\n"
    "the peers. --grid peers: each engine's bare program (tests/peers, built with\n"
    "the tests; $FOURBAR_PEERS_DIR names another folder) beside the harness's\n"
    "ideal nominal model on the same grid, 3 alternating rounds: the harness's\n"
    "cost over the bare program's (bench.json peers[].engine,\n"
    "peers[].harness_over_bare) and their omega peaks' agreement. --grid all is\n"
    "the full grid below (about 6 minutes on the paper case, 5.5 minutes of CPU\n"
    "measured):\n"
    "\n";
/* a planar case's grid (planar_bench.h) */
static const char bench_help_planar[] =
    "\n"
    "A planar case ([linkage] type = planar) runs its own default grid (the other\n"
    "grids are refused; about 30 s of CPU on cases/templates/planar_fourbar.ini,\n"
    "32 s measured; 5 minutes of CPU on cases/watt_sixbar.ini, most of it\n"
    "Simbody's, Siconos's and DART's rows at the case's 5e-6 s step): every\n"
    "engine with a binding of the engine kit, its ideal nominal model against the\n"
    "analytic model (error: the largest relative error of every moving body's\n"
    "omega window peaks, each relative to the larger of that body's two analytic\n"
    "extremes) and its clearance-impact model against the reference of the impact\n"
    "law (error: the largest of the peak force's, the peak penetration's and every\n"
    "moving body's alpha spike's relative errors, the four-bar's definition over\n"
    "every body), each run as fourbar run runs it, 2 revolutions (or the case's\n"
    "fewer), peaks after the first (or over all with [run] peaks = all), at the\n"
    "points of the engine's default grid above (an auto point at the case's h,\n"
    "adaptive ones left out), the first also at h/2, 3 at most: on the planar\n"
    "four-bar ODE at 1e-5 and 5e-6 s, MuJoCo at 1e-5, 5e-6 and 3e-6 s, Bullet at\n"
    "1e-5 and 5e-6 s, Simbody rkmerson at accuracy 1e-4 (h and h/2) and 1e-6, the\n"
    "others at the case's h and h/2.\n"
    "bench.json has the four-bar's keys where they apply, each row's kind,\n"
    "yardstick, error_parts and error_by_body; docs/performance.md.\n";
/* its second part (a string literal stays within C's 4095 characters) */
static const char bench_help_grids[] =
    "Speed against error on every engine: ODE's stepper (dWorldStep; dWorldQuickStep\n"
    "at 10, 20, 50 iterations) x step size (1e-3 to 1e-6 s, and auto: the largest\n"
    "with h x rate <= 0.5 at the fastest contact) x mapping (secant, tangent,\n"
    "matched) x world ERP/CFM, and (in builds with MuJoCo) MuJoCo's integrator\n"
    "(euler, implicit, rk4) x step size (1e-3 to 1e-6 s, 7 values), and (in builds\n"
    "with Bullet) Bullet's solver (sequential impulse at 10, 50, 100 iterations:\n"
    "si-N; mlcp-dantzig: mlcp) x step size (1e-4, 1e-5, 1e-6 s, auto), measured\n"
    "against the analytic solution (ideal stack-up models) and the reference\n"
    "dynamics (clearance impact models; a clearance row's error is the largest of\n"
    "its peak force, max penetration and coupler and follower alpha spike errors,\n"
    "each also reported), a step-halving figure for every fixed-step row (the\n"
    "largest change of those peaks from h to h/2: an error estimate without a\n"
    "reference), two ODE ideal rows at world ERP 1 (h = 1.5e-5 and 2e-5 s), rows\n"
    "with h_s = adaptive on both engines (accuracy 0.3 and 0.1, stepper\n"
    "world-a<accuracy>, <integrator>-a<accuracy>), with wall time per simulated\n"
    "revolution (median of 3 rounds over the whole grid for runs under 1 s; the\n"
    "set-up, the engine's create and the mapping of the samples' memory, apart as\n"
    "setup_s) measured in the same run. Marks one Pareto front per engine and model\n"
    "and names the cheapest configuration for error targets 1e-2, 1e-3 and 1e-4, per\n"
    "engine and across engines. Collider axis: the impact law through the libccd\n"
    "ring (16, 64, 256, 1024 segments) and the faceted ring against ODE's exact\n"
    "collider at h = 1e-5 and 1e-6 s: error against the reference, differences from\n"
    "the exact collider and cost per step (docs/colliders.md). --grid runs one of\n"
    "them (default all); --grid bullet runs Bullet's grid alone beside one ODE row\n"
    "at the case's own settings. In builds with Simbody: Simbody's integrator\n"
    "(rkmerson, rkfeldberg, rk3, cpodes, verlet) x accuracy (1e-3 to 1e-8) at the\n"
    "case's output step (docs/engines.md); --grid simbody runs that grid alone, with\n"
    "ODE's dWorldStep rows (matched mapping; h 1e-4, 1e-5, 1e-6 s and auto) for the\n"
    "comparison. In builds with Siconos and DART: each at h = 1e-5, 3e-6, 1e-6 s\n"
    "and auto (Siconos Moreau-Jean, DART World::step with PGS). frontier: only the\n"
    "step-size frontier (the case's settings at h = 1e-5, 3e-6, 1e-6 s and auto,\n"
    "the ideal rows at ERP 0.8 and 1, and the adaptive rows; docs/step-size.md).\n"
    "--grid scaling (about 20 s of CPU on the\n"
    "paper case): how a run's cost grows, one setting varied at a time: revolutions\n"
    "1, 2, 4, 8, 16 with the reference alone (its and its check's steps per\n"
    "revolution), [clearance] stiffness_scale x1, x10, x100, an ensemble of 1 and 4\n"
    "members at --jobs 1 and 2, 1e4 and 1e5 Monte Carlo samples; each run's CPU\n"
    "time, wall time and up-front estimate (bench.json scaling[]; docs/\n"
    "performance.md). Writes DIR/bench.csv, bench.json and\n"
    "bench.svg (default DIR results/<case>-bench/, beside the run folder\n"
    "results/<case>/; a run into the same folder keeps them); an existing file of\n"
    "those names that no fourbar bench wrote there is replaced only with --overwrite\n"
    "(docs/outputs.md, What fourbar replaces).\n"
    "Before the work the bench is estimated from this case's own runs (each run the\n"
    "grid makes, run twice for a short time and extrapolated: about 5 % of the\n"
    "bench), said on stderr when above 2 s, and refused beyond [run] max_wall_s\n"
    "(--set run.max_wall_s=S) with exit 2. On a terminal a progress line with the\n"
    "time left is drawn on stderr.\n"
    "Exit status: 0 ok, 1 failed, 2 bad input or beyond [run] max_wall_s.\n";

/* bench.svg (fb_bench_drawer) */
static fb_status draw(const char *path, const char *case_name, const fb_bench_row *rows, int n,
                      const fb_bench_marks *marks, fb_diag *diag) {
  return fb_figures_bench(path, FB_FIGURE_SVG, case_name, rows, n, marks, diag);
}

int fb_cmd_bench(int argc, char **argv) {
  static const struct option opts[] = {{"out", required_argument, 0, 'o'},
                                       {"set", required_argument, 0, 's'},
                                       {"json", no_argument, 0, 'j'},
                                       {"grid", required_argument, 0, 'g'},
                                       {"overwrite", no_argument, 0, 'w'},
                                       {"help", no_argument, 0, 'h'},
                                       {0, 0, 0, 0}};
  const char *out = NULL, *sets[FB_CLI_MAX_SETS];
  int nsets = 0, json = 0, overwrite = 0, ch, grids = FB_BENCH_DEFAULT | FB_BENCH_PEERS;
  const char *grid_name = "default";
  optind = 1;
  while ((ch = fb_cli_getopt(argc, argv, "h", opts)) != -1) {
    switch (ch) {
      case 'o': out = optarg; break;
      case 's':
        if (nsets == FB_CLI_MAX_SETS)
          return fb_cli_fail("bench", 2, "more than %d --set", FB_CLI_MAX_SETS);
        sets[nsets++] = optarg;
        break;
      case 'j': json = 1; break;
      case 'w': overwrite = 1; break;
      case 'g':
        grid_name = optarg;
        if (strcmp(optarg, "default") == 0) grids = FB_BENCH_DEFAULT | FB_BENCH_PEERS;
        else if (strcmp(optarg, "peers") == 0) grids = FB_BENCH_PEERS;
        else if (strcmp(optarg, "all") == 0)
          grids = FB_BENCH_SOLVERS | FB_BENCH_SIMBODY | FB_BENCH_COLLIDERS | FB_BENCH_PEERS;
        else if (strcmp(optarg, "solvers") == 0) grids = FB_BENCH_SOLVERS | FB_BENCH_SIMBODY;
        else if (strcmp(optarg, "colliders") == 0) grids = FB_BENCH_COLLIDERS;
        else if (strcmp(optarg, "bullet") == 0) grids = FB_BENCH_BULLET;
        else if (strcmp(optarg, "simbody") == 0) grids = FB_BENCH_SIMBODY;
        else if (strcmp(optarg, "frontier") == 0) grids = FB_BENCH_FRONTIER;
        else if (strcmp(optarg, "scaling") == 0) grids = FB_BENCH_SCALING;
        else
          return fb_cli_fail("bench", 2,
                             "--grid '%s': must be default, peers, all, solvers, colliders, "
                             "bullet, simbody, frontier or scaling",
                             optarg);
        break;
      case 'h':
        fputs(bench_help, stdout);
        fputs(bench_help_grids, stdout);
        fputs(bench_help_planar, stdout);
        return 0;
      default: return fb_cli_bad_option(argv, "h");
    }
  }
  fb_case c;
  char case_path[4096];
  int rc = fb_cli_load_case("bench", argc, argv, optind, sets, nsets, &c, case_path, sizeof case_path);
  if (rc) return rc;
  /* a planar case: its own default grid (planar_bench.h), the other grids the four-bar's */
  if (c.planar.on && grids != (FB_BENCH_DEFAULT | FB_BENCH_PEERS))
    return fb_cli_fail("bench", 2, "--grid %s: %s is a planar case ([linkage] type = planar), on "
                       "which fourbar bench runs its default grid alone (--grid default: every "
                       "engine's kit-built models; docs/performance.md)", grid_name, case_path);
  /* a grid that would measure nothing is refused, never run empty */
  if (grids == FB_BENCH_PEERS && !fb_peers_build(c.mechanism))
    return fb_cli_fail("bench", 2, "--grid peers: the bare programs it runs (tests/peers) build the "
                       "four-bar only, and %s is a %s ([linkage] type = %s): nothing to measure; "
                       "--grid default measures every engine's %s models", case_path,
                       fb_case_mech(&c)->type, fb_case_mech(&c)->type, fb_case_mech(&c)->type);
  char dir[4096];
  if (out) snprintf(dir, sizeof dir, "%s", out);
  else snprintf(dir, sizeof dir, "results/%s-bench", c.name); /* beside, not inside, results/<case>/ */
  /* its files: checked and the folder locked before any work (fileio.h) */
  static const char *const names[] = {"bench.csv", "bench.json", "bench.svg", "bench.figure.json"};
  const fb_outpath_rule rule = {.flag = "--out", .overwrite = overwrite, .input = case_path};
  static fb_outfiles files;
  fb_diag d;
  fb_status st = fb_outfiles_begin(&files, dir, "bench", names, 4, &rule, &d);
  if (st != FB_OK) return fb_cli_fail("bench", st == FB_ERR_ARG ? 2 : 1, "%s", d.msg);
  const fb_bench_opts o = {.c = &c, .dir = dir, .grids = grids, .grid_name = grid_name,
                           .json = json, .write_json = fb_report_write_json, .draw = draw};
  rc = c.planar.on ? fb_bench_planar(&o) : fb_bench_study(&o);
  if (fb_outfiles_end(&files, &d) != FB_OK && !rc) rc = fb_cli_fail("bench", 1, "%s", d.msg);
  return rc;
}
