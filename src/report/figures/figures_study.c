/* study.svg (fourbar sweep, fourbar merge): a study's metrics from its
 * points.csv, as curves against the first axis, heat maps over the first
 * two axes, or for a Monte Carlo axis each metric's empirical CDF and a
 * scatter against the sampled link lengths; study.figure.json beside it. */
#include "figures_internal.h"

#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "casefile.h"
#include "linkage.h"
#include "study.h"
#include "units.h"
#include "report.h"

/* a readable label with its unit for a case key (section.key) or a metric
 * (model.group.name): "crank speed [rpm]", "force max [N] (ode-clearance-impact)" */
static const char *readable(const char *key, char *out, size_t size) {
  static const struct { const char *key, *label; } known[] = {
      {"drive.speed_rpm", "crank speed [rpm]"},
      {"solver.h_s", "step size h [s]"},
      {"clearance.stiffness_scale", "contact stiffness scale [-]"},
      {"clearance.mapping", "ERP/CFM mapping"},
      {"clearance.penalty", "penalty source"},
      {"clearance.restitution", "coefficient of restitution [-]"},
      {"pin.radial_clearance_um", "radial clearance [um]"},
      {"solver.stepper", "stepper"},
  };
  for (size_t k = 0; k < sizeof known / sizeof known[0]; k++)
    if (strcmp(known[k].key, key) == 0) return snprintf(out, size, "%s", known[k].label), out;
  static const struct { const char *suffix, *unit; } units[] = {
      {"_rad_s2", "rad/s^2"}, {"_rad_s", "rad/s"}, {"_rpm", "rpm"}, {"_mm", "mm"}, {"_um", "um"},
      {"_n_m1_5", "N/m^1.5"}, {"_n_s_m", "N s/m"}, {"_n_m", "N/m"}, {"_n", "N"}, {"_m", "m"},
      {"_s", "s"}, {"_deg", "deg"}, {"_kg", "kg"}, {"_rad", "rad"}, {"_m_s2", "m/s^2"}};
  const char *last = strrchr(key, '.');
  char word[128];
  snprintf(word, sizeof word, "%s", last ? last + 1 : key);
  const char *unit = NULL;
  size_t lw = strlen(word);
  for (size_t k = 0; k < sizeof units / sizeof units[0] && !unit; k++) {
    size_t ls = strlen(units[k].suffix);
    if (lw > ls && strcmp(word + lw - ls, units[k].suffix) == 0) {
      unit = units[k].unit;
      word[lw - ls] = '\0';
    }
  }
  for (char *p = word; *p; p++)
    if (*p == '_') *p = ' ';
  /* a metric: model.group.name -> "[group ]name [unit] (model)"; spikes
   * names already say what they are */
  const char *dot = strchr(key, '.');
  char owner[128] = "", group[64] = "";
  if (dot && last && dot != last) {
    snprintf(owner, sizeof owner, " (%.*s)", (int)(dot - key), key);
    if (strncmp(dot + 1, "spikes.", 7) != 0) snprintf(group, sizeof group, "%.*s ", (int)(last - dot - 1), dot + 1);
  }
  snprintf(out, size, "%s%s%s%s%s%s", group, word, unit ? " [" : "", unit ? unit : "", unit ? "]" : "", owner);
  return out;
}

/* values of an axis are log-spaced: all positive, a constant ratio other
 * than 1 (two values: a ratio of 10 or more) */
static int log_spaced(const fb_axis *a) {
  double v[FB_STUDY_MAX_VALUES];
  for (int k = 0; k < a->n; k++) {
    v[k] = fig_cell_num(a->value[k]);
    if (!(v[k] > 0.0)) return 0;
  }
  if (a->n < 2) return 0;
  if (a->n == 2) return fmax(v[0], v[1]) / fmin(v[0], v[1]) >= 10.0;
  const double ratio = v[1] / v[0];
  if (fabs(ratio - 1.0) < 1e-9) return 0;
  for (int k = 2; k < a->n; k++)
    if (fabs(v[k] / v[k - 1] - ratio) > 1e-6 * fabs(ratio)) return 0;
  return 1;
}

