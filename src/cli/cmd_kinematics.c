/* fourbar kinematics: argument parsing and dispatch only: fb_kinematics_run
 * (src/studies/kinematics.h), the result printed by tables_kinematics.h. */
#include <getopt.h>
#include <stdio.h>
#include <string.h>

#include "casefile.h"
#include "cli.h"
#include "kinematics.h"
#include "tables_kinematics.h"
#include "units.h"

static const char kin_help[] =
    "usage: fourbar kinematics [CASE] [--crank-mm L] [--coupler-mm L]\n"
    "                          [--follower-mm L] [--ground-mm L] [--speed-rpm N]\n"
    "                          [--direction cw|ccw] [--branch open|crossed]\n"
    "                          [--type four-bar|slider-crank] [--offset-mm E]\n"
    "                          [--json]\n"
    "\n"
    "Exact peaks of coupler and follower angular velocity [rad/s] and angular\n"
    "acceleration [rad/s^2] over one crank revolution at constant speed, the\n"
    "Grashof class and the transmission angle range [deg].\n"
    "A slider-crank (a CASE with [linkage] type = slider-crank, or --type\n"
    "slider-crank): its class (full-turn when the coupler, the connecting rod, is\n"
    "longer than crank + |offset|) and margin, the stroke, the dead centres (the\n"
    "slider's x and the crank angle at each), the quick-return ratio (the slower\n"
    "stroke's time over the faster's) with each stroke's crank angle and time, the\n"
    "transmission angle range, and the exact peaks of the rod's omega [rad/s] and\n"
    "alpha [rad/s^2] and the slider's velocity [m/s] and acceleration [m/s^2].\n"
    "A planar case ([linkage] type = planar, docs/planar.md): every moving body's\n"
    "omega and alpha extremes by name and the drive angle of each (the planar\n"
    "core; --speed-rpm and --direction apply, the length flags do not).\n"
    "\n"
    "CASE: a case file (or the name of a shipped case, e.g. paper_crank_rocker);\n"
    "its nominal lengths, speed, direction and branch, each replaced by a flag\n"
    "given. Without CASE the four lengths and --speed-rpm are required (a\n"
    "slider-crank's --crank-mm, --coupler-mm and --speed-rpm; --offset-mm is 0\n"
    "unless given).\n"
    "\n"
    "  --direction   crank direction seen from +z (default: the case's, else cw as\n"
    "                in case files)\n"
    "  --branch      assembly branch (default: the case's, else open)\n"
    "  --type        the mechanism (default: the case's, else four-bar)\n"
    "  --offset-mm   a slider-crank's guide offset along +y, either sign (as\n"
    "                [linkage] offset_mm)\n"
    "  --json        one JSON object on standard output\n"
    "The Grashof line compares s + l (shortest and longest link) with p + q (the\n"
    "other two): below, the shortest link turns fully; equal, a change-point\n"
    "linkage, which folds flat at crank angle 0 or 180 deg (no exact peaks: exit 1).\n"
    "A slider-crank's --follower-mm, --ground-mm and --branch, and a four-bar's\n"
    "--offset-mm, are refused (exit 2).\n"
    "Exit status: 0 ok, 1 the crank cannot turn fully (or the linkage folds flat),\n"
    "2 bad input.\n";

/* flags seen but not yet checked against the mechanism */
typedef struct {
  int type;         /* fb_mech_type given with --type, -1 none */
  int fourbar_only; /* index into four-bar-only flags of the first given, -1 none */
  int offset_given; /* --offset-mm given */
} kin_flags;

/* the lengths [mm] into k, from the flags or the case (-1: not given; a
 * slider-crank's offset always given by then), checked with the ranges of
 * fourbar run's case keys; exit status or 0 */
