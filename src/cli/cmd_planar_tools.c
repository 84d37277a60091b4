/* fourbar kinematics, stackup and penalty on a planar case: the planar
 * core's tools (planar_tools.h) and their tables (tables_planar.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cli.h"
#include "units.h"
#include "planar_case.h"
#include "tables_planar.h"

int fb_cmd_kinematics_planar(const fb_case *c, int json) {
  fb_planar *m;
  fb_planar_peaks *p;
  fb_diag d;
  if (fb_planar_tool_peaks(&p, &m, c, &d) != FB_OK) return fb_cli_fail("kinematics", 1, "%s", d.msg);
  static fb_planar_designer designer;
  if (fb_planar_tool_designer(&designer, m, c, &d) != FB_OK) {
    free(p);
    fb_planar_free(m);
    return fb_cli_fail("kinematics", 1, "%s", d.msg);
  }
  fb_report_planar_kinematics(stdout, c, m, p, &designer, json);
  free(p);
  fb_planar_free(m);
  return 0;
}

/* the Monte Carlo's memory bounded before anything runs, as the
 * four-bar's (montecarlo.h): 0, or the exit status; *bytes its estimate */
static int mc_memory(double *bytes, const fb_planar_stackup *s, const fb_cli_mc *mc, double each) {
  double seconds;
  fb_diag d;
  fb_mc_estimate(each, s->nout, s->nlengths, mc->samples, mc->jobs, bytes, &seconds);
  if (fb_mc_check_cost(mc->samples, *bytes, seconds, &d) != FB_OK)
    return fb_cli_fail("stackup", 2, "%s", d.msg);
  return 0;
}

int fb_cmd_stackup_planar(const fb_case *c, int mask, const fb_cli_mc *mc, int json) {
  fb_planar *m;
  fb_diag d;
  if (fb_planar_of_case(&m, c, NULL, &d) != FB_OK) return fb_cli_fail("stackup", 1, "%s", d.msg);
  /* the lengths and the nominal outputs, timed: this case's cost of an
   * evaluation, from which every part is estimated, said and bounded
   * before it starts (work.h) */
  static fb_planar_stackup s;
  double each;
  const int nl0 = fb_planar_stackup_lengths(m); /* the evaluations the probe times */
  const double units = 2.0 * nl0 +
                       ((mask & FB_TOL_CORNERS) ? ldexp(1.0, nl0) : 0.0) +
                       ((mask & FB_TOL_MONTECARLO) ? (double)mc->samples : 0.0);
  fb_status st = fb_planar_stackup_begin(&s, &each, units, c, m, &d);
  if (st != FB_OK) {
    fb_planar_free(m);
    return fb_cli_fail("stackup", st == FB_ERR_ARG ? 2 : 1, "%s", d.msg);
  }
  const int nl = s.nlengths, nv = fb_planar_stackup_varied(&s);
  const double corners = !(mask & FB_TOL_CORNERS) ? 0.0
                         : nv > FB_PLANAR_CORNER_BITS ? INFINITY : ldexp(1.0, nv);
  double bytes = 0.0;
  int rc = (mask & FB_TOL_MONTECARLO) ? mc_memory(&bytes, &s, mc, each) : 0;
  /* (a planar Monte Carlo says its estimate always: each sample is a
   * revolution's peaks) */
  if (!rc) rc = fb_cli_stackup_work(c, mask, 2.0 * nl, corners, mc, each, bytes, 1,
                                    "a revolution's peaks");
  if (rc) {
    fb_planar_stackup_free(&s);
    fb_planar_free(m);
    return rc;
  }
  st = fb_planar_stackup_rss(&s, c, m, fb_cli_progress_rss, mc->progress, &d);
  if (st == FB_OK && (mask & FB_TOL_CORNERS))
    st = fb_planar_stackup_corners(&s, c, m, fb_cli_progress_corners, mc->progress, &d);
  if (st == FB_OK && (mask & FB_TOL_MONTECARLO))
    st = fb_planar_stackup_montecarlo(&s, c, m, mc->samples, mc->seed,
                                      c->distribution ? FB_DIST_UNIFORM : FB_DIST_NORMAL, mc->jobs,
                                      fb_cli_progress_mc, mc->progress, &d);
  if (st != FB_OK) {
    fb_planar_stackup_free(&s);
    fb_planar_free(m);
    return fb_cli_fail("stackup", st == FB_ERR_ARG ? 2 : 1, "%s", d.msg);
  }
  fb_report_planar_stackup(stdout, c, m, &s, json);
  fb_planar_stackup_free(&s);
  fb_planar_free(m);
  return 0;
}

int fb_cmd_penalty_planar(const fb_case *c, const double *rpm, int nspeeds, int json,
                          const char *out_dir) {
  fb_planar *m;
  fb_diag d;
  if (fb_planar_of_case(&m, c, NULL, &d) != FB_OK) return fb_cli_fail("penalty", 1, "%s", d.msg);
  fb_planar_penalty_row *rows = malloc((size_t)nspeeds * (size_t)m->njoints * sizeof *rows);
  int *n = calloc((size_t)nspeeds, sizeof *n);
  fb_status st = rows && n ? FB_OK : fb_diag_set(&d, FB_ERR_NOMEM, "out of memory");
  for (int s = 0; s < nspeeds && st == FB_OK; s++)
    st = fb_planar_penalty_rows(rows + (size_t)s * (size_t)m->njoints, &n[s], c, m,
                                rpm[s] * FB_RAD_S_PER_RPM, &d);
  fb_planar_contact_estimate *est = malloc(2 * (size_t)m->njoints * sizeof *est);
  int nest = 0;
  if (st == FB_OK && !est) st = fb_diag_set(&d, FB_ERR_NOMEM, "out of memory");
  if (st == FB_OK) st = fb_planar_contact_estimates(est, &nest, c, m, &d);
  if (st == FB_OK) fb_report_planar_penalty(stdout, c, m, rows, n, rpm, nspeeds, est, nest, json);
  if (st == FB_OK && out_dir) { /* the folder prepared by the caller */
    int figure_ok;
    fb_diag fd;
    st = fb_report_planar_penalty_files(out_dir, m, rows, n, rpm, nspeeds, &figure_ok, &fd, &d);
    if (st == FB_OK && !figure_ok) fprintf(stderr, "fourbar penalty: warning: %s\n", fd.msg);
    else if (st == FB_OK && !json)
      printf("wrote %s/penalty_physical.csv and penalty_physical.svg\n", out_dir);
  }
  free(est);
  free(rows);
  free(n);
  fb_planar_free(m);
  return st == FB_OK ? 0 : fb_cli_fail("penalty", 1, "%s", d.msg);
}
