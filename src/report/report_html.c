#include "report_html.h"

#include "report_verdict.h"

#include <errno.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "figures.h"
#include "fileio.h"
#include "json_columns.h"
#include "metrics.h"
#include "report.h"
#include "report_page.h" /* fb_report_page_html[], fb_report_page_js[] (generated, meson.build) */

#ifndef FB_UPLOT_DIR
#define FB_UPLOT_DIR "node_modules/uplot/dist"
#endif

static const char *const lib_files[2] = {"uPlot.iife.min.js", "uPlot.min.css"};

/* the plotted series are written with this many significant digits: 1e-10
 * relative, 2e-11 s on the paper case's 0.18 s run, far below a step */
#define SERIES_DIGITS 10

int fb_report_html_library(char *out, size_t size) {
  const char *env = getenv("FOURBAR_UPLOT_DIR");
  snprintf(out, size, "%s", env && *env ? env : FB_UPLOT_DIR);
  for (int k = 0; k < 2; k++) {
    char p[4400];
    snprintf(p, sizeof p, "%s/%s", out, lib_files[k]);
    if (access(p, R_OK) != 0) return 0;
  }
  return 1;
}

/* crank angle in degrees in [0, 360) */
static double deg360(double th) {
  double d = fmod(th * 180.0 / M_PI, 360.0);
  return d < 0.0 ? d + 360.0 : d;
}

/* marks the minimum and maximum of y in each bucket of [0, n) */
static void mark_extremes(unsigned char *keep, const double *y, size_t n, size_t per) {
  for (size_t b = 0; b < n; b += per) {
    const size_t e = b + per < n ? b + per : n;
    size_t lo = b, hi = b;
    for (size_t k = b; k < e; k++) {
      if (y[k] < y[lo]) lo = k;
      if (y[k] > y[hi]) hi = k;
    }
    keep[lo] = keep[hi] = 1;
  }
}

/* the samples of an impact episode [i0, i1] of joint j, padded to [a, b]:
 * all of them, or in a long episode (FB_REPORT_CONTACT_BUCKET) all within
 * FB_REPORT_IMPACT_PAD of either end and inside the extremes of every
 * plotted column (the nb output bodies' omega and alpha, the joint's force,
 * penetration and eccentricity) per bucket */
static void keep_episode(unsigned char *keep, const fb_series *s, int j, int nb, size_t i0, size_t i1,
                         size_t a, size_t b) {
  const size_t pad = FB_REPORT_IMPACT_PAD;
  if (i1 - i0 <= 2 * pad + FB_REPORT_CONTACT_BUCKET) {
    memset(keep + a, 1, b - a + 1);
    return;
  }
  memset(keep + a, 1, i0 + pad - a + 1);
  memset(keep + i1 - pad, 1, b - (i1 - pad) + 1);
  const size_t lo = i0 + pad + 1, len = i1 - pad - lo;
  for (int k = 0; k < nb; k++)
    for (int q = FB_Q_VEL; q <= FB_Q_ACC; q++)
      mark_extremes(keep + lo, s->body[k][q] + lo, len, FB_REPORT_CONTACT_BUCKET);
  static const int cols[4] = {FB_C_FORCE, FB_C_PEN, FB_C_EX, FB_C_EY};
  for (int c = 0; c < 4; c++) mark_extremes(keep + lo, s->contact[j][cols[c]] + lo, len, FB_REPORT_CONTACT_BUCKET);
}

/* one impact episode: the samples [i0, i1] in the impact state with a
 * positive force (metrics.c's definition of an impact) */
typedef struct {
  size_t i0, i1;
} episode;

/* the impact episodes of joint j (fb_metrics_impact_episodes: the same
 * episodes as summary.json's), at most cap; returns the count found */
static size_t episodes(const fb_series *s, int j, episode *out, size_t cap) {
  size_t first[FB_REPORT_MAX_IMPACTS], last[FB_REPORT_MAX_IMPACTS];
  const size_t want = cap < FB_REPORT_MAX_IMPACTS ? cap : FB_REPORT_MAX_IMPACTS;
  const size_t n = fb_metrics_impact_episodes(s, j, INFINITY, first, last, want);
  for (size_t k = 0; k < n && k < want; k++) out[k].i0 = first[k], out[k].i1 = last[k];
  return n;
}

