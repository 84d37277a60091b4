/* The tables of kinematics, penalty and stackup on a planar case
 * (tables_planar.h). */
#include "tables_planar.h"

#include <jansson.h>
#include <math.h>
#include <string.h>

#include "numfmt.h"
#include "report_summary.h"
#include "report_table.h"
#include "resolution.h"
#include "tables_stackup.h"
#include "units.h"

/* finite number or null */
static json_t *num(double x) { return isfinite(x) ? json_real(x) : json_null(); }

static void dump(FILE *f, json_t *o) {
  json_dumpf(o, f, JSON_INDENT(2) | JSON_REAL_PRECISION(12));
  fputc('\n', f);
  json_decref(o);
}

#define CELL(x) FB_NUM_CELL("%.6g", (x), FB_NUM_NONE_TABLE)

/* output i's corner in corner strings a (planar_tools.h: "" for the nominal) */
static const char *at(const char *a, const fb_planar_stackup *s, int i) {
  return a + (size_t)i * ((size_t)s->nlengths + 1);
}

void fb_report_planar_kinematics(FILE *f, const fb_case *c, const fb_planar *m,
                                 const fb_planar_peaks *p, int json) {
  if (json) {
    json_t *o = json_object(), *bodies = json_object();
    json_object_set_new(o, "case", json_string(c->name));
    json_object_set_new(o, "mechanism", json_string("planar"));
    json_object_set_new(o, "drive", json_string(m->joint[m->drive].name));
    json_object_set_new(o, "speed_rpm", num(c->crank_speed / FB_RAD_S_PER_RPM));
    for (int b = 1; b < m->nbodies; b++) {
      const fb_planar_peaks *k = &p[b];
      json_t *e = json_pack("{s:o,s:o,s:o,s:o}", "omega_max_rad_s", num(k->omega_max),
                            "omega_min_rad_s", num(k->omega_min), "alpha_max_rad_s2",
                            num(k->alpha_max), "alpha_min_rad_s2", num(k->alpha_min));
      json_object_set_new(e, "at_drive_angle_rad",
                          json_pack("{s:o,s:o,s:o,s:o}", "omega_max", num(k->where[0]),
                                    "omega_min", num(k->where[1]), "alpha_max", num(k->where[2]),
                                    "alpha_min", num(k->where[3])));
      json_object_set_new(bodies, m->body[b].name, e);
    }
    json_object_set_new(o, "bodies", bodies);
    dump(f, o);
    return;
  }
  fprintf(f, "%s: planar, drive '%s' at %.6g rpm; peaks over a revolution (drive angle from the "
          "assembly configuration)\n", c->name, m->joint[m->drive].name,
          c->crank_speed / FB_RAD_S_PER_RPM);
  fprintf(f, "| body | omega max [rad/s] | at [deg] | omega min [rad/s] | at [deg] | "
          "alpha max [rad/s^2] | at [deg] | alpha min [rad/s^2] | at [deg] |\n"
          "|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (int b = 1; b < m->nbodies; b++) {
    const fb_planar_peaks *k = &p[b];
    const double deg = 1.0 / FB_RAD_PER_DEG;
    fprintf(f, "| %s | %s | %.2f | %s | %.2f | %s | %.2f | %s | %.2f |\n", m->body[b].name,
            CELL(k->omega_max), k->where[0] * deg, CELL(k->omega_min), k->where[1] * deg,
            CELL(k->alpha_max), k->where[2] * deg, CELL(k->alpha_min), k->where[3] * deg);
  }
}

