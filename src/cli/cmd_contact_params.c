/* fourbar contact-params: flags in, fb_cp_run (src/studies/contact_params.h),
 * the result printed as text or JSON (src/report/tables_contact_params.h).
 * No physics here. */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "case.h"
#include "casefile.h"
#include "planar_case.h"
#include "cli.h"
#include "contact_params.h"
#include "model_table.h"
#include "tables_contact_params.h"

static const char params_help[] =
    "usage: fourbar contact-params [--law LAW] [--stiffness K] [--exponent n]\n"
    "         [--damping-n-s-m c | --restitution cr] [--mass-kg m | --mass-kg A:B]\n"
    "         [--h-s h] [--speed-m-s v] [--load-n F] [--no-verify] [--json]\n"
    "       fourbar contact-params --case CASE [--joint NAME]\n"
    "         [--law restitution|hertz] [--h-s h] [--speed-m-s v] [--no-verify]\n"
    "         [--json]\n"
    "\n"
    "The engine parameters that make a soft contact behave like a given physical\n"
    "contact at step h: ODE (per-contact ERP/CFM), Gazebo (SDF kp, kd, max_vel,\n"
    "min_depth), MuJoCo 2.2 (solref/solimp) and Bullet (contact stiffness and\n"
    "damping), each in the engine's own units and syntax. A row is recommended\n"
    "only when it is faithful at h: h omega_c within a run's bound (0.5, at the\n"
    "smallest mass) and every single impact of it, in the engine itself, at every\n"
    "mass and wherever inside a step the contact begins, within 1 % of the\n"
    "continuous contact's restitution and 2 % of its peak penetration. Also\n"
    "printed: the largest faithful step of the contact, and at h the stiffest\n"
    "faithful contact with the same restitution (docs/contact-params.md).\n"
    "\n"
    "  --law          restitution (default: a linear spring with the damper of\n"
    "                 coefficient of restitution cr), linear (spring and damper),\n"
    "                 hertz (K delta^n; with --restitution, a damper of that cr),\n"
    "                 lankarani-nikravesh, hunt-crossley, flores, gonthier (damped\n"
    "                 Hertz laws: translated to the linear spring-damper with the\n"
    "                 law's own restitution and peak penetration at --speed-m-s and\n"
    "                 the design mass)\n"
    "  --stiffness    k [N/m] (Hertz laws: K [N/m^n]); default 1e7\n"
    "  --exponent     n of the Hertz laws (default 1.5)\n"
    "  --restitution  cr: restitution law (0.135, 1], default 0.9; damped Hertz\n"
    "                 laws (0, 1], default 0.9, where the law's own impact must\n"
    "                 leave faster than e^-2 (flores: cr > 0.178, gonthier: cr >\n"
    "                 0.133 at n = 1.5); lankarani-nikravesh and hunt-crossley\n"
    "                 never leave slower than 0.66 and 0.49 (n = 1.5), whatever cr\n"
    "                 (said when the law misses cr by more than 10 %); hertz:\n"
    "                 optional\n"
    "  --damping-n-s-m  c of the linear law [N s/m] (default 0), at most 500\n"
    "                 times critical (c <= 1000 sqrt(k m))\n"
    "  --mass-kg      effective mass along the contact normal [kg], or a range A:B\n"
    "                 (rows designed at the geometric mean, verified at A, it, B);\n"
    "                 default 0.1\n"
    "  --h-s          step size [s]; default: h omega_c = 0.1 at the smallest mass,\n"
    "                 or the largest faithful step when that is smaller; without\n"
    "                 --h-s the stiffest faithful contact is also given at\n"
    "                 MuJoCo's default step (2 ms) and Gazebo's (1 ms)\n"
    "  --speed-m-s    impact speed of the verification and of the Hertz laws'\n"
    "                 operating point [m/s] (default 1)\n"
    "  --load-n       hertz only: linearise at the static penetration of this load\n"
    "                 (tangent stiffness) instead of the impact at --speed-m-s\n"
    "  --case         take the contact from a case file (a path, or a shipped\n"
    "                 case's name): the law of its clearance-restitution models\n"
    "                 (--law restitution: k, cr) or of its clearance-impact models\n"
    "                 (--law hertz: K, n, linearised at the joint's expected force;\n"
    "                 its damper is not carried), the joint's effective-mass range\n"
    "                 over a revolution and every direction, and the run's step\n"
    "                 (unless --h-s)\n"
    "  --joint        the case's clearance joint by name (a planar case's: a\n"
    "                 revolute one); needed when the case has several\n"
    "  --verify       verify (the default; kept for scripts)\n"
    "  --no-verify    skip the single impacts: no largest step, no at_step, rows\n"
    "                 held to the h omega_c rule only and marked unverified\n"
    "  --json         one JSON object (docs/contact-params.md lists the keys)\n"
    "Exit status: 0 ok, 1 a recommended row failed its verification (or could\n"
    "not run), 2 bad input.\n";

