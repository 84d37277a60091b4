/* omega.<ext> and alpha.<ext>: the output bodies' velocity and acceleration
 * (the four-bar's coupler and follower angular velocity and acceleration,
 * the slider-crank's coupler's and its slider's v and a) against crank
 * angle over the peak window, every model overlaid; omega's rows below:
 * each stepping model's residual against the analytic solution of its own
 * lengths, and the engine differences (another engine's model minus the
 * ODE model of the same kind). Body names, symbols, units and columns come
 * from the case's mechanism description (fig_body, fig_column). */
#include "figures_internal.h"

#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "mech_kinematics.h"

/* residual of model i's velocity against the analytic solution of its own
 * lengths at the same instants: resid[k] = y[k] - exact(t[k]) (output body
 * `body`: the four-bar's 0 coupler, 1 follower) for the samples in [t0, t1],
 * the figure's window (NaN outside it, and where the mechanism cannot be
 * solved) */
/* omega.svg's and alpha.svg's one legend under the title: the title's
 * height, one row of legend entries, a panel's own title below it [px], and
 * the most entries in a row [-] */
#define TITLE_PX 30.0
#define KEY_ROW_PX 20.0
#define PANEL_TITLE_PX 34.0
#define KEY_COLUMNS 4

static void residual(const fb_run *r, int i, int body, double t0, double t1, double *resid) {
  const fb_series *s = &r->model[i].run.series;
  const double w = r->c.direction * r->c.crank_speed;
  for (size_t k = 0; k < s->n; k++) {
    double x[FB_MECH_MAX_OUTPUTS][3];
    if (s->t[k] < t0 || s->t[k] > t1) {
      resid[k] = NAN;
      continue;
    }
    const double y = s->body[body][FB_Q_VEL][k];
    if (fb_mech_solve(x, r->c.mechanism, &r->model[i].run.lengths, r->c.branch,
                      r->c.crank_angle0 + w * s->t[k], w, 0.0, NULL) != FB_OK)
      resid[k] = NAN;
    else
      resid[k] = y - x[body][FB_Q_VEL];
  }
}

/* the model of the run that model i is compared with: the first with the
 * engine, lengths, joints and law of the row's partner (model_table.h; ODE's
 * model of the same kind), when model i has one; -1 when there is none */
static int engine_partner(const fb_run *r, int i) {
  const fb_model *p = fb_model_partner_of(r->model[i].run.model);
  if (!p) return -1;
  for (int j = 0; j < r->n; j++) {
    const fb_model *o = r->model[j].run.model;
    if (o->engine == p->engine && o->lengths == p->lengths && o->joints == p->joints &&
        o->law == p->law && r->model[j].run.series.n > 1)
      return j;
  }
  return -1;
}

/* diff[k] = the velocity of output body `body` of model i at its sample k
 * minus model j's at the same instant (linear interpolation between j's
 * samples; NaN outside them) */
static void engine_difference(const fb_run *r, int i, int j, int body, double *diff) {
  const fb_series *a = &r->model[i].run.series, *b = &r->model[j].run.series;
  const double *ya = a->body[body][FB_Q_VEL];
  const double *yb = b->body[body][FB_Q_VEL];
  size_t q = 0;
  for (size_t k = 0; k < a->n; k++) {
    const double t = a->t[k];
    while (q + 2 < b->n && b->t[q + 1] < t) q++;
    if (b->n < 2 || t < b->t[0] || t > b->t[b->n - 1]) {
      diff[k] = NAN;
      continue;
    }
    const double dt = b->t[q + 1] - b->t[q];
    const double w = dt > 0.0 ? (t - b->t[q]) / dt : 0.0;
    diff[k] = ya[k] - (yb[q] + w * (yb[q + 1] - yb[q]));
  }
}

/* omega.svg: the output bodies' velocity (top: the four-bar's coupler and
 * follower omega) and each ODE model's residual against the analytic
 * solution of its lengths (bottom); alpha.svg: their acceleration on a
 * symlog axis */
