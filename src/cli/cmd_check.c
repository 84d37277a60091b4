/* fourbar check: regression of spike magnitudes against committed baselines.
 * Argument parsing and dispatch only: the baselines are check_baselines.c's,
 * the metrics and the calibration check.c's. */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>

#include "check_baselines.h"
#include "cli.h"
#include "report.h"

static const char check_help[] =
    "usage: fourbar check [--cases NAME,...] [--set section.key=value]... [--json]\n"
    "                     [--jobs J]\n"
    "       fourbar check --update [--cases NAME,...]\n"
    "       fourbar check --calibrate [CASEFILE...]\n"
    "\n"
    "Reruns the cases that have a baseline in results/baselines/<case>.json and\n"
    "compares every peak and spike metric with its baseline value and measured\n"
    "tolerance; prints metric, baseline, now, tolerance, verdict, and a last line\n"
    "'N passed, N failed'. Exit status 1 when any metric moved beyond its\n"
    "tolerance. A planar case's metrics are named by its bodies\n"
    "(<model>.<body>.omega_max_rad_s, ...) and a clearance model's or\n"
    "reference's contact (<model>.spikes.force_max_n, penetration_max_m).\n"
    "\n"
    "  --cases      only these case names\n"
    "  --set K=V    override a key in every case (e.g. clearance.stiffness_scale=1.2)\n"
    "  --update     rewrite the baseline values (tolerances kept); prints what\n"
    "               changed\n"
    "  --calibrate  measure values and tolerances anew: each case is rerun with h\n"
    "               1 % smaller, the initial crank angle moved by 1e-12 rad (a\n"
    "               planar case: its drive's speed times 1 + 1e-12; an undriven\n"
    "               one: neither), and once more unchanged; tolerance =\n"
    "               max(1e-12, 1e-9 |value|, 3 x spread).\n"
    "               CASEFILE (relative to cases/) adds a case; none: all baselines\n"
    "  --json       one JSON object with every comparison\n"
    "  --jobs J     run a case's [run] ensemble members in J worker processes\n"
    "               (default 1); the numbers do not depend on J\n";

int fb_cmd_check(int argc, char **argv) {
  static const struct option opts[] = {{"cases", required_argument, 0, 'c'},
                                       {"set", required_argument, 0, 's'},
                                       {"update", no_argument, 0, 'u'},
                                       {"calibrate", no_argument, 0, 'k'},
                                       {"json", no_argument, 0, 'j'},
                                       {"jobs", required_argument, 0, 'J'},
                                       {"help", no_argument, 0, 'h'},
                                       {0, 0, 0, 0}};
  const char *cases = NULL;
  const char *sets[FB_CLI_MAX_SETS];
  int nsets = 0, update = 0, cal = 0, json = 0, jobs = 1, ch;
  optind = 1;
  while ((ch = fb_cli_getopt(argc, argv, "h", opts)) != -1) {
    switch (ch) {
      case 'c': cases = optarg; break;
      case 's':
        if (nsets == FB_CLI_MAX_SETS)
          return fb_cli_fail("check", 2, "more than %d --set", FB_CLI_MAX_SETS);
        sets[nsets++] = optarg;
        break;
      case 'u': update = 1; break;
      case 'k': cal = 1; break;
      case 'j': json = 1; break;
      case 'J': {
        char *end;
        const long j = strtol(optarg, &end, 10);
        if (end == optarg || *end || j < 1 || j > FB_ENSEMBLE_MAX)
          return fb_cli_fail("check", 2, "--jobs %s: must be an integer from 1 to %d", optarg,
                             FB_ENSEMBLE_MAX);
        jobs = (int)j;
        break;
      }
      case 'h': fputs(check_help, stdout); return 0;
      default: return fb_cli_bad_option(argv, "h");
    }
  }
  /* a baseline is the committed case file's: a variant never replaces it */
  if ((update || cal) && nsets > 0)
    return fb_cli_fail("check", 2, "--set with --%s would write the values of a variant (%s%s) into "
                       "the committed baseline of the case: change the case file itself, or "
                       "calibrate a new case file with its own [case] name", update ? "update" : "calibrate",
                       sets[0], nsets > 1 ? ", ..." : "");
  const fb_check_opts o = {.baselines_dir = fb_cli_baselines_dir(), .cases_dir = fb_cli_cases_dir(),
                           .cases = cases, .sets = sets, .nsets = nsets, .update = update,
                           .calibrate = cal, .json = json, .jobs = jobs,
                           .case_files = argv + optind, .ncase_files = argc - optind,
                           .write_json = fb_report_write_json};
  return fb_check_command(&o);
}
