/* fourbar penalty's output (tables_penalty.h). */
#include "tables_penalty.h"

#include <jansson.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fileio.h"
#include "figures.h"
#include "report.h"
#include "units.h"

static const char *mode_name(fb_penalty_mode m) { return m == FB_PENALTY_PAPER ? "paper" : "physical"; }

/* P in both units of row r in mode m: *p_mm [N mm^0.5], *p_m [N m^0.5] */
static void penalty_units(const fb_penalty_row *r, fb_penalty_mode m, double *p_mm, double *p_m) {
  /* P = Kc C^1.5 is N m^0.5 in SI; 1 N mm^0.5 = sqrt(1e-3) N m^0.5 */
  *p_mm = m == FB_PENALTY_PAPER ? r->penalty : r->penalty / sqrt(FB_M_PER_MM);
  *p_m = m == FB_PENALTY_PAPER ? r->penalty * sqrt(FB_M_PER_MM) : r->penalty;
}

/* the name of the study's pin joint j (penalty.h fb_penalty_joint) */
static const char *joint_name(const fb_penalty_study *s, fb_pin_joint j) {
  const fb_mech_desc *m = fb_mech_of(s->mech);
  return fb_mech_joint_name(m, fb_penalty_joint(m, j));
}

/* which force the table's is (the contact block's expected impact force is another) */
static const char *force_is(fb_penalty_mode m) {
  return m == FB_PENALTY_PAPER
             ? "the paper's F = k max|alpha| over a revolution, nominal lengths (its Table I "
               "recipe, docs/paper.md)"
             : "the joint's largest ideal reaction over a revolution (inverse dynamics of the "
               "rigid linkage, nominal lengths, gravity included)";
}

void fb_report_penalty_table(FILE *f, const fb_penalty_study *s, const fb_case *c) {
  const fb_penalty_mode mode = s->mode;
  if (s->rows_skipped) {
    fprintf(f, "%s mode, case %s: no table: %s\n", mode_name(mode), c->name, s->rows_skipped);
    return;
  }
  fprintf(f, "%s mode, case %s\n%8s  %-17s %12s %16s %14s %14s %12s\n"
          "%8s  %-17s %12s %16s %14s %14s %12s\n",
          mode_name(mode), c->name, "speed", "joint",
          mode == FB_PENALTY_PAPER ? "force F" : "reaction", "stiffness Kc", "penalty P",
          "penalty P", "approach", "rpm", "", "N", "N/m", "N mm^0.5", "N m^0.5", "um");
  for (int i = 0; i < s->n_ok; i++)
    for (int j = 0; j < FB_PENALTY_PIN_JOINTS; j++) {
      const fb_penalty_row *r = &s->rows[i][j];
      double p_mm, p_m;
      penalty_units(r, mode, &p_mm, &p_m);
      fprintf(f, "%8g  %-17s %12.6g %16.6e %14.6g %14.6g %12.6g\n", s->rpm[i],
              joint_name(s, r->joint), r->force, r->stiffness, p_mm, p_m,
              r->approach / FB_M_PER_UM);
    }
  if (s->rows_status != FB_OK) return;
  fprintf(f, "%s: %s; Kc, P and the approach are taken at it\n",
          mode == FB_PENALTY_PAPER ? "force F" : "reaction", force_is(mode));
}

fb_status fb_report_penalty_columns(const char *out, const char *mode, const char *speed, int n,
                                    const double *rpm, int njoints, const char *const *joint,
                                    const double *const *force, const double *const *stiffness,
                                    const double *const *penalty_n_m0_5,
                                    const double *const *approach_m, int *figure_ok,
                                    fb_diag *fig_diag, fb_diag *diag) {
  char path[4096];
  snprintf(path, sizeof path, "%s/penalty_%s.csv", out, mode);
  fb_outfile of;
  fb_status st = fb_outfile_open(&of, path, diag);
  if (st != FB_OK) return st;
  fprintf(of.f, "speed_rpm,joint,force_n,stiffness_n_m,penalty_n_mm0_5,penalty_n_m0_5,approach_um\n");
  for (int i = 0; i < n; i++)
    for (int j = 0; j < njoints; j++)
      fprintf(of.f, "%.10g,%s,%.12g,%.12g,%.12g,%.12g,%.12g\n", rpm[i], joint[j], force[j][i],
              stiffness[j][i], penalty_n_m0_5[j][i] / sqrt(FB_M_PER_MM), penalty_n_m0_5[j][i],
              approach_m[j][i] / FB_M_PER_UM);
  if ((st = fb_outfile_commit(&of, diag)) != FB_OK) return st;
  /* the figure: P in the mode's unit (paper: N mm^0.5), the approach in um */
  const int paper = strcmp(mode, "paper") == 0;
  double *col = malloc(2 * (size_t)njoints * (size_t)(n ? n : 1) * sizeof *col);
  const double **p = malloc(2 * (size_t)njoints * sizeof *p);
  if (!col || !p) {
    free(col);
    free(p);
    *figure_ok = 0;
    fb_diag_set(fig_diag, FB_ERR_NOMEM, "out of memory for the penalty figure");
    return FB_OK;
  }
  for (int j = 0; j < njoints; j++) {
    double *pj = col + (size_t)(2 * j) * (size_t)n, *dj = pj + n;
    for (int i = 0; i < n; i++) {
      pj[i] = paper ? penalty_n_m0_5[j][i] / sqrt(FB_M_PER_MM) : penalty_n_m0_5[j][i];
      dj[i] = approach_m[j][i] / FB_M_PER_UM;
    }
    p[j] = pj;
    p[njoints + j] = dj;
  }
  snprintf(path, sizeof path, "%s/penalty_%s.svg", out, mode);
  *figure_ok = fb_figures_penalty(path, FB_FIGURE_SVG, mode, speed, n, rpm, njoints, force,
                                  stiffness, p, p + njoints, joint, fig_diag) == FB_OK;
  free(col);
  free(p);
  return FB_OK;
}

