/* spikes.<ext>: the largest acceleration spike of each output body of each
 * clearance model (the four-bar's coupler and follower alpha, the
 * slider-crank's coupler alpha and slider a) on a microsecond axis, its
 * reference and ideal model at the same instants, the contact force below.
 * Names, units, columns and joints from the case's mechanism description. */
#include "figures_internal.h"

#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* spikes.svg: the window around one spike is the impact episode it lies in
 * (or the FB_SPIKE_MIN_SAMPLES samples around it), widened by one episode
 * length before and two after, so the approach, the rebound and the next
 * impact show; the paper case's episodes last 5-60 us (12 steps) */
#define FB_SPIKE_MIN_SAMPLES 10
/* an impact up to this many samples before the spike is its episode: the
 * rebound's alpha peaks a step or two after the force peak */
#define FB_SPIKE_LOOKBACK 50

/* the index of the largest |y| over t >= t_from, or n when none */
static size_t spike_index(const fb_series *s, const double *y, double t_from) {
  size_t k = s->n;
  for (size_t i = 0; i < s->n; i++)
    if (s->t[i] >= t_from && (k == s->n || fabs(y[i]) > fabs(y[k]))) k = i;
  return k;
}

/* the sample window [*i0, *i1] around spike k and the clearance joint of
 * its contact (-1: none near): the contact episode (state impact or
 * continuous contact) holding k or ending up to FB_SPIKE_LOOKBACK samples
 * before it, clipped to FB_SPIKE_LOOKBACK samples either side of k */
static int spike_window(const fb_series *s, int mask, size_t k, size_t *i0, size_t *i1) {
  size_t a = k, b = k;
  int joint = -1;
  for (int j = 0; j < 4 && joint < 0; j++) {
    if (!(mask & s->contact_mask & (1 << j))) continue;
    const double *st = s->contact[j][FB_C_STATE];
    for (size_t back = 0; back <= FB_SPIKE_LOOKBACK && back <= k; back++)
      if ((int)st[k - back] != FB_STATE_FREE) {
        joint = j;
        b = k - back;
        break;
      }
    if (joint < 0) continue;
    a = b;
    while (a > 0 && k - a < FB_SPIKE_LOOKBACK && (int)st[a - 1] != FB_STATE_FREE) a--;
    while (b + 1 < s->n && b - k < FB_SPIKE_LOOKBACK && (int)st[b + 1] != FB_STATE_FREE) b++;
  }
  size_t len = b - a + 1;
  if (len < FB_SPIKE_MIN_SAMPLES) len = FB_SPIKE_MIN_SAMPLES;
  *i0 = a > len ? a - len : 0;
  *i1 = b + 2 * len < s->n ? b + 2 * len : s->n - 1;
  return joint;
}

/* a datablock of (t - ts [us], y) over [i0, i1] at every sample; returns the
 * points and the extremes */
static int spike_block(FILE *p, const char *name, const fb_series *s, const double *y, size_t i0,
                       size_t i1, double ts, double *lo, double *hi) {
  fprintf(p, "$%s << EOD\n", name);
  int pts = 0;
  for (size_t i = i0; i <= i1 && i < s->n; i++) {
    fprintf(p, "%.9g %.17g\n", (s->t[i] - ts) * 1e6, y[i]);
    if (pts == 0 || y[i] < *lo) *lo = y[i];
    if (pts == 0 || y[i] > *hi) *hi = y[i];
    pts++;
  }
  if (!pts) fprintf(p, "NaN NaN\n");
  fprintf(p, "EOD\n");
  return pts;
}

/* the model of the run named name, or -1 */
static int run_named(const fb_run *r, const char *name) {
  for (int k = 0; k < r->n; k++)
    if (strcmp(r->model[k].run.name, name) == 0) return k;
  return -1;
}

/* the model of the run that is row want, or -1 */
static int run_index(const fb_run *r, const fb_model *want) {
  for (int k = 0; want && k < r->n; k++)
    if (r->model[k].run.model == want) return k;
  return -1;
}

