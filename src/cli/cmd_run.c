/* fourbar run: argument parsing and dispatch only. */
#include <getopt.h>
#include <jansson.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "casefile.h"
#include "cli.h"
#include "clock.h"
#include "contact_params.h"
#include "ensemble.h"
#include "textsafe.h"
#include "figures.h"
#include "fileio.h"
#include "report.h"
#include "report_html.h"
#include "run_folder.h"
#include "work.h"

static const char run_help[] =
    "usage: fourbar run [CASE] [--out DIR] [--set section.key=value]... [--json]\n"
    "                   [--no-figures] [--figure-format svg|png]\n"
    "                   [--series csv|hdf5|none] [--jobs J] [--no-report]\n"
    "\n"
    "Runs the models a case file asks for ([run] models), measures each against the\n"
    "exact analytic solution and writes DIR/summary.json, DIR/timing.json (where\n"
    "the wall time went, by part; the last line printed names the largest),\n"
    "DIR/<model>.csv, figures (gnuplot), DIR/report.md and DIR/report.html\n"
    "(interactive, opens with no server: docs/report.md). The set is\n"
    "written beside DIR and swapped in whole at the end; a second writer to DIR\n"
    "fails at once. Each CSV holds the kinematics, the contact columns of the\n"
    "clearance joints and, for analytic, ODE, MuJoCo and Bullet models, the drive\n"
    "torque and every joint's reaction (drive_torque_n_m, <joint>_reaction_n, ...);\n"
    "summary.json has their peaks under \"loads\". Figures: see docs/figures.md.\n"
    "\n"
    "  CASE          case file (INI); default: the paper's case,\n"
    "                cases/paper_crank_rocker.ini\n"
    "  --out DIR     output folder; default results/<case name>/ (with --set and\n"
    "                no --out the variant goes there too, and the run says so)\n"
    "  --set K=V     override case key K (section.key) with V, e.g.\n"
    "                --set drive.speed_rpm=1500 --set solver.h_s=1e-4\n"
    "  --json        print summary.json (with timing.json's wall_s and\n"
    "                time_per_step_us per model) instead of the table\n"
    "  --no-figures  skip the figures (report.md is still written)\n"
    "  --figure-format svg|png   default svg\n"
    "  --series csv|hdf5|none    time series format, as --set run.series=...:\n"
    "                csv (default) DIR/<model>.csv; hdf5 DIR/series.h5 (one group\n"
    "                per model; needs a build with libhdf5); none. [run] series_every\n"
    "                = N keeps every N-th sample and every impact's (docs/series.md)\n"
    "  --jobs J      run the [run] ensemble members in J worker processes\n"
    "                (default: the processors online, at most the members a\n"
    "                look adds); the numbers do not depend on J\n"
    "                A case without [run] ensemble gets an ensemble of 5 runs of\n"
    "                its clearance models and references when a verdict is\n"
    "                unsettled (a model left its reference, or a reference its\n"
    "                check integration); --set run.ensemble=1 turns it off\n"
    "  --no-report   skip DIR/report.html, the interactive page (docs/report.md)\n"
    "  -h, --help    this text\n"
    "\n"
    "Units: SI in every output (column and key names carry the unit). Peaks are\n"
    "taken over the revolutions after the first ([run] peaks = steady, the default)\n"
    "or from t = 0 ([run] peaks = all). Keys: fourbar keys, docs/keys.md.\n"
    "Exit status: 0 ok (a model that stopped on numerical trouble says so in its\n"
    "status), 1 run failed, 2 bad input.\n";

/* each model's progress: the one progress line of long work (work.h) */
static void progress(const char *model, double fraction, void *user) {
  fb_progress_draw(user, model, fraction);
}

/* the case's variants ([variant.NAME]) loaded now, so a bad one fails before
 * any simulation; then what fb_run_case refuses before its first model (the
 * step resolved, the cost against memory and [run] max_wall_s), found now
 * for the case and every variant: none waits for the models before it.
 * Returns the exit status. */
static int load_variants(fb_case *c, fb_case *variants, const char *case_path,
                         const char *const *sets, int nsets, int jobs) {
  for (int v = 0; v < c->variant_count; v++) {
    fb_diag vd;
    if (fb_casefile_load_variant(&variants[v], case_path, sets, nsets, &c->variant[v], &vd) != FB_OK)
      return fb_cli_fail("run", 2, "%s", vd.msg);
    variants[v].jobs = jobs;
  }
  /* (a case that cannot fit the machine or max_wall_s: exit 1, as a run
   * refused by its estimate always was; a scene the keys cannot make: 2) */
  fb_diag pre;
  int over_cost;
  char where[FB_DIAG_SIZE];
  if (fb_run_preflight(c, &over_cost, &pre) != FB_OK) {
    /* a rule of the keys: where they were given, as a load says it */
    const size_t l = fb_casefile_given_where(where, sizeof where, case_path, sets, nsets, pre.msg);
    return fb_cli_fail("run", over_cost ? 1 : 2, "%s: %s%s%s%s", case_path, pre.msg,
                       l ? " (given: " : "", where, l ? ")" : "");
  }
  for (int v = 0; v < c->variant_count; v++)
    if (fb_run_preflight(&variants[v], &over_cost, &pre) != FB_OK)
      return fb_cli_fail("run", over_cost ? 1 : 2, "%s: variant %s (%s): %s", case_path,
                         c->variant[v].name, c->variant[v].origin, pre.msg);
  return 0;
}

