/* The figures of a planar case's run (figures.h fb_figures_planar), by
 * the description's body and joint names: omega.<ext> and alpha.<ext>, one
 * panel per moving body that turns, every model overlaid against the drive
 * angle over the peak window; slides.<ext>, each prismatic joint's slide,
 * its rate and acceleration (planar_outputs.h), when the description has
 * one; points.<ext>, each output point's path (y against x: a coupler
 * curve), when it has one; contact_<model>_<joint>.<ext> for each
 * reference's clearance joint;
 * figures.json. The samples go through the same
 * datablocks as a four-bar's (fig_datablock on a view of the model's
 * columns: min/max decimation per pixel column, so spikes survive). */
#include "figures_internal.h"

#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "decimate.h"
#include "names.h"
#include "planar_outputs.h"
#include "report_planar_outputs.h"
#include "units.h"

/* a panel's height [px] and the panels across */
#define PANEL_PX 330
#define ACROSS 2
/* an omega panel whose samples span at most FLAT_REL of their magnitude
 * holds a constant (the driven body's speed, an engine's round-off about
 * it: 6e-12 relative in ODE's kit model of the six-bar) and is drawn over
 * +-FLAT_SPAN of it [-] */
#define FLAT_REL 1e-6
#define FLAT_SPAN 0.05

/* model p's samples as a series view (time and drive angle) for fig_datablock */
static fb_series view_of(const fb_planar_model *p) {
  fb_series s;
  memset(&s, 0, sizeof s);
  s.n = p->n;
  s.t = p->t;
  s.crank_angle = p->drive;
  return s;
}

/* the figures' window [t0, t1]: the revolution from the peak window's
 * start, or the run's first when the run ends before it; an undriven
 * run's (its figures against time) the whole run */
static void window_of(const fb_planar_run *r, double *t0, double *t1) {
  if (r->m->drive < 0) {
    *t0 = 0.0;
    *t1 = r->duration;
    return;
  }
  const double period = 2.0 * M_PI / r->c.crank_speed;
  *t0 = r->t_window + period <= r->duration * (1.0 + 1e-9) ? r->t_window : 0.0;
  *t1 = *t0 + period;
}

/* one model's curve in the manifest, in its model-table style */
static json_t *curve(const fb_planar_model *p, const char *column, const char *panel, int pts,
                     double lo, double hi, double t0, double t1) {
  char csv[96];
  snprintf(csv, sizeof csv, "%s.csv", p->name);
  json_t *c = fig_curve(p->name, column, csv, pts, lo, hi, t0, t1);
  json_object_set_new(c, "panel", json_string(panel));
  fig_curve_style(c, NULL, p->name);
  return c;
}

/* a panel's plot command: datablock $<prefix><i>_<panel> of every model i,
 * in its model-table style, the references last so that they show over
 * the engines' curves they judge; with no samples (any 0) a note, which
 * gnuplot needs */
static void plot_models(const plot *pl, const fb_planar_run *r, char prefix, int panel, int any) {
  char sp[96], mn[160];
  if (!any) {
    fprintf(pl->p, "set label 1 'no samples in the window' at graph 0.5,0.5 center\n"
                   "plot NaN notitle\nunset label 1\n");
    return;
  }
  fprintf(pl->p, "plot ");
  for (int pass = 0, first = 1; pass < 2; pass++)
    for (int i = 0; i < r->n; i++) {
      if (!r->model[i].reference != !pass) continue;
      fprintf(pl->p, "%s$%c%d_%d using 1:2 with lines %s title '%s'", first ? "" : ", ", prefix, i,
              panel, fig_style_spec(NULL, r->model[i].name, sp, sizeof sp),
              fig_esc(r->model[i].name, mn, sizeof mn));
      first = 0;
    }
  fprintf(pl->p, "\n");
}

/* the abscissa's gnuplot settings: the drive angle over a revolution
 * [deg], or time [ms] (timed: an undriven run, fig_datablock_x) */
