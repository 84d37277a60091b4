/* fourbar impact: argument parsing and dispatch only: fb_impact_study_run
 * (src/studies/impact_study.h), the result printed by tables_impact.h. */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "impact_study.h"
#include "tables_impact.h"

static const char impact_help[] =
    "usage: fourbar impact [--law L] [--stiffness K] [--exponent n]\n"
    "                      [--restitution cr]\n"
    "                      [--damping-n-s-m c] [--damping-depth-m d] [--mass-kg m]\n"
    "                      [--speed-m-s v] [--h-s h] [--stepper world|quick]\n"
    "                      [--quick-iterations N] [--mapping M] [--engine ode|bullet]\n"
    "                      [--bullet-solver S] [--bullet-iterations N] [--json]\n"
    "\n"
    "One body hits one contact: ODE with the law mapped into ERP/CFM every step,\n"
    "against an adaptive high-accuracy integration of the same law (GSL rk8pd)\n"
    "and, where one exists, the closed form. Reports maximum penetration [m],\n"
    "contact duration [s], peak force [N] and achieved restitution [-].\n"
    "\n"
    "  --law          hertz (default), lankarani-nikravesh, hunt-crossley, flores,\n"
    "                 gonthier, linear, impact, restitution\n"
    "  --stiffness    K [N/m^n] (k or penalty p [N/m] for linear, restitution);\n"
    "                 default 1e10\n"
    "  --exponent     n (default 1.5; 1 for linear and restitution)\n"
    "  --restitution  target cr (default 0.9); flores and gonthier: cr >= 0.001\n"
    "                 (their damping factor grows as 1/cr)\n"
    "  --damping-n-s-m   c of the linear law, c_max of the impact law (default 0;\n"
    "                 at most 500 times critical damping; other laws: refused)\n"
    "  --damping-depth-m d_max of the impact law (default 1e-5; other laws: refused)\n"
    "  --mass-kg      default 1;  --speed-m-s  impact speed, default 1\n"
    "  --h-s          ODE step; default: estimated contact duration / 200\n"
    "  --mapping      matched (default, as fourbar run: [clearance] mapping): ERP/CFM\n"
    "                 chosen so the one-step update of the body has the continuous\n"
    "                 spring-damper's poles exp(s h) (tangent stiffness, the body's\n"
    "                 mass); or secant or tangent linearisation of the law into\n"
    "                 ERP = h k/(h k + c), CFM = 1/(h k + c) (a backward-Euler spring\n"
    "                 that adds a damper h k); or matched-static: matched, turning to\n"
    "                 the law's own stiffness once a contact lasts one contact period\n"
    "                 (a single impact never does: the matched figures)\n"
    "  --engine       ode (default), or bullet: Bullet too, beside ODE, with the same\n"
    "                 row (docs/engines.md); secant/tangent on a linear law is then\n"
    "                 Bullet's own stiffness/damping conversion\n"
    "  --bullet-solver  sequential-impulse or mlcp-dantzig (default)\n"
    "  --bullet-iterations  sequential-impulse sweeps, 1 to 100000 (default 100)\n"
    "Exit status: 0 ok, 1 failed, 2 bad input.\n";

