/* fourbar stackup's output (tables_stackup.h): the stack-up as one JSON
 * object or as text tables. */
#include "tables_stackup.h"

#include <jansson.h>
#include <math.h>
#include <string.h>

#include "linkage.h"

/* a quantile bound for JSON: null when the sample cannot bound that side */
static json_t *bound_json(double x) { return isfinite(x) ? json_real(x) : json_null(); }

struct json_t *fb_report_mc_ci_json(const size_t q_rank[3][2], double level) {
  /* which order statistics bound each quantile (null: none at this level) */
  json_t *ci = json_object(), *ranks = json_object();
  static const char *const qn[3] = {"q00135", "q50", "q99865"};
  json_object_set_new(ci, "level", json_real(level));
  json_object_set_new(ci, "method", json_string("distribution-free, order statistics (binomial)"));
  for (int j = 0; j < 3; j++)
    json_object_set_new(ranks, qn[j],
                        json_pack("[o,o]", q_rank[j][0] ? json_integer((json_int_t)q_rank[j][0]) : json_null(),
                                  q_rank[j][1] ? json_integer((json_int_t)q_rank[j][1]) : json_null()));
  json_object_set_new(ci, "ranks", ranks);
  return ci;
}

struct json_t *fb_report_mc_output_json(const double q[3], const double q_ci[3][2], double mean,
                                        double std) {
  json_t *m = json_pack("{s:f,s:f,s:f,s:f,s:f}", "q00135", q[0], "q50", q[1], "q99865", q[2],
                        "mean", mean, "std", std);
  static const char *const lo[3] = {"q00135_ci_lo", "q50_ci_lo", "q99865_ci_lo"};
  static const char *const hi[3] = {"q00135_ci_hi", "q50_ci_hi", "q99865_ci_hi"};
  for (int j = 0; j < 3; j++) {
    json_object_set_new(m, lo[j], bound_json(q_ci[j][0]));
    json_object_set_new(m, hi[j], bound_json(q_ci[j][1]));
  }
  return m;
}

int fb_report_mc_bound(char *buf, size_t size, double x) {
  if (!isfinite(x)) {
    snprintf(buf, size, "-");
    return 1;
  }
  snprintf(buf, size, "%.6g", x);
  return 0;
}

void fb_report_mc_footer(FILE *f, size_t samples, int uniform, int jobs, double wall_s) {
  fprintf(f, "\nMonte Carlo: %zu samples (%s), %d job%s, %.3f s (%.2f us per sample)\n", samples,
          uniform ? "uniform" : "normal, 3 sigma at the limit", jobs, jobs == 1 ? "" : "s", wall_s,
          1e6 * wall_s / (double)samples);
}

void fb_report_stackup_json(FILE *f, const fb_stackup_result *r, const fb_case *c, int mask,
                            unsigned long seed, int jobs) {
  json_t *o = json_object(), *outs = json_array();
  json_object_set_new(o, "case", json_string(c->name));
  json_object_set_new(o, "distribution", json_string(c->distribution ? "uniform" : "normal"));
  json_object_set_new(o, "samples", json_integer((json_int_t)r->samples));
  json_object_set_new(o, "seed", json_integer((json_int_t)seed));
  json_object_set_new(o, "jobs", json_integer((json_int_t)jobs));
  json_object_set_new(o, "montecarlo_wall_s", json_real(r->mc_wall_s));
  const fb_mech_desc *mech = fb_case_mech(c);
  const int nl = mech->nlengths;
  json_t *tol = json_object();
  for (int k = 0; k < nl; k++) {
    json_t *l = json_object();
    json_object_set_new(l, "nominal_m", json_real(c->nominal.length[k]));
    json_object_set_new(l, "plus_minus_m", json_real(c->plus_minus[k]));
    json_object_set_new(l, "source", json_string(c->tolerance_source[k]));
    json_object_set_new(tol, mech->length[k], l);
  }
  json_object_set_new(o, "links", tol);
  if (mask & FB_TOL_MONTECARLO)
    json_object_set_new(o, "quantile_ci", fb_report_mc_ci_json(r->q_rank, r->ci_level));
  for (int i = 0; i < FB_TOL_NOUT; i++) {
    json_t *x = json_object(), *s = json_object();
    json_object_set_new(x, "name", json_string(fb_tol_output_name_of(c->mechanism, i)));
    json_object_set_new(x, "nominal", json_real(r->nominal[i]));
    for (int k = 0; k < nl; k++) json_object_set_new(s, mech->length[k], json_real(r->sens[i][k]));
    json_object_set_new(x, "sensitivity_per_m", s);
    if (mask & FB_TOL_CORNERS)
      json_object_set_new(x, "corners", json_pack("{s:f,s:f}", "min", r->corner_min[i], "max", r->corner_max[i]));
    if (mask & FB_TOL_RSS)
      json_object_set_new(x, "rss", json_pack("{s:f,s:f}", "min", r->nominal[i] - r->rss_half[i], "max",
                                              r->nominal[i] + r->rss_half[i]));
    if (mask & FB_TOL_MONTECARLO)
      json_object_set_new(x, "montecarlo", fb_report_mc_output_json(r->q[i], (const double(*)[2])r->q_ci[i],
                                                                    r->mc_mean[i], r->mc_std[i]));
    json_array_append_new(outs, x);
  }
  json_object_set_new(o, "outputs", outs);
  json_dumpf(o, f, JSON_INDENT(2) | JSON_REAL_PRECISION(12));
  fputc('\n', f);
  json_decref(o);
}