fb_status fb_report_penalty_files(const char *out, const fb_penalty_study *s, int *figure_ok,
                                  fb_diag *fig_diag, fb_diag *diag) {
  enum { J = FB_PENALTY_PIN_JOINTS, N = FB_PENALTY_SPEEDS_MAX };
  static double col_f[J][N], col_k[J][N], col_pm[J][N], col_d[J][N];
  const int n = s->n_ok;
  for (int i = 0; i < n; i++)
    for (int j = 0; j < J; j++) {
      const fb_penalty_row *r = &s->rows[i][j];
      double p_mm;
      penalty_units(r, s->mode, &p_mm, &col_pm[j][i]);
      col_f[j][i] = r->force;
      col_k[j][i] = r->stiffness;
      col_d[j][i] = r->approach;
    }
  const double *f[J], *k[J], *pm[J], *d[J];
  const char *names[J];
  for (int j = 0; j < J; j++) {
    f[j] = col_f[j];
    k[j] = col_k[j];
    pm[j] = col_pm[j];
    d[j] = col_d[j];
    names[j] = joint_name(s, (fb_pin_joint)j);
  }
  return fb_report_penalty_columns(out, mode_name(s->mode), "crank speed", n, s->rpm, J, names,
                                   f, k, pm, d, figure_ok, fig_diag, diag);
}

/* the rule that turned the case's penalty source into the laws' stiffness */
static const char *stiffness_rule(const fb_case *c) {
  switch (c->clearance.penalty) {
    case FB_PENALTY_SOURCE_PHYSICAL:
      return "physical: F_j = the joint's largest inverse-dynamics reaction over a revolution, "
             "delta_j = Johnson's pin-in-hole approach at F_j; impact law K = F_j / delta_j^n "
             "(secant through Johnson's curve), restitution law p = dF/d delta at F_j (tangent)";
    case FB_PENALTY_SOURCE_PAPER:
      return "paper: Kc (Eq. 7) read as N/mm^1.5 for the impact law (n = 1.5), P read as N/mm "
             "for the restitution law";
    case FB_PENALTY_SOURCE_GOLDSMITH:
      return "goldsmith: paper Eq. 3-5, K = 4 / (3 (s1 + s2)) sqrt(R_pin R_hole / (R_hole - "
             "R_pin)), s_i = (1 - nu_i^2) / E_i, for the impact law (n = 1.5); restitution law "
             "p = dF/d delta of K delta^1.5 at the joint's largest inverse-dynamics reaction";
    default: return "explicit: the case's stiffness keys";
  }
}

void fb_report_penalty_contact_text(FILE *f, const fb_penalty_study *s) {
  if (!s->has_contact) return;
  const fb_case *c = &s->run_case;
  const fb_linkage *su = &s->stackup;
  const fb_mech_desc *mech = fb_case_mech(c);
  char lengths[256];
  size_t n = 0;
  lengths[0] = '\0';
  for (int k = 0; k < mech->nlengths && n < sizeof lengths; k++)
    n += (size_t)snprintf(lengths + n, sizeof lengths - n, "%s%s %.6g", k ? ", " : "",
                          mech->length[k], su->length[k] * 1e3);
  fprintf(f, "\ncontact a fourbar run of %s uses (stack-up lengths, corner %s: %s mm; %s):\n",
          c->name, s->corner, lengths, stiffness_rule(c));
  for (int j = 0; j < 4; j++)
    for (int m = 0; m < 2; m++) {
      if (!(c->clearance.mask & (1 << j))) continue;
      const fb_contact_estimate *e = &s->est[m][j];
      fb_report_print_contact_law(f, fb_case_joint_name(c, j), &s->laws[m][j], s->mapping);
      fprintf(f, "  %-17s %-12s effective mass %.4g .. %.4g kg over a revolution, expected "
              "impact force %.6g N (%g x the ideal reaction %.6g N), omega_c %.4g rad/s, "
              "damper c / m_eff %.4g 1/s\n",
              "", "", e->m_eff_min, e->m_eff_max, e->force_expected, FB_IMPACT_LOAD_FACTOR,
              e->force_expected / FB_IMPACT_LOAD_FACTOR, e->omega_c, e->rates.damper_rate);
    }
  fprintf(f, "expected impact force: %g x the joint's largest ideal reaction at the stack-up "
          "lengths (a load applied suddenly peaks at twice its static value), at %.6g rpm; it "
          "sets omega_c = sqrt(k_t / m_eff_min)\n",
          FB_IMPACT_LOAD_FACTOR, c->crank_speed / FB_RAD_S_PER_RPM);
  fprintf(f, "[solver] h_s = auto: h = %.4g s (h x rate <= %g at the fastest contact, its rate "
          "(the larger of omega_c and c / m_eff) %.4g 1/s; at most one revolution / %g)%s\n",
          s->h_auto, FB_H_OMEGA_C_BOUND, s->omega_c, FB_H_AUTO_STEPS_PER_REV,
          c->solver.h_mode == FB_STEP_FIXED ? "; this case fixes h_s instead" : "");
}