static const char *x_axis(int timed) {
  return timed ? "set autoscale x\nset xtics autofreq\nset xlabel 'time [ms]'\n"
               : "set xrange [0:360]\nset xtics 60\nset xlabel 'drive angle [deg]'\n";
}

/* omega.<ext> (alpha 0) or alpha.<ext> (alpha 1, symlog axis per panel),
 * against the drive angle, or an undriven run's against time */
static fb_status omega_alpha(const fb_planar_run *r, const char *dir, fb_figure_format fmt,
                             int alpha, json_t *figs, fb_diag *diag) {
  const fb_planar *m = r->m;
  int turning[FB_PLANAR_SPEC_MAX_BODIES + 1], nb = 0; /* a ram's angle is the ground's: no panel */
  for (int b = 1; b < m->nbodies && nb <= FB_PLANAR_SPEC_MAX_BODIES; b++)
    if (fb_planar_body_turns(m, b)) turning[nb++] = b;
  const int rows = (nb + ACROSS - 1) / ACROSS, k = alpha ? 2 : 1;
  static const char *const suffix[3] = {"angle_rad", "omega_rad_s", "alpha_rad_s2"};
  const char *name = alpha ? "alpha" : "omega";
  plot pl;
  fb_status st = fig_plot_open(&pl, dir, name, fmt, 1400, 60 + PANEL_PX * rows, diag);
  if (st != FB_OK) return st;
  pl.columns /= ACROSS;
  double t0, t1;
  window_of(r, &t0, &t1);
  json_t *curves = json_array();
  char en[200], mn[160], col[96];
  const int timed = m->drive < 0; /* undriven: no drive angle to draw against */
  if (timed)
    fprintf(pl.p, "set multiplot layout %d,%d title '%s: %s against time (%s), t = %.4g to "
            "%.4g s'\n%sset key inside top right box opaque font ',8'\n", rows, ACROSS,
            fig_esc(r->c.name, en, sizeof en), alpha ? "angular acceleration" : "angular velocity",
            m->torque_joint >= 0 ? "driven by a torque" : "undriven", t0, t1, x_axis(1));
  else
    fprintf(pl.p, "set multiplot layout %d,%d title '%s: %s against the drive angle (%s, %s: "
            "runs %s), t = %.4g to %.4g s'\n%sset key inside top right box opaque font ',8'\n",
            rows, ACROSS, fig_esc(r->c.name, en, sizeof en),
            alpha ? "angular acceleration" : "angular velocity",
            fig_esc(m->joint[m->drive].name, mn, sizeof mn), r->c.direction < 0 ? "cw" : "ccw",
            r->c.direction < 0 ? "right to left" : "left to right", t0, t1, x_axis(0));
  for (int nth = 0; nth < nb; nth++) {
    const int b = turning[nth];
    double lo_all = 0.0, hi_all = 0.0;
    int any = 0;
    snprintf(col, sizeof col, "%s_%s", m->body[b].name, suffix[k]);
    for (int i = 0; i < r->n; i++) {
      const fb_planar_model *p = &r->model[i];
      const fb_series v = view_of(p);
      char dname[32];
      snprintf(dname, sizeof dname, "m%d_%d", i, b);
      double lo = NAN, hi = NAN;
      const int pts = fig_datablock_x(&pl, dname, &v,
                                      p->q + ((size_t)(b - 1) * 3 + (size_t)k) * p->n, t0, t1,
                                      timed, &lo, &hi);
      if (pts) lo_all = any ? fmin(lo_all, lo) : lo, hi_all = any ? fmax(hi_all, hi) : hi, any = 1;
      json_array_append_new(curves, curve(p, col, m->body[b].name, pts, lo, hi, t0, t1));
    }
    if (nth == 1) fprintf(pl.p, "unset key\n"); /* one legend, in the first panel */
    if (alpha) {
      fig_symlog_axis(&pl, fmin(lo_all, 0.0), fmax(hi_all, 0.0), NULL);
    } else if (any && hi_all - lo_all <= FLAT_REL * fmax(fabs(lo_all), fabs(hi_all))) {
      /* a constant omega (the driven body's) within round-off: a range of
       * +-FLAT_SPAN of it, not gnuplot's autoscale of the round-off */
      const double mid = 0.5 * (lo_all + hi_all), d = fmax(FLAT_SPAN * fabs(mid), 1.0);
      fprintf(pl.p, "set yrange [%.17g:%.17g]\n", mid - d, mid + d);
    } else {
      fprintf(pl.p, "set autoscale y\n");
    }
    fig_esc(m->body[b].name, en, sizeof en);
    fprintf(pl.p, "set title '%s'\nset ylabel '%s %s [%s]'\n", en, en, alpha ? "alpha" : "omega",
            alpha ? "rad/s^2, symlog" : "rad/s");
    plot_models(&pl, r, 'm', b, any);
  }
  fprintf(pl.p, "unset multiplot\n");
  st = fig_plot_close(&pl, diag);
  char file[128];
  snprintf(file, sizeof file, "%s.%s", name, fig_ext(fmt));
  char title[128];
  snprintf(title, sizeof title, "angular %s of every moving body against %s",
           alpha ? "acceleration" : "velocity", timed ? "time" : "the drive angle");
  if (st == FB_OK)
    fig_manifest_add(figs, file, title, curves);
  else
    json_decref(curves);
  return st;
}