/* what the set holds besides the run's own files, and how it went */
typedef struct {
  const char *dir;       /* the output folder, as named in messages */
  const char *case_path;
  const char *command;   /* the command line, for report.md */
  int figures, html;     /* --no-figures, --no-report */
  fb_figure_format fmt;
  int nfig, charts;      /* figures drawn; 1 when report.html has its charts */
  fb_write_costs costs;  /* what writing the set cost (timing.json) */
  double run_wall_s;     /* the run's wall time when timing.json was written [s] */
} run_set;

/* waits for the figures' gnuplots (fb_figures_start), counting the wait in
 * figures_s; an error message into diag unless one is there (*failed) */
static fb_status figures_finish(run_set *w, int failed, fb_diag *diag) {
  if (!w->figures) return FB_OK;
  const double t0 = fb_clock_s();
  fb_diag d;
  const fb_status st = fb_figures_finish(&d);
  w->costs.figures_s += fb_clock_s() - t0;
  if (st != FB_OK && !failed) *diag = d;
  return st;
}

/* The result set into the staging folder (fb_run_set_writer): the figures'
 * scripts and their gnuplots started first, and the series' worker
 * process, which draw and write while this process writes summary.json
 * and report.html; then both waited for, and report.md. The figures and the report belong to the set:
 * a set with a figure or the report missing or damaged (a full disk) is
 * not committed, and the folder keeps the set it had; timing.json last,
 * counting the others. Returns the exit status. */
static int write_set(const char *stage, const fb_run *r, void *user) {
  run_set *w = user;
  fb_diag diag;
  char names[64][128];
  char note[1200] = "Figures were not requested (--no-figures).";
  const double tf = fb_clock_s();
  fb_status st = FB_OK;
  if (w->figures) st = fb_figures_start(r, stage, w->fmt, names, 64, &w->nfig, &diag);
  w->costs.figures_s = fb_clock_s() - tf;
  if (st != FB_OK) {
    figures_finish(w, 1, &diag);
    return fb_cli_fail("run", 1, "%s; nothing was written to %s (it keeps what it held)", diag.msg,
                       w->dir);
  }
  /* the series in a worker process of their own, beside the rest (report.h) */
  fb_report_series_start(stage, r, w->case_path, &w->costs);
  st = fb_report_write_summary(stage, r, w->case_path, &w->costs, &diag);
  const double tr = fb_clock_s();
  /* report.html belongs to the set too (report_html.h) */
  if (w->html && st == FB_OK) {
    json_t *sj = fb_report_summary_json(r, w->case_path);
    st = fb_report_html_write(stage, r, sj, &w->charts, &diag);
    json_decref(sj);
  }
  double report_s = fb_clock_s() - tr;
  fb_diag sd;
  const fb_status ss = fb_report_series_finish(&w->costs, &sd);
  if (ss != FB_OK) { /* the series' cause first, as when they were written first */
    figures_finish(w, 1, &diag);
    return fb_cli_fail("run", 1, "%s; nothing was written to %s (it keeps what it held)", sd.msg, w->dir);
  }
  if (figures_finish(w, st != FB_OK, &diag) != FB_OK || st != FB_OK)
    return fb_cli_fail("run", 1, "%s; nothing was written to %s (it keeps what it held)", diag.msg,
                       w->dir);
  const double tm = fb_clock_s();
  if (fb_report_write_markdown(stage, r, w->case_path, w->command, names, w->nfig, note, &diag) != FB_OK)
    return fb_cli_fail("run", 1, "%s; nothing was written to %s (it keeps what it held)", diag.msg,
                       w->dir);
  w->costs.report_s = report_s + fb_clock_s() - tm;
  if (fb_report_write_timing(stage, r, &w->costs, &w->run_wall_s, &diag) != FB_OK)
    return fb_cli_fail("run", 1, "%s", diag.msg);
  return 0;
}

/* the step the run took, verified as fourbar contact-params --case verifies
 * its contact, when a restitution-law model ran (run.h, fb_step_check) */
