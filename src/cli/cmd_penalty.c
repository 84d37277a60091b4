/* fourbar penalty: argument parsing and dispatch only. */
#include <getopt.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "casefile.h"
#include "cli.h"
#include "figures.h"
#include "fileio.h"
#include "penalty.h"
#include "report.h"
#include "resolution.h"
#include "scene_def.h"
#include "units.h"

#define MAX_SPEEDS 1000
/* the speeds of the paper's Tables I to III (--table) */
#define PAPER_SPEEDS_RPM "100:1500:100"
#define MAX_SETS 256

static const char penalty_help[] =
    "usage: fourbar penalty [CASE] [--mode paper|physical]\n"
    "                       [--speeds-rpm LIST | --table]\n"
    "                       [--set section.key=value]... [--json] [--out DIR]\n"
    "\n"
    "Contact stiffness Kc (paper Eq. 7), penalty parameter P = Kc C^1.5 (Eq. 9)\n"
    "and mutual approach at the case's crank speed (or per speed of a list), for\n"
    "the crank-coupler and coupler-follower joints.\n"
    "\n"
    "  --mode physical  inverse-dynamics joint reaction, the case's radial\n"
    "                   clearance and pin length, Johnson's line contact\n"
    "  --mode paper     the recipe that reproduces the paper's Tables I to III\n"
    "                   (docs/paper.md)\n"
    "                   default: the case's [clearance] penalty, as fourbar run\n"
    "                   uses it (physical unless the case says paper)\n"
    "  --speeds-rpm     FROM:TO:STEP or a comma list (default: the case's\n"
    "                   [drive] speed_rpm)\n"
    "  --table          the paper's speeds, 100:1500:100 rpm (its Tables I to III)\n"
    "  --out DIR        also write DIR/penalty_<mode>.csv and the figure\n"
    "                   DIR/penalty_<mode>.svg (force, stiffness, penalty, approach\n"
    "                   against speed: the paper's Figures 2 to 4)\n"
    "  CASE             default: the paper's case\n"
    "P is printed in both units, N mm^0.5 (the paper's Table II) and N m^0.5\n"
    "(SI): columns penalty_n_mm0_5 and penalty_n_m0_5 in every mode.\n"
    "Two forces, two purposes. The table's force is the load Kc is taken at:\n"
    "physical mode, the joint's largest ideal reaction over a revolution (inverse\n"
    "dynamics of the rigid linkage at its nominal lengths, gravity included);\n"
    "paper mode, the paper's F = k max|alpha| (docs/paper.md). The contact block's\n"
    "expected impact force is twice the largest ideal reaction at the stack-up\n"
    "corner's lengths (a load applied suddenly peaks at twice its static value);\n"
    "it sets the contact frequency omega_c and so the automatic step.\n"
    "Then, for a case with clearance joints, the contact a fourbar run of the case\n"
    "uses (the same code path: its laws, stiffness and damping per joint, which\n"
    "lengths and which rule), the effective-mass range, expected impact force and\n"
    "contact frequency, and the step [solver] h_s = auto gives (JSON: \"contact\").\n"
    "Exit status: 0 ok, 1 failed, 2 bad input.\n";

