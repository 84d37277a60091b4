/* bench.<ext> (fourbar bench): error against wall time per revolution,
 * one colour per model, each model's Pareto front joined, titled with the
 * engines it ran on; each error target's cheapest configuration across
 * engines ringed and named, the targets drawn as lines, the peers'
 * harness/bare ratios written in the chart's corner; with its manifest
 * <name>.figure.json. */
#include "figures_internal.h"

#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "bench_study.h"
#include "report.h"

/* models a bench's chart holds at most (every engine's ideal and clearance
 * models, the colliders' and the tuned rows' with room to spare) */
#define BENCH_FIG_MODELS 32

static int by_wall(const void *a, const void *b) {
  const fb_bench_row *x = *(const fb_bench_row *const *)a, *y = *(const fb_bench_row *const *)b;
  return (x->wall_per_rev > y->wall_per_rev) - (x->wall_per_rev < y->wall_per_rev);
}

/* a row with a place on the chart: a run that stopped (NaN error) or whose
 * cost is not a number has none (no placeholder point) */
static int measured(const fb_bench_row *b) {
  return isfinite(b->error) && b->wall_per_rev > 0.0 && isfinite(b->wall_per_rev);
}

/* the engines of the drawn rows, in order of first appearance: "ode,
 * mujoco and bullet"; returns their count */
static int engines_text(char *out, size_t size, const fb_bench_row *rows, int n) {
  const char *seen[BENCH_FIG_MODELS];
  int ne = 0;
  for (int i = 0; i < n; i++) {
    int known = !measured(&rows[i]);
    for (int k = 0; k < ne && !known; k++) known = strcmp(seen[k], rows[i].engine) == 0;
    if (!known && ne < BENCH_FIG_MODELS) seen[ne++] = rows[i].engine;
  }
  size_t used = 0;
  out[0] = '\0';
  for (int k = 0; k < ne && used < size; k++)
    used += (size_t)snprintf(out + used, size - used, "%s%s", k == 0 ? "" : k + 1 < ne ? ", " : " and ",
                             seen[k]);
  return ne;
}

/* an error target as text: "1e-2" (a power of ten), else "%g" */
static const char *target_text(char *out, size_t size, double t) {
  const double e = round(log10(t));
  if (fabs(t / pow(10.0, e) - 1.0) < 1e-9) snprintf(out, size, "1e%d", (int)e);
  else snprintf(out, size, "%g", t);
  return out;
}

/* the cheapest configurations' rings and names: one point per row, named
 * with every target it is the cheapest for ("ideal <= 1e-2, 1e-3") */
static int write_cheapest(FILE *p, const fb_bench_row *rows, const fb_bench_marks *m) {
  static const char *kind[2] = {"ideal", "clearance"};
  int written = 0;
  fprintf(p, "$cheap << EOD\n");
  for (int q = 0; q < 2 && m; q++)
    for (int t = 0; t < FB_BENCH_TARGETS; t++) {
      const int i = m->cheapest[q][t];
      int first = 1; /* the row's first target of this kind: it carries the label */
      for (int u = 0; u < t; u++) first &= m->cheapest[q][u] != i;
      if (i < 0 || !first || !measured(&rows[i])) continue;
      char label[96], tt[32];
      size_t used = (size_t)snprintf(label, sizeof label, "%s <= %s", kind[q],
                                     target_text(tt, sizeof tt, m->target[t]));
      for (int u = t + 1; u < FB_BENCH_TARGETS && used < sizeof label; u++)
        if (m->cheapest[q][u] == i)
          used += (size_t)snprintf(label + used, sizeof label - used, ", %s",
                                   target_text(tt, sizeof tt, m->target[u]));
      fprintf(p, "%.9g %.9g \"%s\"\n", rows[i].wall_per_rev, fmax(rows[i].error, 1e-12), label);
      written++;
    }
  fprintf(p, "EOD\n");
  return written;
}

/* the peers' harness/bare ratios, in the chart's upper left corner */
static void write_peers(FILE *p, const fb_bench_marks *m) {
  if (!m || m->npeers <= 0) return;
  char text[1024];
  size_t used = (size_t)snprintf(text, sizeof text, "harness / bare program (peers):");
  for (int i = 0; i < m->npeers && used < sizeof text; i++) {
    const fb_peer_row *r = &m->peers[i];
    if (r->ran && isfinite(r->harness_over_bare))
      used += (size_t)snprintf(text + used, sizeof text - used, "\\n%s %.2f", r->engine,
                               r->harness_over_bare);
    else
      used += (size_t)snprintf(text + used, sizeof text - used, "\\n%s not run", r->engine);
  }
  fprintf(p, "set label 1 \"%s\" at graph 0.015, graph 0.975 left front font ',9' noenhanced\n",
          text);
}

