/* fourbar run on a planar case ([linkage] type = planar): its models on
 * the planar core (planar_run.h) into the output folder, whole or nothing
 * new (outdir.h), outputs by body name (report_planar.h), figures
 * (figures.h fb_figures_planar) and report.html (report_html_planar.h). */
#include <jansson.h>
#include <stdio.h>

#include "cli.h"
#include "figures.h"
#include "outdir.h"
#include "report_html_planar.h"
#include "report_planar.h"

/* what fb_cmd_run_planar refuses before any work; 0 or the exit status */
static int refuse(const fb_case *c, const char *case_path) {
  fb_diag d;
  if (c->variant_count > 0)
    return fb_cli_fail("run", 2, "%s: [variant.%s]: a planar case's variants do not run yet; "
                       "run the case with --set instead", case_path, c->variant[0].name);
  if (c->series == FB_SERIES_HDF5)
    return fb_cli_fail("run", 2, "%s: [run] series = hdf5: a planar case's run writes csv or "
                       "none yet", case_path);
  if (fb_planar_run_check(c, &d) != FB_OK) return fb_cli_fail("run", 2, "%s: %s", case_path, d.msg);
  return 0;
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

int fb_cmd_run_planar(const fb_case *c, const char *case_path, const char *dir, int json,
                      const char *command, int figures, int png, int html) {
  int rc = refuse(c, case_path);
  if (rc) return rc;
  fb_diag d;
  /* figures need gnuplot: found out before the simulation, not after it */
  if (figures && fb_figures_check_gnuplot(&d) != FB_OK) return fb_cli_fail("run", 1, "%s", d.msg);
  static fb_outdir od;
  fb_status st = fb_outdir_lock(&od, dir, 1, NULL, &d);
  if (st == FB_OK) st = fb_outdir_stage(&od, &d);
  if (st != FB_OK) {
    fb_outdir_release(&od);
    return fb_cli_fail("run", st == FB_ERR_ARG ? 2 : 1, "%s", d.msg);
  }
  static fb_planar_run r;
  if (fb_planar_run_case(&r, c, &d) != FB_OK) {
    fb_outdir_release(&od);
    return fb_cli_fail("run", 1, "%s: %s", case_path, d.msg);
  }
  int nfig = 0, charts = 0;
  st = write_set(od.stage, &r, case_path, command, figures, png, html, &nfig, &charts, &d);
  if (st == FB_OK) st = fb_outdir_commit(&od, &d);
  fb_outdir_release(&od);
  if (st != FB_OK) {
    fb_planar_run_free(&r);
    return fb_cli_fail("run", 1, "%s; %s keeps what it held", d.msg, dir);
  }
  if (json) {
    json_t *j = fb_report_planar_summary_json(&r, case_path);
    json_dumpf(j, stdout, JSON_INDENT(2) | JSON_REAL_PRECISION(12));
    fputc('\n', stdout);
    json_decref(j);
  } else {
    fb_report_planar_table(stdout, &r);
    printf("wrote %s/summary.json, timing.json, %s, %d figures, report.md%s\n", dir,
           c->series == FB_SERIES_CSV ? "one CSV per model" : "no time series", nfig,
           html ? " and report.html" : "");
  }
  if (html && !charts)
    fprintf(stderr, "fourbar run: note: %s/report.html has no charts: the charting library uPlot "
            "was not found (run npm ci in the fourbar source folder, or set FOURBAR_UPLOT_DIR)\n",
            dir);
  fb_planar_run_free(&r);
  return 0;
}