/* slides.<ext>: every prismatic joint's slide [mm], its rate [m/s] and
 * acceleration [m/s^2, symlog] against the drive angle (an undriven run's
 * against time), a row per joint, every model overlaid */
static fb_status slides(const fb_planar_run *r, const char *dir, fb_figure_format fmt,
                        json_t *figs, fb_diag *diag) {
  const fb_planar *m = r->m;
  const int ns = fb_planar_slide_count(m);
  plot pl;
  fb_status st = fig_plot_open(&pl, dir, "slides", fmt, 1400, 60 + PANEL_PX * ns, diag);
  if (st != FB_OK) return st;
  pl.columns /= 3;
  double t0, t1;
  window_of(r, &t0, &t1);
  json_t *curves = json_array();
  char en[200], col[128];
  const int timed = m->drive < 0; /* undriven: against time, as omega and alpha */
  fprintf(pl.p, "set multiplot layout %d,3 title '%s: slides against %s, t = %.4g to %.4g s'\n"
          "%sset key inside top right box opaque font ',8'\n", ns,
          fig_esc(r->c.name, en, sizeof en), timed ? "time" : "the drive angle", t0, t1,
          x_axis(timed));
  static const char *const what[3] = {"slide [mm]", "slide rate [m/s]",
                                       "slide acceleration [m/s^2, symlog]"};
  double *mm = malloc((r->n && r->model[0].n ? r->model[0].n : 1) * sizeof *mm);
  const int np = FB_PLANAR_POINT_QUANTITIES * m->npoints;
  int panel = 0;
  for (int j = 0, si = 0; j < m->njoints && mm; j++) {
    if (m->joint[j].kind != FB_KIND_PRISMATIC) continue;
    for (int q = 0; q < 3; q++, panel++) {
      const int c = np + FB_PLANAR_SLIDE_QUANTITIES * si + q;
      fb_report_planar_output_column(col, sizeof col, m, c);
      double lo_all = 0.0, hi_all = 0.0;
      int any = 0;
      for (int i = 0; i < r->n; i++) {
        const fb_planar_model *p = &r->model[i];
        const fb_series v = view_of(p);
        const double *y = p->out ? p->out + (size_t)c * p->n : NULL;
        if (y && q == 0) { /* the slide in mm */
          double *grown = realloc(mm, (p->n ? p->n : 1) * sizeof *mm);
          if (!grown) break;
          mm = grown;
          for (size_t x = 0; x < p->n; x++) mm[x] = y[x] / FB_M_PER_MM;
          y = mm;
        }
        char dname[32];
        snprintf(dname, sizeof dname, "s%d_%d", i, panel);
        double lo = NAN, hi = NAN;
        const int pts = y ? fig_datablock_x(&pl, dname, &v, y, t0, t1, timed, &lo, &hi) : 0;
        if (pts) lo_all = any ? fmin(lo_all, lo) : lo, hi_all = any ? fmax(hi_all, hi) : hi, any = 1;
        json_array_append_new(curves, curve(p, col, m->joint[j].name, pts, lo, hi, t0, t1));
      }
      if (panel == 1) fprintf(pl.p, "unset key\n");
      if (q == 2) fig_symlog_axis(&pl, fmin(lo_all, 0.0), fmax(hi_all, 0.0), NULL);
      else fprintf(pl.p, "unset nonlinear y\nset ytics autofreq\nset autoscale y\n");
      fprintf(pl.p, "set title '%s'\nset ylabel '%s'\n", fig_esc(m->joint[j].name, en, sizeof en),
              what[q]);
      plot_models(&pl, r, 's', panel, any);
    }
    si++;
  }
  free(mm);
  fprintf(pl.p, "unset multiplot\n");
  st = fig_plot_close(&pl, diag);
  char file[128];
  snprintf(file, sizeof file, "slides.%s", fig_ext(fmt));
  if (st == FB_OK)
    fig_manifest_add(figs, file, timed ? "every prismatic joint's slide, its rate and "
                                         "acceleration against time"
                                       : "every prismatic joint's slide, its rate and "
                                         "acceleration against the drive angle",
                     curves);
  else
    json_decref(curves);
  return st;
}

