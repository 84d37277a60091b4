/* fourbar stackup: argument parsing and dispatch only: fb_tol_analyse_jobs
 * (tolerance.h) with a progress bar, the result printed by tables_stackup.h. */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "casefile.h"
#include "cli.h"
#include "textsafe.h"
#include "clock.h"
#include "linkage.h"
#include "planar_tools.h"
#include "tables_stackup.h"
#include "tolerance.h"

static const char stackup_help[] =
    "usage: fourbar stackup [CASE] [--method corners|rss|montecarlo] [--samples N]\n"
    "                       [--seed S] [--jobs J] [--set section.key=value]...\n"
    "                       [--json]\n"
    "\n"
    "How the outputs move within the link-length tolerances. For each output\n"
    "(peaks of coupler and follower angular velocity [rad/s] and acceleration\n"
    "[rad/s^2], transmission angle extremes [rad]): nominal value, exact\n"
    "sensitivity to each link length [unit/m], worst-case range over the 16\n"
    "corners, RSS 3-sigma band, Monte Carlo quantiles at 0.135 %, 50 %, 99.865 %\n"
    "(GSL mt19937; [tolerance] distribution = normal or uniform), each with a\n"
    "95 % distribution-free confidence interval from order statistics: a bound\n"
    "shown as '-' needs more samples.\n"    "A planar case ([linkage] type = planar, docs/planar.md): ISO 2768-1 ([tolerance]\n"
    "class) on each body's joint-to-joint distances; every moving body's omega and\n"
    "alpha extremes: sensitivities by central differences, the RSS band, the worst\n"
    "case over every corner (2^n for n lengths: the six-bar's 10, 1024 corners), the\n"
    "Monte Carlo as above (3000 samples by default, the fewest round number whose\n"
    "tail quantiles' intervals are bounded), each evaluation a revolution's peaks\n"
    "(about 50 ms of CPU on the six-bar).\n"
    "A slider-crank case ([linkage] type = slider-crank): over its crank, coupler\n"
    "and guide offset (8 corners), the outputs are the rod's (coupler_*) omega and\n"
    "alpha peaks, the slider's velocity [m/s] and acceleration [m/s^2] peaks\n"
    "(slider_velocity_max_m_s, ...), the smallest transmission angle [rad] and the\n"
    "stroke [m] (stroke_m).\n"
    "\n"
    "  --method    run one method (repeatable); default all three\n"
    "  --samples   Monte Carlo samples (default 10000; 3000 on a planar case)\n"
    "  --seed      Monte Carlo seed (default 1): same seed, same numbers\n"
    "  --jobs      threads evaluating the samples (default 1); the samples are\n"
    "              drawn in order from the seed, so every J gives the same numbers\n"
    "  --set K=V   override case key K (section.key), as fourbar run takes it\n"
    "  --json      one JSON object on standard output (keys: docs/commands.md,\n"
    "              stackup)\n"
    "  CASE        default: the paper's case, cases/paper_crank_rocker.ini\n"
    "Before the work: the cost of one evaluation of this case is measured (its\n"
    "outputs at the nominal lengths), the corners, RSS and samples are estimated from\n"
    "it and said on standard error when above 2 s; work estimated beyond [run]\n"
    "max_wall_s (--set run.max_wall_s=S) is refused with exit 2, naming the cheaper\n"
    "methods. A progress line goes to standard error on a terminal only.\n"
    "Exit status: 0 ok, 1 failed, 2 bad input or beyond [run] max_wall_s.\n";

