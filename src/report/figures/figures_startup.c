/* startup.<ext>: the start-up, revolution 1, against log time. */
#include "figures_internal.h"

#include <jansson.h>
#include <math.h>
#include <stdio.h>

#include "start.h"

/* startup.<ext>: omega and alpha of coupler and follower against time over
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
  double amax = 0.0, amin = 0.0;
  for (int p = 0; p < 4; p++) { /* coupler omega, follower omega, coupler alpha, follower alpha */
    const int b = p & 1, alpha = p >> 1;
    for (int q = 0; q < nm; q++) {
      const int i = order[q];
      const fb_series *s = &r->model[i].run.series;
      const double *y = alpha ? (b ? s->follower_alpha : s->coupler_alpha)
                              : (b ? s->follower_omega : s->coupler_omega);
      char dname[32], csv[96], col[48];
      snprintf(dname, sizeof dname, "s%d_%d", p, i);
      double lo = NAN, hi = NAN;
      const int pts = fig_datablock_x(&pl, dname, s, y, t0, t1, 1, &lo, &hi);
      if (alpha && pts) amax = fmax(amax, hi), amin = fmin(amin, lo);
      snprintf(csv, sizeof csv, "%s.csv", r->model[i].run.name);
      snprintf(col, sizeof col, "%s_%s", b ? "follower" : "coupler",
               alpha ? "alpha_rad_s2" : "omega_rad_s");
      json_t *c = fig_curve(r->model[i].run.name, col, csv, pts, lo, hi, t0, t1);
      json_object_set_new(c, "panel", json_string(p == 0   ? "coupler omega"
                                                  : p == 1 ? "follower omega"
                                                  : p == 2 ? "coupler alpha"
                                                           : "follower alpha"));
      fig_curve_style(c, r->model[i].run.name);
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
    const int b = p & 1, alpha = p >> 1;
    if (p == 1) fprintf(pl.p, "unset key\n"); /* one legend, in the first panel */
    if (p == 2) {
      /* symlog as alpha.svg, the range to the decade above the spikes */
      const double top = fig_decade_above(amax, 1.15), bottom = -fig_decade_above(amin, 1.15);
      fprintf(pl.p, "C = %.1f\nset nonlinear y via sgn(y)*log10(1+abs(y)/C) inverse "
                    "sgn(y)*C*(10**abs(y)-1)\nset yrange [%.6g:%.6g]\nset ytics (",
              SYMLOG_C, bottom, top);
      int first = 1;
      for (double d = -bottom; d >= SYMLOG_C * 0.999; d /= 10.0, first = 0)
        fprintf(pl.p, "%s'-1e%d' %.6g", first ? "" : ", ", (int)lround(log10(d)), -d);
      fprintf(pl.p, ", '0' 0");
      for (double d = SYMLOG_C; d <= top * 1.001; d *= 10.0)
        fprintf(pl.p, ", '1e%d' %.6g", (int)lround(log10(d)), d);
      fprintf(pl.p, ")\n");
    }
    fprintf(pl.p, "set title '%s %s'\nset ylabel '%s [%s]'\nplot ", b ? "follower" : "coupler",
            alpha ? "angular acceleration" : "angular velocity", alpha ? "alpha" : "omega",
            alpha ? "rad/s^2 (symlog)" : "rad/s");
    for (int q = 0; q < nm; q++) {
      const int i = order[q];
      char mn[160], sp[96];
      fprintf(pl.p, "%s$s%d_%d using 1:2 with lines %s title '%s'", q ? ", " : "", p, i,
              fig_style_spec(r->model[i].run.name, sp, sizeof sp),
              fig_esc(r->model[i].run.name, mn, sizeof mn));
    }
    fprintf(pl.p, "\n");
  }
  fprintf(pl.p, "unset multiplot\n");
  st = fig_plot_close(&pl, diag);
  char file[128];
  snprintf(file, sizeof file, "startup.%s", fig_ext(fmt));
  if (st == FB_OK)
    fig_manifest_add(figs, file, "start-up: angular velocity and acceleration against log time", curves);
  else
    json_decref(curves);
  return st;
}
