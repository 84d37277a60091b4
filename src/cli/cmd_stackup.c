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

/* a Monte Carlo estimated longer than this is announced on stderr [s] */
#define STACKUP_NOTE_S 10.0
#define MAX_SETS 256

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
    "case over every corner (2^n for n lengths: the six-bar's 10, 1024 corners, about\n"
    "46 s), the Monte Carlo as above, each sample a revolution's peaks (about 48 ms\n"
    "of CPU on the six-bar: 3000 samples by default, the fewest round number whose\n"
    "tail quantiles' intervals are bounded, about 145 s; the estimate is printed).\n"
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
    "A progress bar goes to standard error on a terminal only.\n"
    "Exit status: 0 ok, 1 failed, 2 bad input.\n";

/* progress bar on a terminal (quiet otherwise): redrawn at most every 0.1 s */
typedef struct {
  int on;         /* standard error is a terminal and the output is text */
  size_t samples; /* total */
  double t0;      /* start [s]; 0: at the first call (a planar case's, after its corners) */
  double last;    /* last redraw [s] */
} progress_bar;

static void progress(double fraction, void *user) {
  progress_bar *b = user;
  if (!b->on) return;
  const double now = fb_clock_s();
  if (b->t0 == 0.0) b->t0 = now;
  if (fraction < 1.0 && now - b->last < 0.1) return;
  b->last = now;
  enum { W = 30 };
  char bar[W + 1];
  const int full = (int)(fraction * W);
  for (int i = 0; i < W; i++) bar[i] = i < full ? '#' : '-';
  bar[W] = 0;
  const double el = now - b->t0;
  fputc('\r', fb_text_raw_stderr()); /* ours: never escaped */
  fprintf(stderr, "  Monte Carlo [%s] %3.0f%%  %zu/%zu  %.1f s", bar, 100.0 * fraction,
          (size_t)(fraction * (double)b->samples), b->samples, el);
  if (fraction > 0.0 && fraction < 1.0) fprintf(stderr, ", %.1f s left ", el * (1.0 - fraction) / fraction);
  else fputs("              ", stderr);
  if (fraction >= 1.0) fputc('\n', stderr);
  fflush(stderr);
}

/* the cost note on stderr (fb_cli_mc's note) */
static void note(size_t samples, double seconds, double bytes, int jobs) {
  fprintf(stderr, "fourbar stackup: %zu Monte Carlo samples: an estimated %.3g s and %.3g GB "
          "with %d job%s (--jobs J divides the time)\n", samples, seconds, bytes / 1e9, jobs,
          jobs > 1 ? "s" : "");
}

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
  const char *sets[MAX_SETS];
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
        if (nsets == MAX_SETS) return fb_cli_fail("stackup", 2, "more than %d --set", MAX_SETS);
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
  progress_bar bar = {isatty(2) && !json, (size_t)samples, 0.0, 0.0};
  if (c.planar.on) /* over its bodies' lengths (planar_tools.h) */
    return fb_cmd_stackup_planar(&c, mask, &(fb_cli_mc){(size_t)samples, (unsigned long)seed,
                                                         (int)jobs, progress, &bar, note}, json);
  /* a long Monte Carlo says what it will cost before it starts */
  if (mask & FB_TOL_MONTECARLO) {
    if (fb_tol_check_cost(c.mechanism, (size_t)samples, (int)jobs, &d) != FB_OK)
      return fb_cli_fail("stackup", 2, "%s", d.msg);
    double bytes, seconds;
    fb_tol_estimate(c.mechanism, (size_t)samples, (int)jobs, &bytes, &seconds);
    if (seconds > STACKUP_NOTE_S) note((size_t)samples, seconds, bytes, (int)jobs);
  }
  static fb_stackup_result r;
  bar.t0 = fb_clock_s();
  fb_status st = fb_tol_analyse_jobs(&r, &c, mask, (size_t)samples, (unsigned long)seed,
                                     c.distribution ? FB_DIST_UNIFORM : FB_DIST_NORMAL, (int)jobs,
                                     progress, &bar, &d);
  if (st != FB_OK) return fb_cli_fail("stackup", 1, "%s", d.msg);
  if (json) fb_report_stackup_json(stdout, &r, &c, mask, (unsigned long)seed, (int)jobs);
  else fb_report_stackup_text(stdout, &r, &c, mask);
  return 0;
}