/* the sample of largest |y| over [i0, i1] */
static double largest(const double *y, size_t i0, size_t i1) {
  double v = y[i0];
  for (size_t i = i0; i <= i1; i++)
    if (fabs(y[i]) > fabs(v)) v = y[i];
  return v;
}

/* output body k's series key in report-data.js for quantity q,
 * <body>_<symbol> (the four-bar's coupler_omega, follower_alpha; the
 * slider-crank's slider_v, slider_a), into buf (returned) */
static const char *series_key(const fb_mech_desc *mech, int k, int q, char *buf, size_t size) {
  snprintf(buf, size, "%s_%s", fb_mech_output_name(mech, k), fb_mech_output_symbol(mech, k, q));
  return buf;
}

/* output body k's CSV column of quantity q (coupler_alpha_rad_s2,
 * slider_a_m_s2) into buf (returned) */
static const char *body_column(const fb_mech_desc *mech, int k, int q, char *buf, size_t size) {
  int body[FB_MECH_MAX_OUTPUTS];
  const int n = fb_mech_outputs(mech, body);
  if (k < 0 || k >= n) {
    snprintf(buf, size, "?");
    return buf;
  }
  return fb_mech_body_column(mech, body[k], q, buf, size);
}

/* one model's kept samples and its small members, written by write_model */
typedef struct {
  json_t *head;   /* name ... kept, impacts */
  json_t *joints; /* per joint in contact: joint, impacts, listed */
  size_t *idx;    /* the kept samples, ascending */
  size_t nk;
} model_data;

/* one model's data: decimated series, contact columns, impacts; bodies,
 * columns and joints named by the case's mechanism (the four-bar's
 * coupler_omega ... follower_alpha, crank-coupler) */