void fb_report_planar_penalty(FILE *f, const fb_case *c, const fb_planar *m,
                              const fb_planar_penalty_row *rows, const int *n, const double *rpm,
                              int nspeeds, const fb_planar_contact_estimate *est, int nest,
                              int json) {
  json_t *arr = json ? json_array() : NULL;
  if (!json)
    fprintf(f, "%s: physical mode (largest ideal reaction over a revolution, Johnson's "
            "pin-in-hole contact, c = %.6g um, L = %.6g mm)\n| speed [rpm] | joint | force [N] | "
            "Kc [N/m] | P [N m^0.5] | P [N mm^0.5] | approach [um] |\n"
            "|---:|---|---:|---:|---:|---:|---:|\n", c->name, c->radial_clearance / FB_M_PER_UM,
            c->pin_length / FB_M_PER_MM);
  for (int s = 0; s < nspeeds; s++)
    for (int i = 0; i < n[s]; i++) {
      const fb_planar_penalty_row *r = &rows[s * m->njoints + i];
      const double p_mm = r->penalty / sqrt(FB_M_PER_MM); /* 1 N mm^0.5 = sqrt(1e-3) N m^0.5 */
      if (json)
        json_array_append_new(
            arr, json_pack("{s:o,s:s,s:o,s:o,s:o,s:o,s:o}", "speed_rpm", num(rpm[s]), "joint",
                           m->joint[r->joint].name, "force_n", num(r->force), "stiffness_n_m",
                           num(r->stiffness), "penalty_n_m0_5", num(r->penalty),
                           "penalty_n_mm0_5", num(p_mm), "approach_m", num(r->approach)));
      else
        fprintf(f, "| %.6g | %s | %s | %s | %s | %s | %s |\n", rpm[s], m->joint[r->joint].name,
                CELL(r->force), CELL(r->stiffness), CELL(r->penalty), CELL(p_mm),
                CELL(r->approach / FB_M_PER_UM));
    }
  /* the contact block: each clearance pin under the two laws a run's
   * models take (the four-bar's, tables_penalty.c) */
  json_t *cj = json ? json_array() : NULL;
  if (nest && !json)
    fprintf(f, "\ncontact a fourbar run of %s uses (nominal lengths; physical: F_j = the joint's "
            "largest inverse-dynamics reaction over a revolution, delta_j = Johnson's pin-in-hole "
            "approach at F_j; impact law K = F_j / delta_j^n, restitution law p = dF/d delta at "
            "F_j):\n", c->name);
  for (int k = 0; k < nest; k++) {
    const fb_planar_contact_estimate *e = &est[k];
    const char *name = m->joint[e->joint].name;
    if (json) {
      json_t *o = fb_report_contact_law_json(name, &e->law, (fb_mapping)c->clearance.mapping);
      json_object_set_new(o, "model", json_string(e->impact ? "clearance-impact"
                                                            : "clearance-restitution"));
      json_object_set_new(o, "effective_mass_estimate_kg",
                          json_pack("{s:o,s:o}", "min", num(e->m_eff_min), "max",
                                    num(e->m_eff_max)));
      json_object_set_new(o, "force_expected_n", num(e->force_expected));
      json_object_set_new(o, "reaction_n", num(e->reaction_max));
      json_object_set_new(o, "omega_c_rad_s", num(e->omega_c));
      json_object_set_new(o, "damper_rate_1_s", num(e->rates.damper_rate));
      json_object_set_new(o, "approach_speed_m_s", num(e->rates.approach_speed));
      json_object_set_new(o, "damper_ramp_rate_1_s", num(e->rates.ramp_rate));
      json_object_set_new(o, "rate_from", json_string(e->rates.limit));
      json_object_set_new(o, "h_resolving_s", num(e->h_resolving));
      json_array_append_new(cj, o);
      continue;
    }
    fb_report_print_contact_law(f, name, &e->law, (fb_mapping)c->clearance.mapping);
    fprintf(f, "  %-17s %-12s effective mass %.4g .. %.4g kg over a revolution, expected impact "
            "force %.6g N (%g x the ideal reaction %.6g N), omega_c %.4g rad/s "
            "and the damper's c / m_eff %.4g 1/s: h <= %.3g s keeps h x rate <= %g (the %s)\n",
            "", "", e->m_eff_min, e->m_eff_max, e->force_expected, FB_IMPACT_LOAD_FACTOR,
            e->reaction_max, e->omega_c, e->rates.damper_rate, e->h_resolving,
            FB_H_OMEGA_C_BOUND, strcmp(e->rates.limit, "damper") == 0 ? "damper" : "stiffness");
  }
  double h = INFINITY;
  for (int k = 0; k < nest; k++) h = fmin(h, est[k].h_resolving);
  if (nest && !json)
    fprintf(f, "the step that resolves every clearance contact: %.3g s (a planar run's "
            "[solver] h_s = auto); fourbar run "
            "prints each engine clearance model's largest h omega_c at its contacts\n", h);
  if (json)
    dump(f, json_pack("{s:s,s:s,s:s,s:o,s:o,s:o}", "case", c->name, "mechanism", "planar", "mode",
                      "physical", "rows", arr, "contact", cj, "h_resolving_s",
                      nest ? num(h) : json_null()));
}

