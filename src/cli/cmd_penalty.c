/* fourbar penalty: argument parsing and dispatch only: fb_penalty_study_run
 * (src/studies/penalty_study.h), the output tables_penalty.h's. */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "casefile.h"
#include "cli.h"
#include "fileio.h"
#include "penalty_study.h"
#include "tables_penalty.h"
#include "units.h"

#define MAX_SPEEDS FB_PENALTY_SPEEDS_MAX
/* the speeds of the paper's Tables I to III (--table) */
#define PAPER_SPEEDS_RPM "100:1500:100"

static const char penalty_help[] =
    "usage: fourbar penalty [CASE] [--mode paper|physical]\n"
    "                       [--speeds-rpm LIST | --table]\n"
    "                       [--set section.key=value]... [--json]\n"
    "                       [--out DIR [--overwrite]]\n"
    "\n"
    "Contact stiffness Kc (paper Eq. 7), penalty parameter P = Kc C^1.5 (Eq. 9)\n"
    "and mutual approach at the case's crank speed (or per speed of a list), for\n"
    "the crank-coupler and coupler-follower joints (a slider-crank's crank-coupler\n"
    "and coupler-slider, physical mode only: the paper's recipe is its four-bar's,\n"
    "and paper mode prints one line saying so instead of the table). A planar case\n"
    "([linkage] type = planar): physical mode at every revolute joint, by name.\n"
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
    "                   against speed: the paper's Figures 2 to 4); a planar\n"
    "                   case: a row per speed and revolute joint, a curve per joint\n"
    "  --overwrite      replace those files when no fourbar penalty wrote them\n"
    "                   (without it such a file is refused, exit 2)\n"
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
    "contact frequency, and the step [solver] h_s = auto gives (JSON: \"contact\");\n"
    "a planar case's pins at their nominal lengths, with the step that resolves\n"
    "them (JSON: \"h_resolving_s\", the step its h_s = auto takes).\n"
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

/* the study, its table, files and contact block; returns the exit status */
static int penalty_out(const fb_case *c, fb_penalty_mode mode, const double *rpm, int n, int json,
                       const char *out_dir) {
  fb_diag diag;
  static fb_penalty_study ps;
  fb_penalty_study_run(&ps, c, mode, rpm, n);
  if (!json) fb_report_penalty_table(stdout, &ps, c);
  if (ps.rows_status != FB_OK) return fb_cli_fail("penalty", 1, "%s", ps.rows_msg);
  if (out_dir && ps.rows_skipped) {
    fprintf(stderr, "fourbar penalty: warning: --out %s: no table to write (%s mode, a %s)\n",
            out_dir, mode == FB_PENALTY_PAPER ? "paper" : "physical", fb_case_mech(c)->type);
  } else if (out_dir) {
    int figure_ok;
    fb_diag fd;
    if (fb_report_penalty_files(out_dir, &ps, &figure_ok, &fd, &diag) != FB_OK)
      return fb_cli_fail("penalty", 1, "%s", diag.msg);
    const char *mname = mode == FB_PENALTY_PAPER ? "paper" : "physical";
    if (!figure_ok) fprintf(stderr, "fourbar penalty: warning: %s\n", fd.msg);
    else if (!json) printf("wrote %s/penalty_%s.csv and penalty_%s.svg\n", out_dir, mname, mname);
  }
  if (ps.contact_status != FB_OK) return fb_cli_fail("penalty", 1, "%s", ps.contact_msg);
  if (json) fb_report_penalty_json(stdout, &ps, c);
  else fb_report_penalty_contact_text(stdout, &ps);
  return 0;
}

int fb_cmd_penalty(int argc, char **argv) {
  static const struct option opts[] = {{"mode", required_argument, 0, 'm'},
                                       {"speeds-rpm", required_argument, 0, 's'},
                                       {"table", no_argument, 0, 'T'},
                                       {"set", required_argument, 0, 'S'},
                                       {"json", no_argument, 0, 'j'},
                                       {"out", required_argument, 0, 'o'},
                                       {"overwrite", no_argument, 0, 'w'},
                                       {"help", no_argument, 0, 'h'},
                                       {0, 0, 0, 0}};
  int mode_given = 0;
  fb_penalty_mode mode = FB_PENALTY_PHYSICAL;
  static double rpm[MAX_SPEEDS];
  int n = 0, json = 0, nsets = 0, ch, speeds_given = 0, overwrite = 0;
  const char *out_dir = NULL;
  const char *sets[FB_CLI_MAX_SETS];
  optind = 1;
  while ((ch = fb_cli_getopt(argc, argv, "h", opts)) != -1) {
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
        if (nsets == FB_CLI_MAX_SETS)
          return fb_cli_fail("penalty", 2, "more than %d --set", FB_CLI_MAX_SETS);
        sets[nsets++] = optarg;
        break;
      case 'j': json = 1; break;
      case 'o': out_dir = optarg; break;
      case 'w': overwrite = 1; break;
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

  /* physical mode at every revolute joint of a planar case (planar_tools.h) */
  if (c.planar.on && mode == FB_PENALTY_PAPER)
    return fb_cli_fail("penalty", 2, "--mode paper: the paper's recipe is its four-bar's; a "
                       "planar case runs physical mode");
  /* its files: checked and the folder locked before any work (fileio.h) */
  char csv[32], svg[32];
  snprintf(csv, sizeof csv, "penalty_%s.csv", mode == FB_PENALTY_PAPER ? "paper" : "physical");
  snprintf(svg, sizeof svg, "penalty_%s.svg", mode == FB_PENALTY_PAPER ? "paper" : "physical");
  const char *const names[2] = {csv, svg};
  const fb_outpath_rule rule = {.flag = "--out", .overwrite = overwrite, .input = case_path};
  static fb_outfiles files;
  if (out_dir) {
    fb_status ost = fb_outfiles_begin(&files, out_dir, "penalty", names, 2, &rule, &diag);
    if (ost != FB_OK) return fb_cli_fail("penalty", ost == FB_ERR_ARG ? 2 : 1, "%s", diag.msg);
  }
  rc = c.planar.on ? fb_cmd_penalty_planar(&c, rpm, n, json, out_dir)
                   : penalty_out(&c, mode, rpm, n, json, out_dir);
  if (out_dir && fb_outfiles_end(&files, &diag) != FB_OK && !rc)
    return fb_cli_fail("penalty", 1, "%s", diag.msg);
  return rc;
}