static int parse_speeds(const char *text, double *out, int *n) {
  double a, b, s;
  char tail;
  *n = 0;
  if (sscanf(text, "%lf:%lf:%lf%c", &a, &b, &s, &tail) == 3) {
    if (!(s > 0) || !(b >= a) || !(a > 0) || (b - a) / s > MAX_SPEEDS) return 0;
    for (double v = a; v <= b + 1e-9 * s && *n < MAX_SPEEDS; v = a + s * (*n)) out[(*n)++] = v;
    return *n > 0;
  }
  char buf[4096];
  snprintf(buf, sizeof buf, "%s", text);
  char *save = NULL;
  for (char *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
    char *end;
    double v = strtod(tok, &end);
    if (end == tok || *end != '\0' || !(v > 0) || !isfinite(v) || *n == MAX_SPEEDS) return 0;
    out[(*n)++] = v;
  }
  return *n > 0;
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

/* the contact a run of case c uses, through the run's own law resolution */
static int contact_used(const fb_case *in, int json, json_t *out) {
  if (!in->clearance.mask) return 0;
  /* the scene stage a run goes through, with both clearance laws asked for */
  static fb_case c;
  static fb_scene_def def;
  c = *in;
  c.model_count = 2;
  snprintf(c.models[0], FB_NAME_SIZE, "ode-clearance-impact");
  snprintf(c.models[1], FB_NAME_SIZE, "ode-clearance-restitution");
  fb_diag d;
  if (fb_scene_def_from_case(&def, &c, &d) != FB_OK) return fb_cli_fail("penalty", 1, "%s", d.msg);
  c = def.source;
  fb_contact_law laws[2][4];
  fb_contact_estimate est[2][4];
  memcpy(laws[0], def.law[FB_MODEL_LAW_IMPACT], sizeof laws[0]);
  memcpy(laws[1], def.law[FB_MODEL_LAW_RESTITUTION], sizeof laws[1]);
  for (int m = 0; m < 2; m++)
    if (fb_contact_estimates(est[m], &c, laws[m], &d) != FB_OK)
      return fb_cli_fail("penalty", 1, "%s", d.msg);
  double h, w;
  if (fb_step_auto(&h, &w, &c, &d) != FB_OK) return fb_cli_fail("penalty", 1, "%s", d.msg);
  const fb_linkage su = def.lengths[FB_LENGTHS_STACKUP];
  char corner[FB_LINK_COUNT + 1];
  for (int k = 0; k < FB_LINK_COUNT; k++) corner[k] = "-0+"[c.stackup.corner[k] + 1];
  corner[FB_LINK_COUNT] = '\0';
  const fb_mapping mapping = (fb_mapping)c.clearance.mapping;
  if (json) {
    json_t *arr = json_array();
    for (int j = 0; j < 4; j++)
      for (int m = 0; m < 2; m++) {
        if (!(c.clearance.mask & (1 << j))) continue;
        json_t *o = fb_report_contact_law_json(j, &laws[m][j], mapping);
        json_object_set_new(o, "model", json_string(m == 0 ? "ode-clearance-impact" : "ode-clearance-restitution"));
        json_object_set_new(o, "effective_mass_estimate_kg",
                            json_pack("{s:f,s:f}", "min", est[m][j].m_eff_min, "max", est[m][j].m_eff_max));
        json_object_set_new(o, "force_expected_n", json_real(est[m][j].force_expected));
        json_object_set_new(o, "reaction_stackup_n",
                            json_real(est[m][j].force_expected / FB_IMPACT_LOAD_FACTOR));
        json_object_set_new(o, "omega_c_rad_s", json_real(est[m][j].omega_c));
        json_array_append_new(arr, o);
      }
    json_object_set_new(out, "contact", arr);
    json_object_set_new(out, "contact_lengths", json_string("stack-up"));
    json_object_set_new(out, "contact_stackup_corner", json_string(corner));
    json_object_set_new(out, "contact_rule", json_string(stiffness_rule(&c)));
    json_object_set_new(out, "h_auto_s", json_real(h));
    json_object_set_new(out, "force_expected_is",
                        json_string("impact load factor x reaction_stackup_n, the joint's largest "
                                    "ideal reaction over a revolution at the stack-up lengths"));
    json_object_set_new(out, "impact_load_factor", json_real(FB_IMPACT_LOAD_FACTOR));
    json_object_set_new(out, "h_omega_c_bound", json_real(FB_H_OMEGA_C_BOUND));
    return 0;
  }
  printf("\ncontact a fourbar run of %s uses (stack-up lengths, corner %s: crank %.6g, coupler "
         "%.6g, follower %.6g, ground %.6g mm; %s):\n",
         c.name, corner, su.length[0] * 1e3, su.length[1] * 1e3, su.length[2] * 1e3,
         su.length[3] * 1e3, stiffness_rule(&c));
  for (int j = 0; j < 4; j++)
    for (int m = 0; m < 2; m++) {
      if (!(c.clearance.mask & (1 << j))) continue;
      fb_report_print_contact_law(stdout, j, &laws[m][j], mapping);
      printf("  %-17s %-12s effective mass %.4g .. %.4g kg over a revolution, expected impact "
             "force %.6g N (%g x the ideal reaction %.6g N), omega_c %.4g rad/s\n",
             "", "", est[m][j].m_eff_min, est[m][j].m_eff_max, est[m][j].force_expected,
             FB_IMPACT_LOAD_FACTOR, est[m][j].force_expected / FB_IMPACT_LOAD_FACTOR,
             est[m][j].omega_c);
    }
  printf("expected impact force: %g x the joint's largest ideal reaction at the stack-up "
         "lengths (a load applied suddenly peaks at twice its static value), at %.6g rpm; it "
         "sets omega_c = sqrt(k_t / m_eff_min)\n",
         FB_IMPACT_LOAD_FACTOR, c.crank_speed / FB_RAD_S_PER_RPM);
  printf("[solver] h_s = auto: h = %.4g s (h omega_c <= %g at the stiffest contact, omega_c = "
         "%.4g rad/s; at most one revolution / %g)%s\n",
         h, FB_H_OMEGA_C_BOUND, w, FB_H_AUTO_STEPS_PER_REV,
         c.solver.h_mode == FB_STEP_FIXED ? "; this case fixes h_s instead" : "");
  return 0;
}

int fb_cmd_penalty(int argc, char **argv) {
  static const struct option opts[] = {{"mode", required_argument, 0, 'm'},
                                       {"speeds-rpm", required_argument, 0, 's'},
                                       {"table", no_argument, 0, 'T'},
                                       {"set", required_argument, 0, 'S'},
                                       {"json", no_argument, 0, 'j'},
                                       {"out", required_argument, 0, 'o'},
                                       {"help", no_argument, 0, 'h'},
                                       {0, 0, 0, 0}};
  int mode_given = 0;
  fb_penalty_mode mode = FB_PENALTY_PHYSICAL;
  static double rpm[MAX_SPEEDS];
  int n = 0, json = 0, nsets = 0, ch, speeds_given = 0;
  const char *out_dir = NULL;
  const char *sets[MAX_SETS];
  optind = 1;
  while ((ch = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
    switch (ch) {
      case 'm':
        if (strcmp(optarg, "paper") == 0) mode = FB_PENALTY_PAPER;
        else if (strcmp(optarg, "physical") == 0) mode = FB_PENALTY_PHYSICAL;
        else return fb_cli_fail("penalty", 2, "--mode '%s': must be paper or physical", optarg);
        mode_given = 1;
        break;
      case 'T':
      case 's':
        if (speeds_given)
          return fb_cli_fail("penalty", 2, "give the speeds once: --speeds-rpm or --table");
        speeds_given = 1;
        if (ch == 'T') {
          parse_speeds(PAPER_SPEEDS_RPM, rpm, &n);
          break;
        }
        if (!parse_speeds(optarg, rpm, &n))
          return fb_cli_fail("penalty", 2,
                             "--speeds-rpm '%s': expected FROM:TO:STEP or a comma list of "
                             "positive speeds (at most %d)",
                             optarg, MAX_SPEEDS);
        /* each speed within the range a case's [drive] speed_rpm has */
        for (int k = 0; k < n; k++) {
          fb_diag rd;
          if (fb_casefile_check_range("drive", "speed_rpm", rpm[k], "--speeds-rpm", &rd) != FB_OK)
            return fb_cli_fail("penalty", 2, "%s", rd.msg);
        }
        break;
      case 'S':
        if (nsets == MAX_SETS) return fb_cli_fail("penalty", 2, "more than %d --set", MAX_SETS);
        sets[nsets++] = optarg;
        break;
      case 'j': json = 1; break;
      case 'o': out_dir = optarg; break;
      case 'h': fputs(penalty_help, stdout); return 0;
      default: return fb_cli_bad_option(argv, "h");
    }
  }
  fb_case c;
  fb_diag diag;
  char case_path[4096];
  int rc = fb_cli_load_case("penalty", argc, argv, optind, sets, nsets, &c, case_path, sizeof case_path);
  if (rc) return rc;
  /* one default with fourbar run: the case's penalty source (explicit
   * stiffness has no estimate to show: physical) */
  if (!mode_given)
    mode = c.clearance.penalty == FB_PENALTY_SOURCE_PAPER ? FB_PENALTY_PAPER : FB_PENALTY_PHYSICAL;
  /* one speed by default: the case's, the one its run and contact block use */
  if (!speeds_given) {
    rpm[0] = c.crank_speed / FB_RAD_S_PER_RPM;
    n = 1;
  }

  if (out_dir && fb_outdir_prepare(out_dir, &diag) != FB_OK)
    return fb_cli_fail("penalty", 1, "%s", diag.msg);
  static double col_f[2][MAX_SPEEDS], col_k[2][MAX_SPEEDS], col_p[2][MAX_SPEEDS], col_d[2][MAX_SPEEDS],
      col_pm[2][MAX_SPEEDS];
  json_t *rows = json_array();
  const char *unit = mode == FB_PENALTY_PAPER ? "N mm^0.5 (paper)" : "N m^0.5";
  if (!json)
    printf("%s mode, case %s\n%8s  %-17s %12s %16s %14s %14s %12s\n"
           "%8s  %-17s %12s %16s %14s %14s %12s\n",
           mode == FB_PENALTY_PAPER ? "paper" : "physical", c.name, "speed", "joint",
           mode == FB_PENALTY_PAPER ? "force F" : "reaction",
           "stiffness Kc", "penalty P", "penalty P", "approach", "rpm", "", "N", "N/m", "N mm^0.5",
           "N m^0.5", "um");
  for (int i = 0; i < n; i++) {
    fb_penalty_row r[2];
    if (fb_penalty_rows(r, &c, mode, rpm[i] * FB_RAD_S_PER_RPM, &diag) != FB_OK) {
      json_decref(rows);
      return fb_cli_fail("penalty", 1, "%s", diag.msg);
    }
    for (int j = 0; j < 2; j++) {
      const double approach_um = r[j].approach / FB_M_PER_UM;
      /* P = Kc C^1.5 is N m^0.5 in SI; 1 N mm^0.5 = sqrt(1e-3) N m^0.5 */
      const double p_mm = mode == FB_PENALTY_PAPER ? r[j].penalty : r[j].penalty / sqrt(FB_M_PER_MM);
      const double p_m = mode == FB_PENALTY_PAPER ? r[j].penalty * sqrt(FB_M_PER_MM) : r[j].penalty;
      col_pm[j][i] = p_m;
      col_f[j][i] = r[j].force;
      col_k[j][i] = r[j].stiffness;
      col_p[j][i] = r[j].penalty;
      col_d[j][i] = approach_um;
      if (json) {
        json_t *o = json_object();
        json_object_set_new(o, "speed_rpm", json_real(rpm[i]));
        json_object_set_new(o, "joint", json_string(fb_pin_joint_name(r[j].joint)));
        json_object_set_new(o, "force_n", json_real(r[j].force));
        json_object_set_new(o, "stiffness_n_m", json_real(r[j].stiffness));
        json_object_set_new(o, "penalty", json_real(r[j].penalty)); /* unit: penalty_units */
        json_object_set_new(o, "penalty_n_mm0_5", json_real(p_mm));
        json_object_set_new(o, "penalty_n_m0_5", json_real(p_m));
        json_object_set_new(o, "approach_um", json_real(approach_um));
        json_array_append_new(rows, o);
      } else {
        printf("%8g  %-17s %12.6g %16.6e %14.6g %14.6g %12.6g\n", rpm[i],
               fb_pin_joint_name(r[j].joint), r[j].force, r[j].stiffness, p_mm, p_m, approach_um);
      }
    }
  }
  /* which force the table's is (the contact block's expected impact force is another) */
  const char *force_is =
      mode == FB_PENALTY_PAPER
          ? "the paper's F = k max|alpha| over a revolution, nominal lengths (its Table I recipe, "
            "docs/paper.md)"
          : "the joint's largest ideal reaction over a revolution (inverse dynamics of the rigid "
            "linkage, nominal lengths, gravity included)";
  if (!json)
    printf("%s: %s; Kc, P and the approach are taken at it\n",
           mode == FB_PENALTY_PAPER ? "force F" : "reaction", force_is);
  if (out_dir) {
    const char *mname = mode == FB_PENALTY_PAPER ? "paper" : "physical";
    char path[4096];
    snprintf(path, sizeof path, "%s/penalty_%s.csv", out_dir, mname);
    fb_outfile of;
    if (fb_outfile_open(&of, path, &diag) != FB_OK) {
      json_decref(rows);
      return fb_cli_fail("penalty", 1, "%s", diag.msg);
    }
    fprintf(of.f, "speed_rpm,joint,force_n,stiffness_n_m,penalty_n_mm0_5,penalty_n_m0_5,approach_um\n");
    for (int i = 0; i < n; i++)
      for (int j = 0; j < 2; j++)
        fprintf(of.f, "%.10g,%s,%.12g,%.12g,%.12g,%.12g,%.12g\n", rpm[i],
                fb_pin_joint_name((fb_pin_joint)j), col_f[j][i], col_k[j][i],
                col_pm[j][i] / sqrt(FB_M_PER_MM), col_pm[j][i], col_d[j][i]);
    if (fb_outfile_commit(&of, &diag) != FB_OK) {
      json_decref(rows);
      return fb_cli_fail("penalty", 1, "%s", diag.msg);
    }
    snprintf(path, sizeof path, "%s/penalty_%s.svg", out_dir, mname);
    const double *f2[2] = {col_f[0], col_f[1]}, *k2[2] = {col_k[0], col_k[1]};
    const double *p2[2] = {col_p[0], col_p[1]}, *d2[2] = {col_d[0], col_d[1]};
    if (fb_figures_penalty(path, FB_FIGURE_SVG, mname, n, rpm, f2, k2, p2, d2, &diag) != FB_OK)
      fprintf(stderr, "fourbar penalty: warning: %s\n", diag.msg);
    else if (!json)
      printf("wrote %s/penalty_%s.csv and penalty_%s.svg\n", out_dir, mname, mname);
  }
  if (json) {
    json_t *o = json_object();
    json_object_set_new(o, "mode", json_string(mode == FB_PENALTY_PAPER ? "paper" : "physical"));
    json_object_set_new(o, "case", json_string(c.name));
    json_object_set_new(o, "penalty_units", json_string(unit));
    json_object_set_new(o, "force_n_is", json_string(force_is));
    json_object_set_new(o, "rows", rows);
    if ((rc = contact_used(&c, 1, o)) != 0) {
      json_decref(o);
      return rc;
    }
    json_dumpf(o, stdout, JSON_INDENT(2) | JSON_REAL_PRECISION(12));
    fputc('\n', stdout);
    json_decref(o);
  } else {
    json_decref(rows);
    if ((rc = contact_used(&c, 0, NULL)) != 0) return rc;
  }
  return 0;
}