/* the samples of model p in [t0, t1]: their first index and count */
static size_t window_samples(const fb_planar_model *p, double t0, double t1, size_t *count) {
  size_t i0 = 0;
  while (i0 < p->n && p->t[i0] < t0) i0++;
  size_t i1 = i0;
  while (i1 < p->n && p->t[i1] <= t1) i1++;
  *count = i1 - i0;
  return i0;
}

/* points.<ext>: every output point's path over the window, y against x
 * [mm] on equal axes (a coupler curve), a panel per point, every model
 * overlaid, each path decimated to the pixels it crosses (decimate.h) */
static fb_status points(const fb_planar_run *r, const char *dir, fb_figure_format fmt,
                        json_t *figs, fb_diag *diag) {
  const fb_planar *m = r->m;
  const int np = m->npoints, rows = (np + ACROSS - 1) / ACROSS;
  plot pl;
  fb_status st = fig_plot_open(&pl, dir, "points", fmt, 1400, 60 + 2 * PANEL_PX * rows, diag);
  if (st != FB_OK) return st;
  double t0, t1;
  window_of(r, &t0, &t1);
  json_t *curves = json_array();
  char en[200], mn[160], col[128];
  fprintf(pl.p, "set multiplot layout %d,%d title '%s: output points%s, t = %.4g to %.4g s'\n"
          "set size ratio -1\nset xlabel 'x [mm]'\nset ylabel 'y [mm]'\n"
          "set key inside top right box opaque font ',8'\n", rows, np < ACROSS ? np : ACROSS,
          fig_esc(r->c.name, en, sizeof en), m->drive >= 0 ? " over a revolution" : "", t0, t1);
  for (int k = 0; k < np && st == FB_OK; k++) {
    const int cx = FB_PLANAR_POINT_QUANTITIES * k, cy = cx + 1;
    /* the panel's extent over every model, for the pixel the paths are
     * decimated to */
    double span = 0.0;
    for (int i = 0; i < r->n; i++) {
      const fb_planar_model *p = &r->model[i];
      size_t count;
      const size_t i0 = window_samples(p, t0, t1, &count);
      if (!p->out || !count) continue;
      double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
      for (size_t x = i0; x < i0 + count; x++)
        for (int a = 0; a < 2; a++) {
          const double v = p->out[(size_t)(a ? cy : cx) * p->n + x];
          lo[a] = fmin(lo[a], v), hi[a] = fmax(hi[a], v);
        }
      span = fmax(span, fmax(hi[0] - lo[0], hi[1] - lo[1]) / FB_M_PER_MM);
    }
    const double cell = (span > 0.0 ? span : 1.0) / (double)(pl.columns / ACROSS);
    int drawn = 0;
    for (int i = 0; i < r->n; i++) {
      const fb_planar_model *p = &r->model[i];
      size_t count;
      const size_t i0 = window_samples(p, t0, t1, &count);
      double *xy = p->out && count ? malloc(2 * count * sizeof *xy) : NULL;
      size_t *keep = xy ? malloc(count * sizeof *keep) : NULL;
      size_t kept = 0;
      double ylo = NAN, yhi = NAN;
      if (xy && keep) {
        for (size_t x = 0; x < count; x++) {
          xy[x] = p->out[(size_t)cx * p->n + i0 + x] / FB_M_PER_MM;
          xy[count + x] = p->out[(size_t)cy * p->n + i0 + x] / FB_M_PER_MM;
          ylo = x ? fmin(ylo, xy[count + x]) : xy[count + x];
          yhi = x ? fmax(yhi, xy[count + x]) : xy[count + x];
        }
        kept = fb_decimate_path(xy, xy + count, NULL, count, cell, keep);
      }
      fprintf(pl.p, "$p%d_%d << EOD\n", i, k);
      for (size_t q = 0; q < kept; q++)
        fprintf(pl.p, "%.9g %.9g\n", xy[keep[q]], xy[count + keep[q]]);
      fprintf(pl.p, "%sEOD\n", kept ? "" : "NaN NaN\n");
      drawn += kept > 0;
      fb_report_planar_output_column(col, sizeof col, m, cy); /* y, against x */
      json_array_append_new(curves, curve(p, col, m->point[k].name, (int)kept, ylo, yhi, t0, t1));
      free(xy);
      free(keep);
    }
    if (k == 1) fprintf(pl.p, "unset key\n");
    fprintf(pl.p, "set title '%s (on %s)'\n", fig_esc(m->point[k].name, en, sizeof en),
            fig_esc(m->body[m->point[k].body].name, mn, sizeof mn));
    plot_models(&pl, r, 'p', k, drawn);
  }
  fprintf(pl.p, "unset multiplot\n");
  st = fig_plot_close(&pl, diag);
  char file[128];
  snprintf(file, sizeof file, "points.%s", fig_ext(fmt));
  if (st == FB_OK)
    fig_manifest_add(figs, file, "every output point's path, y against x (a coupler curve)",
                     curves);
  else
    json_decref(curves);
  return st;
}

