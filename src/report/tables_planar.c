/* The tables of kinematics, penalty and stackup on a planar case
 * (tables_planar.h). */
#include "tables_planar.h"

#include <jansson.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "names.h"
#include "numfmt.h"
#include "report_summary.h"
#include "report_table.h"
#include "resolution.h"
#include "tables_penalty.h"
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

#define QRR_IS "the slower stroke's time over the faster's at constant drive speed (>= 1)"
#define MU_IS                                                                               \
  "90 deg - |pressure angle| where a binary link drives another moving body: the angle "    \
  "between the link's line and the velocity of the joint as a point of the driven body "    \
  "(about its ground pivot, along its ground guide, else its own motion); undefined "       \
  "elsewhere"

/* {"x_m", "drive_angle_rad"} of a dead centre */
static json_t *dead_centre(double x, double at) {
  return json_pack("{s:o,s:o}", "x_m", num(x), "drive_angle_rad", num(at));
}

/* the designer's slides and transmission angles into o (kinematics --json) */
static void designer_json(json_t *o, const fb_planar *m, const fb_planar_designer *d) {
  json_t *slides = json_object(), *mu = json_object();
  char word[FB_PLANAR_NAME_SIZE];
  for (int i = 0; i < d->nslides; i++) {
    const fb_planar_slide_kin *k = &d->slide[i];
    json_t *e = json_object();
    json_object_set_new(e, "stroke_m", num(k->stroke));
    json_object_set_new(e, "dead_centre_outer", dead_centre(k->pos.max, k->pos.at_max));
    json_object_set_new(e, "dead_centre_inner", dead_centre(k->pos.min, k->pos.at_min));
    json_object_set_new(e, "quick_return_ratio", num(k->quick_return_ratio));
    json_object_set_new(e, "quick_return_ratio_is", json_string(QRR_IS));
    json_object_set_new(e, "outstroke", json_pack("{s:o,s:o}", "drive_angle_rad",
                                                  num(k->outstroke_angle), "time_s",
                                                  num(k->outstroke_time)));
    json_object_set_new(e, "return", json_pack("{s:o,s:o}", "drive_angle_rad",
                                               num(k->return_angle), "time_s",
                                               num(k->return_time)));
    const double v[6] = {k->pos.max, k->pos.min, k->vel.max, k->vel.min, k->acc.max, k->acc.min};
    static const char *const key[6] = {"position_max_m", "position_min_m", "velocity_max_m_s",
                                       "velocity_min_m_s", "acceleration_max_m_s2",
                                       "acceleration_min_m_s2"};
    for (int x = 0; x < 6; x++) json_object_set_new(e, key[x], num(v[x]));
    json_object_set_new(slides, fb_name_word(word, sizeof word, m->joint[k->joint].name), e);
  }
  for (int i = 0; i < d->ntransmissions; i++) {
    const fb_planar_transmission_kin *t = &d->transmission[i];
    const double deg = 1.0 / FB_RAD_PER_DEG;
    json_object_set_new(
        mu, fb_name_word(word, sizeof word, m->joint[t->at.joint].name),
        json_pack("{s:s,s:s,s:o,s:o,s:{s:o,s:o}}", "link", m->body[t->at.link].name, "driven",
                  m->body[t->at.driven].name, "transmission_angle_min_deg", num(t->mu.min * deg),
                  "transmission_angle_max_deg", num(t->mu.max * deg), "at_drive_angle_rad", "min",
                  num(t->mu.at_min), "max", num(t->mu.at_max)));
  }
  json_t *points = json_object();
  for (int i = 0; i < d->npoints; i++) {
    const fb_planar_point_kin *k = &d->point[i];
    json_t *e = json_object();
    for (int axis = 0; axis < 2; axis++) {
      const fb_planar_extreme *x = &k->q[axis], *v = &k->q[2 + axis], *a = &k->q[4 + axis];
      json_object_set_new(e, axis ? "y" : "x",
                          json_pack("{s:o,s:o,s:o,s:o,s:o,s:o}", "position_max_m", num(x->max),
                                    "position_min_m", num(x->min), "velocity_max_m_s",
                                    num(v->max), "velocity_min_m_s", num(v->min),
                                    "acceleration_max_m_s2", num(a->max),
                                    "acceleration_min_m_s2", num(a->min)));
    }
    json_object_set_new(e, "speed_max_m_s", num(k->speed.max));
    json_object_set_new(e, "acceleration_max_m_s2", num(k->accel.max));
    json_object_set_new(points, fb_name_word(word, sizeof word, m->point[i].name), e);
  }
  json_object_set_new(o, "points", points);
  json_object_set_new(o, "slides", slides);
  json_object_set_new(o, "transmission", mu);
  json_object_set_new(o, "transmission_angle_is", json_string(MU_IS));
}