static void step_check(fb_run *r, void *user) {
  (void)user;
  int restitution = 0;
  for (int i = 0; i < r->n; i++)
    restitution |= r->model[i].run.model->law == FB_MODEL_LAW_RESTITUTION &&
                   !r->model[i].run.model->rigid && fb_engine_steps_world(r->model[i].run.model->engine);
  fb_diag diag;
  if (restitution && fb_cp_case_step_check(&r->step_check, &r->c, r->c.solver.h, &diag) != FB_OK) {
    r->step_check.checked = 0;
    fprintf(stderr, "fourbar run: note: the step's single-impact verification did not run: %s\n",
            diag.msg);
  }
}

/* what the run wrote, on stdout: summary.json (with each model's wall time
 * from timing.json) with --json, else the table, the files and, last, where
 * the time went (timing.json's largest parts) */
static void print_run(const fb_run *r, const run_set *w, int json) {
  if (json) {
    json_t *j = fb_report_summary_json(r, w->case_path);
    json_t *t = fb_report_timing_json(r, &w->costs, w->run_wall_s);
    for (int i = 0; i < r->n; i++) {
      json_t *m = json_array_get(json_object_get(j, "models"), (size_t)i);
      json_t *tm = json_array_get(json_object_get(t, "models"), (size_t)i);
      json_object_set(m, "wall_s", json_object_get(tm, "wall_s"));
      json_object_set(m, "time_per_step_us", json_object_get(tm, "time_per_step_us"));
    }
    json_dumpf(j, stdout, JSON_INDENT(2) | JSON_REAL_PRECISION(12));
    fputc('\n', stdout);
    json_decref(j);
    json_decref(t);
  } else {
    fb_report_print_table(stdout, r);
    char series[64];
    if (r->c.series == FB_SERIES_CSV) snprintf(series, sizeof series, "%d CSV files", r->n);
    else if (r->c.series == FB_SERIES_HDF5) snprintf(series, sizeof series, "series.h5 (%d models)", r->n);
    else snprintf(series, sizeof series, "no time series");
    printf("wrote %s/summary.json, timing.json, %s, %d figures, report.md%s\n", w->dir, series,
           w->nfig, w->html ? " and report.html" : "");
    char line[1024];
    fb_report_timing_line(line, sizeof line, r, &w->costs, w->run_wall_s);
    printf("%s\n", line);
  }
}

/* the command line for report.md: argv[0] is "fourbar run" (main.c); the
 * rest quoted for a POSIX shell, cut with " ..." */
static void command_text(char *command, size_t size, int argc, char **argv) {
  snprintf(command, size, "%s", argv[0]);
  for (int i = 1; i < argc; i++) {
    strncat(command, " ", size - strlen(command) - 1);
    if (!fb_cli_shell_word(command, size, argv[i])) {
      strncat(command, " ...", size - strlen(command) - 1);
      break;
    }
  }
}

/* --set without --out writes the variant into the case's own folder: said
 * on stderr (docs/commands.md, "run"), with whether it replaced an earlier run */
static void note_variant(const char *dir, const char *name, const char *const *sets, int nsets,
                         int replaces) {
  fprintf(stderr, "fourbar run: note: --set without --out: %s/ now holds this variant of case %s (",
          dir, name);
  for (int i = 0; i < nsets; i++) fprintf(stderr, "%s%s", i ? ", " : "", sets[i]);
  fprintf(stderr, ")%s; give --out DIR to keep runs apart\n",
          replaces ? ", replacing the run that was there" : "");
}

