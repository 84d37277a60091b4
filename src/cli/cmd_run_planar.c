/* fourbar run on a planar case ([linkage] type = planar): its models on
 * the planar core (planar_run.h) into the output folder, whole or nothing
 * new (outdir.h), outputs by body name (report_planar.h), figures
 * (figures.h fb_figures_planar) and report.html (report_html_planar.h),
 * through the folder owner the four-bar's run uses (run_folder.h: the same
 * note on a signal, the same kept files said). */
#include <jansson.h>
#include <stdio.h>
#include <string.h>

#include "casefile.h"
#include "cli.h"
#include "figures.h"
#include "model_table.h"
#include "pilot.h"
#include "run_folder.h"
#include "start.h"
#include "units.h"
#include "variants.h"
#include "work.h"
#include "report_html_planar.h"
#include "report_planar.h"

/* what fb_cmd_run_planar refuses before any work, with where the key was
 * given (the case file's line or the --set), naming variant v when the
 * case is one (else NULL); 0 or the exit status */
static int refuse(const fb_case *c, const char *case_path, const char *const *sets, int nsets,
                  const fb_case_variant *v) {
  char of[FB_DIAG_SIZE] = "";
  if (v) snprintf(of, sizeof of, "variant %s (%s): ", v->name, v->origin);
  fb_diag d;
  char where[FB_DIAG_SIZE];
  if (fb_planar_run_check(c, &d) != FB_OK) {
    const size_t l = fb_casefile_given_where(where, sizeof where, case_path, sets, nsets, d.msg);
    return fb_cli_fail("run", 2, "%s: %s%s%s%s%s", case_path, of, d.msg, l ? " (given: " : "",
                       where, l ? ")" : "");
  }
  return 0;
}

/* a note when the case's clearance joints run in none of the models it
 * lists (its default models run them) */
static void note_idle_clearance(const fb_case *c) {
  if (!c->clearance.mask) return;
  for (int i = 0; i < c->model_count; i++) {
    const fb_model *m = fb_model_find(c->models[i]);
    if ((m && m->joints == FB_JOINTS_CLEARANCE) || strncmp(c->models[i], "reference", 9) == 0)
      return;
  }
  for (int j = 0; j < c->planar.njoints; j++)
    if (c->clearance.mask & (1 << j))
      fprintf(stderr, "fourbar run: note: clearance joint '%s' runs in none of the models "
              "([run] models%s: the ideal mechanism); name its clearance models to run it, e.g. "
              "--set run.models=analytic,reference,ode-clearance-impact (fourbar models lists "
              "them)\n", c->planar.joint[j].name,
              fb_casefile_given(c, "run", "models") ? "" : " not given");
}

/* the run's set into the staging folder: figures, report.html, then the
 * series, summary.json, timing.json and report.md (which lists the
 * figures); *nfig the figures drawn, *charts whether report.html has its
 * charts */
static fb_status write_set(const char *stage, const fb_planar_run *r, const char *case_path,
                           const char *command, int figures, int png, int html, int *nfig,
                           int *charts, fb_diag *d) {
  char names[64][128];
  *nfig = 0;
  *charts = 0;
  fb_status st = FB_OK;
  if (figures)
    st = fb_figures_planar(r, stage, png ? FB_FIGURE_PNG : FB_FIGURE_SVG, names, 64, nfig, d);
  if (st == FB_OK && html) {
    json_t *sj = fb_report_planar_summary_json(r, case_path);
    st = fb_report_html_write_planar(stage, r, sj, charts, d);
    json_decref(sj);
  }
  if (st == FB_OK) st = fb_report_planar_write(stage, r, case_path, command, names, *nfig, d);
  return st;
}

/* the planar run as fb_folder_run's callbacks (run_folder.h) */
typedef struct {
  const fb_case *c;
  const fb_case *variants;  /* the case's variants, loaded (c->variant_count) */
  const char *case_path, *command;
  int figures, png, html;
  int nfig, charts;   /* figures drawn; 1 when report.html has its charts */
  fb_planar_run r;
  fb_diag write_diag; /* why the set was not written */
} planar_job;

/* long work said and bounded before it starts (work.h): the run's cost
 * from two short runs of this case (pilot.h), in the folder's lifetime so
 * that a signal meanwhile says what the folder keeps; a run refused by its
 * estimate exits 1, as the four-bar's */