static int numeric_axis(const fb_axis *a) {
  if (a->montecarlo) return 0;
  for (int k = 0; k < a->n; k++)
    if (isnan(fig_cell_num(a->value[k]))) return 0;
  return 1;
}

/* index of text among the axis's values, -1 if none */
static int axis_index(const fb_axis *a, const char *text) {
  for (int k = 0; k < a->n; k++)
    if (strcmp(a->value[k], text) == 0) return k;
  return -1;
}

static int by_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

fb_status fb_figures_study(const fb_study *s, const char *dir, fb_diag *diag) {
  char csvpath[4200];
  snprintf(csvpath, sizeof csvpath, "%s/points.csv", dir);
  study_csv t;
  if (!fig_csv_read(&t, csvpath)) {
    fig_csv_free(&t);
    return FB_OK; /* nothing to draw */
  }
  char names[8][128];
  int n = 0;
  if (s->nplot) {
    for (int k = 0; k < s->nplot; k++) snprintf(names[n++], 128, "%s", s->plot[k]);
  } else {
    /* the spike metrics first (the distribution a clearance study exists
     * for), then the others in column order, up to four */
    for (int pass = 0; pass < 2; pass++)
      for (int c = t.status_col + 1; c < t.ncol && n < 4; c++)
        if (strcmp(t.head[c], "warnings") != 0 && (strstr(t.head[c], ".spikes.") != NULL) == (pass == 0))
          snprintf(names[n++], 128, "%s", t.head[c]);
  }
  if (n == 0) {
    fig_csv_free(&t);
    return FB_OK;
  }
  const fb_axis *x = &s->axis[0];
  const int mc = x->montecarlo;
  /* Monte Carlo: per metric, its empirical CDF and a scatter against the
   * sampled lengths (deviation from nominal); grids: one panel per metric */
  const int cols = mc ? 2 : (n > 1 ? 2 : 1), rows = mc ? n : (n + 1) / 2;
  plot pl;
  fb_status st = fig_plot_open(&pl, dir, "study", FB_FIGURE_SVG, mc ? 1300 : 1400, 440 * rows, diag);
  if (st != FB_OK) {
    fig_csv_free(&t);
    return st;
  }
  double nominal_mm[FB_LINK_COUNT] = {0};
  int lcol[FB_LINK_COUNT];
  if (mc) {
    fb_case base;
    const char *fixed[FB_STUDY_MAX_SETS];
    for (int k = 0; k < s->nsets; k++) fixed[k] = s->sets[k];
    const int loaded = fb_casefile_load(&base, s->case_path, fixed, s->nsets, NULL) == FB_OK;
    for (int k = 0; k < FB_LINK_COUNT; k++) {
      char key[64];
      snprintf(key, sizeof key, "linkage.%s_mm", fb_link_name(k));
      lcol[k] = fig_csv_col(&t, key);
      nominal_mm[k] = loaded ? base.nominal.length[k] / FB_M_PER_MM : NAN;
    }
  }
  json_t *panels = json_array();
  char en[160], ep[600], lab[300], lab2[300], tmp[600];
  fprintf(pl.p, "set key noenhanced outside right top vertical box\n"
                "set multiplot layout %d,%d title 'study %s (%s)' noenhanced\n",
          rows, cols, fig_gp_text(s->name, 0, en, sizeof en), fig_gp_text(s->path, 0, ep, sizeof ep));
  for (int m = 0; m < n; m++) {
    const int mcol = fig_csv_col(&t, names[m]);
    fig_gp_text(readable(names[m], tmp, sizeof tmp), 0, lab, sizeof lab);
    json_t *panel = json_pack("{s:s,s:s}", "metric", names[m], "ylabel", tmp);
    int stopped = 0;
    if (mc) {
      /* empirical CDF of the finished samples */
      double *v = malloc((t.nrow + 1) * sizeof *v);
      size_t nv = 0;
      for (size_t r = 0; r < t.nrow; r++) {
        const double y = mcol >= 0 ? fig_cell_num(t.cell[r][mcol]) : NAN;
        if (strcmp(t.cell[r][t.status_col], "ok") != 0) stopped++;
        else if (isfinite(y)) v[nv++] = y;
      }
      qsort(v, nv, sizeof *v, by_double);
      fprintf(pl.p, "$cdf%d << EOD\n", m);
      for (size_t k = 0; k < nv; k++) fprintf(pl.p, "%.17g %.17g\n", v[k], (double)(k + 1) / (double)nv);
      if (!nv) fprintf(pl.p, "NaN NaN\n");
      fprintf(pl.p, "EOD\n");
      free(v);
      fprintf(pl.p, "unset logscale\nset title 'distribution over %zu samples%s' noenhanced\n"
                    "set xlabel '%s' noenhanced\nset ylabel 'fraction of samples at or below [-]'\n"
                    "set yrange [0:1.05]\nplot $cdf%d using 1:2 with steps lw 2 lc rgb '#d62728' "
                    "title 'empirical CDF', $cdf%d using 1:2 with points pt 7 ps 0.5 lc rgb '#d62728' notitle\n"
                    "set autoscale y\n",
              nv, stopped ? " (stopped samples left out)" : "", lab, m, m);
      /* scatter against each sampled length's deviation from nominal */
      static const char *const link_color[FB_LINK_COUNT] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd"};
      int nl = 0;
      for (int k = 0; k < FB_LINK_COUNT; k++) {
        fprintf(pl.p, "$sc%d_%d << EOD\n", m, k);
        int np = 0;
        for (size_t r = 0; r < t.nrow && lcol[k] >= 0 && mcol >= 0; r++) {
          const double l = fig_cell_num(t.cell[r][lcol[k]]), y = fig_cell_num(t.cell[r][mcol]);
          if (isfinite(l) && isfinite(y) && isfinite(nominal_mm[k])) {
            fprintf(pl.p, "%.17g %.17g\n", l - nominal_mm[k], y);
            np++;
          }
        }
        if (!np) fprintf(pl.p, "NaN NaN\n");
        fprintf(pl.p, "EOD\n");
        nl += np > 0;
      }
      fprintf(pl.p, "set title 'against the sampled link lengths' noenhanced\n"
                    "set xlabel 'sampled length minus nominal [mm]'\nset ylabel '%s' noenhanced\nplot ",
              lab);
      for (int k = 0; k < FB_LINK_COUNT; k++)
        fprintf(pl.p, "%s$sc%d_%d using 1:2 with points pt %d ps 0.9 lc rgb '%s' title '%s'", k ? ", " : "",
                m, k, 5 + 2 * k, link_color[k], fb_link_name(k));
      fprintf(pl.p, "\n");
      json_object_set_new(panel, "kind", json_string("montecarlo: empirical CDF and scatter against "
                                                     "sampled lengths"));
      json_object_set_new(panel, "samples", json_integer((json_int_t)nv));
      json_object_set_new(panel, "lengths_plotted", json_integer(nl));
    } else if (s->heatmap) {
      /* cells over the first two axes (their value order), each labelled;
       * further axes at their first value */
      const fb_axis *y = &s->axis[1];
      const int xc = fig_csv_col(&t, x->key), yc = fig_csv_col(&t, y->key);
      fprintf(pl.p, "$hm%d << EOD\n", m);
      int cells = 0;
      for (size_t r = 0; r < t.nrow && xc >= 0 && yc >= 0 && mcol >= 0; r++) {
        int first = 1;
        for (int a = 2; a < s->naxes; a++) {
          const int ac = fig_csv_col(&t, s->axis[a].key);
          first &= ac >= 0 && strcmp(t.cell[r][ac], s->axis[a].value[0]) == 0;
        }
        const int ix = axis_index(x, t.cell[r][xc]), iy = axis_index(y, t.cell[r][yc]);
        const double z = fig_cell_num(t.cell[r][mcol]);
        const int ok = strcmp(t.cell[r][t.status_col], "ok") == 0;
        if (!first || ix < 0 || iy < 0) continue;
        if (!ok) stopped++;
        fprintf(pl.p, "%d %d %.17g %s\n", ix, iy, z, ok ? "ok" : "stopped");
        cells++;
      }
      if (!cells) fprintf(pl.p, "0 0 NaN ok\n");
      fprintf(pl.p, "EOD\n");
      fprintf(pl.p, "unset logscale\nunset key\nset title '%s' noenhanced\nset xlabel '%s' noenhanced\nset ylabel '%s' noenhanced\n"
                    "set cblabel '%s' noenhanced\nset palette rgb 33,13,10\nset xrange [-0.5:%d.5]\n"
                    "set yrange [-0.5:%d.5]\nset xtics (",
              lab, fig_gp_text(readable(x->key, tmp, sizeof tmp), 0, lab2, sizeof lab2),
              fig_gp_text(readable(y->key, ep, sizeof ep), 0, en, sizeof en), lab, x->n - 1, y->n - 1);
      for (int k = 0; k < x->n; k++) fprintf(pl.p, "%s'%s' %d", k ? ", " : "", fig_gp_text(x->value[k], 0, tmp, sizeof tmp), k);
      fprintf(pl.p, ")\nset ytics (");
      for (int k = 0; k < y->n; k++) fprintf(pl.p, "%s'%s' %d", k ? ", " : "", fig_gp_text(y->value[k], 0, tmp, sizeof tmp), k);
      fprintf(pl.p, ")\nplot $hm%d using 1:2:3 with image notitle, "
                    "$hm%d using 1:2:(strcol(4) eq 'ok' ? sprintf('%%.3g', $3) : sprintf('%%.3g (stopped)', $3)) "
                    "with labels font ',10' notitle\n"
                    "unset xtics\nunset ytics\nset xtics\nset ytics\nset autoscale\nset key noenhanced outside right top vertical box\n",
              m, m);
      json_object_set_new(panel, "kind", json_string("heatmap"));
      json_object_set_new(panel, "cells", json_integer(cells));
      json_object_set_new(panel, "xlabel", json_string(readable(x->key, tmp, sizeof tmp)));
    } else {
      /* the metric against the first axis, one series per combination of the
       * other axes; written per series, so every line is drawn */
      const int xnum = numeric_axis(x), xlog = xnum && log_spaced(x);
      const int xc = fig_csv_col(&t, x->key);
      int combos = 1;
      for (int a = 1; a < s->naxes; a++) combos *= s->axis[a].n;
      if (combos > 12) combos = 12;
      json_t *series = json_array();
      fprintf(pl.p, "$stop%d << EOD\n", m);
      double ylo = INFINITY;
      for (size_t r = 0; r < t.nrow && mcol >= 0; r++) {
        const double y = fig_cell_num(t.cell[r][mcol]);
        if (isfinite(y)) ylo = fmin(ylo, y);
      }
      for (size_t r = 0; r < t.nrow && xc >= 0; r++)
        if (strcmp(t.cell[r][t.status_col], "ok") != 0) {
          /* a stopped point: at its value if it has one, else at the lowest value drawn */
          const double xv = xnum ? fig_cell_num(t.cell[r][xc]) : axis_index(x, t.cell[r][xc]);
          double y = mcol >= 0 ? fig_cell_num(t.cell[r][mcol]) : NAN;
          if (!isfinite(y)) y = isfinite(ylo) ? ylo : 0.0;
          fprintf(pl.p, "%.17g %.17g\n", xv, y);
          stopped++;
        }
      if (!stopped) fprintf(pl.p, "NaN NaN\n");
      fprintf(pl.p, "EOD\n");
      for (int k = 0; k < combos; k++) {
        char title[1024] = "";
        size_t lt = 0;
        int rest = k, want[FB_STUDY_MAX_AXES], acol[FB_STUDY_MAX_AXES];
        for (int a = s->naxes - 1; a >= 1; a--) {
          const fb_axis *ax = &s->axis[a];
          want[a] = rest % ax->n;
          rest /= ax->n;
          acol[a] = fig_csv_col(&t, ax->key);
        }
        for (int a = 1; a < s->naxes; a++)
          lt += (size_t)snprintf(title + lt, lt < sizeof title ? sizeof title - lt : 0, "%s%s = %s",
                                 lt ? ", " : "", readable(s->axis[a].key, tmp, sizeof tmp),
                                 s->axis[a].value[want[a]]);
        fprintf(pl.p, "$s%d_%d << EOD\n", m, k);
        int np = 0;
        for (size_t r = 0; r < t.nrow && xc >= 0 && mcol >= 0; r++) {
          int match = 1;
          for (int a = 1; a < s->naxes; a++)
            match &= acol[a] >= 0 && strcmp(t.cell[r][acol[a]], s->axis[a].value[want[a]]) == 0;
          const double y = fig_cell_num(t.cell[r][mcol]);
          const double xv = xnum ? fig_cell_num(t.cell[r][xc]) : axis_index(x, t.cell[r][xc]);
          if (!match || !isfinite(y) || !isfinite(xv)) continue;
          fprintf(pl.p, "%.17g %.17g\n", xv, y);
          np++;
        }
        if (!np) fprintf(pl.p, "NaN NaN\n");
        fprintf(pl.p, "EOD\n");
        json_array_append_new(series, json_pack("{s:s,s:i}", "title", s->naxes > 1 ? title : names[m],
                                                "points", np));
      }
      fprintf(pl.p, "set title '%s' noenhanced\nset xlabel '%s' noenhanced\nset ylabel '%s' noenhanced\n%s\n",
              lab, fig_gp_text(readable(x->key, tmp, sizeof tmp), 0, lab2, sizeof lab2), lab,
              xlog ? "set logscale x\nset format x '%g'" : "unset logscale x\nset format x '% h'");
      if (!xnum) {
        fprintf(pl.p, "set xrange [-0.5:%d.5]\nset xtics (", x->n - 1);
        for (int k = 0; k < x->n; k++)
          fprintf(pl.p, "%s'%s' %d", k ? ", " : "", fig_gp_text(x->value[k], 0, tmp, sizeof tmp), k);
        fprintf(pl.p, ")\n");
      } else {
        fprintf(pl.p, "set autoscale x\nset xtics\nset offsets graph 0.03, graph 0.03, graph 0.05, graph 0.05\n");
      }
      fprintf(pl.p, "plot ");
      for (int k = 0; k < combos; k++) {
        const char *title = json_string_value(json_object_get(json_array_get(series, (size_t)k), "title"));
        fprintf(pl.p, "%s$s%d_%d using 1:2 with linespoints pt 7 lw 1.5 title '%s'", k ? ", " : "", m, k,
                fig_gp_text(title, 0, tmp, sizeof tmp));
      }
      if (stopped)
        fprintf(pl.p, ", $stop%d using 1:2 with points pt 4 ps 2 lw 2 lc rgb '#d62728' title 'stopped (%d "
                      "points, status not ok; drawn at their value or the panel floor)'", m, stopped);
      fprintf(pl.p, "\n");
      fprintf(pl.p, "set offsets 0, 0, 0, 0\nunset logscale x\n");
      json_object_set_new(panel, "kind", json_string("curves"));
      json_object_set_new(panel, "xlabel", json_string(readable(x->key, tmp, sizeof tmp)));
      json_object_set_new(panel, "xlog", json_boolean(xlog));
      json_object_set_new(panel, "series", series);
    }
    json_object_set_new(panel, "stopped", json_integer(stopped));
    json_array_append_new(panels, panel);
  }
  fprintf(pl.p, "unset multiplot\n");
  st = fig_plot_close(&pl, diag);
  fig_csv_free(&t);
  if (st == FB_OK) {
    char mpath[4400];
    snprintf(mpath, sizeof mpath, "%s/study.figure.json", dir);
    json_t *o = json_pack("{s:s,s:o}", "file", "study.svg", "panels", panels);
    st = fb_report_write_json(mpath, o, diag);
    json_decref(o);
  } else {
    json_decref(panels);
  }
  return st;
}