int fb_cmd_stackup(int argc, char **argv) {
  static const struct option opts[] = {{"method", required_argument, 0, 'm'},
                                       {"samples", required_argument, 0, 'n'},
                                       {"seed", required_argument, 0, 's'},
                                       {"jobs", required_argument, 0, 'J'},
                                       {"set", required_argument, 0, 'S'},
                                       {"json", no_argument, 0, 'j'},
                                       {"help", no_argument, 0, 'h'},
                                       {0, 0, 0, 0}};
  int mask = 0, json = 0, nsets = 0, ch;
  double samples = 0, seed = 1, jobs = 1; /* samples 0: the mechanism's default */
  const char *sets[FB_CLI_MAX_SETS];
  optind = 1;
  while ((ch = fb_cli_getopt(argc, argv, "h", opts)) != -1) {
    switch (ch) {
      case 'm':
        if (strcmp(optarg, "corners") == 0) mask |= FB_TOL_CORNERS;
        else if (strcmp(optarg, "rss") == 0) mask |= FB_TOL_RSS;
        else if (strcmp(optarg, "montecarlo") == 0) mask |= FB_TOL_MONTECARLO;
        else return fb_cli_fail("stackup", 2, "--method '%s': must be corners, rss or montecarlo", optarg);
        break;
      case 'n':
        if (!fb_cli_double("stackup", "--samples", optarg, &samples)) return 2;
        if (!(samples >= 1 && samples <= 1e8 && samples == floor(samples)))
          return fb_cli_fail("stackup", 2, "--samples %s: must be an integer from 1 to 1e8", optarg);
        break;
      case 's':
        if (!fb_cli_double("stackup", "--seed", optarg, &seed)) return 2;
        if (!(seed >= 0 && seed <= 4294967295.0 && seed == floor(seed)))
          return fb_cli_fail("stackup", 2, "--seed %s: must be an integer from 0 to 4294967295", optarg);
        break;
      case 'J':
        if (!fb_cli_double("stackup", "--jobs", optarg, &jobs)) return 2;
        if (!(jobs >= 1 && jobs <= FB_TOL_MAX_JOBS && jobs == floor(jobs)))
          return fb_cli_fail("stackup", 2, "--jobs %s: must be an integer from 1 to %d", optarg,
                             FB_TOL_MAX_JOBS);
        break;
      case 'S':
        if (nsets == FB_CLI_MAX_SETS)
          return fb_cli_fail("stackup", 2, "more than %d --set", FB_CLI_MAX_SETS);
        sets[nsets++] = optarg;
        break;
      case 'j': json = 1; break;
      case 'h': fputs(stackup_help, stdout); return 0;
      default: return fb_cli_bad_option(argv, "h");
    }
  }
  if (mask == 0) mask = FB_TOL_CORNERS | FB_TOL_RSS | FB_TOL_MONTECARLO;
  fb_case c;
  fb_diag d;
  char case_path[4096];
  int rc = fb_cli_load_case("stackup", argc, argv, optind, sets, nsets, &c, case_path, sizeof case_path);
  if (rc) return rc;
  if (samples == 0) samples = c.planar.on ? FB_PLANAR_MC_SAMPLES : 10000;
  static fb_progress bar;
  fb_progress_init(&bar, json);
  const fb_cli_mc mc = {(size_t)samples, (unsigned long)seed, (int)jobs, &bar};
  if (c.planar.on) /* over its bodies' lengths (planar_tools.h) */
    return fb_cmd_stackup_planar(&c, mask, &mc, json);
  /* the work said and bounded before it starts, from this case's own cost
   * of an evaluation (a corner or a sample: its outputs and their peaks) */
  const double corners = (mask & FB_TOL_CORNERS) ? ldexp(1.0, fb_case_mech(&c)->nlengths) : 0.0;
  double each;
  if (fb_tol_eval_cost(&each, NULL, corners + ((mask & FB_TOL_MONTECARLO) ? samples : 0.0), &c,
                       &d) != FB_OK)
    return fb_cli_fail("stackup", 1, "%s", d.msg);
  if ((mask & FB_TOL_MONTECARLO) && fb_tol_check_cost(each, (size_t)samples, (int)jobs, &d) != FB_OK)
    return fb_cli_fail("stackup", 2, "%s", d.msg);
  double bytes, seconds;
  fb_tol_estimate(each, (size_t)samples, (int)jobs, &bytes, &seconds);
  if ((rc = fb_cli_stackup_work(&c, mask, 0.0, corners, &mc, each, bytes, 0,
                                "the outputs' peaks")) != 0)
    return rc;
  static fb_stackup_result r;
  fb_status st = fb_tol_analyse_jobs(&r, &c, mask, (size_t)samples, (unsigned long)seed,
                                     c.distribution ? FB_DIST_UNIFORM : FB_DIST_NORMAL, (int)jobs,
                                     fb_cli_progress_mc, &bar, &d);
  if (st != FB_OK) return fb_cli_fail("stackup", 1, "%s", d.msg);
  if (json) fb_report_stackup_json(stdout, &r, &c, mask, (unsigned long)seed, (int)jobs);
  else fb_report_stackup_text(stdout, &r, &c, mask);
  return 0;
}