fb_status fig_omega_alpha(const fb_run *r, const char *dir, fb_figure_format fmt, int alpha,
                          json_t *figs, fb_diag *diag) {
  const char *name = alpha ? "alpha" : "omega";
  plot pl;
  /* omega.svg's rows: values, residuals, engine differences (450 px each) */
  int nrows = 1;
  if (!alpha) {
    int res = 0, dif = 0;
    for (int i = 0; i < r->n; i++) {
      res |= fb_engine_steps_world(r->model[i].run.model->engine) && r->model[i].run.series.n > 0;
      dif |= engine_partner(r, i) >= 0;
    }
    nrows += res + dif;
  }
  fb_status st = fig_plot_open(&pl, dir, name, fmt, alpha ? 1100 : 1400, alpha ? 850 : 450 * nrows, diag);
  if (st != FB_OK) return st;
  if (!alpha) pl.columns /= 2; /* omega.svg: the two output bodies side by side */
  const double period = 2.0 * M_PI / r->c.crank_speed;
  const double t0 = r->t_window, t1 = r->t_window + period;
  json_t *curves = json_array();
  int order[FB_MAX_MODELS];
  const int nm = fig_draw_order(r, order);
  double amax[2] = {0.0, 0.0}, amin[2] = {0.0, 0.0}; /* each body's plotted extremes */
  int has_resid[FB_MAX_MODELS] = {0};
  /* samples each model's value ([0]) and residual ([1]) curve of each body
   * holds in the window: a panel whose curves hold none (every model there
   * stopped before the window) draws a note instead, which gnuplot needs */
  int npts[2][FB_MAX_MODELS][2] = {{{0}}};
  for (int q = 0; q < nm; q++) {
    const int i = order[q];
    const fb_series *s = &r->model[i].run.series;
    for (int b = 0; b < 2; b++) {
      char dname[32];
      snprintf(dname, sizeof dname, "m%d_%d", i, b);
      const double *y = s->body[b][alpha ? FB_Q_ACC : FB_Q_VEL];
      double lo = NAN, hi = NAN;
      /* a stepping engine's acceleration at t = 0 is its first step's start
       * artefact (ODE: the velocity-level step has no drift to correct yet
       * and applies almost none), not the mechanism's: drawn from the first
       * step on */
      const double ta = alpha && fb_engine_steps_world(r->model[i].run.model->engine)
                            ? fmax(t0, 0.5 * r->model[i].run.h)
                            : t0;
      const int pts = fig_datablock(&pl, dname, s, y, ta, t1, &lo, &hi);
      npts[0][i][b] = pts;
      if (pts > 0) {
        amax[b] = fmax(amax[b], hi);
        amin[b] = fmin(amin[b], lo);
      }
      char csv[96], col[64];
      snprintf(csv, sizeof csv, "%s.csv", r->model[i].run.name);
      fig_column(r, b, alpha ? FB_Q_ACC : FB_Q_VEL, NULL, col, sizeof col);
      json_t *c = fig_curve(r->model[i].run.name, col, csv, pts, lo, hi, t0, t1);
      json_object_set_new(c, "panel", json_string(fig_body(r, b)));
      fig_curve_style(c, r, r->model[i].run.name);
      json_array_append_new(curves, c);
    }
  }
  /* residual panels: ODE models only (the analytic ones are the yardstick) */
  if (!alpha)
    for (int q = 0; q < nm; q++) {
      const int i = order[q];
      const fb_series *s = &r->model[i].run.series;
      if (!fb_engine_steps_world(r->model[i].run.model->engine) || s->n == 0) continue;
      double *res = malloc(s->n * sizeof *res);
      if (!res) continue;
      has_resid[i] = 1;
      for (int b = 0; b < 2; b++) {
        residual(r, i, b, t0, t1, res);
        char dname[32], col[64], csv[96], panel[64];
        snprintf(dname, sizeof dname, "r%d_%d", i, b);
        double lo = NAN, hi = NAN;
        const int pts = fig_datablock(&pl, dname, s, res, t0, t1, &lo, &hi);
        npts[1][i][b] = pts;
        fig_column(r, b, FB_Q_VEL, "residual", col, sizeof col);
        snprintf(csv, sizeof csv, "%s.csv", r->model[i].run.name);
        json_t *c = fig_curve(r->model[i].run.name, col, csv, pts, lo, hi, t0, t1);
        snprintf(panel, sizeof panel, "%s residual", fig_body(r, b));
        json_object_set_new(c, "panel", json_string(panel));
        json_object_set_new(c, "derived", json_string("model minus the analytic solution of its own "
                                                      "lengths at the same instants"));
        fig_curve_style(c, r, r->model[i].run.name);
        json_array_append_new(curves, c);
      }
      free(res);
    }
  /* engine difference panels: another engine's model minus ODE's of the
   * same kind, at the same instants */
  int partner[FB_MAX_MODELS];
  int any_resid = 0, any_diff = 0;
  for (int i = 0; i < r->n; i++) {
    any_resid |= has_resid[i];
    partner[i] = alpha ? -1 : engine_partner(r, i);
    if (partner[i] < 0) continue;
    const fb_series *s = &r->model[i].run.series;
    double *d = malloc((s->n ? s->n : 1) * sizeof *d);
    if (!d) {
      partner[i] = -1;
      continue;
    }
    any_diff = 1;
    for (int b = 0; b < 2; b++) {
      engine_difference(r, i, partner[i], b, d);
      char dname[32], col[64], csv[96], panel[64];
      snprintf(dname, sizeof dname, "d%d_%d", i, b);
      double lo = NAN, hi = NAN;
      const int pts = fig_datablock(&pl, dname, s, d, t0, t1, &lo, &hi);
      fig_column(r, b, FB_Q_VEL, "engine_difference", col, sizeof col);
      snprintf(csv, sizeof csv, "%s.csv", r->model[i].run.name);
      json_t *c = fig_curve(r->model[i].run.name, col, csv, pts, lo, hi, t0, t1);
      snprintf(panel, sizeof panel, "%s engine difference", fig_body(r, b));
      json_object_set_new(c, "panel", json_string(panel));
      char what[256];
      snprintf(what, sizeof what, "%s minus %s at the same instants", r->model[i].run.name,
               r->model[partner[i]].run.name);
      json_object_set_new(c, "derived", json_string(what));
      fig_curve_style(c, r, r->model[i].run.name);
      json_array_append_new(curves, c);
    }
    free(d);
  }
  const int rows = 1 + any_resid + any_diff;
  char en[160], what[160];
  const double rpm = r->c.crank_speed * 60.0 / (2.0 * M_PI);
  /* a clockwise drive decreases the crank angle: its motion runs right to left */
  const char *dirnote = r->c.direction > 0 ? "ccw drive: motion runs left to right"
                                           : "cw drive: crank angle decreases, motion runs right to left";
  /* one legend for the figure, in rows across its top under the title
   * (KEY_PX pixels): the models are the same in every panel, and a legend
   * beside each panel took half the figure's width */
  const double height = alpha ? 850.0 : 450.0 * rows;
  const int key_rows = (nm + KEY_COLUMNS - 1) / KEY_COLUMNS;
  const double top = 1.0 - (TITLE_PX + KEY_ROW_PX * (key_rows + 0.5) + PANEL_TITLE_PX) / height;
  fprintf(pl.p, "set multiplot layout %d,%d title '%s: %s against crank angle (revolution %d, %.0f rpm; %s)' "
                "margins 0.06,0.98,%.4f,%.4f spacing 0.07,%.4f\n",
          alpha ? 2 : rows, alpha ? 1 : 2, fig_esc(r->c.name, en, sizeof en),
          fig_quantity_all(r, alpha ? FB_Q_ACC : FB_Q_VEL, what, sizeof what), r->c.peaks == FB_PEAKS_ALL ? 1 : 2,
          rpm, dirnote, 60.0 / height, top, 110.0 / height);
  fprintf(pl.p, "set xrange [0:360]\nset xtics 30\nset xlabel 'crank angle [deg] (counter-clockwise from +x)'\n");
  json_t *axis = json_object();
  /* alpha.svg's symlog axis: one for both panels when the bodies share a
   * unit (the four-bar's rad/s^2), else one per panel (the slider-crank's
   * rad/s^2 and m/s^2: no range is shared across units), in "panels" */
  const int one_axis = fig_same_unit(r, FB_Q_ACC);
  json_t *panel_axes = NULL;
  if (alpha) {
    if (one_axis)
      fig_symlog_axis(&pl, fmin(amin[0], amin[1]), fmax(amax[0], amax[1]), axis);
    else
      panel_axes = json_array();
    /* the linear band in each body's unit (the four-bar's: rad/s^2 alone) */
    char scale[160];
    if (fig_same_unit(r, FB_Q_ACC))
      snprintf(scale, sizeof scale, "symlog, linear within +-1000 %s", fig_unit(r, 0, FB_Q_ACC));
    else
      snprintf(scale, sizeof scale, "symlog, linear within +-1000 in each body's unit (%s %s, %s %s)",
               fig_body(r, 0), fig_unit(r, 0, FB_Q_ACC), fig_body(r, 1), fig_unit(r, 1, FB_Q_ACC));
    json_object_set_new(axis, "scale", json_string(scale));
    if (panel_axes) json_object_set_new(axis, "panels", panel_axes);
  }
  json_object_set_new(axis, "direction", json_string(r->c.direction > 0 ? "ccw" : "cw"));
  json_object_set_new(axis, "note", json_string(dirnote));
  for (int b = 0; b < (alpha ? 2 : 2 * rows); b++) {
    const int body = b % 2;
    /* rows: values, then residuals (when an ODE-like model ran), then the
     * engine differences (when two engines ran the same kind of model) */
    const int row = b / 2;
    const int resid = row == 1 && any_resid;
    const int diffrow = row >= 1 && !resid;
    if (diffrow) {
      /* the legend inside the panel: its long entries would squeeze the plot beside it */
      fprintf(pl.p, "set title '%s: engine difference (minus the ODE model of the same kind, same instants)'\n"
                    "set ylabel '%s %s difference [%s]'\nset autoscale y\n"
                    "set key inside bottom left opaque box font ',8'\n",
              fig_body(r, body), fig_body(r, body), fig_symbol(r, body, FB_Q_VEL), fig_unit(r, body, FB_Q_VEL));
      fprintf(pl.p, "plot ");
      int anyd = 0;
      for (int q = 0; q < nm; q++) {
        const int i = order[q];
        if (partner[i] < 0) continue;
        char mn[160], pn[160], sp[96];
        fprintf(pl.p, "%s$d%d_%d using 1:2 with lines %s title '%s - %s'", anyd ? ", " : "", i, body,
                fig_style_spec(r, r->model[i].run.name, sp, sizeof sp), fig_esc(r->model[i].run.name, mn, sizeof mn),
                fig_esc(r->model[partner[i]].run.name, pn, sizeof pn));
        anyd = 1;
      }
      fprintf(pl.p, "\n");
      continue;
    }
    fprintf(pl.p, "unset key\n"); /* the figure's one legend comes last (below) */
    if (resid) {
      fprintf(pl.p, "set title '%s: model minus analytic (same link lengths, same instants)'\n"
                    "set ylabel '%s %s residual [%s]'\nset autoscale y\n",
              fig_body(r, body), fig_body(r, body), fig_symbol(r, body, FB_Q_VEL), fig_unit(r, body, FB_Q_VEL));
    } else {
      const int q = alpha ? FB_Q_ACC : FB_Q_VEL;
      if (alpha && !one_axis) {
        json_t *pa = json_pack("{s:s}", "panel", fig_body(r, body));
        fig_symlog_axis(&pl, amin[body], amax[body], pa);
        json_array_append_new(panel_axes, pa);
      }
      fprintf(pl.p, "set title '%s'\nset ylabel '%s %s [%s%s]'\n", fig_body(r, body), fig_body(r, body),
              fig_symbol(r, body, q), fig_unit(r, body, q), alpha ? " (symlog)" : "");
    }
    fprintf(pl.p, "plot ");
    int any = 0, held = 0;
    for (int q = 0; q < nm; q++) {
      const int i = order[q];
      if (!(resid && !has_resid[i])) held += npts[resid][i][body];
    }
    for (int q = 0; q < nm && held > 0; q++) {
      const int i = order[q];
      if (resid && !has_resid[i]) continue;
      char mn[160], sp[96];
      fprintf(pl.p, "%s$%c%d_%d using 1:2 with lines %s title '%s'", any ? ", " : "", resid ? 'r' : 'm', i,
              body, fig_style_spec(r, r->model[i].run.name, sp, sizeof sp), fig_esc(r->model[i].run.name, mn, sizeof mn));
      any = 1;
    }
    if (!any && held == 0 && nm > 0 && (!resid || any_resid))
      fprintf(pl.p, "0 with lines lc rgb '#888888' title 'no sample in the window: every model "
                    "here stopped before it'");
    else if (!any) fprintf(pl.p, "0 with lines lc rgb '#888888' title 'no ODE model in this run'");
    fprintf(pl.p, "\n");
  }
  /* the figure's one legend, across its top under the title: a plot of
   * nothing over the whole page whose key names every model in its style
   * (the panels hold the same models, and a legend beside each took half
   * the figure's width) */
  fprintf(pl.p, "set origin 0,0\nset size 1,1\nunset border\nunset tics\nunset xlabel\n"
                "unset ylabel\nunset title\nunset grid\nset xrange [0:1]\nset yrange [0:1]\n"
                "set key at screen 0.5, screen %.4f center top horizontal maxrows %d box opaque "
                "samplen 3 font ',10'\nplot ", 1.0 - TITLE_PX / height, key_rows);
  for (int q = 0; q < nm; q++) {
    const int i = order[q];
    char mn[160], sp[96];
    fprintf(pl.p, "%sNaN with lines %s title '%s'", q ? ", " : "",
            fig_style_spec(r, r->model[i].run.name, sp, sizeof sp),
            fig_esc(r->model[i].run.name, mn, sizeof mn));
  }
  fprintf(pl.p, "%s\n", nm ? "" : "NaN notitle");
  fprintf(pl.p, "unset multiplot\n");
  st = fig_plot_close(&pl, diag);
  char file[128];
  snprintf(file, sizeof file, "%s.%s", name, fig_ext(fmt));
  if (st == FB_OK) {
    char title[240];
    snprintf(title, sizeof title, "%s against crank angle%s",
             fig_quantity_all(r, alpha ? FB_Q_ACC : FB_Q_VEL, what, sizeof what), alpha ? "" : ", and residuals");
    fig_manifest_add(figs, file, title, curves);
    json_object_set_new(json_array_get(figs, json_array_size(figs) - 1), "axis", axis);
  } else {
    json_decref(curves);
    json_decref(axis);
  }
  return st;
}