/* contact_<model>_<joint>.<ext>: a reference's contact force and
 * penetration at its k-th clearance joint against the drive angle */
static fb_status contact(const fb_planar_run *r, const fb_planar_model *p, int k_joint,
                         const char *dir, fb_figure_format fmt, json_t *figs, char *file,
                         size_t fsize, fb_diag *diag) {
  const fb_planar_ref_joint *ct = &p->ref.at[k_joint];
  const char *joint = r->m->joint[ct->joint].name;
  char jcol[64], name[160], en[200], jn[160];
  fb_name_word(jcol, sizeof jcol, joint);
  snprintf(name, sizeof name, "contact_%s_%s", p->name, jcol);
  snprintf(file, fsize, "%.118s.%s", name, fig_ext(fmt));
  plot pl;
  fb_status st = fig_plot_open(&pl, dir, name, fmt, 1100, 750, diag);
  if (st != FB_OK) return st;
  double t0, t1;
  window_of(r, &t0, &t1);
  const fb_series v = view_of(p);
  json_t *curves = json_array();
  static const char *const what[2] = {"force_n", "penetration_m"};
  double *um = NULL;
  for (int k = 0; k < 2; k++) {
    const double *y = k ? ct->pen : ct->force;
    if (k) { /* the penetration drawn in um */
      um = malloc((p->n ? p->n : 1) * sizeof *um);
      if (!um) break;
      for (size_t i = 0; i < p->n; i++) um[i] = ct->pen[i] / FB_M_PER_UM;
      y = um;
    }
    char dname[16], col[96];
    snprintf(dname, sizeof dname, "c%d", k);
    snprintf(col, sizeof col, "%s_%s", joint, what[k]);
    double lo = NAN, hi = NAN;
    const int pts = fig_datablock(&pl, dname, &v, y, t0, t1, &lo, &hi);
    json_array_append_new(curves, curve(p, col, k ? "penetration" : "force", pts, lo, hi, t0, t1));
  }
  free(um);
  char sp[96];
  fig_style_spec(NULL, p->name, sp, sizeof sp);
  fprintf(pl.p, "set multiplot layout 2,1 title '%s: %s, clearance at %s, t = %.4g to %.4g s'\n"
          "%sunset key\n"
          "set title 'contact force on the pin'\nset ylabel 'force [N]'\nplot $c0 using 1:2 with "
          "lines %s\nset title 'penetration depth'\nset ylabel 'penetration [um]'\nplot $c1 using "
          "1:2 with lines %s\nunset multiplot\n", fig_esc(r->c.name, en, sizeof en), p->name,
          fig_esc(joint, jn, sizeof jn), t0, t1, x_axis(0), sp, sp);
  st = fig_plot_close(&pl, diag);
  char title[256];
  snprintf(title, sizeof title, "%s: contact force and penetration at %s", p->name, joint);
  if (st == FB_OK) fig_manifest_add(figs, file, title, curves);
  else json_decref(curves);
  return st;
}

