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
    "                          [--direction cw|ccw] [--branch open|crossed] [--json]\n"
    "\n"
    "Exact peaks of coupler and follower angular velocity [rad/s] and angular\n"
    "acceleration [rad/s^2] over one crank revolution at constant speed, the\n"
    "Grashof class and the transmission angle range [deg].\n"
    "\n"
    "CASE: a case file (or the name of a shipped case, e.g. paper_crank_rocker);\n"
    "its nominal lengths, speed, direction and branch, each replaced by a flag\n"
    "given. Without CASE the four lengths and --speed-rpm are required.\n"
    "\n"
    "  --direction   crank direction seen from +z (default: the case's, else cw as\n"
    "                in case files)\n"
    "  --branch      assembly branch (default: the case's, else open)\n"
    "  --json        one JSON object on standard output\n"
    "The Grashof line compares s + l (shortest and longest link) with p + q (the\n"
    "other two): below, the shortest link turns fully; equal, a change-point\n"
    "linkage, which folds flat at crank angle 0 or 180 deg (no exact peaks: exit 1).\n"
    "Exit status: 0 ok, 1 the crank cannot turn fully (or the linkage folds flat),\n"
    "2 bad input.\n";

int fb_cmd_kinematics(int argc, char **argv) {
  static const struct option opts[] = {{"crank-mm", required_argument, 0, 'a'},
                                       {"coupler-mm", required_argument, 0, 'b'},
                                       {"follower-mm", required_argument, 0, 'c'},
                                       {"ground-mm", required_argument, 0, 'g'},
                                       {"speed-rpm", required_argument, 0, 'n'},
                                       {"direction", required_argument, 0, 'd'},
                                       {"branch", required_argument, 0, 'r'},
                                       {"json", no_argument, 0, 'j'},
                                       {"help", no_argument, 0, 'h'},
                                       {0, 0, 0, 0}};
  double mm[FB_LINK_COUNT] = {-1, -1, -1, -1}, rpm = -1;
  int dir = 0, json = 0, ch, branch_given = 0; /* dir 0: not given */
  fb_branch branch = FB_BRANCH_OPEN;
  const char *flag_of[FB_LINK_COUNT] = {"--crank-mm", "--coupler-mm", "--follower-mm",
                                        "--ground-mm"};
  optind = 1;
  while ((ch = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
    switch (ch) {
      case 'a': if (!fb_cli_double("kinematics", "--crank-mm", optarg, &mm[FB_CRANK])) return 2; break;
      case 'b': if (!fb_cli_double("kinematics", "--coupler-mm", optarg, &mm[FB_COUPLER])) return 2; break;
      case 'c': if (!fb_cli_double("kinematics", "--follower-mm", optarg, &mm[FB_FOLLOWER])) return 2; break;
      case 'g': if (!fb_cli_double("kinematics", "--ground-mm", optarg, &mm[FB_GROUND])) return 2; break;
      case 'n': if (!fb_cli_double("kinematics", "--speed-rpm", optarg, &rpm)) return 2; break;
      case 'd':
        if (strcmp(optarg, "cw") == 0) dir = -1;
        else if (strcmp(optarg, "ccw") == 0) dir = +1;
        else return fb_cli_fail("kinematics", 2, "--direction '%s': must be cw or ccw", optarg);
        break;
      case 'r':
        branch_given = 1;
        if (strcmp(optarg, "open") == 0) branch = FB_BRANCH_OPEN;
        else if (strcmp(optarg, "crossed") == 0) branch = FB_BRANCH_CROSSED;
        else return fb_cli_fail("kinematics", 2, "--branch '%s': must be open or crossed", optarg);
        break;
      case 'j': json = 1; break;
      case 'h': fputs(kin_help, stdout); return 0;
      default: return fb_cli_bad_option(argv, "h");
    }
  }
  /* a case gives what no flag gave; without one the case files' defaults */
  char case_path[4096] = "";
  if (optind < argc) {
    static fb_case c;
    if (fb_cli_load_case("kinematics", argc, argv, optind, NULL, 0, &c, case_path,
                         sizeof case_path) != 0)
      return 2;
    for (int i = 0; i < FB_LINK_COUNT; i++)
      if (mm[i] == -1) mm[i] = c.nominal.length[i] / FB_M_PER_MM;
    if (rpm == -1) rpm = c.crank_speed / FB_RAD_S_PER_RPM;
    if (dir == 0) dir = c.direction;
    if (!branch_given) branch = c.branch;
  }
  if (dir == 0) dir = -1; /* cw, the [drive] direction default */
  static fb_kinematics k;
  for (int i = 0; i < FB_LINK_COUNT; i++) {
    if (mm[i] == -1) return fb_cli_fail("kinematics", 2, "%s is required; see --help", flag_of[i]);
    char key[32];
    snprintf(key, sizeof key, "%s_mm", fb_link_name(i));
    fb_diag rd; /* the ranges of fourbar run's case keys */
    if (fb_casefile_check_range("linkage", key, mm[i], flag_of[i], &rd) != FB_OK)
      return fb_cli_fail("kinematics", 2, "%s", rd.msg);
    k.lk.length[i] = mm[i] * FB_M_PER_MM;
    k.mm[i] = mm[i];
    const char *why = fb_casefile_length_implausible(k.lk.length[i]);
    if (why && !case_path[0]) /* (a case's lengths: said by fb_cli_load_case) */
      fprintf(stderr, "fourbar kinematics: warning: %s %g: a link length %s; the flag is in "
              "millimetres\n", flag_of[i], mm[i], why);
  }
  if (rpm == -1) return fb_cli_fail("kinematics", 2, "--speed-rpm is required; see --help");
  fb_diag rd;
  if (fb_casefile_check_range("drive", "speed_rpm", rpm, "--speed-rpm", &rd) != FB_OK)
    return fb_cli_fail("kinematics", 2, "%s", rd.msg);
  k.rpm = rpm;
  k.dir = dir;
  k.branch = branch;
  k.case_path = case_path;
  fb_diag diag;
  if (fb_kinematics_run(&k, &diag) != FB_OK) return fb_cli_fail("kinematics", 1, "%s", diag.msg);
  if (json) fb_report_kinematics_json(stdout, &k);
  else fb_report_kinematics_text(stdout, &k);
  return 0;
}