static int kin_lengths(fb_kinematics *k, double mm[FB_LINK_COUNT]) {
  static const char *const fourbar_flags[FB_LINK_COUNT] = {"--crank-mm", "--coupler-mm",
                                                           "--follower-mm", "--ground-mm"};
  static const char *const sc_flags[FB_LINK_COUNT] = {"--crank-mm", "--coupler-mm",
                                                      "--offset-mm", NULL};
  const int sc = k->mech == FB_MECH_SLIDER_CRANK;
  const char *const *flag_of = sc ? sc_flags : fourbar_flags;
  const fb_mech_desc *m = fb_mech_of(k->mech);
  for (int i = 0; i < FB_LINK_COUNT; i++) {
    if (i >= m->nlengths) {
      k->lk.length[i] = k->mm[i] = 0.0;
      continue;
    }
    if (mm[i] == -1 && !(sc && i == FB_LENGTH_OFFSET)) return fb_cli_fail("kinematics", 2, "%s is required; see --help", flag_of[i]);
    char key[32];
    snprintf(key, sizeof key, "%s_mm", m->length[i]);
    fb_diag rd; /* the ranges of fourbar run's case keys */
    if (fb_casefile_check_range("linkage", key, mm[i], flag_of[i], &rd) != FB_OK)
      return fb_cli_fail("kinematics", 2, "%s", rd.msg);
    k->lk.length[i] = mm[i] * FB_M_PER_MM;
    k->mm[i] = mm[i];
    const char *why = fb_casefile_length_implausible(k->lk.length[i]);
    if (sc && i == FB_LENGTH_OFFSET) why = NULL; /* an offset may be 0 or small */
    if (why && !k->case_path[0]) /* (a case's lengths: said by fb_cli_load_case) */
      fprintf(stderr, "fourbar kinematics: warning: %s %g: a link length %s; the flag is in "
              "millimetres\n", flag_of[i], mm[i], why);
  }
  return 0;
}

/* the mechanism: the case's, else --type's, else the four-bar; a flag of
 * the other mechanism refused; exit status or 0 */
static int kin_mechanism(fb_kinematics *k, const kin_flags *fl, int case_mech) {
  static const char *const fourbar_only[] = {"--follower-mm", "--ground-mm", "--branch"};
  if (case_mech >= 0 && fl->type >= 0 && fl->type != case_mech)
    return fb_cli_fail("kinematics", 2, "--type %s: the case is a %s ([linkage] type = %s)",
                       fb_mech_of((fb_mech_type)fl->type)->type,
                       fb_mech_of((fb_mech_type)case_mech)->type,
                       fb_mech_of((fb_mech_type)case_mech)->type);
  k->mech = (fb_mech_type)(case_mech >= 0 ? case_mech : fl->type >= 0 ? fl->type : FB_MECH_FOURBAR);
  if (k->mech == FB_MECH_SLIDER_CRANK && fl->fourbar_only >= 0)
    return fb_cli_fail("kinematics", 2, "%s is a four-bar flag, but the mechanism is a "
                       "slider-crank: give --crank-mm, --coupler-mm, --offset-mm",
                       fourbar_only[fl->fourbar_only]);
  if (k->mech != FB_MECH_SLIDER_CRANK && fl->offset_given)
    return fb_cli_fail("kinematics", 2, "--offset-mm is a slider-crank flag, but the mechanism "
                       "is a four-bar: add --type slider-crank (or give a slider-crank case)");
  return 0;
}

