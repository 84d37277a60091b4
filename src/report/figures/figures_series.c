/* A run's series into a figure: the crank angle in degrees, a series as a
 * gnuplot datablock decimated to the figure's pixel columns (decimate.h),
 * the order models are drawn in, the range of the symlog axis, the
 * manifest's (figures.json) entries for a figure and its curves, and the
 * names of the run's bodies and joints (its case's mechanism description). */
#include "figures_internal.h"

#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "decimate.h"
#include "names.h"

/* crank angle in degrees in [0, 360) */
double fig_crank_deg(double th) {
  double d = fmod(th * 180.0 / M_PI, 360.0);
  return d < 0.0 ? d + 360.0 : d;
}

/* writes a datablock of (crank deg, y) over the window, min/max-decimated
 * per pixel column of the figure (decimate.h); a blank line where the crank
 * angle wraps; returns the points written and the extremes of what was
 * plotted (equal to the window's: min/max decimation) */
int fig_datablock(const plot *pl, const char *name, const fb_series *s, const double *y,
                  double t0, double t1, double *ymin, double *ymax) {
  return fig_datablock_x(pl, name, s, y, t0, t1, 0, ymin, ymax);
}

/* as fig_datablock, x either the crank angle [deg] (x_time = 0) or the time [ms]
 * (x_time = 1: no wrap, pixel columns equally wide in log t from t0 > 0, as
 * the log axis draws them, so the first microseconds keep their samples) */
int fig_datablock_x(const plot *pl, const char *name, const fb_series *s, const double *y,
                    double t0, double t1, int x_time, double *ymin, double *ymax) {
  FILE *p = pl->p;
  size_t i0 = 0, i1 = 0;
  while (i0 < s->n && s->t[i0] < t0) i0++;
  i1 = i0;
  while (i1 < s->n && s->t[i1] <= t1) i1++;
  const size_t count = i1 > i0 ? i1 - i0 : 0;
  /* the abscissa the figure draws, and the samples each pixel column keeps */
  const int logt = x_time && t0 > 0.0 && t1 > t0;
  double *ax = malloc((count ? count : 1) * sizeof *ax);
  size_t *keep = malloc((count ? count : 1) * sizeof *keep);
  size_t m = 0;
  if (ax && keep) {
    for (size_t k = 0; k < count; k++)
      ax[k] = logt ? log(s->t[i0 + k]) : x_time ? s->t[i0 + k] : fig_crank_deg(s->crank_angle[i0 + k]);
    const double a0 = logt ? log(t0) : x_time ? t0 : 0.0, a1 = logt ? log(t1) : x_time ? t1 : 360.0;
    m = fb_decimate_minmax(ax, y + i0, count, a0, a1 > a0 ? a1 : a0 + 1.0, pl->columns, keep);
  } else { /* no memory for the decimation: every sample */
    for (size_t k = 0; keep && k < count; k++) keep[m++] = k;
  }
  fprintf(p, "$%s << EOD\n", name);
  int pts = 0;
  double last = -1.0;
  for (size_t q = 0; q < m || (!keep && q < count); q++) {
    const size_t i = i0 + (keep ? keep[q] : q);
    if (isnan(y[i])) continue;
    double x = x_time ? s->t[i] * 1e3 : fig_crank_deg(s->crank_angle[i]);
    if (!x_time && last >= 0.0 && fabs(x - last) > 180.0) fprintf(p, "\n");
    fprintf(p, x_time ? "%.9g %.17g\n" : "%.6f %.17g\n", x, y[i]);
    if (pts == 0 || y[i] < *ymin) *ymin = y[i];
    if (pts == 0 || y[i] > *ymax) *ymax = y[i];
    last = x;
    pts++;
  }
  fprintf(p, "EOD\n");
  free(ax);
  free(keep);
  return pts;
}

void fig_symlog_axis(const plot *pl, double lo, double hi, json_t *axis) {
  /* symlog: linear within +-C, logarithmic beyond; every decade that holds
   * data labelled; 15 % headroom beyond the largest spike */
  const double top = fig_decade_above(hi, 1.15), bottom = -fig_decade_above(lo, 1.15);
  fprintf(pl->p, "C = %.1f\nset nonlinear y via sgn(y)*log10(1+abs(y)/C) inverse "
                 "sgn(y)*C*(10**abs(y)-1)\nset yrange [%.6g:%.6g]\nset ytics (",
          SYMLOG_C, bottom, top);
  json_t *tics = json_array();
  int first = 1;
  for (double d = -bottom; d >= SYMLOG_C * 0.999; d /= 10.0) {
    fprintf(pl->p, "%s'-1e%d' %.6g", first ? "" : ", ", (int)lround(log10(d)), -d);
    json_array_append_new(tics, json_real(-d));
    first = 0;
  }
  fprintf(pl->p, ", '0' 0");
  json_array_append_new(tics, json_real(0.0));
  for (double d = SYMLOG_C; d <= top * 1.001; d *= 10.0) {
    fprintf(pl->p, ", '1e%d' %.6g", (int)lround(log10(d)), d);
    json_array_append_new(tics, json_real(d));
  }
  fprintf(pl->p, ")\n");
  if (axis) {
    json_object_set_new(axis, "y_min", json_real(bottom));
    json_object_set_new(axis, "y_max", json_real(top));
    json_object_set_new(axis, "y_tics", tics);
  } else {
    json_decref(tics);
  }
}