/* the stack-up's Monte Carlo keys of o (as fourbar stackup's on a
 * four-bar: distribution, samples, seed, jobs, montecarlo_wall_s,
 * quantile_ci when run) */
static void mc_json(json_t *o, const fb_planar_stackup *s) {
  json_object_set_new(o, "distribution",
                      json_string(s->mc_dist == FB_DIST_UNIFORM ? "uniform" : "normal"));
  json_object_set_new(o, "samples", json_integer((json_int_t)s->mc.samples));
  json_object_set_new(o, "seed", json_integer((json_int_t)s->mc_seed));
  json_object_set_new(o, "jobs", json_integer(s->mc.jobs));
  json_object_set_new(o, "montecarlo_wall_s", json_real(s->mc.wall_s));
  if (s->mc.samples)
    json_object_set_new(o, "quantile_ci", fb_report_mc_ci_json(s->mc.q_rank, s->mc.ci_level));
}

/* the quantiles' intervals, one row per output, and the run's line */
static void mc_text(FILE *f, const fb_planar *m, const fb_planar_stackup *s) {
  char name[128];
  fprintf(f, "\nMonte Carlo quantiles with %.0f %% confidence intervals (order statistics X_(l) .. "
          "X_(u))\n| output | 0.135%% | 50%% | 99.865%% |\n|---|---|---|---|\n",
          100.0 * s->mc.ci_level);
  int open_side = 0;
  for (int i = 0; i < s->nout; i++) {
    fprintf(f, "| %s |", fb_planar_output_name(name, sizeof name, m, i));
    for (int j = 0; j < FB_MC_NQ; j++) {
      char a[32], b[32];
      open_side |= fb_report_mc_bound(a, sizeof a, s->mc.out[i].q_ci[j][0]);
      open_side |= fb_report_mc_bound(b, sizeof b, s->mc.out[i].q_ci[j][1]);
      fprintf(f, " [%s, %s] |", a, b);
    }
    fputc('\n', f);
  }
  if (open_side)
    fprintf(f, "('-': %zu samples cannot bound that side of a tail quantile at this level; use "
            "more samples)\n", s->mc.samples);
  fb_report_mc_footer(f, s->mc.samples, s->mc_dist == FB_DIST_UNIFORM, s->mc.jobs, s->mc.wall_s);
}