void fb_report_stackup_text(FILE *f, const fb_stackup_result *r, const fb_case *c, int mask) {
  const fb_mech_desc *mech = fb_case_mech(c);
  const int nl = mech->nlengths;
  const fb_mech_type t = c->mechanism;
  fprintf(f, "stack-up of case %s at %.6g rpm:", c->name, c->crank_speed * 60 / (2 * M_PI));
  if (mech->title_names_type) fprintf(f, " %s,", mech->type);
  for (int k = 0; k < nl; k++)
    fprintf(f, "%s %s %.4g +- %.3g mm", k ? "," : "", mech->length[k], c->nominal.length[k] * 1e3,
              c->plus_minus[k] * 1e3);
  fprintf(f, "\n\n%-28s %12s %12s %12s %12s %12s %12s %12s %12s\n", "output", "nominal",
            "corner min", "corner max", "rss min", "rss max", "mc 0.135%", "mc 50%", "mc 99.865%");
  for (int i = 0; i < FB_TOL_NOUT; i++) {
    fprintf(f, "%-28s %12.6g", fb_tol_output_name_of(t, i), r->nominal[i]);
    if (mask & FB_TOL_CORNERS) fprintf(f, " %12.6g %12.6g", r->corner_min[i], r->corner_max[i]);
    else fprintf(f, " %12s %12s", "-", "-");
    if (mask & FB_TOL_RSS) fprintf(f, " %12.6g %12.6g", r->nominal[i] - r->rss_half[i], r->nominal[i] + r->rss_half[i]);
    else fprintf(f, " %12s %12s", "-", "-");
    if (mask & FB_TOL_MONTECARLO) fprintf(f, " %12.6g %12.6g %12.6g", r->q[i][0], r->q[i][1], r->q[i][2]);
    else fprintf(f, " %12s %12s %12s", "-", "-", "-");
    fputc('\n', f);
  }
  /* the exact sensitivities of every output to every link length, each with
   * its unit (the output's unit per metre of length) */
  fprintf(f, "\nsensitivities d(output)/d(link length), exact derivatives (per metre of length):\n");
  fprintf(f, "%-28s", "output");
  for (int k = 0; k < nl; k++) fprintf(f, " %12s", mech->length[k]);
  fprintf(f, "  %s\n", "unit");
  for (int i = 0; i < FB_TOL_NOUT; i++) {
    fprintf(f, "%-28s", fb_tol_output_name_of(t, i));
    for (int k = 0; k < nl; k++) fprintf(f, " %12.5g", r->sens[i][k]);
    const char *unit = fb_tol_output_unit_of(t, i);
    fprintf(f, "  %s%sper m\n", unit, unit[0] ? " " : "");
  }
  const int pos = fb_mech_position_length(mech); /* a signed position's note at 0 */
  if (pos >= 0 && mech->position_zero_note && c->nominal.length[pos] == 0.0)
    fprintf(f, "%s\n", mech->position_zero_note);
  if (mask & FB_TOL_MONTECARLO) {
    fprintf(f, "\nMonte Carlo quantiles with %.0f %% confidence intervals (order statistics X_(l) .. X_(u)):\n",
              100.0 * r->ci_level);
    fprintf(f, "%-28s %27s %27s %27s\n", "output", "0.135%", "50%", "99.865%");
    int open_side = 0;
    for (int i = 0; i < FB_TOL_NOUT; i++) {
      fprintf(f, "%-28s", fb_tol_output_name_of(t, i));
      for (int j = 0; j < 3; j++) {
        char a[32], b[32];
        open_side |= fb_report_mc_bound(a, sizeof a, r->q_ci[i][j][0]);
        open_side |= fb_report_mc_bound(b, sizeof b, r->q_ci[i][j][1]);
        fprintf(f, "   [%11s, %11s]", a, b);
      }
      fputc('\n', f);
    }
    if (open_side)
      fprintf(f, "('-': %zu samples cannot bound that side of a tail quantile at this level; "
                "use more samples)\n", r->samples);
    fb_report_mc_footer(f, r->samples, c->distribution != 0, r->jobs, r->mc_wall_s);
  }
}