int fb_cmd_run(int argc, char **argv) {
  static const struct option opts[] = {{"out", required_argument, 0, 'o'},
                                       {"set", required_argument, 0, 's'},
                                       {"json", no_argument, 0, 'j'},
                                       {"no-figures", no_argument, 0, 'n'},
                                       {"figure-format", required_argument, 0, 'f'},
                                       {"series", required_argument, 0, 'S'},
                                       {"jobs", required_argument, 0, 'J'},
                                       {"no-report", no_argument, 0, 'R'},
                                       {"help", no_argument, 0, 'h'},
                                       {0, 0, 0, 0}};
  const char *out_dir = NULL;
  int jobs = 0; /* not given: fb_ensemble_default_jobs */
  const char *sets[FB_CLI_MAX_SETS + 1];
  char series_set[64];
  int series_at = -1; /* the slot of --series in sets */
  int nsets = 0, json = 0, figures = 1, html = 1, ch;
  fb_figure_format fmt = FB_FIGURE_SVG;
  optind = 1;
  while ((ch = fb_cli_getopt(argc, argv, "o:s:jh", opts)) != -1) {
    switch (ch) {
      case 'o': out_dir = optarg; break;
      case 's':
        if (nsets >= FB_CLI_MAX_SETS)
          return fb_cli_fail("run", 2, "more than %d --set", FB_CLI_MAX_SETS);
        sets[nsets++] = optarg;
        break;
      case 'j': json = 1; break;
      case 'n': figures = 0; break;
      case 'R': html = 0; break;
      case 'f':
        if (strcmp(optarg, "svg") == 0) fmt = FB_FIGURE_SVG;
        else if (strcmp(optarg, "png") == 0) fmt = FB_FIGURE_PNG;
        else return fb_cli_fail("run", 2, "--figure-format '%s': must be svg or png", optarg);
        break;
      case 'S':
        /* the case key's parser checks the value (and a build without HDF5) */
        snprintf(series_set, sizeof series_set, "run.series=%.40s", optarg);
        if (series_at < 0) series_at = nsets++;
        sets[series_at] = series_set;
        break;
      case 'J': {
        char *end;
        const long j = strtol(optarg, &end, 10);
        if (end == optarg || *end || j < 1 || j > FB_ENSEMBLE_MAX)
          return fb_cli_fail("run", 2, "--jobs %s: must be an integer from 1 to %d", optarg,
                             FB_ENSEMBLE_MAX);
        jobs = (int)j;
        break;
      }
      case 'h': fputs(run_help, stdout); return 0;
      default: return fb_cli_bad_option(argv, "o:s:jh");
    }
  }
  if (jobs == 0) jobs = fb_ensemble_default_jobs();
  fb_diag diag;
  fb_case c;
  char case_path[4096];
  int rc = fb_cli_load_case("run", argc, argv, optind, sets, nsets, &c, case_path, sizeof case_path);
  if (rc) return rc;
  c.jobs = jobs;
  /* a case that leaves [run] ensemble unset lets the run add one where a
   * verdict is unsettled (run.h, FB_ENSEMBLE_AUTO; docs/verdicts.md) */
  if (!fb_casefile_given(&c, "run", "ensemble")) c.ensemble_auto = FB_ENSEMBLE_AUTO;
  char dir[4096];
  if (out_dir)
    snprintf(dir, sizeof dir, "%s", out_dir);
  else
    snprintf(dir, sizeof dir, "results/%s", c.name);
  static char again[8192], command[8192];
  command_text(command, sizeof command, argc, argv);
  fb_cli_command_line(again, sizeof again, argc, argv, NULL);
  if (c.planar.on)
    return fb_cmd_run_planar(&c, case_path, sets, nsets, dir, json, command, again, figures,
                             fmt == FB_FIGURE_PNG, html);
  static fb_case variants[FB_MAX_VARIANTS];
  if ((rc = load_variants(&c, variants, case_path, sets, nsets, jobs)) != 0) return rc;

  /* --set without --out writes the variant into the case's own folder: said
   * on stderr (docs/commands.md, "run"), with whether it replaced an earlier run */
  struct stat prev;
  char prev_summary[4200];
  snprintf(prev_summary, sizeof prev_summary, "%s/summary.json", dir);
  const int replaces = stat(prev_summary, &prev) == 0;
  /* figures need gnuplot: found out before the simulation, not after it */
  if (figures && fb_figures_check_gnuplot(&diag) != FB_OK) return fb_cli_fail("run", 1, "%s", diag.msg);
  run_set w = {.dir = dir, .case_path = case_path, .command = command, .figures = figures,
               .html = html, .fmt = fmt};
  static fb_progress ps;
  fb_progress_init(&ps, json);
  const fb_run_folder_job job = {.dir = dir, .c = &c, .variants = variants,
                                 .nvariants = c.variant_count, .progress = progress,
                                 .progress_user = &ps, .again = again, .write = write_set,
                                 .write_user = &w, .after_run = step_check};
  static fb_run r;
  switch (fb_run_into_folder(&r, &job, &rc, &diag)) {
    case FB_RUN_FOLDER_OK: break;
    case FB_RUN_FOLDER_DIR: return fb_cli_fail("run", 1, "%s", diag.msg);
    case FB_RUN_FOLDER_BAD: return fb_cli_fail("run", 2, "%s", diag.msg);
    case FB_RUN_FOLDER_RUN: return fb_cli_fail("run", 1, "%s: %s", case_path, diag.msg); /* the file whose keys to fix */
    case FB_RUN_FOLDER_WRITE: return rc;
  }
  if (nsets > 0 && !out_dir) note_variant(dir, c.name, sets, nsets, replaces);
  print_run(&r, &w, json);
  if (html && !w.charts)
    fprintf(stderr, "fourbar run: note: %s/report.html has no charts: the charting library uPlot "
            "was not found (run npm ci in the fourbar source folder, or bash scripts/quickstart.sh "
            "build, then run again; or set FOURBAR_UPLOT_DIR)\n", dir);
  fb_run_free(&r);
  return 0;
}
