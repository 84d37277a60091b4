/* fourbar kinematics: argument parsing and dispatch only. */
#include <getopt.h>
#include <jansson.h>
#include <stdio.h>
#include <string.h>

#include "analytic.h"
#include "casefile.h"
#include "cli.h"
#include "report.h"
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
  fb_linkage lk;
  for (int i = 0; i < FB_LINK_COUNT; i++) {
    if (mm[i] == -1) return fb_cli_fail("kinematics", 2, "%s is required; see --help", flag_of[i]);
    char key[32];
    snprintf(key, sizeof key, "%s_mm", fb_link_name(i));
    fb_diag rd; /* the ranges of fourbar run's case keys */
    if (fb_casefile_check_range("linkage", key, mm[i], flag_of[i], &rd) != FB_OK)
      return fb_cli_fail("kinematics", 2, "%s", rd.msg);
    lk.length[i] = mm[i] * FB_M_PER_MM;
    const char *why = fb_casefile_length_implausible(lk.length[i]);
    if (why && !case_path[0]) /* (a case's lengths: said by fb_cli_load_case) */
      fprintf(stderr, "fourbar kinematics: warning: %s %g: a link length %s; the flag is in "
              "millimetres\n", flag_of[i], mm[i], why);
  }
  if (rpm == -1) return fb_cli_fail("kinematics", 2, "--speed-rpm is required; see --help");
  fb_diag rd;
  if (fb_casefile_check_range("drive", "speed_rpm", rpm, "--speed-rpm", &rd) != FB_OK)
    return fb_cli_fail("kinematics", 2, "%s", rd.msg);
  const double omega2 = dir * rpm * FB_RAD_S_PER_RPM;

  fb_diag diag;
  fb_peaks p;
  double mu_min, mu_max;
  fb_grashof g = fb_linkage_grashof(&lk);
  char grashof[512];
  fb_linkage_grashof_text(grashof, sizeof grashof, &lk);
  /* a change-point linkage folds flat on its way round: no peaks to give */
  if (g == FB_GRASHOF_CHANGE_POINT)
    return fb_cli_fail("kinematics", 1,
                       "crank %g, coupler %g, follower %g, ground %g mm: %s; a crank driven "
                       "through a fold has no exact peaks: make s + l differ from p + q (s + l < "
                       "p + q for a crank-rocker)",
                       mm[0], mm[1], mm[2], mm[3], grashof);
  fb_status st = fb_linkage_transmission_range(&lk, &mu_min, &mu_max, &diag);
  if (st == FB_OK) st = fb_analytic_peaks(&p, &lk, branch, omega2, &diag);
  if (st != FB_OK) return fb_cli_fail("kinematics", 1, "%s; %s", grashof, diag.msg);
  const double deg = 1.0 / FB_RAD_PER_DEG;
  if (json) {
    json_t *o = json_object();
    json_t *l = json_object();
    for (int i = 0; i < FB_LINK_COUNT; i++) json_object_set_new(l, fb_link_name(i), json_real(lk.length[i]));
    json_object_set_new(o, "lengths_m", l);
    json_object_set_new(o, "case_file", case_path[0] ? json_string(case_path) : json_null());
    json_object_set_new(o, "speed_rpm", json_real(rpm));
    json_object_set_new(o, "crank_omega_rad_s", json_real(omega2));
    json_object_set_new(o, "direction", json_string(dir > 0 ? "ccw" : "cw"));
    json_object_set_new(o, "branch", json_string(branch == FB_BRANCH_OPEN ? "open" : "crossed"));
    json_object_set_new(o, "grashof", json_string(fb_grashof_name(g)));
    double sl, pq;
    fb_linkage_grashof_sums(&lk, &sl, &pq, NULL, NULL);
    json_object_set_new(o, "grashof_s_plus_l_m", json_real(sl));
    json_object_set_new(o, "grashof_p_plus_q_m", json_real(pq));
    json_object_set_new(o, "coupler", fb_report_body_peaks_json(&p.coupler));
    json_object_set_new(o, "follower", fb_report_body_peaks_json(&p.follower));
    json_object_set_new(o, "transmission_angle_min_deg", json_real(mu_min * deg));
    json_object_set_new(o, "transmission_angle_max_deg", json_real(mu_max * deg));
    json_dumpf(o, stdout, JSON_INDENT(2) | JSON_REAL_PRECISION(12));
    fputc('\n', stdout);
    json_decref(o);
    return 0;
  }
  if (case_path[0]) printf("case: %s\n", case_path);
  printf("linkage: crank %g, coupler %g, follower %g, ground %g mm (%s), %g rpm %s, %s branch\n",
         mm[0], mm[1], mm[2], mm[3], fb_grashof_name(g), rpm, dir > 0 ? "ccw" : "cw",
         branch == FB_BRANCH_OPEN ? "open" : "crossed");
  printf("%s\n", grashof);
  printf("%-9s %12s %12s %14s %14s\n", "body", "omega_max", "omega_min", "alpha_max", "alpha_min");
  printf("%-9s %12s %12s %14s %14s\n", "", "rad/s", "rad/s", "rad/s^2", "rad/s^2");
  printf("%-9s %12.6f %12.6f %14.4f %14.4f\n", "coupler", p.coupler.omega_max, p.coupler.omega_min,
         p.coupler.alpha_max, p.coupler.alpha_min);
  printf("%-9s %12.6f %12.6f %14.4f %14.4f\n", "follower", p.follower.omega_max,
         p.follower.omega_min, p.follower.alpha_max, p.follower.alpha_min);
  printf("transmission angle: %.4f to %.4f deg\n", mu_min * deg, mu_max * deg);
  return 0;
}
