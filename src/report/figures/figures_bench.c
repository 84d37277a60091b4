/* bench.<ext> (fourbar bench): error against wall time per revolution,
 * one colour per model, each model's Pareto front joined, with its
 * manifest <name>.figure.json. */
#include "figures_internal.h"

#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bench.h"
#include "report.h"

static int by_wall(const void *a, const void *b) {
  const fb_bench_row *x = *(const fb_bench_row *const *)a, *y = *(const fb_bench_row *const *)b;
  return (x->wall_per_rev > y->wall_per_rev) - (x->wall_per_rev < y->wall_per_rev);
}

fb_status fb_figures_bench(const char *path, fb_figure_format fmt, const char *case_name,
                           const void *rows_, int n, fb_diag *diag) {
  const fb_bench_row *rows = rows_;
  char dir[4096], name[256];
  fig_split_path(path, dir, sizeof dir, name, sizeof name);
  plot pl;
  fb_status st = fig_plot_open(&pl, dir, name, fmt, 1000, 700, diag);
  if (st != FB_OK) return st;
  /* the models of the grid, in order of first appearance */
  const char *models[8];
  const fb_model *model_rows[8];
  int nm = 0;
  for (int i = 0; i < n; i++) {
    int seen = 0;
    for (int q = 0; q < nm; q++) seen |= model_rows[q] == rows[i].row;
    if (!seen && nm < 8) {
      model_rows[nm] = rows[i].row;
      models[nm++] = rows[i].model;
    }
  }
  /* only measured rows are drawn: a run that stopped (NaN error) or whose
   * cost is not a number has no place on the chart (no placeholder point) */
  json_t *curves = json_array();
  int drawn[8] = {0}, fronts[8] = {0};
  for (int q = 0; q < nm; q++) {
    const fb_bench_row *front[FB_BENCH_MAX_ROWS];
    int nf = 0;
    double x0 = NAN, x1 = NAN, y0 = NAN, y1 = NAN;
    fprintf(pl.p, "$all%d << EOD\n", q);
    for (int i = 0; i < n; i++) {
      const fb_bench_row *b = &rows[i];
      if (b->row != model_rows[q] || !isfinite(b->error) || !(b->wall_per_rev > 0.0) ||
          !isfinite(b->wall_per_rev))
        continue;
      /* an exact result (error 0) sits at the axis floor of 1e-12 */
      const double y = fmax(b->error, 1e-12);
      fprintf(pl.p, "%.9g %.9g\n", b->wall_per_rev, y);
      x0 = drawn[q] ? fmin(x0, b->wall_per_rev) : b->wall_per_rev;
      x1 = drawn[q] ? fmax(x1, b->wall_per_rev) : b->wall_per_rev;
      y0 = drawn[q] ? fmin(y0, y) : y;
      y1 = drawn[q] ? fmax(y1, y) : y;
      drawn[q]++;
      if (b->pareto && nf < FB_BENCH_MAX_ROWS) front[nf++] = b;
    }
    fprintf(pl.p, "EOD\n$front%d << EOD\n", q);
    qsort(front, (size_t)nf, sizeof front[0], by_wall);
    for (int i = 0; i < nf; i++)
      fprintf(pl.p, "%.9g %.9g\n", front[i]->wall_per_rev, fmax(front[i]->error, 1e-12));
    fprintf(pl.p, "EOD\n");
    fronts[q] = nf;
    json_t *c = json_pack("{s:s,s:i,s:i}", "model", models[q], "points", drawn[q], "pareto_points", nf);
    if (drawn[q]) {
      json_object_set_new(c, "x_min", json_real(x0));
      json_object_set_new(c, "x_max", json_real(x1));
      json_object_set_new(c, "y_min", json_real(y0));
      json_object_set_new(c, "y_max", json_real(y1));
    }
    fig_curve_style(c, NULL, models[q]);
    json_array_append_new(curves, c);
  }
  char en[160];
  fprintf(pl.p, "set title '%s: error against cost, both engines (fourbar bench)'\nset logscale xy\n"
                "set format x '10^{%%L}'\nset format y '10^{%%L}'\n"
                "set xlabel 'wall time per simulated revolution [s]'\n"
                "set ylabel 'error against the exact yardstick [-]'\nset key outside right top box\n"
                "set offsets graph 0.03, graph 0.03, graph 0.05, graph 0.05\n",
          fig_esc(case_name, en, sizeof en));
  int any = 0;
  fprintf(pl.p, "plot ");
  for (int q = 0; q < nm; q++) {
    if (!drawn[q]) continue;
    const model_style ms = fig_style_of(models[q]);
    const char *what = model_rows[q] && !fb_model_has_clearance(model_rows[q])
                           ? "omega peaks vs analytic"
                           : "force, penetration vs reference";
    char mn[160];
    fig_esc(models[q], mn, sizeof mn);
    fprintf(pl.p, "%s$all%d using 1:2 with points pt 7 ps 0.8 lc rgb '%s' title '%s (%s)'", any ? ", " : "", q,
            ms.color, mn, what);
    if (fronts[q])
      fprintf(pl.p, ", $front%d using 1:2 with linespoints pt 7 lw 2 dt %d lc rgb '%s' title '%s: Pareto front'",
              q, ms.dash, ms.color, mn);
    any = 1;
  }
  if (!any) fprintf(pl.p, "1 with lines lc rgb '#888888' title 'no configuration finished'");
  fprintf(pl.p, "\n");
  st = fig_plot_close(&pl, diag);
  if (st == FB_OK) {
    /* the manifest beside it: what was drawn, for the tests and the reader */
    char mpath[4400], file[300];
    snprintf(mpath, sizeof mpath, "%s/%s.figure.json", dir, name);
    snprintf(file, sizeof file, "%s.%s", name, fig_ext(fmt));
    json_t *figs = json_array();
    fig_manifest_add(figs, file, "error against cost", curves);
    json_t *o = json_pack("{s:o}", "figures", figs);
    st = fb_report_write_json(mpath, o, diag);
    json_decref(o);
  } else {
    json_decref(curves);
  }
  return st;
}