static fb_status model_json(model_data *out, const fb_run *r, int mi) {
  const fb_model_result *m = &r->model[mi];
  const fb_series *s = &m->run.series;
  const fb_model *row = m->run.model;
  const fb_model *ref = fb_model_reference_of(row), *ideal = fb_model_ideal_of(row);
  json_t *o = json_pack("{s:s,s:s,s:b,s:s?,s:s?,s:s?,s:i}", "name", m->run.name, "engine",
                        fb_engine_name(row->engine), "clearance", m->run.clearance_mask != 0,
                        "reference", ref ? ref->name : NULL, "ideal", ideal ? ideal->name : NULL,
                        "color", fb_figure_model_color(r, row->name), "dash",
                        fb_figure_model_dash(r, row->name));
  unsigned char *keep = calloc(s->n ? s->n : 1, 1);
  size_t *idx = malloc((s->n ? s->n : 1) * sizeof *idx);
  episode *ep = malloc(FB_REPORT_MAX_IMPACTS * sizeof *ep);
  if (!o || !keep || !idx || !ep) {
    free(keep), free(idx), free(ep), json_decref(o);
    return FB_ERR_NOMEM;
  }
  const size_t per = s->n > 2 * FB_REPORT_BUCKETS ? (s->n + FB_REPORT_BUCKETS - 1) / FB_REPORT_BUCKETS : 1;
  const fb_mech_desc *mech = fb_case_mech(&r->c);
  int body[FB_MECH_MAX_OUTPUTS];
  const int nb = fb_mech_outputs(mech, body);
  if (s->n) {
    for (int k = 0; k < nb; k++) {
      mark_extremes(keep, s->body[k][FB_Q_VEL], s->n, per);
      mark_extremes(keep, s->body[k][FB_Q_ACC], s->n, per);
    }
    keep[0] = keep[s->n - 1] = 1;
  }
  json_t *impacts = json_array(), *joints = json_array();
  for (int j = 0; j < 4; j++) {
    if (!(s->contact_mask & (1 << j))) continue;
    mark_extremes(keep, s->contact[j][FB_C_FORCE], s->n, per);
    mark_extremes(keep, s->contact[j][FB_C_PEN], s->n, per);
    /* every change of contact state: the orbit's colours change there */
    for (size_t i = 1; i < s->n; i++)
      if (s->contact[j][FB_C_STATE][i] != s->contact[j][FB_C_STATE][i - 1]) keep[i - 1] = keep[i] = 1;
    const size_t ne = episodes(s, j, ep, FB_REPORT_MAX_IMPACTS);
    const size_t listed = ne < FB_REPORT_MAX_IMPACTS ? ne : FB_REPORT_MAX_IMPACTS;
    for (size_t k = 0; k < listed; k++) {
      const size_t a = ep[k].i0 > FB_REPORT_IMPACT_PAD ? ep[k].i0 - FB_REPORT_IMPACT_PAD : 0;
      const size_t b = ep[k].i1 + FB_REPORT_IMPACT_PAD < s->n ? ep[k].i1 + FB_REPORT_IMPACT_PAD : s->n - 1;
      keep_episode(keep, s, j, nb, ep[k].i0, ep[k].i1, a, b);
      double fmax_n = 0.0, pmax = 0.0;
      for (size_t i = ep[k].i0; i <= ep[k].i1; i++) {
        fmax_n = fmax(fmax_n, s->contact[j][FB_C_FORCE][i]);
        pmax = fmax(pmax, s->contact[j][FB_C_PEN][i]);
      }
      /* each output body's acceleration over the episode and the free
       * flight it ends in (the rebound spike follows the force peak by a
       * step or two), under its CSV column's name */
      const size_t a2 = ep[k].i1 + 3 < s->n ? ep[k].i1 + 3 : s->n - 1;
      json_t *im = json_pack("{s:s,s:s,s:f,s:f,s:f,s:f,s:f}", "model", m->run.name,
                             "joint", fb_case_joint_name(&r->c, j), "t_s", s->t[ep[k].i0], "t_end_s",
                             s->t[ep[k].i1], "crank_angle_deg", deg360(s->crank_angle[ep[k].i0]),
                             "force_n", fmax_n, "penetration_m", pmax);
      for (int ob = 0; ob < nb; ob++) {
        char col[64];
        json_object_set_new(im, body_column(mech, ob, FB_Q_ACC, col, sizeof col),
                            json_real(largest(s->body[ob][FB_Q_ACC], ep[k].i0, a2)));
      }
      json_array_append_new(impacts, im);
    }
    json_t *jo = json_pack("{s:s,s:i,s:i}", "joint", fb_case_joint_name(&r->c, j), "impacts", (int)ne,
                           "listed", (int)listed);
    json_array_append_new(joints, jo);
  }
  size_t nk = 0;
  for (size_t i = 0; i < s->n; i++)
    if (keep[i]) idx[nk++] = i;
  json_object_set_new(o, "samples", json_integer((json_int_t)s->n));
  json_object_set_new(o, "kept", json_integer((json_int_t)nk));
  json_object_set_new(o, "impacts", impacts);
  free(keep), free(ep);
  *out = (model_data){o, joints, idx, nk};
  return FB_OK;
}

/* model mi's object: its small members, then the kept samples of every
 * series and contact column (json_columns.h); returns 0 or -1 */
static int write_model(FILE *f, const fb_run *r, int mi, const model_data *md, size_t flags) {
  const fb_series *s = &r->model[mi].run.series;
  const fb_mech_desc *mech = fb_case_mech(&r->c);
  const int nb = fb_mech_outputs(mech, (int[FB_MECH_MAX_OUTPUTS]){0});
  const size_t *idx = md->idx, nk = md->nk;
  int bad = fb_json_open_object(f, md->head, flags);
  bad |= fb_json_column(f, "t", s->t, idx, nk, 1.0, SERIES_DIGITS);
  for (int b = 0; b < nb; b++)
    for (int q = FB_Q_VEL; q <= FB_Q_ACC; q++) {
      char key[64];
      bad |= fb_json_column(f, series_key(mech, b, q, key, sizeof key), s->body[b][q], idx, nk, 1.0,
                            SERIES_DIGITS);
    }
  bad |= fputs(",\"joints\":[", f) < 0;
  size_t q = 0;
  for (int j = 0; j < 4; j++) {
    if (!(s->contact_mask & (1 << j))) continue;
    double *const *col = s->contact[j];
    if (q) bad |= fputc(',', f) == EOF;
    bad |= fb_json_open_object(f, json_array_get(md->joints, q++), flags);
    bad |= fb_json_column(f, "force_n", col[FB_C_FORCE], idx, nk, 1.0, SERIES_DIGITS);
    bad |= fb_json_column(f, "penetration_um", col[FB_C_PEN], idx, nk, 1e6, SERIES_DIGITS);
    bad |= fb_json_column(f, "ecc_x_um", col[FB_C_EX], idx, nk, 1e6, SERIES_DIGITS);
    bad |= fb_json_column(f, "ecc_y_um", col[FB_C_EY], idx, nk, 1e6, SERIES_DIGITS);
    bad |= fb_json_column(f, "state", col[FB_C_STATE], idx, nk, 1.0, SERIES_DIGITS);
    bad |= fputc('}', f) == EOF;
  }
  bad |= fputs("]}", f) < 0;
  return bad ? -1 : 0;
}