static fb_status job_run(void *user, fb_diag *d) {
  planar_job *x = user;
  const fb_case *c = x->c;
  fb_pilot p;
  fb_status st = fb_pilot_case(&p, c, d);
  if (st != FB_OK) return st;
  for (int v = 0; v < c->variant_count; v++) { /* each variant is a run of its own */
    fb_pilot pv;
    fb_diag vd;
    if ((st = fb_pilot_case(&pv, &x->variants[v], &vd)) != FB_OK)
      return fb_diag_set(d, st, "variant %s: %s", c->variant[v].name, vd.msg);
    p.wall_s += pv.wall_s;
    p.cpu_s += pv.cpu_s;
    p.pilot_cpu_s += pv.pilot_cpu_s;
  }
  char what[256], basis[96], est[48];
  snprintf(what, sizeof what, "%d model%s over %.6g s ([run] revolutions = %g)%s", c->model_count,
           c->model_count > 1 ? "s" : "", fb_case_duration(c), c->revolutions,
           c->variant_count ? " and its variants" : "");
  st = fb_work_bound(p.wall_s, c->max_wall_s, what, "lower [run] revolutions, raise [solver] h_s "
                     "or run fewer [run] models", d);
  if (st != FB_OK) return st;
  snprintf(basis, sizeof basis, "from two short runs of it, which took %s",
           fb_work_duration(est, sizeof est, p.pilot_cpu_s));
  fb_work_note("run", what, p.cpu_s, basis, "", 0);
  st = fb_planar_run_case(&x->r, c, d);
  if (st == FB_OK && c->variant_count) {
    fprintf(stderr, "fourbar run: %d variant%s of %s after its models\n", c->variant_count,
            c->variant_count > 1 ? "s" : "", c->name);
    st = fb_planar_run_variants(&x->r, x->variants, c->variant_count, d);
  }
  return st;
}

static int job_write(const char *stage, void *user) {
  planar_job *x = user;
  return write_set(stage, &x->r, x->case_path, x->command, x->figures, x->png, x->html, &x->nfig,
                   &x->charts, &x->write_diag) != FB_OK;
}

static void job_discard(void *user) { fb_planar_run_free(&((planar_job *)user)->r); }

int fb_cmd_run_planar(const fb_case *c, const char *case_path, const char *const *sets, int nsets,
                      const char *dir, int json, const char *command, const char *again,
                      int figures, int png, int html) {
  int rc = refuse(c, case_path, sets, nsets, NULL);
  if (rc) return rc;
  note_idle_clearance(c);
  fb_diag d;
  /* figures need gnuplot: found out before the simulation, not after it */
  if (figures && fb_figures_check_gnuplot(&d) != FB_OK) return fb_cli_fail("run", 1, "%s", d.msg);
  /* the variants loaded now: a bad one fails before any work */
  static fb_case variants[FB_MAX_VARIANTS];
  for (int v = 0; v < c->variant_count && v < FB_MAX_VARIANTS; v++) {
    fb_diag vd;
    if (fb_casefile_load_variant(&variants[v], case_path, sets, nsets, &c->variant[v], &vd) != FB_OK)
      return fb_cli_fail("run", 2, "%s", vd.msg);
    if ((rc = refuse(&variants[v], case_path, sets, nsets, &c->variant[v])) != 0) return rc;
  }
  static planar_job x;
  x = (planar_job){.c = c, .variants = variants, .case_path = case_path, .command = command,
                   .figures = figures, .png = png, .html = html};
  const fb_folder_job job = {dir, again, job_run, job_write, job_discard, &x};
  int write_rc;
  switch (fb_folder_run(&job, &write_rc, &d)) {
    case FB_RUN_FOLDER_OK: break;
    case FB_RUN_FOLDER_DIR: return fb_cli_fail("run", 1, "%s", d.msg);
    case FB_RUN_FOLDER_BAD: return fb_cli_fail("run", 2, "%s", d.msg);
    case FB_RUN_FOLDER_RUN: return fb_cli_fail("run", 1, "%s: %s", case_path, d.msg);
    case FB_RUN_FOLDER_WRITE:
      return fb_cli_fail("run", 1, "%s; %s keeps what it held", x.write_diag.msg, dir);
  }
  const fb_planar_run *r = &x.r;
  if (json) {
    json_t *j = fb_report_planar_summary_json(r, case_path);
    json_dumpf(j, stdout, JSON_INDENT(2) | JSON_REAL_PRECISION(12));
    fputc('\n', stdout);
    json_decref(j);
  } else {
    fb_report_planar_table(stdout, r);
    printf("wrote %s/summary.json, timing.json, %s, %d figures, report.md%s\n", dir,
           c->series == FB_SERIES_CSV    ? "one CSV per model"
           : c->series == FB_SERIES_HDF5 ? "series.h5"
                                         : "no time series",
           x.nfig, html ? " and report.html" : "");
  }
  if (html && !x.charts)
    fprintf(stderr, "fourbar run: note: %s/report.html has no charts: the charting library uPlot "
            "was not found (run npm ci in the fourbar source folder, or set FOURBAR_UPLOT_DIR)\n",
            dir);
  fb_planar_run_free(&x.r);
  return 0;
}