/* spikes.<ext>: for each clearance model (the simulated ones, which step a
 * world, else the reference: a clearance model is one or the other), the
 * largest acceleration spike of each output body over the peak window on a
 * microsecond axis around the spike, the reference of its law and its ideal
 * model overlaid at the same instants, the contact force below. Nothing is drawn (and *drawn = 0) for a run without clearance
 * model. */
fb_status fig_spikes(const fb_run *r, const char *dir, fb_figure_format fmt, json_t *figs,
                     int *drawn, fb_diag *diag) {
  int list[FB_MAX_MODELS], nc = 0;
  for (int pass = 0; pass < 2 && nc == 0; pass++)
    for (int i = 0; i < r->n; i++)
      if (r->model[i].has_spikes && r->model[i].run.series.n > 0 &&
          !fb_engine_steps_world(r->model[i].run.model->engine) == (pass == 1))
        list[nc++] = i;
  *drawn = 0;
  if (nc == 0) return FB_OK;
  plot pl;
  fb_status st = fig_plot_open(&pl, dir, "spikes", fmt, 1300, 430 * nc + 60, diag);
  if (st != FB_OK) return st;
  json_t *curves = json_array();
  char en[160];
  fprintf(pl.p, "set multiplot layout %d,2 title '%s: the largest %s spike of each clearance model "
                "(peak window), reference and ideal model at the same instants'\n",
          2 * nc, fig_esc(r->c.name, en, sizeof en), fig_symbol_all(r, FB_Q_ACC));
  fprintf(pl.p, "set xlabel 'time from the spike [us]'\n");
  for (int q = 0; q < nc; q++) {
    const int mi = list[q];
    const fb_model_result *m = &r->model[mi];
    const fb_series *s = &m->run.series;
    const int ri = run_index(r, fb_model_reference_of(m->run.model));
    /* the ideal model its spike ratios divide by (summary.json's
     * spikes.alpha_reference: the row's ideal model when it ran, else
     * analytic-stackup, drawn when it ran: a slider-crank's reference,
     * whose row names an ODE model that does not build one) */
    const int ii = run_named(r, m->spikes_reference);
    int others[3] = {mi, ri >= 0 && r->model[ri].run.series.n == s->n ? ri : -1,
                     ii >= 0 && r->model[ii].run.series.n == s->n ? ii : -1};
    const char *role[3] = {"model", "reference", "ideal"};
    size_t w0[2], w1[2];
    int joint[2];
    double ts[2];
    for (int b = 0; b < 2; b++) {
      const double *y = s->body[b][FB_Q_ACC];
      const size_t k = spike_index(s, y, r->t_window);
      joint[b] = spike_window(s, m->run.clearance_mask, k, &w0[b], &w1[b]);
      ts[b] = s->t[k];
      for (int o = 0; o < 3; o++) {
        if (others[o] < 0) continue;
        const fb_series *so = &r->model[others[o]].run.series;
        char dname[32], csv[96], col[64], panel[160];
        snprintf(dname, sizeof dname, "a%d_%d_%d", q, b, o);
        double lo = NAN, hi = NAN;
        const int pts = spike_block(pl.p, dname, so, so->body[b][FB_Q_ACC], w0[b], w1[b], ts[b], &lo, &hi);
        snprintf(csv, sizeof csv, "%s.csv", r->model[others[o]].run.name);
        fig_column(r, b, FB_Q_ACC, NULL, col, sizeof col);
        json_t *c = fig_curve(r->model[others[o]].run.name, col, csv, pts, lo, hi, s->t[w0[b]], s->t[w1[b]]);
        snprintf(panel, sizeof panel, "%s %s spike", m->run.name, fig_body(r, b));
        json_object_set_new(c, "panel", json_string(panel));
        json_object_set_new(c, "role", json_string(role[o]));
        json_object_set_new(c, "spike_time_s", json_real(ts[b]));
        fig_curve_style(c, r, r->model[others[o]].run.name);
        json_array_append_new(curves, c);
        /* the contact force of the spike's joint, model and reference */
        const int fj = joint[b] >= 0 ? joint[b] : -1;
        if (o == 2 || fj < 0 || !(so->contact_mask & (1 << fj))) continue;
        snprintf(dname, sizeof dname, "f%d_%d_%d", q, b, o);
        lo = hi = NAN;
        const int fp = spike_block(pl.p, dname, so, so->contact[fj][FB_C_FORCE], w0[b], w1[b], ts[b],
                                   &lo, &hi);
        char jn[32];
        snprintf(col, sizeof col, "%s_force_n", fig_joint_column(r, fj, jn, sizeof jn));
        c = fig_curve(r->model[others[o]].run.name, col, csv, fp, lo, hi, s->t[w0[b]], s->t[w1[b]]);
        snprintf(panel, sizeof panel, "%s %s spike force", m->run.name, fig_body(r, b));
        json_object_set_new(c, "panel", json_string(panel));
        json_object_set_new(c, "role", json_string(role[o]));
        json_object_set_new(c, "spike_time_s", json_real(ts[b]));
        fig_curve_style(c, r, r->model[others[o]].run.name);
        json_array_append_new(curves, c);
      }
    }
    /* row 1: the acceleration of each output body; row 2: the force below each */
    for (int row = 0; row < 2; row++)
      for (int b = 0; b < 2; b++) {
        char mn[160];
        const double deg = fig_crank_deg(s->crank_angle[0] + (ts[b] - s->t[0]) * r->c.direction * r->c.crank_speed);
        /* the legend inside, where the spike leaves the panel empty (a
         * negative spike's is at the top: the key at the bottom), so the
         * panel keeps the figure's width */
        const int down = row == 0 && s->body[b][FB_Q_ACC][spike_index(s, s->body[b][FB_Q_ACC],
                                                                      r->t_window)] < 0.0;
        fprintf(pl.p, "set key inside %s right opaque box font ',8'\n", down ? "bottom" : "top");
        if (row == 0)
          fprintf(pl.p, "set title '%s: %s %s spike at t = %.6f ms (crank %.1f deg)'\n"
                        "set ylabel '%s %s [%s]'\nplot ",
                  fig_esc(m->run.name, mn, sizeof mn), fig_body(r, b), fig_symbol(r, b, FB_Q_ACC), ts[b] * 1e3,
                  deg, fig_body(r, b), fig_symbol(r, b, FB_Q_ACC), fig_unit(r, b, FB_Q_ACC));
        else
          fprintf(pl.p, "set title '%s: contact force at the %s joint'\nset ylabel 'force [N]'\nplot ",
                  fig_esc(m->run.name, mn, sizeof mn), joint[b] >= 0 ? fig_joint(r, joint[b]) : "(no impact)");
        int any = 0;
        /* the model first, the ideal model, then the reference on top of the
         * model it checks: a line with open circles, so that where the two
         * agree both still show */
        static const int draw[3] = {0, 2, 1};
        for (int d = 0; d < 3; d++) {
          const int o = draw[d];
          if (others[o] < 0 || (row == 1 && (o == 2 || joint[b] < 0 ||
                                             !(r->model[others[o]].run.series.contact_mask & (1 << joint[b])))))
            continue;
          char on[160], sp[96];
          fprintf(pl.p, "%s$%c%d_%d_%d using 1:2 with linespoints %s %s title '%s%s'",
                  any ? ", " : "", row ? 'f' : 'a', q, b, o,
                  o == 1 ? "pt 6 ps 0.7" : "pt 7 ps 0.35",
                  fig_style_spec(r, r->model[others[o]].run.name, sp, sizeof sp),
                  fig_esc(r->model[others[o]].run.name, on, sizeof on),
                  o == 1 ? " (reference)" : o == 2 ? " (ideal)" : "");
          any = 1;
        }
        if (!any) fprintf(pl.p, "0 with lines lc rgb '#888888' title 'no impact near this spike'");
        fprintf(pl.p, "\n");
      }
  }
  fprintf(pl.p, "unset multiplot\n");
  st = fig_plot_close(&pl, diag);
  char file[128];
  snprintf(file, sizeof file, "spikes.%s", fig_ext(fmt));
  if (st == FB_OK) {
    char title[200];
    snprintf(title, sizeof title, "largest %s spikes on a microsecond axis, reference and ideal overlaid, "
             "contact force below", fig_symbol_all(r, FB_Q_ACC));
    fig_manifest_add(figs, file, title, curves);
    *drawn = 1;
  } else {
    json_decref(curves);
  }
  return st;
}
