/* verdict_<model>.<ext>: what a verdict on statistics rests on, one figure
 * per model judged on them (verdict_stats.h, docs/verdicts.md). */
#include "figures_internal.h"

#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "impact.h"
#include "report_verdict.h"

/* the members' datablocks: each member's impact peak forces sorted, as an
 * empirical distribution (force, share of its impacts at or below); returns
 * the points written and widens *lo, *hi to the forces */
static int ecdf_blocks(FILE *p, const char *side, const fb_model_result *m, double *lo, double *hi) {
  int points = 0;
  for (int k = 0; k < m->ensemble.members; k++) {
    const fb_impact_values *v = &m->member_impacts[k];
    fprintf(p, "$%s%d << EOD\n", side, k);
    double *x = malloc((v->n ? v->n : 1) * sizeof *x);
    if (x && v->n) memcpy(x, v->force, v->n * sizeof *x);
    for (size_t i = 1; x && i < v->n; i++) /* insertion sort: tens of impacts */
      for (size_t j = i; j > 0 && x[j] < x[j - 1]; j--) {
        const double t = x[j];
        x[j] = x[j - 1];
        x[j - 1] = t;
      }
    for (size_t i = 0; x && i < v->n; i++) {
      fprintf(p, "%.9g %.6g\n", x[i], (double)(i + 1) / (double)v->n);
      *lo = fmin(*lo, x[i]);
      *hi = fmax(*hi, x[i]);
      points++;
    }
    if (!x || v->n == 0) fprintf(p, "NaN NaN\n");
    fprintf(p, "EOD\n");
    free(x);
  }
  return points;
}

/* each member's impacts per revolution at x (a column of points spread by
 * the member's index), in $<side>rate */
static void rate_block(FILE *p, const char *side, const fb_ensemble *e, double x) {
  fprintf(p, "$%srate << EOD\n", side);
  for (int k = 0; k < e->members; k++)
    fprintf(p, "%.6g %.9g\n", x + 0.3 * ((double)k / (e->members > 1 ? e->members - 1 : 1) - 0.5),
            e->member[k].rate);
  fprintf(p, "EOD\n");
}