/* copies the library file name from folder lib into dir, atomically */
static fb_status copy_file(const char *lib, const char *name, const char *dir, fb_diag *diag) {
  char from[4400], to[4400];
  snprintf(from, sizeof from, "%s/%s", lib, name);
  snprintf(to, sizeof to, "%s/%s", dir, name);
  int not_regular = 0;
  FILE *in = fb_fopen_regular(from, &not_regular);
  if (!in)
    return fb_diag_set(diag, FB_ERR_IO, "%s: cannot read: %s", from,
                       not_regular ? "not a regular file" : strerror(errno));
  fb_outfile out;
  fb_status st = fb_outfile_open(&out, to, diag);
  if (st != FB_OK) {
    fclose(in);
    return st;
  }
  char buf[65536];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, in)) > 0)
    if (fwrite(buf, 1, n, out.f) != n) break;
  const int bad = ferror(in);
  fclose(in);
  if (bad) {
    fb_outfile_abort(&out);
    return fb_diag_set(diag, FB_ERR_IO, "%s: read failed", from);
  }
  return fb_outfile_commit(&out, diag);
}

/* the output bodies of mechanism mech for the page (docs/report.md): per
 * body its name, whether it translates, its symbols, units, CSV columns,
 * series keys (<body>_<symbol>) and the summary.json keys of its headline
 * peaks (fb_mech_output_key) */
static json_t *outputs_json(const fb_mech_desc *mech) {
  static const char *const peak[5] = {"%s.omega_max_rad_s", "%s.omega_min_rad_s", "%s.alpha_max_rad_s2",
                                      "%s.alpha_min_rad_s2", "spikes.alpha_peak_ratio_%s"};
  static const char *const fourbar_name[FB_MECH_MAX_OUTPUTS] = {"coupler", "follower"};
  int body[FB_MECH_MAX_OUTPUTS];
  const int nb = fb_mech_outputs(mech, body);
  json_t *a = json_array();
  for (int k = 0; k < nb; k++) {
    json_t *sym = json_array(), *unit = json_array(), *col = json_array(), *key = json_array(),
           *sum = json_array();
    char buf[96], tmpl[96];
    for (int q = 0; q < 3; q++) {
      json_array_append_new(sym, json_string(fb_mech_output_symbol(mech, k, q)));
      json_array_append_new(unit, json_string(fb_mech_output_unit(mech, k, q)));
      json_array_append_new(col, json_string(body_column(mech, k, q, buf, sizeof buf)));
      json_array_append_new(key, q == FB_Q_POS ? json_null() : json_string(series_key(mech, k, q, buf, sizeof buf)));
    }
    for (int p = 0; p < 5; p++) {
      snprintf(tmpl, sizeof tmpl, peak[p], fourbar_name[k]);
      json_array_append_new(sum, json_string(fb_mech_output_key(buf, sizeof buf, mech, tmpl)));
    }
    json_array_append_new(a, json_pack("{s:s,s:b,s:o,s:o,s:o,s:o,s:o}", "name", fb_mech_output_name(mech, k),
                                       "translates", fb_mech_output_translates(mech, k), "symbol", sym, "unit",
                                       unit, "column", col, "series", key, "summary", sum));
  }
  return a;
}

