/* startup.<ext>: the start-up, revolution 1, against log time. */
#include "figures_internal.h"

#include <jansson.h>
#include <math.h>
#include <stdio.h>

#include "start.h"

/* startup.<ext>: the output bodies' velocity and acceleration (the
 * four-bar's coupler and follower omega and alpha, the slider-crank's
 * coupler's and its slider's v and a) against time over
 * revolution 1 on a logarithmic time axis (from the first step), every model
 * in its own style: the first impacts of a rest start sit in the first
 * microseconds, the run-in's decay over the milliseconds after */
fb_status fig_startup(const fb_run *r, const char *dir, fb_figure_format fmt,
                      json_t *figs, fb_diag *diag) {
  plot pl;
  fb_status st = fig_plot_open(&pl, dir, "startup", fmt, 1300, 950, diag);
  if (st != FB_OK) return st;
  pl.columns /= 2; /* two panels across */
  const double t0 = 0.5 * r->c.solver.h, t1 = r->t_startup_end; /* a log axis has no t = 0 */
  json_t *curves = json_array();
  int order[FB_MAX_MODELS];
  const int nm = fig_draw_order(r, order);
  double amax[2] = {0.0, 0.0}, amin[2] = {0.0, 0.0}; /* each body's acceleration extremes */
  for (int p = 0; p < 4; p++) { /* body 0 and 1 velocity, then body 0 and 1 acceleration */
    const int b = p & 1, alpha = p >> 1, qty = alpha ? FB_Q_ACC : FB_Q_VEL;
    for (int q = 0; q < nm; q++) {
      const int i = order[q];
      const fb_series *s = &r->model[i].run.series;
      const double *y = s->body[b][qty];
      char dname[32], csv[96], col[64], panel[64];
      snprintf(dname, sizeof dname, "s%d_%d", p, i);
      double lo = NAN, hi = NAN;
      const int pts = fig_datablock_x(&pl, dname, s, y, t0, t1, 1, &lo, &hi);
      if (alpha && pts) amax[b] = fmax(amax[b], hi), amin[b] = fmin(amin[b], lo);
      snprintf(csv, sizeof csv, "%s.csv", r->model[i].run.name);
      fig_column(r, b, qty, NULL, col, sizeof col);
      json_t *c = fig_curve(r->model[i].run.name, col, csv, pts, lo, hi, t0, t1);
      snprintf(panel, sizeof panel, "%s %s", fig_body(r, b), fig_symbol(r, b, qty));
      json_object_set_new(c, "panel", json_string(panel));
      fig_curve_style(c, r, r->model[i].run.name);
      json_array_append_new(curves, c);
    }
  }
  char en[160];
  fprintf(pl.p,
          "set multiplot layout 2,2 title '%s: the start-up, revolution 1 (start = %s, pin %s; "
          "log time)'\n",
          fig_esc(r->c.name, en, sizeof en), fb_start_name(r->c.start),
          fb_pin_start_name(r->c.pin_start));
  fprintf(pl.p, "set logscale x\nset format x '10^{%%L}'\nset xlabel 'time [ms]'\n"
                "set xrange [%.9g:%.9g]\nset key inside top left box opaque font ',8'\n",
          t0 * 1e3, t1 * 1e3);
  for (int p = 0; p < 4; p++) {
    const int b = p & 1, alpha = p >> 1, qty = alpha ? FB_Q_ACC : FB_Q_VEL;
    if (p == 1) fprintf(pl.p, "unset key\n"); /* one legend, in the first panel */
    /* symlog as alpha.svg, the range to the decade above the spikes: one
     * range for both panels when the bodies share a unit (the four-bar's
     * rad/s^2), else each panel its own (the slider-crank's m/s^2) */
    const int one_axis = fig_same_unit(r, FB_Q_ACC);
    if (p == 2 && one_axis)
      fig_symlog_axis(&pl, fmin(amin[0], amin[1]), fmax(amax[0], amax[1]), NULL);
    else if (alpha && !one_axis)
      fig_symlog_axis(&pl, amin[b], amax[b], NULL);
    fprintf(pl.p, "set title '%s %s'\nset ylabel '%s [%s%s]'\nplot ", fig_body(r, b), fig_quantity(r, b, qty),
            fig_symbol(r, b, qty), fig_unit(r, b, qty), alpha ? " (symlog)" : "");
    for (int q = 0; q < nm; q++) {
      const int i = order[q];
      char mn[160], sp[96];
      fprintf(pl.p, "%s$s%d_%d using 1:2 with lines %s title '%s'", q ? ", " : "", p, i,
              fig_style_spec(r, r->model[i].run.name, sp, sizeof sp),
              fig_esc(r->model[i].run.name, mn, sizeof mn));
    }
    fprintf(pl.p, "\n");
  }
  fprintf(pl.p, "unset multiplot\n");
  st = fig_plot_close(&pl, diag);
  char file[128];
  snprintf(file, sizeof file, "startup.%s", fig_ext(fmt));
  if (st == FB_OK) {
    /* the four-bar's bodies all turn: "angular velocity and acceleration" */
    int turn = 1;
    for (int k = 0; k < fig_outputs(r); k++) turn &= !fb_mech_output_translates(fb_case_mech(&r->c), k);
    char title[160];
    snprintf(title, sizeof title, "start-up: %svelocity and acceleration against log time", turn ? "angular " : "");
    fig_manifest_add(figs, file, title, curves);
  } else {
    json_decref(curves);
  }
  return st;
}