static void contact_json(json_t *out, const fb_penalty_study *s) {
  const fb_case *c = &s->run_case;
  json_t *arr = json_array();
  for (int j = 0; j < 4; j++)
    for (int m = 0; m < 2; m++) {
      if (!(c->clearance.mask & (1 << j))) continue;
      const fb_contact_estimate *e = &s->est[m][j];
      json_t *o = fb_report_contact_law_json(fb_case_joint_name(c, j), &s->laws[m][j], s->mapping);
      json_object_set_new(o, "model", json_string(s->contact_models[m]));
      json_object_set_new(o, "effective_mass_estimate_kg",
                          json_pack("{s:f,s:f}", "min", e->m_eff_min, "max", e->m_eff_max));
      json_object_set_new(o, "force_expected_n", json_real(e->force_expected));
      json_object_set_new(o, "reaction_stackup_n",
                          json_real(e->force_expected / FB_IMPACT_LOAD_FACTOR));
      json_object_set_new(o, "omega_c_rad_s", json_real(e->omega_c));
      json_array_append_new(arr, o);
    }
  json_object_set_new(out, "contact", arr);
  json_object_set_new(out, "contact_lengths", json_string("stack-up"));
  json_object_set_new(out, "contact_stackup_corner", json_string(s->corner));
  json_object_set_new(out, "contact_rule", json_string(stiffness_rule(c)));
  json_object_set_new(out, "h_auto_s", json_real(s->h_auto));
  json_object_set_new(out, "force_expected_is",
                      json_string("impact load factor x reaction_stackup_n, the joint's largest "
                                  "ideal reaction over a revolution at the stack-up lengths"));
  json_object_set_new(out, "impact_load_factor", json_real(FB_IMPACT_LOAD_FACTOR));
  json_object_set_new(out, "h_omega_c_bound", json_real(FB_H_OMEGA_C_BOUND));
}

void fb_report_penalty_json(FILE *f, const fb_penalty_study *s, const fb_case *c) {
  json_t *rows = json_array();
  for (int i = 0; i < s->n_ok; i++)
    for (int j = 0; j < FB_PENALTY_PIN_JOINTS; j++) {
      const fb_penalty_row *r = &s->rows[i][j];
      double p_mm, p_m;
      penalty_units(r, s->mode, &p_mm, &p_m);
      json_t *o = json_object();
      json_object_set_new(o, "speed_rpm", json_real(s->rpm[i]));
      json_object_set_new(o, "joint", json_string(joint_name(s, r->joint)));
      json_object_set_new(o, "force_n", json_real(r->force));
      json_object_set_new(o, "stiffness_n_m", json_real(r->stiffness));
      json_object_set_new(o, "penalty", json_real(r->penalty)); /* unit: penalty_units */
      json_object_set_new(o, "penalty_n_mm0_5", json_real(p_mm));
      json_object_set_new(o, "penalty_n_m0_5", json_real(p_m));
      json_object_set_new(o, "approach_um", json_real(r->approach / FB_M_PER_UM));
      json_array_append_new(rows, o);
    }
  json_t *o = json_object();
  json_object_set_new(o, "mode", json_string(mode_name(s->mode)));
  json_object_set_new(o, "case", json_string(c->name));
  json_object_set_new(o, "penalty_units", json_string(s->mode == FB_PENALTY_PAPER
                                                          ? "N mm^0.5 (paper)" : "N m^0.5"));
  json_object_set_new(o, "force_n_is", json_string(force_is(s->mode)));
  json_object_set_new(o, "rows", rows);
  if (s->rows_skipped) json_object_set_new(o, "rows_skipped", json_string(s->rows_skipped));
  if (s->has_contact) contact_json(o, s);
  json_dumpf(o, f, JSON_INDENT(2) | JSON_REAL_PRECISION(12));
  fputc('\n', f);
  json_decref(o);
}