static int parse_mass(const char *s, fb_cp_request *q) {
  char *end;
  q->mass_min = strtod(s, &end);
  q->mass_max = q->mass_min;
  if (*end == ':') q->mass_max = strtod(end + 1, &end);
  if (*end != '\0' || end == s) return 0;
  return 1;
}

/* ---- flags ------------------------------------------------------------------ */

/* the command's name in its messages */
static const char *const P = "contact-params";

/* --case on a planar case: the clearance joint (joint_arg, or the case's
 * one) of its description into q; *jname its name (static). Returns 0 or
 * the exit status, having said why. */
static int request_planar(fb_cp_request *q, const fb_case *c, const char *path,
                          const char *joint_arg, const char **jname) {
  static char name[FB_NAME_SIZE];
  fb_planar *m;
  fb_diag d;
  if (fb_planar_of_case(&m, c, NULL, &d) != FB_OK) return fb_cli_fail(P, 2, "%s", d.msg);
  const unsigned mask = (unsigned)c->clearance.mask;
  char names[512] = "";
  int joint = -1, n = 0;
  for (int j = 0; j < m->njoints; j++) {
    if (joint_arg && strcmp(joint_arg, m->joint[j].name) == 0) joint = j;
    if (!(mask & (1u << j))) continue;
    if (!joint_arg) joint = j;
    n++;
    if (names[0]) strncat(names, ", ", sizeof names - strlen(names) - 1);
    strncat(names, m->joint[j].name, sizeof names - strlen(names) - 1);
  }
  int rc = 0;
  if (n == 0)
    rc = fb_cli_fail(P, 2, "--case %s has no clearance joint ([clearance] joints): no contact to "
                     "take", path);
  else if (!joint_arg && n > 1)
    rc = fb_cli_fail(P, 2, "--case %s has %d clearance joints (%s): name one with --joint", path, n,
                     names);
  else if (joint < 0 || !(mask & (1u << joint)))
    rc = fb_cli_fail(P, 2, "--joint '%s': must be a clearance joint of the case ([clearance] "
                     "joints): %s", joint_arg, names);
  if (!rc && fb_cp_request_from_planar(q, c, m, joint, &d) != FB_OK)
    rc = fb_cli_fail(P, 2, "--case %s: %s", path, d.msg);
  if (!rc) {
    snprintf(name, sizeof name, "%s", m->joint[joint].name);
    *jname = name;
  }
  fb_planar_free(m);
  return rc;
}

