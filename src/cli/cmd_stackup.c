/* fourbar stackup: argument parsing and dispatch only. */
#include <getopt.h>
#include <jansson.h>
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
    "shown as '-' needs more samples.\n"
    "\n"
    "  --method    run one method (repeatable); default all three\n"
    "  --samples   Monte Carlo samples (default 10000)\n"
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
  double t0;      /* start [s] */
  double last;    /* last redraw [s] */
} progress_bar;

static void progress(double fraction, void *user) {
  progress_bar *b = user;
  if (!b->on) return;
  const double now = fb_clock_s();
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

/* a quantile bound for JSON: null when the sample cannot bound that side */
static json_t *bound_json(double x) { return isfinite(x) ? json_real(x) : json_null(); }

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
  double samples = 10000, seed = 1, jobs = 1;
  const char *sets[MAX_SETS];
  optind = 1;
  while ((ch = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
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
  /* a long Monte Carlo says what it will cost before it starts */
  if (mask & FB_TOL_MONTECARLO) {
    if (fb_tol_check_cost((size_t)samples, (int)jobs, &d) != FB_OK)
      return fb_cli_fail("stackup", 2, "%s", d.msg);
    double bytes, seconds;
    fb_tol_estimate((size_t)samples, (int)jobs, &bytes, &seconds);
    if (seconds > STACKUP_NOTE_S)
      fprintf(stderr, "fourbar stackup: %.0f Monte Carlo samples: an estimated %.3g s and %.3g GB "
              "with %d job%s (--jobs J divides the time)\n", samples, seconds, bytes / 1e9,
              (int)jobs, jobs > 1 ? "s" : "");
  }
  static fb_stackup_result r;
  progress_bar bar = {isatty(2) && !json, (size_t)samples, fb_clock_s(), 0.0};
  fb_status st = fb_tol_analyse_jobs(&r, &c, mask, (size_t)samples, (unsigned long)seed,
                                     c.distribution ? FB_DIST_UNIFORM : FB_DIST_NORMAL, (int)jobs,
                                     progress, &bar, &d);
  if (st != FB_OK) return fb_cli_fail("stackup", 1, "%s", d.msg);
  if (json) {
    json_t *o = json_object(), *outs = json_array();
    json_object_set_new(o, "case", json_string(c.name));
    json_object_set_new(o, "distribution", json_string(c.distribution ? "uniform" : "normal"));
    json_object_set_new(o, "samples", json_integer((json_int_t)r.samples));
    json_object_set_new(o, "seed", json_integer((json_int_t)seed));
    json_object_set_new(o, "jobs", json_integer((json_int_t)jobs));
    json_object_set_new(o, "montecarlo_wall_s", json_real(r.mc_wall_s));
    json_t *tol = json_object();
    for (int k = 0; k < FB_LINK_COUNT; k++) {
      json_t *l = json_object();
      json_object_set_new(l, "nominal_m", json_real(c.nominal.length[k]));
      json_object_set_new(l, "plus_minus_m", json_real(c.plus_minus[k]));
      json_object_set_new(l, "source", json_string(c.tolerance_source[k]));
      json_object_set_new(tol, fb_link_name(k), l);
    }
    json_object_set_new(o, "links", tol);
    if (mask & FB_TOL_MONTECARLO) {
      /* which order statistics bound each quantile (null: none at this level) */
      json_t *ci = json_object(), *ranks = json_object();
      static const char *const qn[3] = {"q00135", "q50", "q99865"};
      json_object_set_new(ci, "level", json_real(r.ci_level));
      json_object_set_new(ci, "method", json_string("distribution-free, order statistics (binomial)"));
      for (int j = 0; j < 3; j++)
        json_object_set_new(ranks, qn[j],
                            json_pack("[o,o]", r.q_rank[j][0] ? json_integer((json_int_t)r.q_rank[j][0]) : json_null(),
                                      r.q_rank[j][1] ? json_integer((json_int_t)r.q_rank[j][1]) : json_null()));
      json_object_set_new(ci, "ranks", ranks);
      json_object_set_new(o, "quantile_ci", ci);
    }
    for (int i = 0; i < FB_TOL_NOUT; i++) {
      json_t *x = json_object(), *s = json_object();
      json_object_set_new(x, "name", json_string(fb_tol_output_name(i)));
      json_object_set_new(x, "nominal", json_real(r.nominal[i]));
      for (int k = 0; k < FB_LINK_COUNT; k++) json_object_set_new(s, fb_link_name(k), json_real(r.sens[i][k]));
      json_object_set_new(x, "sensitivity_per_m", s);
      if (mask & FB_TOL_CORNERS)
        json_object_set_new(x, "corners", json_pack("{s:f,s:f}", "min", r.corner_min[i], "max", r.corner_max[i]));
      if (mask & FB_TOL_RSS)
        json_object_set_new(x, "rss", json_pack("{s:f,s:f}", "min", r.nominal[i] - r.rss_half[i], "max",
                                                r.nominal[i] + r.rss_half[i]));
      if (mask & FB_TOL_MONTECARLO) {
        json_t *m = json_pack("{s:f,s:f,s:f,s:f,s:f}", "q00135", r.q[i][0], "q50", r.q[i][1],
                              "q99865", r.q[i][2], "mean", r.mc_mean[i], "std", r.mc_std[i]);
        static const char *const lo[3] = {"q00135_ci_lo", "q50_ci_lo", "q99865_ci_lo"};
        static const char *const hi[3] = {"q00135_ci_hi", "q50_ci_hi", "q99865_ci_hi"};
        for (int j = 0; j < 3; j++) {
          json_object_set_new(m, lo[j], bound_json(r.q_ci[i][j][0]));
          json_object_set_new(m, hi[j], bound_json(r.q_ci[i][j][1]));
        }
        json_object_set_new(x, "montecarlo", m);
      }
      json_array_append_new(outs, x);
    }
    json_object_set_new(o, "outputs", outs);
    json_dumpf(o, stdout, JSON_INDENT(2) | JSON_REAL_PRECISION(12));
    fputc('\n', stdout);
    json_decref(o);
    return 0;
  }
  printf("stack-up of case %s at %.6g rpm:", c.name, c.crank_speed * 60 / (2 * M_PI));
  for (int k = 0; k < FB_LINK_COUNT; k++)
    printf("%s %s %.4g +- %.3g mm", k ? "," : "", fb_link_name(k), c.nominal.length[k] * 1e3,
           c.plus_minus[k] * 1e3);
  printf("\n\n%-28s %12s %12s %12s %12s %12s %12s %12s %12s\n", "output", "nominal",
         "corner min", "corner max", "rss min", "rss max", "mc 0.135%", "mc 50%", "mc 99.865%");
  for (int i = 0; i < FB_TOL_NOUT; i++) {
    printf("%-28s %12.6g", fb_tol_output_name(i), r.nominal[i]);
    if (mask & FB_TOL_CORNERS) printf(" %12.6g %12.6g", r.corner_min[i], r.corner_max[i]);
    else printf(" %12s %12s", "-", "-");
    if (mask & FB_TOL_RSS) printf(" %12.6g %12.6g", r.nominal[i] - r.rss_half[i], r.nominal[i] + r.rss_half[i]);
    else printf(" %12s %12s", "-", "-");
    if (mask & FB_TOL_MONTECARLO) printf(" %12.6g %12.6g %12.6g", r.q[i][0], r.q[i][1], r.q[i][2]);
    else printf(" %12s %12s %12s", "-", "-", "-");
    putchar('\n');
  }
  /* the exact sensitivities of every output to every link length, each with
   * its unit (the output's unit per metre of length) */
  printf("\nsensitivities d(output)/d(link length), exact derivatives (per metre of length):\n");
  printf("%-28s %12s %12s %12s %12s  %s\n", "output", "crank", "coupler", "follower", "ground",
         "unit");
  for (int i = 0; i < FB_TOL_NOUT; i++) {
    const char *name = fb_tol_output_name(i);
    const char *unit = strstr(name, "_rad_s2") ? "rad/s^2 per m"
                       : strstr(name, "_rad_s") ? "rad/s per m"
                       : strstr(name, "_rad") ? "rad per m"
                                              : "per m";
    printf("%-28s", name);
    for (int k = 0; k < FB_LINK_COUNT; k++) printf(" %12.5g", r.sens[i][k]);
    printf("  %s\n", unit);
  }
  if (mask & FB_TOL_MONTECARLO) {
    printf("\nMonte Carlo quantiles with %.0f %% confidence intervals (order statistics X_(l) .. X_(u)):\n",
           100.0 * r.ci_level);
    printf("%-28s %27s %27s %27s\n", "output", "0.135%", "50%", "99.865%");
    int open_side = 0;
    for (int i = 0; i < FB_TOL_NOUT; i++) {
      printf("%-28s", fb_tol_output_name(i));
      for (int j = 0; j < 3; j++) {
        char a[32] = "-", b[32] = "-";
        if (isfinite(r.q_ci[i][j][0])) snprintf(a, sizeof a, "%.6g", r.q_ci[i][j][0]);
        else open_side = 1;
        if (isfinite(r.q_ci[i][j][1])) snprintf(b, sizeof b, "%.6g", r.q_ci[i][j][1]);
        else open_side = 1;
        printf("   [%11s, %11s]", a, b);
      }
      putchar('\n');
    }
    if (open_side)
      printf("('-': %zu samples cannot bound that side of a tail quantile at this level; "
             "use more samples)\n", r.samples);
    printf("\nMonte Carlo: %zu samples (%s), %d job%s, %.3f s (%.2f us per sample)\n", r.samples,
           c.distribution ? "uniform" : "normal, 3 sigma at the limit", r.jobs, r.jobs == 1 ? "" : "s",
           r.mc_wall_s, 1e6 * r.mc_wall_s / (double)r.samples);
  }
  return 0;
}