fb_status fb_figures_bench(const char *path, fb_figure_format fmt, const char *case_name,
                           const void *rows_, int n, const struct fb_bench_marks_s *marks,
                           fb_diag *diag) {
  const fb_bench_row *rows = rows_;
  char dir[4096], name[256];
  fig_split_path(path, dir, sizeof dir, name, sizeof name);
  plot pl;
  fb_status st = fig_plot_open(&pl, dir, name, fmt, 1000, 800, diag);
  if (st != FB_OK) return st;
  /* the models of the grid, in order of first appearance */
  const char *models[BENCH_FIG_MODELS];
  const fb_model *model_rows[BENCH_FIG_MODELS];
  int nm = 0;
  for (int i = 0; i < n; i++) {
    int seen = 0;
    for (int q = 0; q < nm; q++) seen |= model_rows[q] == rows[i].row;
    if (!seen && nm < BENCH_FIG_MODELS) {
      model_rows[nm] = rows[i].row;
      models[nm++] = rows[i].model;
    }
  }
  json_t *curves = json_array();
  int drawn[BENCH_FIG_MODELS] = {0}, fronts[BENCH_FIG_MODELS] = {0};
  for (int q = 0; q < nm; q++) {
    const fb_bench_row *front[FB_BENCH_MAX_ROWS];
    int nf = 0;
    double x0 = NAN, x1 = NAN, y0 = NAN, y1 = NAN;
    fprintf(pl.p, "$all%d << EOD\n", q);
    for (int i = 0; i < n; i++) {
      const fb_bench_row *b = &rows[i];
      if (b->row != model_rows[q] || !measured(b)) continue;
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
  const int ncheap = write_cheapest(pl.p, rows, marks);
  char en[160], engines[256], ee[300];
  const int ne = engines_text(engines, sizeof engines, rows, n);
  /* the title's two lines joined by gnuplot's string concatenation: the
   * single-quoted parts keep fig_esc's escapes as they are */
  fprintf(pl.p, "set title '%s: error against cost on %d engine%s, %s (fourbar bench)' . "
                "\"\\n\" . '{/*0.85 ideal models: omega peaks against the analytic solution; "
                "clearance models: peak force, penetration and alpha spikes against the "
                "reference}'\n"
                "set logscale xy\nset format x '10^{%%L}'\nset format y '10^{%%L}'\n"
                "set xlabel 'wall time per simulated revolution [s]'\n"
                "set ylabel 'error against the exact yardstick [-]'\n"
                "set key outside below center horizontal maxrows 6 font ',9' spacing 1.1\n"
                "set bmargin at screen 0.17\n"
                "set offsets graph 0.03, graph 0.03, graph 0.05, graph 0.05\n",
          fig_esc(case_name, en, sizeof en), ne, ne == 1 ? "" : "s",
          fig_esc(engines, ee, sizeof ee));
  /* the error targets, as faint lines the cheapest rows sit under */
  for (int t = 0; marks && t < FB_BENCH_TARGETS; t++) {
    char tt[32];
    fprintf(pl.p, "set arrow %d from graph 0, first %g to graph 1, first %g nohead back dt 3 "
                  "lc rgb '#b0b0b0'\n", t + 1, marks->target[t], marks->target[t]);
    fprintf(pl.p, "set label %d 'target %s' at graph 0.99, first %g right offset 0,0.6 "
                  "font ',8' tc rgb '#909090' noenhanced\n", t + 2, target_text(tt, sizeof tt,
                  marks->target[t]), marks->target[t]);
  }
  write_peers(pl.p, marks);
  int any = 0;
  fprintf(pl.p, "plot ");
  for (int q = 0; q < nm; q++) {
    if (!drawn[q]) continue;
    const model_style ms = fig_style_of(models[q]);
    const char *what = model_rows[q] && !fb_model_has_clearance(model_rows[q]) ? "vs analytic"
                                                                             : "vs reference";
    char mn[160];
    fig_esc(models[q], mn, sizeof mn);
    /* one legend entry per model: its front's, or its points' without one */
    fprintf(pl.p, "%s$all%d using 1:2 with points pt 7 ps 0.8 lc rgb '%s' ", any ? ", " : "", q,
            ms.color);
    if (fronts[q])
      fprintf(pl.p, "notitle, $front%d using 1:2 with linespoints pt 7 lw 2 dt %d lc rgb '%s' "
                    "title '%s (%s)'", q, ms.dash, ms.color, mn, what);
    else
      fprintf(pl.p, "title '%s (%s)'", mn, what);
    any = 1;
  }
  if (ncheap)
    fprintf(pl.p, ", $cheap using 1:2 with points pt 6 ps 2.6 lw 1.5 lc rgb '#000000' "
                  "title 'cheapest per error target, across engines', $cheap using 1:2:3 with "
                  "labels left offset 1.6,0.6 font ',9' noenhanced notitle");
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
    json_object_set_new(json_array_get(figs, 0), "engines", json_string(engines));
    json_object_set_new(json_array_get(figs, 0), "cheapest_marked", json_integer(ncheap));
    st = fb_report_write_json(mpath, o, diag);
    json_decref(o);
  } else {
    json_decref(curves);
  }
  return st;
}