int fb_cmd_contact_params(int argc, char **argv) {
  static const struct option opts[] = {
      {"law", required_argument, 0, 'L'},       {"stiffness", required_argument, 0, 'k'},
      {"exponent", required_argument, 0, 'n'},  {"restitution", required_argument, 0, 'e'},
      {"damping-n-s-m", required_argument, 0, 'c'}, {"mass-kg", required_argument, 0, 'm'},
      {"h-s", required_argument, 0, 'H'},       {"speed-m-s", required_argument, 0, 'v'},
      {"load-n", required_argument, 0, 'F'},    {"verify", no_argument, 0, 'V'},
      {"no-verify", no_argument, 0, 'N'},       {"json", no_argument, 0, 'j'},
      {"help", no_argument, 0, 'h'},            {"case", required_argument, 0, 'C'},
      {"joint", required_argument, 0, 'J'},     {0, 0, 0, 0}};
  fb_cp_request q;
  fb_cp_request_default(&q);
  int ch, json = 0, m_given = 0, k_given = 0, h_given = 0;
  const char *case_arg = NULL, *joint_arg = NULL;
  optind = 1;
  while ((ch = fb_cli_getopt(argc, argv, "h", opts)) != -1) {
    switch (ch) {
      case 'L':
        q.law = fb_law_parse(optarg);
        if (!(q.law == FB_LAW_LINEAR || q.law == FB_LAW_RESTITUTION || q.law == FB_LAW_HERTZ ||
              q.law == FB_LAW_LANKARANI_NIKRAVESH || q.law == FB_LAW_HUNT_CROSSLEY ||
              q.law == FB_LAW_FLORES || q.law == FB_LAW_GONTHIER))
          return fb_cli_fail(P, 2, "--law '%s': must be restitution, linear, hertz, "
                             "lankarani-nikravesh, hunt-crossley, flores or gonthier", optarg);
        break;
      case 'k': if (!fb_cli_double(P, "--stiffness", optarg, &q.stiffness)) return 2; k_given = 1; break;
      case 'n': if (!fb_cli_double(P, "--exponent", optarg, &q.exponent)) return 2; break;
      case 'e': if (!fb_cli_double(P, "--restitution", optarg, &q.restitution)) return 2; break;
      case 'c': if (!fb_cli_double(P, "--damping-n-s-m", optarg, &q.damping)) return 2; break;
      case 'm':
        if (!parse_mass(optarg, &q))
          return fb_cli_fail(P, 2, "--mass-kg '%s': a mass in kg or a range A:B", optarg);
        m_given = 1;
        break;
      case 'C': case_arg = optarg; break;
      case 'J': joint_arg = optarg; break;
      case 'H': if (!fb_cli_double(P, "--h-s", optarg, &q.h)) return 2; h_given = 1; break;
      case 'v': if (!fb_cli_double(P, "--speed-m-s", optarg, &q.speed)) return 2; break;
      case 'F': if (!fb_cli_double(P, "--load-n", optarg, &q.load)) return 2; break;
      case 'V': q.verify = 1; break;
      case 'N': q.verify = 0; break;
      case 'j': json = 1; break;
      case 'h': fputs(params_help, stdout); return 0;
      default: return fb_cli_fail(P, 2, "unknown option '%s'; see fourbar contact-params --help",
                                  argv[optind - 1]);
    }
  }
  if (optind < argc) return fb_cli_fail(P, 2, "unexpected argument '%s'", argv[optind]);
  char case_path[4096] = "";
  int joint = -1;
  const char *jname = NULL; /* the joint's name in the case's mechanism */
  if (joint_arg && !case_arg)
    return fb_cli_fail(P, 2, "--joint %s: names a joint of a case; give --case too", joint_arg);
  if (case_arg) {
    if (k_given || !isnan(q.restitution) || !isnan(q.damping) || !isnan(q.exponent) || m_given ||
        !isnan(q.load))
      return fb_cli_fail(P, 2, "--case takes the stiffness, exponent, damping or restitution, "
                         "effective mass and operating point from the case: drop %s",
                         k_given ? "--stiffness" : !isnan(q.restitution) ? "--restitution"
                         : !isnan(q.damping) ? "--damping-n-s-m" : !isnan(q.exponent) ? "--exponent"
                         : m_given ? "--mass-kg" : "--load-n");
    if (q.law != FB_LAW_RESTITUTION && q.law != FB_LAW_HERTZ)
      return fb_cli_fail(P, 2, "--law %s with --case: a case's clearance models use the "
                         "restitution law (--law restitution, the default) and the impact law "
                         "(--law hertz)", fb_law_name(q.law));
    fb_cli_case_path(case_path, sizeof case_path, case_arg);
    fb_case cs;
    fb_diag cd;
    if (fb_cli_case_file(P, case_path, NULL, 0, &cs) != 0) return 2;
    if (cs.planar.on) { /* a planar case: its description's clearance pins */
      q.case_path = case_path;
      const int rc = request_planar(&q, &cs, case_path, joint_arg, &jname);
      if (rc) return rc;
    } else if (joint_arg) {
      const fb_mech_desc *mech = fb_case_mech(&cs);
      char names[160] = "";
      for (int j = 0; j < mech->njoints; j++) {
        if (strcmp(joint_arg, mech->joint[j].name) == 0) joint = j;
        if (!mech->joint[j].clearance_ok) continue;
        if (names[0]) strncat(names, ", ", sizeof names - strlen(names) - 1);
        strncat(names, mech->joint[j].name, sizeof names - strlen(names) - 1);
      }
      if (joint < 0)
        return fb_cli_fail(P, 2, "--joint '%s': must be a joint of the case's %s: %s", joint_arg,
                           mech->type, names);
    } else {
      int n = 0;
      for (int j = 0; j < 4; j++)
        if (cs.clearance.mask & (1 << j)) joint = j, n++;
      if (n > 1)
        return fb_cli_fail(P, 2, "--case %s has %d clearance joints: name one with --joint",
                           case_path, n);
    }
    if (!cs.planar.on) {
      if (joint >= 0) jname = fb_case_joint_name(&cs, joint);
      q.case_path = case_path; /* messages name the case's keys, not flags never given */
      if (fb_cp_request_from_case(&q, &cs, joint, &cd) != FB_OK)
        return fb_cli_fail(P, 2, "--case %s: %s", case_path, cd.msg);
    }
  }
  /* no step given: also the answers at MuJoCo's and Gazebo's default steps */
  q.engine_steps = !h_given;
  static fb_cp_result o;
  fb_diag diag;
  fb_status st = fb_cp_run(&o, &q, &diag);
  if (st != FB_OK) return fb_cli_fail(P, st == FB_ERR_NUMERIC ? 1 : 2, "%s", diag.msg);
  if (json) fb_report_cp_json(stdout, &o, case_path, jname);
  else fb_report_cp_text(stdout, &o, case_path, jname);
  return o.failed ? 1 : 0;
}