/* the designer's slides and transmission angles as text */
static void designer_text(FILE *f, const fb_planar *m, const fb_planar_designer *d) {
  const double deg = 1.0 / FB_RAD_PER_DEG;
  if (d->npoints > 0)
    fprintf(f, "| point | x min [m] | x max [m] | y min [m] | y max [m] | speed max [m/s] | at [deg] "
               "| acceleration max [m/s^2] | at [deg] |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (int i = 0; i < d->npoints; i++) {
    const fb_planar_point_kin *k = &d->point[i];
    fprintf(f, "| %s | %s | %s | %s | %s | %s | %.2f | %s | %.2f |\n", m->point[i].name,
            CELL(k->q[0].min), CELL(k->q[0].max), CELL(k->q[1].min), CELL(k->q[1].max),
            CELL(k->speed.max), k->speed.at_max * deg, CELL(k->accel.max), k->accel.at_max * deg);
  }
  for (int i = 0; i < d->nslides; i++) {
    const fb_planar_slide_kin *k = &d->slide[i];
    fprintf(f, "slide '%s': stroke %.6f mm between the dead centres:\n"
               "  outer %.6f mm at drive angle %.4f deg\n  inner %.6f mm at drive angle %.4f deg\n"
               "quick-return ratio %.6f (slower stroke's time over the faster's): outstroke "
               "(inner to outer) %.4f deg of drive, %.6g s; return %.4f deg, %.6g s\n"
               "  velocity %s to %s m/s, acceleration %s to %s m/s^2\n",
            m->joint[k->joint].name, k->stroke / FB_M_PER_MM, k->pos.max / FB_M_PER_MM,
            k->pos.at_max * deg, k->pos.min / FB_M_PER_MM, k->pos.at_min * deg, k->quick_return_ratio,
            k->outstroke_angle * deg, k->outstroke_time, k->return_angle * deg, k->return_time,
            CELL(k->vel.min), CELL(k->vel.max), CELL(k->acc.min), CELL(k->acc.max));
  }
  if (d->ntransmissions == 0) {
    fprintf(f, "transmission angle: undefined (no binary link drives another moving body)\n");
    return;
  }
  fprintf(f, "transmission angle (90 deg - |pressure angle| where a binary link drives a body):\n"
             "| joint | link | driven | min [deg] | at [deg] | max [deg] | at [deg] |\n"
             "|---|---|---|---:|---:|---:|---:|\n");
  for (int i = 0; i < d->ntransmissions; i++) {
    const fb_planar_transmission_kin *t = &d->transmission[i];
    fprintf(f, "| %s | %s | %s | %.4f | %.2f | %.4f | %.2f |\n", m->joint[t->at.joint].name,
            m->body[t->at.link].name, m->body[t->at.driven].name, t->mu.min * deg,
            t->mu.at_min * deg, t->mu.max * deg, t->mu.at_max * deg);
  }
}

void fb_report_planar_kinematics(FILE *f, const fb_case *c, const fb_planar *m,
                                 const fb_planar_peaks *p, const fb_planar_designer *d,
                                 int json) {
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
    designer_json(o, m, d);
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
  designer_text(f, m, d);
}

fb_status fb_report_planar_penalty_files(const char *out, const fb_planar *m,
                                         const fb_planar_penalty_row *rows, const int *n,
                                         const double *rpm, int nspeeds, int *figure_ok,
                                         fb_diag *fig_diag, fb_diag *diag) {
  const int nj = nspeeds > 0 ? n[0] : 0; /* every revolute joint, at every speed */
  for (int s = 1; s < nspeeds; s++)
    if (n[s] != nj)
      return fb_diag_set(diag, FB_ERR_ARG, "penalty rows: %d joints at %g rpm, %d at %g rpm",
                         n[s], rpm[s], nj, rpm[0]);
  const size_t ns = (size_t)(nspeeds ? nspeeds : 1);
  double *col = malloc(4 * (size_t)(nj ? nj : 1) * ns * sizeof *col);
  const double **c = malloc(4 * (size_t)(nj ? nj : 1) * sizeof *c);
  const char **name = malloc((size_t)(nj ? nj : 1) * sizeof *name);
  fb_status st = col && c && name ? FB_OK : fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  for (int k = 0; k < nj && st == FB_OK; k++) {
    double *f = col + (size_t)(4 * k) * ns, *kc = f + ns, *p = kc + ns, *d = p + ns;
    for (int s = 0; s < nspeeds; s++) {
      const fb_planar_penalty_row *r = &rows[(size_t)s * (size_t)m->njoints + (size_t)k];
      f[s] = r->force;
      kc[s] = r->stiffness;
      p[s] = r->penalty;
      d[s] = r->approach;
    }
    c[k] = f;
    c[nj + k] = kc;
    c[2 * nj + k] = p;
    c[3 * nj + k] = d;
    name[k] = m->joint[rows[k].joint].name;
  }
  if (st == FB_OK)
    st = fb_report_penalty_columns(out, "physical", "drive speed", nspeeds, rpm, nj, name, c,
                                   c + nj, c + 2 * nj, c + 3 * nj, figure_ok, fig_diag, diag);
  free(col);
  free(c);
  free(name);
  return st;
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
            FB_H_OMEGA_C_BOUND, e->rates.limit);
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
  json_object_set_new(o, "samples_unassembled", json_integer((json_int_t)s->mc.unassembled));
  json_object_set_new(o, "samples_unassembled_first",
                      s->mc.unassembled ? json_string(s->mc.unassembled_msg) : json_null());
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
  if (s->mc.unassembled)
    fprintf(f, "%zu more samples cannot assemble or turn a revolution and are left out of the "
            "statistics, which are over the %zu that do (the first, sample %zu: %s)\n",
            s->mc.unassembled, s->mc.samples, s->mc.unassembled_first, s->mc.unassembled_msg);
}