void fig_manifest_add(json_t *figs, const char *file, const char *title, json_t *curves) {
  json_t *o = json_object();
  json_object_set_new(o, "file", json_string(file));
  json_object_set_new(o, "title", json_string(title));
  json_object_set_new(o, "curves", curves);
  json_array_append_new(figs, o);
}

json_t *fig_curve(const char *model, const char *column, const char *csv, int points,
                  double ymin, double ymax, double t0, double t1) {
  json_t *o = json_pack("{s:s,s:s,s:s,s:i}", "model", model, "column", column, "csv", csv,
                        "points", points);
  if (isfinite(ymin)) {
    json_object_set_new(o, "y_min", json_real(ymin));
    json_object_set_new(o, "y_max", json_real(ymax));
    json_object_set_new(o, "time_from_s", json_real(t0));
    json_object_set_new(o, "time_to_s", json_real(t1));
  }
  return o;
}

/* yardsticks (analytic, reference) are drawn first, underneath the simulated models */
int fig_draw_order(const fb_run *r, int order[]) {
  int n = 0;
  for (int pass = 0; pass < 2; pass++)
    for (int i = 0; i < r->n; i++)
      if (!fb_engine_steps_world(r->model[i].run.model->engine) == (pass == 0)) order[n++] = i;
  return n;
}

/* the decade at or above |y| * headroom, at least SYMLOG_C */
double fig_decade_above(double y, double headroom) {
  const double a = fabs(y) * headroom;
  return a <= SYMLOG_C ? SYMLOG_C : pow(10.0, ceil(log10(a) - 1e-12));
}

/* ---- the run's bodies and joints ------------------------------------------ */

int fig_outputs(const fb_run *r) {
  int out[FB_MECH_MAX_OUTPUTS];
  return fb_mech_outputs(fb_case_mech(&r->c), out);
}

const char *fig_body(const fb_run *r, int k) { return fb_mech_output_name(fb_case_mech(&r->c), k); }

const char *fig_symbol(const fb_run *r, int k, int q) {
  return fb_mech_output_symbol(fb_case_mech(&r->c), k, q);
}

const char *fig_unit(const fb_run *r, int k, int q) {
  return fb_mech_output_unit(fb_case_mech(&r->c), k, q);
}

const char *fig_quantity(const fb_run *r, int k, int q) {
  static const char *const turn[3] = {"angle", "angular velocity", "angular acceleration"};
  static const char *const slide[3] = {"position", "velocity", "acceleration"};
  if (q < 0 || q > 2) return "?";
  return fb_mech_output_translates(fb_case_mech(&r->c), k) ? slide[q] : turn[q];
}

const char *fig_quantity_all(const fb_run *r, int q, char *out, size_t size) {
  const int n = fig_outputs(r);
  int same = 1;
  for (int k = 1; k < n; k++) same &= strcmp(fig_quantity(r, k, q), fig_quantity(r, 0, q)) == 0;
  if (same) {
    snprintf(out, size, "%s", fig_quantity(r, 0, q));
    return out;
  }
  size_t used = 0;
  out[0] = '\0';
  for (int k = 0; k < n && used < size; k++) {
    const int w = snprintf(out + used, size - used, "%s%s %s", k == 0 ? "" : k + 1 < n ? ", " : " and ",
                           fig_body(r, k), fig_quantity(r, k, q));
    if (w < 0) break;
    used += (size_t)w;
  }
  return out;
}

const char *fig_symbol_all(const fb_run *r, int q) {
  static const char *const word[3] = {"position", "velocity", "acceleration"};
  const int n = fig_outputs(r);
  for (int k = 1; k < n; k++)
    if (strcmp(fig_symbol(r, k, q), fig_symbol(r, 0, q)) != 0) return q >= 0 && q < 3 ? word[q] : "?";
  return fig_symbol(r, 0, q);
}

int fig_same_unit(const fb_run *r, int q) {
  const int n = fig_outputs(r);
  for (int k = 1; k < n; k++)
    if (strcmp(fig_unit(r, k, q), fig_unit(r, 0, q)) != 0) return 0;
  return 1;
}

const char *fig_column(const fb_run *r, int k, int q, const char *word, char *out, size_t size) {
  const fb_mech_desc *m = fb_case_mech(&r->c);
  int body[FB_MECH_MAX_OUTPUTS];
  const int n = fb_mech_outputs(m, body);
  if (k < 0 || k >= n) {
    snprintf(out, size, "?");
    return out;
  }
  char full[96];
  fb_mech_body_column(m, body[k], q, full, sizeof full);
  if (!word) {
    snprintf(out, size, "%s", full);
    return out;
  }
  /* <body>_<symbol>_<unit>: the word goes between symbol and unit */
  const char *sym = fb_mech_output_symbol(m, k, q);
  const size_t head = strlen(m->body[body[k]].name) + 1 + strlen(sym);
  snprintf(out, size, "%.*s_%s%s", (int)head, full, word, strlen(full) > head ? full + head : "");
  return out;
}

const char *fig_joint(const fb_run *r, int j) { return fb_case_joint_name(&r->c, j); }

const char *fig_joint_column(const fb_run *r, int j, char *out, size_t size) {
  return fb_name_word(out, size, fig_joint(r, j));
}
