/* contact_<model>_<joint>.<ext> and startup_contact_<model>_<joint>.<ext>:
 * one clearance joint of one model, the pin centre's orbit inside the
 * clearance circle coloured by contact state (free flight, impact,
 * continuous contact) and the contact force, over the peak window or over
 * the start-up (against log time), the reference dynamics' force overlaid. */
#include "figures_internal.h"
#include "metrics.h"

#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "decimate.h"

/* state colours of the orbit (as gnuplot rgb integers and as text) */
static const unsigned state_rgb[3] = {0x2a9d8f, 0xe63946, 0x1d3557};
static const char *const state_name[3] = {"free flight", "impact", "continuous contact"};

/* pin orbit and contact force of one clearance joint of one model */
static fb_status contact_figure(const fb_run *r, int mi, int j, const char *dir,
                                fb_figure_format fmt, json_t *figs, char *file, size_t fsize,
                                int startup, fb_diag *diag) {
  const fb_model_result *m = &r->model[mi];
  const fb_series *s = &m->run.series;
  char joint[32], name[100];
  fig_joint_column(r, j, joint, sizeof joint); /* the case's joint: coupler_slider in a slider-crank */
  snprintf(name, sizeof name, "%scontact_%s_%s", startup ? "startup_" : "", m->run.name, joint);
  plot pl;
  fb_status st = fig_plot_open(&pl, dir, name, fmt, 1300, 600, diag);
  if (st != FB_OK) return st;
  pl.columns /= 2; /* the orbit and the force side by side */
  const double period = 2.0 * M_PI / r->c.crank_speed;
  /* the peak window's first revolution, or revolution 1 (the start-up); the
   * start-up's force against log time from the first step */
  const double t0 = startup ? 0.0 : r->t_window;
  const double t1 = startup ? r->t_startup_end : r->t_window + period;
  const double tf0 = startup ? 0.5 * r->c.solver.h : t0;
  const int rev = startup || r->c.peaks == FB_PEAKS_ALL ? 1 : 2;
  /* the orbit as one path in um, each segment coloured by the state at its
   * start, decimated to the pixels it crosses (decimate.h: a sample is kept
   * where the path enters another pixel of the panel, and at every change
   * of state, so no impact is under-drawn) */
  size_t i0 = 0;
  while (i0 < s->n && s->t[i0] < t0) i0++;
  size_t i1 = i0;
  while (i1 < s->n && s->t[i1] <= t1) i1++;
  const double *ex = s->contact[j][FB_C_EX], *ey = s->contact[j][FB_C_EY], *state = s->contact[j][FB_C_STATE];
  const double c_um = r->c.radial_clearance * 1e6;
  /* the clearance circle with a margin, or the whole path when the pin sinks
   * deeper (a start-up beyond the penalty model's validity) */
  double e_um = 0.0;
  for (size_t i = i0; i < i1; i++) e_um = fmax(e_um, 1e6 * hypot(ex[i], ey[i]));
  const double span = fmax(1.35 * c_um, 1.05 * e_um);
  /* the panel's pixel: the square plot spans 2 span over at most its width */
  const double cell_um = 2.0 * span / (double)pl.columns;
  const size_t count = i1 - i0;
  double *ox = malloc((count ? count : 1) * sizeof *ox), *oy = malloc((count ? count : 1) * sizeof *oy);
  size_t *keep = malloc((count ? count : 1) * sizeof *keep);
  size_t kept = 0;
  if (ox && oy && keep) {
    for (size_t k = 0; k < count; k++) {
      ox[k] = ex[i0 + k] * 1e6;
      oy[k] = ey[i0 + k] * 1e6;
    }
    kept = fb_decimate_path(ox, oy, state + i0, count, cell_um, keep);
  } else {
    for (size_t k = 0; keep && k < count; k++) keep[kept++] = k;
  }
  int orbit_pts = 0, impacts = 0;
  fprintf(pl.p, "$orbit << EOD\n");
  for (size_t q = 0; q < kept; q++) {
    const size_t i = i0 + keep[q];
    const int k = (int)state[i] >= 0 && (int)state[i] < 3 ? (int)state[i] : 0;
    fprintf(pl.p, "%.6f %.6f %u\n", ex[i] * 1e6, ey[i] * 1e6, state_rgb[k]);
    orbit_pts++;
  }
  free(ox);
  free(oy);
  free(keep);
  fprintf(pl.p, "EOD\n$impacts << EOD\n");
  /* an impact's onset, as every count defines it (fb_metrics_next_impact) */
  size_t ia, ib;
  for (size_t i = 0; fb_metrics_next_impact(s, j, i, &ia, &ib) && ia < i1; i = ib + 1)
    if (ia >= i0) {
      fprintf(pl.p, "%.6f %.6f\n", ex[ia] * 1e6, ey[ia] * 1e6);
      impacts++;
    }
  if (!impacts) fprintf(pl.p, "NaN NaN\n");
  fprintf(pl.p, "EOD\n");
  double flo = NAN, fhi = NAN;
  const int force_pts =
      fig_datablock_x(&pl, "force", s, s->contact[j][FB_C_FORCE], tf0, t1, startup, &flo, &fhi);
  /* the reference dynamics of the same law, when the run has it, overlaid */
  int ri = -1;
  if (m->has_ref_error)
    for (int k = 0; k < r->n; k++)
      if (r->model[k].run.model == fb_model_reference_of(m->run.model) &&
          (r->model[k].run.series.contact_mask & (1 << j)))
        ri = k;
  double rlo = NAN, rhi = NAN;
  int ref_pts = 0;
  if (ri >= 0)
    ref_pts = fig_datablock_x(&pl, "rforce", &r->model[ri].run.series,
                          r->model[ri].run.series.contact[j][FB_C_FORCE], tf0, t1, startup, &rlo, &rhi);
  char mn[160], rn[160], sp[96];
  fprintf(pl.p, "set multiplot layout 1,2 title '%s, %s joint: pin in hole (revolution %d%s)'\n",
          fig_esc(m->run.name, mn, sizeof mn), fig_joint(r, j), rev,
          startup ? ", the start-up" : ""); /* joint names have no underscore */
  fprintf(pl.p, "set size ratio -1\nset title 'pin centre relative to hole centre (path)'\n"
                "set xlabel 'eccentricity x [um]'\nset ylabel 'eccentricity y [um]'\n"
                "set object 1 circle at 0,0 size %.6f fs empty border lc rgb '#888888' lw 1.5\n"
                "set xrange [%.4f:%.4f]\nset yrange [%.4f:%.4f]\nset key bottom right box\n",
          c_um, -span, span, -span, span);
  fprintf(pl.p, "plot $orbit using 1:2:3 with lines lw 1.2 lc rgb variable notitle, "
                "$impacts using 1:2 with points pt 2 ps 1.4 lw 1.5 lc rgb 'black' title 'impact start (%d)'",
          impacts);
  for (int k = 0; k < 3; k++)
    fprintf(pl.p, ", NaN with lines lw 2 lc rgb '#%06x' title '%s'", state_rgb[k], state_name[k]);
  fprintf(pl.p, ", NaN with lines lc rgb '#888888' title 'clearance circle'\n");
  fprintf(pl.p, "unset object 1\nset size noratio\nset autoscale\nset key top right box\n"
                "set title 'contact force'\n");
  if (startup)
    fprintf(pl.p, "set logscale x\nset format x '10^{%%L}'\nset xrange [%.9g:%.9g]\n"
                  "set xlabel 'time [ms]'\n",
            tf0 * 1e3, t1 * 1e3);
  else
    fprintf(pl.p, "set xrange [0:360]\nset xtics 60\nset xlabel 'crank angle [deg]'\n");
  fprintf(pl.p, "set ylabel 'contact force on the pin [N]'\n"
                "plot $force using 1:2 with lines %s title '%s'",
          fig_style_spec(r, m->run.name, sp, sizeof sp), mn);
  if (ri >= 0) {
    char sr[96];
    fprintf(pl.p, ", $rforce using 1:2 with lines %s title '%s: reference dynamics'",
            fig_style_spec(r, r->model[ri].run.name, sr, sizeof sr), fig_esc(r->model[ri].run.name, rn, sizeof rn));
  }
  fprintf(pl.p, "\nunset multiplot\n");
  st = fig_plot_close(&pl, diag);
  snprintf(file, fsize, "%s.%s", name, fig_ext(fmt));
  if (st == FB_OK) {
    char csv[96], col[96];
    snprintf(csv, sizeof csv, "%s.csv", m->run.name);
    json_t *curves = json_array();
    snprintf(col, sizeof col, "%s_ecc_x_m,%s_ecc_y_m", joint, joint);
    json_t *c = fig_curve(m->run.name, col, csv, orbit_pts, NAN, NAN, t0, t1);
    json_object_set_new(c, "impacts", json_integer(impacts));
    json_object_set_new(c, "pixel_um", json_real(cell_um));
    json_object_set_new(c, "time_from_s", json_real(t0));
    json_object_set_new(c, "time_to_s", json_real(t1));
    json_array_append_new(curves, c);
    snprintf(col, sizeof col, "%s_force_n", joint);
    c = fig_curve(m->run.name, col, csv, force_pts, flo, fhi, tf0, t1);
    fig_curve_style(c, r, m->run.name);
    json_array_append_new(curves, c);
    if (ri >= 0) {
      snprintf(csv, sizeof csv, "%s.csv", r->model[ri].run.name);
      c = fig_curve(r->model[ri].run.name, col, csv, ref_pts, rlo, rhi, tf0, t1);
      fig_curve_style(c, r, r->model[ri].run.name);
      json_array_append_new(curves, c);
    }
    fig_manifest_add(figs, file,
                 startup ? "pin orbit and contact force, revolution 1 (start-up)"
                         : "pin orbit and contact force",
                 curves);
  }
  return st;
}

/* contact_figure for every clearance joint of every model that has the
 * window's metrics (startup 0: the steady window, spikes measured; 1: the
 * start-up of a clearance model), each file name appended to names */
fb_status fig_contact_figures(const fb_run *r, const char *dir, fb_figure_format fmt,
                              int startup, json_t *figs, char names[][128], int max, int *n,
                              fb_diag *diag) {
  fb_status st = FB_OK;
  for (int i = 0; i < r->n && st == FB_OK; i++) {
    const fb_model_result *m = &r->model[i];
    if (startup ? !(m->has_startup && m->run.clearance_mask) : !m->has_spikes) continue;
    for (int j = 0; j < 4 && st == FB_OK; j++) {
      if (!(m->run.series.contact_mask & (1 << j))) continue;
      char file[128];
      st = contact_figure(r, i, j, dir, fmt, figs, file, sizeof file, startup, diag);
      if (st == FB_OK && *n < max) snprintf(names[(*n)++], 128, "%s", file);
    }
  }
  return st;
}