/* the run's small members: case, speed, ..., verdicts (everything but models) */
static json_t *run_json(const fb_run *r, int charts) {
  json_t *d = json_object();
  const fb_case *c = &r->c;
  json_object_set_new(d, "format", json_integer(1));
  json_object_set_new(d, "case", json_string(c->name));
  json_object_set_new(d, "speed_rpm", json_real(c->crank_speed * 60.0 / (2.0 * M_PI)));
  json_object_set_new(d, "direction", json_integer(c->direction));
  json_object_set_new(d, "crank_angle0_deg", json_real(c->crank_angle0 * 180.0 / M_PI));
  json_object_set_new(d, "radial_clearance_um", json_real(c->radial_clearance * 1e6));
  json_object_set_new(d, "t_window_s", json_real(r->t_window));
  json_object_set_new(d, "h_s", json_real(c->solver.h));
  json_object_set_new(d, "charts", json_boolean(charts));
  /* the page's own outputs are the four-bar's (coupler, follower: omega,
   * alpha); any other mechanism's are written here, so that the four-bar's
   * data stay as they were */
  if (fb_case_mech(c) != &fb_mech_fourbar) json_object_set_new(d, "outputs", outputs_json(fb_case_mech(c)));
  /* what each verdict on statistics rests on, for its panel */
  json_object_set_new(d, "verdicts", fb_report_verdicts_json(r, fb_figure_model_color));
  return d;
}

/* window.FOURBAR_DATA's value: the run's small members, then "models", each
 * model decimated and written column by column; returns 0, -1 on a failed
 * write, -2 out of memory */
static int write_run(FILE *f, const fb_run *r, int charts, size_t flags) {
  json_t *d = run_json(r, charts);
  int bad = fb_json_open_object(f, d, flags | JSON_REAL_PRECISION(SERIES_DIGITS));
  json_decref(d);
  bad |= fputs(",\"models\":[", f) < 0;
  for (int i = 0; i < r->n && !bad; i++) {
    model_data md;
    if (model_json(&md, r, i) != FB_OK) return -2;
    if (i) bad |= fputc(',', f) == EOF;
    bad |= write_model(f, r, i, &md, flags | JSON_REAL_PRECISION(SERIES_DIGITS));
    json_decref(md.head), json_decref(md.joints), free(md.idx);
  }
  bad |= fputs("]}", f) < 0;
  return bad ? -1 : 0;
}

/* the four-bar's window.FOURBAR_DATA value (write_run) for write_data */
typedef struct {
  const fb_run *r;
  int charts;
} run_value;

static int write_run_value(FILE *f, const void *arg, size_t flags) {
  const run_value *v = arg;
  return write_run(f, v->r, v->charts, flags);
}

/* another writer's data (a json_t) as window.FOURBAR_DATA's value */
static int write_json_value(FILE *f, const void *arg, size_t flags) {
  return json_dumpf(arg, f, flags | JSON_REAL_PRECISION(SERIES_DIGITS)) != 0 ? -1 : 0;
}

/* A stream through to the FILE cookie with '`' and '$' written as JSON's
 * \u0060 and \u0024 (they occur in JSON text inside strings only): the
 * JSON text then sits whole in a JavaScript template literal (String.raw),
 * where those two are the only characters with a meaning. */
static ssize_t raw_write(void *cookie, const char *buf, size_t n) {
  FILE *f = cookie;
  size_t from = 0;
  for (size_t i = 0; i < n; i++)
    if (buf[i] == '`' || buf[i] == '$') {
      fwrite(buf + from, 1, i - from, f);
      fputs(buf[i] == '`' ? "\\u0060" : "\\u0024", f);
      from = i + 1;
    }
  fwrite(buf + from, 1, n - from, f);
  return ferror(f) ? -1 : (ssize_t)n;
}

/* one JSON value into f as JSON.parse(String.raw`...`): JSON.parse, not an
 * object literal, because a literal takes a key "__proto__" for the
 * object's prototype (a body of that name would vanish), and JSON.parse
 * keeps it as a key (names are data; the page copies every object into one
 * without a prototype, report_page.js). Returns value's status, -1 on a
 * failed write. */