/* fb_planar_dim_kind's names in JSON and the table */
static const char *const DIM_KIND[] = {"distance", "offset", "angle"};

/* dimension L of m as JSON: a distance's or an offset's nominal_m and
 * plus_minus_m, an angle's nominal_rad and plus_minus_rad */
static json_t *length_json(const fb_planar *m, const fb_planar_length *L) {
  const int angle = L->kind == FB_PLANAR_DIM_ANGLE;
  json_t *o = json_pack("{s:s,s:s,s:o,s:s}", "body", m->body[L->body].name, "kind",
                        DIM_KIND[L->kind], "from",
                        L->joint[0] >= 0 ? json_string(m->joint[L->joint[0]].name) : json_null(),
                        "to", m->joint[L->joint[1]].name);
  json_object_set_new(o, angle ? "nominal_rad" : "nominal_m", num(L->nominal));
  json_object_set_new(o, angle ? "plus_minus_rad" : "plus_minus_m", num(L->plus_minus));
  json_object_set_new(o, "source", json_string(L->source));
  return o;
}

void fb_report_planar_stackup(FILE *f, const fb_case *c, const fb_planar *m,
                              const fb_planar_stackup *s, int json) {
  char name[128];
  if (json) {
    json_t *o = json_object(), *lengths = json_array(), *outs = json_array();
    json_object_set_new(o, "case", json_string(c->name));
    json_object_set_new(o, "mechanism", json_string("planar"));
    for (int k = 0; k < s->nlengths; k++) json_array_append_new(lengths, length_json(m, &s->length[k]));
    for (int i = 0; i < s->nout; i++) {
      json_t *per_m = json_array(), *per_rad = json_array();
      for (int k = 0; k < s->nlengths; k++) {
        const int angle = s->length[k].kind == FB_PLANAR_DIM_ANGLE;
        json_array_append_new(per_m, angle ? json_null() : num(s->sens[i * s->nlengths + k]));
        json_array_append_new(per_rad, angle ? num(s->sens[i * s->nlengths + k]) : json_null());
      }
      json_array_append_new(
          outs, json_pack("{s:s,s:o,s:o,s:o,s:{s:o,s:o},s:o}", "name",
                          fb_planar_output_name(name, sizeof name, m, i), "nominal",
                          num(s->nominal[i]), "sensitivity_per_m", per_m, "sensitivity_per_rad",
                          per_rad, "rss", "low",
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
    json_object_set_new(o, "corners_unassembled", json_integer(s->corners_unassembled));
    json_object_set_new(o, "corners_unassembled_first", s->corners_unassembled
                                                            ? json_string(s->unassembled_first)
                                                            : json_null());
    json_object_set_new(o, "outputs", outs);
    dump(f, o);
    return;
  }
  fprintf(f, "%s: planar, %d dimensions (each body's joint-to-joint distances, a slot's or "
          "guide's offset and angle)\n| body | dimension | from | to | nominal | +- | source |\n"
          "|---|---|---|---|---:|---:|---|\n", c->name, s->nlengths);
  for (int k = 0; k < s->nlengths; k++) {
    const fb_planar_length *L = &s->length[k];
    const int angle = L->kind == FB_PLANAR_DIM_ANGLE;
    const double unit = angle ? M_PI / 180.0 : FB_M_PER_MM;
    fprintf(f, "| %s | %s | %s | %s | %.6g %s | %.4g %s | %s |\n", m->body[L->body].name,
            DIM_KIND[L->kind], L->joint[0] >= 0 ? m->joint[L->joint[0]].name : "+x",
            m->joint[L->joint[1]].name, L->nominal / unit, angle ? "deg" : "mm",
            L->plus_minus / unit, angle ? "deg" : "mm", L->source);
  }
  if (s->corners_unassembled)
    fprintf(f, "\n%lld of the %lld corners cannot assemble or turn a revolution, so the worst "
            "case is over the other %lld (the first: %s)", s->corners_unassembled,
            s->corners + s->corners_unassembled, s->corners, s->unassembled_first);
  if (s->corners)
    fprintf(f, "\nworst case over %s %lld corners (at: one sign per length, in the order above); "
            "RSS band 3 sigma\n", s->corners_unassembled ? "the" : "all", s->corners);
  else if (s->corners_unassembled)
    fprintf(f, "\nno corner assembles; RSS band 3 sigma\n");
  else
    fprintf(f, "\nworst case not run (--method corners runs its %.0f corners); RSS band 3 sigma\n",
            pow(2.0, fb_planar_stackup_varied(s)));
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
