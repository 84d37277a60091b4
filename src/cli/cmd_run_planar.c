/* fourbar run on a planar case ([linkage] type = planar): its models on
 * the planar core (planar_run.h) into the output folder, whole or nothing
 * new (outdir.h), outputs by body name (report_planar.h). */
#include <jansson.h>
#include <stdio.h>

#include "cli.h"
#include "outdir.h"
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

int fb_cmd_run_planar(const fb_case *c, const char *case_path, const char *dir, int json,
                      const char *command) {
  int rc = refuse(c, case_path);
  if (rc) return rc;
  static fb_outdir od;
  fb_diag d;
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
  st = fb_report_planar_write(od.stage, &r, case_path, command, &d);
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
    printf("wrote %s/summary.json, timing.json, %s, report.md (a planar case: no figures yet)\n",
           dir, c->series == FB_SERIES_CSV ? "one CSV per model" : "no time series");
  }
  fb_planar_run_free(&r);
  return 0;
}