static int write_parsed(FILE *f, int (*value)(FILE *, const void *, size_t), const void *arg,
                        size_t flags) {
  cookie_io_functions_t io = {.write = raw_write};
  FILE *g = fopencookie(f, "w", io);
  if (!g) return -1;
  fputs("JSON.parse(String.raw`", f);
  const int w = value(g, arg, flags);
  const int bad = fclose(g) != 0;
  fputs("`)", f);
  return w ? w : bad || ferror(f) ? -1 : 0;
}

/* summary.json's value, as it is written there (write_parsed's value) */
static int write_summary_value(FILE *f, const void *arg, size_t flags) {
  return json_dumpf(arg, f, flags | JSON_REAL_PRECISION(12)) != 0 ? -1 : 0;
}

/* writes report-data.js: the data value writes (0, -1 on a failed write,
 * -2 out of memory), then summary.json's value */
static fb_status write_data(const char *dir, int (*value)(FILE *, const void *, size_t),
                            const void *arg, const json_t *summary, fb_diag *diag) {
  char path[4400];
  snprintf(path, sizeof path, "%s/report-data.js", dir);
  fb_outfile out;
  fb_status st = fb_outfile_open(&out, path, diag);
  if (st != FB_OK) return st;
  /* JSON_ENSURE_ASCII | JSON_ESCAPE_SLASH: no "</script>", no U+2028 */
  const size_t flags = JSON_COMPACT | JSON_ENSURE_ASCII | JSON_ESCAPE_SLASH;
  fputs("/* fourbar run data for report.html (docs/report.md) */\nwindow.FOURBAR_DATA = ", out.f);
  const int w = write_parsed(out.f, value, arg, flags);
  fputs(";\nwindow.FOURBAR_DATA.summary = ", out.f);
  int bad = w != 0 || write_parsed(out.f, write_summary_value, summary, flags) != 0;
  fputs(";\n", out.f);
  if (bad) {
    fb_outfile_abort(&out);
    if (w == -2) return fb_diag_set(diag, FB_ERR_NOMEM, "report.html: out of memory");
    return fb_diag_set(diag, FB_ERR_IO, "%s: JSON write failed", path);
  }
  return fb_outfile_commit(&out, diag);
}

/* copies the chart library into dir when it is found (*charts) */
static fb_status copy_library(const char *dir, int *charts, fb_diag *diag) {
  char lib[4096];
  *charts = fb_report_html_library(lib, sizeof lib);
  fb_status st = FB_OK;
  for (int k = 0; k < 2 && *charts && st == FB_OK; k++) st = copy_file(lib, lib_files[k], dir, diag);
  return st;
}

/* report.html: static markup, then the static script inline */
static fb_status write_page(const char *dir, int charts, fb_diag *diag) {
  char path[4400];
  snprintf(path, sizeof path, "%s/report.html", dir);
  fb_outfile out;
  const fb_status st = fb_outfile_open(&out, path, diag);
  if (st != FB_OK) return st;
  fwrite(fb_report_page_html, 1, sizeof fb_report_page_html, out.f);
  /* the library only when it was copied: a missing file would be a failed
   * request and a console error */
  if (charts)
    fputs("<link rel=\"stylesheet\" href=\"uPlot.min.css\">\n"
          "<script src=\"uPlot.iife.min.js\"></script>\n", out.f);
  fputs("<script src=\"report-data.js\"></script>\n<script>\n", out.f);
  fwrite(fb_report_page_js, 1, sizeof fb_report_page_js, out.f);
  fputs("</script>\n</body>\n</html>\n", out.f);
  return fb_outfile_commit(&out, diag);
}

fb_status fb_report_html_write(const char *dir, const fb_run *r, const json_t *summary, int *charts,
                               fb_diag *diag) {
  fb_status st = copy_library(dir, charts, diag);
  const run_value v = {r, *charts};
  if (st == FB_OK) st = write_data(dir, write_run_value, &v, summary, diag);
  return st == FB_OK ? write_page(dir, *charts, diag) : st;
}

fb_status fb_report_html_write_data(const char *dir, json_t *data, const json_t *summary,
                                    int *charts, fb_diag *diag) {
  fb_status st = copy_library(dir, charts, diag);
  json_object_set_new(data, "charts", json_boolean(*charts));
  if (st == FB_OK) st = write_data(dir, write_json_value, data, summary, diag);
  json_decref(data);
  return st == FB_OK ? write_page(dir, *charts, diag) : st;
}