static fb_status one_figure(const fb_run *r, const fb_model_result *m, const fb_model_result *ref,
                            const char *dir, fb_figure_format fmt, json_t *figs, char *file,
                            size_t file_size, fb_diag *diag) {
  char name[100];
  snprintf(name, sizeof name, "verdict_%.80s", m->run.name);
  plot pl;
  fb_status st = fig_plot_open(&pl, dir, name, fmt, 1500, 520, diag);
  if (st != FB_OK) return st;
  pl.columns /= 3;
  json_t *curves = json_array();
  double lo = INFINITY, hi = 0.0;
  const int pm = ecdf_blocks(pl.p, "m", m, &lo, &hi), pr = ecdf_blocks(pl.p, "r", ref, &lo, &hi);
  rate_block(pl.p, "m", &m->ensemble, 2.0);
  rate_block(pl.p, "r", &ref->ensemble, 1.0);
  /* the first impacts: force and penetration errors [%] with their bounds */
  const fb_first_check *fc = &m->first_check;
  const fb_reference_error *e = &m->ref_error;
  fprintf(pl.p, "$first << EOD\n");
  for (int k = 0; k < fc->compared; k++)
    fprintf(pl.p, "%d %.6g %.6g\n", k + 1, 100.0 * e->first_impact_force_rel[k],
            100.0 * e->first_impact_penetration_rel[k]);
  if (fc->compared == 0) fprintf(pl.p, "NaN NaN NaN\n");
  fprintf(pl.p, "EOD\n$rebound << EOD\n1 %.6g\nEOD\n",
          100.0 * (m->first_impact.rebound / r->c.clearance.restitution - 1.0));
  const char *derived = "per member: summary.json impact_statistics.per_member and verdict_test";
  const char *who[2] = {m->run.name, ref->run.name};
  const int pts[2] = {pm, pr};
  for (int s = 0; s < 2; s++) {
    json_t *c = fig_curve(who[s], "impact peak force per member", "summary.json", pts[s],
                          NAN, NAN, NAN, NAN);
    json_object_set_new(c, "panel", json_string("impact peak force distribution"));
    json_object_set_new(c, "derived", json_string(derived));
    fig_curve_style(c, r, who[s]);
    json_array_append_new(curves, c);
  }
  char title[1400], en[1500];
  fb_report_test_title(title, sizeof title, m);
  fprintf(pl.p, "set multiplot layout 1,3 title '%s' font ',10'\n", fig_esc(title, en, sizeof en));
  const model_style ms = fig_style_in(r, m->run.name);
  char mn[160], rn[160];
  fig_esc(m->run.name, mn, sizeof mn);
  fig_esc(ref->run.name, rn, sizeof rn);
  const int rigid = m->run.model->rigid;
  /* (a) each member's impact peak forces, the reference's under the model's
   * (a rigid model's impulses have no finite peak force to compare) */
  fprintf(pl.p, "set title 'impact peak forces of each member (empirical distribution)%s'\n"
                "set logscale x\nset xlabel 'impact peak force [N]'\n"
                "set ylabel 'share of the member''s impacts at or below'\nset yrange [0:1.02]\n"
                "set key inside bottom right opaque box font ',9'\n",
          rigid ? ": shown, not compared" : "");
  if (isfinite(lo) && hi > lo) fprintf(pl.p, "set xrange [%.6g:%.6g]\n", 0.8 * lo, 1.25 * hi);
  fprintf(pl.p, "plot ");
  for (int k = 0; k < ref->ensemble.members; k++) {
    fprintf(pl.p, "%s$r%d using 1:2 with steps lc rgb '#9a9a9a' lw 1 ", k ? ", " : "", k);
    if (k == 0) fprintf(pl.p, "title '%s, %d members'", rn, ref->ensemble.members);
    else fprintf(pl.p, "notitle");
  }
  for (int k = 0; k < m->ensemble.members; k++) {
    fprintf(pl.p, ", $m%d using 1:2 with steps lc rgb '%s' lw 1 ", k, ms.color);
    if (k == 0) fprintf(pl.p, "title '%s, %d members'", mn, m->ensemble.members);
    else fprintf(pl.p, "notitle");
  }
  fprintf(pl.p, "\n");
  /* (b) each member's impacts per revolution, and each side's mean */
  const fb_equiv *rate = NULL;
  for (int q = 0; q < m->test.n; q++)
    if (m->test.kind[q] == FB_STAT_RATE) rate = &m->test.eq[q];
  fprintf(pl.p, "$means << EOD\n0.75 %.9g\n1.25 %.9g\n\n1.75 %.9g\n2.25 %.9g\nEOD\n",
          rate ? rate->mean_y : NAN, rate ? rate->mean_y : NAN, rate ? rate->mean_x : NAN,
          rate ? rate->mean_x : NAN);
  fprintf(pl.p, "unset logscale x\nset xrange [0.4:2.6]\nset xtics ('%s' 1, '%s' 2)\n"
                "set xlabel ''\nset ylabel 'impacts per revolution'\nset yrange [0:*]\n"
                "set title 'impact rate of each member: ratio %.3g [%.3g, %.3g], margin [%.3g, %.3g]'\n"
                "set key inside top left opaque box font ',9'\n"
                "plot $rrate using 1:2 with points pt 7 ps 0.7 lc rgb '#9a9a9a' title 'members', "
                "$mrate using 1:2 with points pt 7 ps 0.7 lc rgb '%s' notitle, "
                "$means using 1:2 with lines lw 3 lc rgb '#000000' title 'mean'\n",
          rn, mn, rate ? rate->ratio : NAN, rate ? rate->lo : NAN, rate ? rate->hi : NAN,
          rate ? 1.0 / rate->margin : NAN, rate ? rate->margin : NAN, ms.color);
  /* (c) the first impacts, one to one, and their bounds */
  /* the first impact alone is held; the next are listed (verdict_stats.h) */
  fprintf(pl.p, "$bound << EOD\n0.5 %g\n1.5 %g\nEOD\n", 100.0 * fc->bound, 100.0 * fc->bound);
  fprintf(pl.p, "set xrange [0.5:3.5]\nset xtics 1\nset xlabel 'impact of the run, before it parts'\n"
                "set ylabel '%s against %s [%%]'\nset autoscale y\n"
                "set title 'first %s held: %s (%.0f %% of its bound)%s'\n"
                "set key inside top right opaque box font ',9'\nset style fill solid 0.6\n"
                "set boxwidth 0.3\nplot ",
          rigid ? "rebound ratio error" : "relative error", rigid ? "cr of the law" : rn,
          rigid ? "rebound" : "impact", fc->ok ? "within its bound" : "beyond it",
          100.0 * fc->worst, rigid ? "" : "; 2 and 3 listed");
  if (rigid)
    fprintf(pl.p, "$rebound using 1:2 with boxes lc rgb '%s' title 'rebound ratio', ", ms.color);
  else
    fprintf(pl.p, "$first using ($1-0.16):2 with boxes lc rgb '%s' title 'peak force', "
                  "$first using ($1+0.16):3 with boxes lc rgb '#555555' title 'peak penetration', ",
            ms.color);
  fprintf(pl.p, "$bound using 1:2 with steps dt 2 lc rgb '#000000' title 'bound', "
                "$bound using 1:(-$2) with steps dt 2 lc rgb '#000000' notitle\n");
  fprintf(pl.p, "unset multiplot\n");
  st = fig_plot_close(&pl, diag);
  snprintf(file, file_size, "%s.%s", name, fig_ext(fmt));
  if (st == FB_OK) fig_manifest_add(figs, file, "a verdict on statistics: members against the reference's", curves);
  else json_decref(curves);
  return st;
}

fb_status fig_verdicts(const fb_run *r, const char *dir, fb_figure_format fmt, json_t *figs,
                       char names[][128], int max, int *n, fb_diag *diag) {
  fb_status st = FB_OK;
  for (int i = 0; i < r->n && st == FB_OK; i++) {
    const fb_model_result *m = &r->model[i];
    if (m->basis != FB_BASIS_STATISTICS || !m->has_test) continue;
    const fb_model_result *ref = NULL;
    for (int k = 0; k < r->n; k++)
      if (strcmp(r->model[k].run.name, m->ref_name) == 0) ref = &r->model[k];
    if (!ref || !ref->has_ensemble) continue;
    char file[128];
    st = one_figure(r, m, ref, dir, fmt, figs, file, sizeof file, diag);
    if (st == FB_OK && *n < max) snprintf(names[(*n)++], 128, "%s", file);
  }
  return st;
}