fb_status fb_figures_planar(const fb_planar_run *r, const char *dir, fb_figure_format fmt,
                            char names[][128], int max, int *n, fb_diag *diag) {
  *n = 0;
  json_t *figs = json_array();
  fb_status st = FB_OK;
  fig_batch_begin(); /* the figures drawn side by side */
  /* the figures are against the drive angle; an undriven case's (a free
   * start or a torque drive, r->m->drive < 0) omega, alpha and slides
   * against time, its points' paths over the whole run, and no contact
   * figure yet */
  const int driven = r->m->drive >= 0;
  for (int alpha = 0; alpha < 2 && st == FB_OK; alpha++) {
    st = omega_alpha(r, dir, fmt, alpha, figs, diag);
    if (st == FB_OK && *n < max) snprintf(names[(*n)++], 128, "%s.%s", alpha ? "alpha" : "omega", fig_ext(fmt));
  }
  if (st == FB_OK && fb_planar_slide_count(r->m) > 0) {
    st = slides(r, dir, fmt, figs, diag);
    if (st == FB_OK && *n < max) snprintf(names[(*n)++], 128, "slides.%s", fig_ext(fmt));
  }
  if (st == FB_OK && r->m->npoints > 0) {
    st = points(r, dir, fmt, figs, diag);
    if (st == FB_OK && *n < max) snprintf(names[(*n)++], 128, "points.%s", fig_ext(fmt));
  }
  for (int i = 0; i < r->n && st == FB_OK && driven; i++) {
    if (!r->model[i].reference || !r->model[i].force) continue;
    for (int k = 0; k < r->model[i].ref.njoints && st == FB_OK; k++) { /* one per joint */
      char file[128];
      st = contact(r, &r->model[i], k, dir, fmt, figs, file, sizeof file, diag);
      if (st == FB_OK && *n < max) snprintf(names[(*n)++], 128, "%s", file);
    }
  }
  return fig_batch_finish(st, figs, dir, diag);
}