int fb_cmd_impact(int argc, char **argv) {
  static const struct option opts[] = {
      {"law", required_argument, 0, 'L'},           {"stiffness", required_argument, 0, 'k'},
      {"exponent", required_argument, 0, 'n'},      {"restitution", required_argument, 0, 'e'},
      {"damping-n-s-m", required_argument, 0, 'c'}, {"damping-depth-m", required_argument, 0, 'd'},
      {"mass-kg", required_argument, 0, 'm'},       {"speed-m-s", required_argument, 0, 'v'},
      {"h-s", required_argument, 0, 'H'},           {"stepper", required_argument, 0, 'S'},
      {"quick-iterations", required_argument, 0, 'q'},
      {"mapping", required_argument, 0, 'M'},       {"json", no_argument, 0, 'j'},
      {"engine", required_argument, 0, 'E'},        {"bullet-solver", required_argument, 0, 'B'},
      {"bullet-iterations", required_argument, 0, 'I'},
      {"help", no_argument, 0, 'h'},                {0, 0, 0, 0}};
  fb_impact_request rq;
  memset(&rq, 0, sizeof rq);
  fb_impact_def d;
  memset(&d, 0, sizeof d);
  d.law = fb_contact_law_default();
  d.mass = 1.0;
  d.speed = 1.0;
  d.stepper = FB_STEPPER_WORLD;
  d.quick_iterations = 20;
  d.mapping = FB_MAPPING_MATCHED; /* the case key's default: one default with fourbar run */
  d.names = &fb_impact_flag_names; /* messages name the flags (impact.h) */
  double h = 0.0, q = 20, bt_iter = 100;
  fb_bullet_opts bt = fb_bullet_opts_default();
  int json = 0, ch, exponent_given = 0, damping_given = 0, depth_given = 0;
  optind = 1;
  while ((ch = fb_cli_getopt(argc, argv, "h", opts)) != -1) {
    switch (ch) {
      case 'L':
        d.law.kind = fb_law_parse(optarg);
        if (d.law.kind == FB_LAW_COUNT)
          return fb_cli_fail("impact", 2, "--law '%s': unknown law; see --help", optarg);
        break;
      case 'k': if (!fb_cli_double("impact", "--stiffness", optarg, &d.law.stiffness)) return 2; break;
      case 'n': if (!fb_cli_double("impact", "--exponent", optarg, &d.law.exponent)) return 2; exponent_given = 1; break;
      case 'e': if (!fb_cli_double("impact", "--restitution", optarg, &d.law.restitution)) return 2; break;
      case 'c': if (!fb_cli_double("impact", "--damping-n-s-m", optarg, &d.law.damping)) return 2; damping_given = 1; break;
      case 'd': if (!fb_cli_double("impact", "--damping-depth-m", optarg, &d.law.damping_depth)) return 2; depth_given = 1; break;
      case 'm': if (!fb_cli_double("impact", "--mass-kg", optarg, &d.mass)) return 2; break;
      case 'v': if (!fb_cli_double("impact", "--speed-m-s", optarg, &d.speed)) return 2; break;
      case 'H': if (!fb_cli_double("impact", "--h-s", optarg, &h)) return 2; break;
      case 'q': if (!fb_cli_double("impact", "--quick-iterations", optarg, &q)) return 2; break;
      case 'S':
        if (strcmp(optarg, "world") == 0) d.stepper = FB_STEPPER_WORLD;
        else if (strcmp(optarg, "quick") == 0) d.stepper = FB_STEPPER_QUICK;
        else return fb_cli_fail("impact", 2, "--stepper '%s': must be world or quick", optarg);
        break;
      case 'M':
        d.mapping = fb_mapping_parse(optarg);
        if (d.mapping == FB_MAPPING_COUNT)
          return fb_cli_fail("impact", 2, "--mapping '%s': must be secant, tangent, matched or "
                             "matched-static",
                             optarg);
        break;
      case 'j': json = 1; break;
      case 'E':
        if (strcmp(optarg, "ode") == 0) rq.engine = NULL; /* ODE runs always */
        else if (strcmp(optarg, "bullet") == 0) rq.engine = "bullet";
        else return fb_cli_fail("impact", 2, "--engine '%s': must be ode or bullet", optarg);
        break;
      case 'B':
        if (strcmp(optarg, "sequential-impulse") == 0) bt.solver = FB_BULLET_SEQUENTIAL_IMPULSE;
        else if (strcmp(optarg, "mlcp-dantzig") == 0) bt.solver = FB_BULLET_MLCP_DANTZIG;
        else return fb_cli_fail("impact", 2, "--bullet-solver '%s': must be sequential-impulse or "
                                "mlcp-dantzig", optarg);
        break;
      case 'I': if (!fb_cli_double("impact", "--bullet-iterations", optarg, &bt_iter)) return 2; break;
      case 'h': fputs(impact_help, stdout); return 0;
      default: return fb_cli_bad_option(argv, "h");
    }
  }
  if (optind < argc) return fb_cli_fail("impact", 2, "unexpected argument '%s'", argv[optind]);
  /* a flag the law does not use is refused, never ignored */
  if (damping_given && d.law.kind != FB_LAW_LINEAR && d.law.kind != FB_LAW_IMPACT)
    return fb_cli_fail("impact", 2, "--damping-n-s-m with --law %s: only the linear law (its "
                       "damper c) and the impact law (its c_max) take a damper; the %s law's "
                       "damping follows from --restitution", fb_law_name(d.law.kind),
                       fb_law_name(d.law.kind));
  if (depth_given && d.law.kind != FB_LAW_IMPACT)
    return fb_cli_fail("impact", 2, "--damping-depth-m with --law %s: only the impact law (its "
                       "d_max) takes a damping depth", fb_law_name(d.law.kind));
  if (d.law.kind == FB_LAW_LINEAR || d.law.kind == FB_LAW_RESTITUTION) {
    if (exponent_given && d.law.exponent != 1.0)
      return fb_cli_fail("impact", 2, "--exponent %g: the %s law is linear (n = 1)",
                         d.law.exponent, fb_law_name(d.law.kind));
    d.law.exponent = 1.0;
  }
  if (!(q >= 1 && q <= 1e6 && q == floor(q)))
    return fb_cli_fail("impact", 2, "--quick-iterations %g: must be an integer >= 1", q);
  d.quick_iterations = (int)q;
  if (!(bt_iter >= 1 && bt_iter <= 100000 && bt_iter == floor(bt_iter)))
    return fb_cli_fail("impact", 2, "--bullet-iterations %g: must be an integer 1 to 100000",
                       bt_iter);
  bt.iterations = (int)bt_iter;
  rq.d = d;
  rq.h = h;
  rq.opts.bullet = bt;
  static fb_impact_study s;
  fb_diag diag;
  if (fb_impact_study_run(&s, &rq, &diag) != FB_OK)
    return fb_cli_fail("impact", s.bad_input ? 2 : 1, "%s", diag.msg);
  if (json) {
    fb_report_impact_json(stdout, &s);
    return fb_report_impact_ok(&s) ? 0 : 1;
  }
  const char *failed = fb_report_impact_text(stdout, &s);
  return failed ? fb_cli_fail("impact", 1, "%s", failed) : 0;
}