void fb_report_planar_stackup(FILE *f, const fb_case *c, const fb_planar *m,
                              const fb_planar_stackup *s, int json) {
  char name[128];
  if (json) {
    json_t *o = json_object(), *lengths = json_array(), *outs = json_array();
    json_object_set_new(o, "case", json_string(c->name));
    json_object_set_new(o, "mechanism", json_string("planar"));
    for (int k = 0; k < s->nlengths; k++) {
      const fb_planar_length *L = &s->length[k];
      json_array_append_new(lengths, json_pack("{s:s,s:s,s:s,s:o,s:o,s:s}", "body",
                                               m->body[L->body].name, "from",
                                               m->joint[L->joint[0]].name, "to",
                                               m->joint[L->joint[1]].name, "nominal_m",
                                               num(L->nominal), "plus_minus_m",
                                               num(L->plus_minus), "source", L->source));
    }
    for (int i = 0; i < s->nout; i++) {
      json_t *sens = json_array();
      for (int k = 0; k < s->nlengths; k++)
        json_array_append_new(sens, num(s->sens[i * s->nlengths + k]));
      json_array_append_new(
          outs, json_pack("{s:s,s:o,s:o,s:{s:o,s:o},s:o}", "name",
                          fb_planar_output_name(name, sizeof name, m, i), "nominal",
                          num(s->nominal[i]), "sensitivity_per_m", sens, "rss", "low",
                          num(s->nominal[i] - s->rss_half[i]), "high",
                          num(s->nominal[i] + s->rss_half[i]), "corners",
                          s->corners ? json_pack("{s:o,s:o,s:s,s:s}", "min", num(s->lo[i]),
                                                 "max", num(s->hi[i]), "min_at",
                                                 at(s->lo_at, s, i), "max_at", at(s->hi_at, s, i))
                                     : json_null()));
      const fb_mc_output *q = s->mc.out ? &s->mc.out[i] : NULL;
      json_object_set_new(json_array_get(outs, (size_t)i), "montecarlo",
                          s->mc.samples ? fb_report_mc_output_json(q->q, (const double(*)[2])q->q_ci,
                                                                   q->mean, q->std)
                                        : json_null());
    }
    mc_json(o, s);
    json_object_set_new(o, "lengths", lengths);
    json_object_set_new(o, "corners", json_integer(s->corners));
    json_object_set_new(o, "outputs", outs);
    dump(f, o);
    return;
  }
  fprintf(f, "%s: planar, %d lengths (each body's joint-to-joint distances)\n| body | from | to | "
          "nominal [mm] | +- [mm] | source |\n|---|---|---|---:|---:|---|\n", c->name,
          s->nlengths);
  for (int k = 0; k < s->nlengths; k++) {
    const fb_planar_length *L = &s->length[k];
    fprintf(f, "| %s | %s | %s | %.6g | %.4g | %s |\n", m->body[L->body].name,
            m->joint[L->joint[0]].name, m->joint[L->joint[1]].name, L->nominal / FB_M_PER_MM,
            L->plus_minus / FB_M_PER_MM, L->source);
  }
  if (s->corners)
    fprintf(f, "\nworst case over all %lld corners (at: one sign per length, in the order above); "
            "RSS band 3 sigma\n", s->corners);
  else
    fprintf(f, "\nworst case not run (--method corners runs its %.0f corners); RSS band 3 sigma\n",
            pow(2.0, s->nlengths));
  const int mc = s->mc.samples > 0;
  fprintf(f, "| output | nominal | RSS low | RSS high | corners min | at | corners max | at |%s\n"
          "|---|---:|---:|---:|---:|---|---:|---|%s\n",
          mc ? " mc 0.135% | mc 50% | mc 99.865% |" : "", mc ? "---:|---:|---:|" : "");
  for (int i = 0; i < s->nout; i++) {
    fprintf(f, "| %s | %s | %s | %s | %s | %s | %s | %s |",
            fb_planar_output_name(name, sizeof name, m, i), CELL(s->nominal[i]),
            CELL(s->nominal[i] - s->rss_half[i]), CELL(s->nominal[i] + s->rss_half[i]),
            CELL(s->corners ? s->lo[i] : NAN), at(s->lo_at, s, i),
            CELL(s->corners ? s->hi[i] : NAN), at(s->hi_at, s, i));
    if (mc)
      fprintf(f, " %s | %s | %s |", CELL(s->mc.out[i].q[0]), CELL(s->mc.out[i].q[1]),
              CELL(s->mc.out[i].q[2]));
    fputc('\n', f);
  }
  if (mc) mc_text(f, m, s);
}