int fb_cmd_kinematics(int argc, char **argv) {
  static const struct option opts[] = {{"crank-mm", required_argument, 0, 'a'},
                                       {"coupler-mm", required_argument, 0, 'b'},
                                       {"follower-mm", required_argument, 0, 'c'},
                                       {"ground-mm", required_argument, 0, 'g'},
                                       {"speed-rpm", required_argument, 0, 'n'},
                                       {"direction", required_argument, 0, 'd'},
                                       {"branch", required_argument, 0, 'r'},
                                       {"type", required_argument, 0, 't'},
                                       {"offset-mm", required_argument, 0, 'e'},
                                       {"json", no_argument, 0, 'j'},
                                       {"help", no_argument, 0, 'h'},
                                       {0, 0, 0, 0}};
  double mm[FB_LINK_COUNT] = {-1, -1, -1, -1}, rpm = -1, offset = -1;
  int dir = 0, json = 0, ch, branch_given = 0; /* dir 0: not given */
  kin_flags fl = {-1, -1, 0};
  fb_branch branch = FB_BRANCH_OPEN;
  optind = 1;
  while ((ch = fb_cli_getopt(argc, argv, "h", opts)) != -1) {
    switch (ch) {
      case 'a': if (!fb_cli_double("kinematics", "--crank-mm", optarg, &mm[FB_CRANK])) return 2; break;
      case 'b': if (!fb_cli_double("kinematics", "--coupler-mm", optarg, &mm[FB_COUPLER])) return 2; break;
      case 'c': if (!fb_cli_double("kinematics", "--follower-mm", optarg, &mm[FB_FOLLOWER])) return 2;
        if (fl.fourbar_only < 0) fl.fourbar_only = 0;
        break;
      case 'g': if (!fb_cli_double("kinematics", "--ground-mm", optarg, &mm[FB_GROUND])) return 2;
        if (fl.fourbar_only < 0) fl.fourbar_only = 1;
        break;
      case 'n': if (!fb_cli_double("kinematics", "--speed-rpm", optarg, &rpm)) return 2; break;
      case 'd':
        if (strcmp(optarg, "cw") == 0) dir = -1;
        else if (strcmp(optarg, "ccw") == 0) dir = +1;
        else return fb_cli_fail("kinematics", 2, "--direction '%s': must be cw or ccw", optarg);
        break;
      case 'r':
        branch_given = 1;
        if (fl.fourbar_only < 0) fl.fourbar_only = 2;
        if (strcmp(optarg, "open") == 0) branch = FB_BRANCH_OPEN;
        else if (strcmp(optarg, "crossed") == 0) branch = FB_BRANCH_CROSSED;
        else return fb_cli_fail("kinematics", 2, "--branch '%s': must be open or crossed", optarg);
        break;
      case 't':
        if ((fl.type = fb_mech_find(optarg)) < 0)
          return fb_cli_fail("kinematics", 2, "--type '%s': must be four-bar or slider-crank", optarg);
        break;
      case 'e': if (!fb_cli_double("kinematics", "--offset-mm", optarg, &offset)) return 2;
        fl.offset_given = 1;
        break;
      case 'j': json = 1; break;
      case 'h': fputs(kin_help, stdout); return 0;
      default: return fb_cli_bad_option(argv, "h");
    }
  }
  /* a case gives what no flag gave; without one the case files' defaults */
  char case_path[4096] = "";
  static fb_case c;
  int case_mech = -1;
  if (optind < argc) {
    if (fb_cli_load_case("kinematics", argc, argv, optind, NULL, 0, &c, case_path,
                         sizeof case_path) != 0)
      return 2;
    case_mech = (int)c.mechanism;
  }
  if (case_mech >= 0 && c.planar.on) { /* its geometry is its joints' (docs/planar.md) */
    static const char *const flag[FB_LINK_COUNT] = {"--crank-mm", "--coupler-mm", "--follower-mm",
                                                    "--ground-mm"};
    for (int i = 0; i < FB_LINK_COUNT; i++)
      if (mm[i] != -1)
        return fb_cli_fail("kinematics", 2, "%s: the case is a planar one, whose lengths are its "
                           "joints' positions ([joint.NAME] at_mm)", flag[i]);
    if (branch_given || fl.type >= 0 || fl.offset_given)
      return fb_cli_fail("kinematics", 2, "--branch, --type and --offset-mm do not apply to a "
                         "planar case (its joints' positions give its branch and shape)");
    fb_diag rd;
    if (rpm != -1 && fb_casefile_check_range("drive", "speed_rpm", rpm, "--speed-rpm", &rd) != FB_OK)
      return fb_cli_fail("kinematics", 2, "%s", rd.msg);
    if (rpm != -1) c.crank_speed = rpm * FB_RAD_S_PER_RPM;
    if (dir != 0) c.direction = dir;
    return fb_cmd_kinematics_planar(&c, json);
  }
  static fb_kinematics k;
  k.case_path = case_path;
  int rc = kin_mechanism(&k, &fl, case_mech);
  if (rc) return rc;
  if (case_mech >= 0) {
    for (int i = 0; i < FB_LINK_COUNT; i++)
      if (mm[i] == -1) mm[i] = c.nominal.length[i] / FB_M_PER_MM;
    if (rpm == -1) rpm = c.crank_speed / FB_RAD_S_PER_RPM;
    if (dir == 0) dir = c.direction;
    if (!branch_given) branch = c.branch;
  }
  if (dir == 0) dir = -1; /* cw, the [drive] direction default */
  if (k.mech == FB_MECH_SLIDER_CRANK) /* the flag's, the case's, else the key's default 0 */
    mm[FB_LENGTH_OFFSET] = fl.offset_given ? offset
                           : case_mech >= 0 ? c.nominal.length[FB_LENGTH_OFFSET] / FB_M_PER_MM
                                            : 0.0;
  if ((rc = kin_lengths(&k, mm)) != 0) return rc;
  if (rpm == -1) return fb_cli_fail("kinematics", 2, "--speed-rpm is required; see --help");
  fb_diag rd;
  if (fb_casefile_check_range("drive", "speed_rpm", rpm, "--speed-rpm", &rd) != FB_OK)
    return fb_cli_fail("kinematics", 2, "%s", rd.msg);
  k.rpm = rpm;
  k.dir = dir;
  k.branch = branch;
  fb_diag diag;
  if (fb_kinematics_run(&k, &diag) != FB_OK) return fb_cli_fail("kinematics", 1, "%s", diag.msg);
  if (json) fb_report_kinematics_json(stdout, &k);
  else fb_report_kinematics_text(stdout, &k);
  return 0;
}
