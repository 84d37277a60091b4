/* fourbar impact: argument parsing and dispatch only. */
#include <getopt.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "fb_config.h"
#include "impact.h"
#include "model_table.h"

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
    "  --restitution  target cr (default 0.9)\n"
    "  --damping-n-s-m   c of the linear law, c_max of the impact law (default 0)\n"
    "  --damping-depth-m d_max of the impact law (default 1e-5)\n"
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

static json_t *result_json(const fb_impact_result *r) {
  json_t *o = json_object();
  json_object_set_new(o, "penetration_max_m", json_real(r->penetration_max));
  json_object_set_new(o, "contact_duration_s", json_real(r->contact_duration));
  json_object_set_new(o, "force_max_n", json_real(r->force_max));
  json_object_set_new(o, "restitution_achieved", json_real(r->restitution));
  json_object_set_new(o, "steps", json_integer((json_int_t)r->steps));
  json_object_set_new(o, "wall_s", json_real(r->wall_s));
  return o;
}

static double rel(double x, double ref) { return ref != 0.0 ? (x - ref) / fabs(ref) : x - ref; }

static json_t *error_json(const fb_impact_result *x, const fb_impact_result *ref) {
  json_t *o = json_object();
  json_object_set_new(o, "penetration_max_rel", json_real(rel(x->penetration_max, ref->penetration_max)));
  json_object_set_new(o, "contact_duration_rel", json_real(rel(x->contact_duration, ref->contact_duration)));
  json_object_set_new(o, "force_max_rel", json_real(rel(x->force_max, ref->force_max)));
  json_object_set_new(o, "restitution_rel", json_real(rel(x->restitution, ref->restitution)));
  return o;
}

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
  fb_impact_def d;
  memset(&d, 0, sizeof d);
  d.law = fb_contact_law_default();
  d.mass = 1.0;
  d.speed = 1.0;
  d.stepper = FB_STEPPER_WORLD;
  d.quick_iterations = 20;
  d.mapping = FB_MAPPING_MATCHED; /* the case key's default: one default with fourbar run */
  double h = 0.0, q = 20, bt_iter = 100;
  int with_bullet = 0;
  fb_bullet_opts bt = fb_bullet_opts_default();
  int json = 0, ch, exponent_given = 0;
  optind = 1;
  while ((ch = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
    switch (ch) {
      case 'L':
        d.law.kind = fb_law_parse(optarg);
        if (d.law.kind == FB_LAW_COUNT)
          return fb_cli_fail("impact", 2, "--law '%s': unknown law; see --help", optarg);
        break;
      case 'k': if (!fb_cli_double("impact", "--stiffness", optarg, &d.law.stiffness)) return 2; break;
      case 'n': if (!fb_cli_double("impact", "--exponent", optarg, &d.law.exponent)) return 2; exponent_given = 1; break;
      case 'e': if (!fb_cli_double("impact", "--restitution", optarg, &d.law.restitution)) return 2; break;
      case 'c': if (!fb_cli_double("impact", "--damping-n-s-m", optarg, &d.law.damping)) return 2; break;
      case 'd': if (!fb_cli_double("impact", "--damping-depth-m", optarg, &d.law.damping_depth)) return 2; break;
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
        if (strcmp(optarg, "ode") == 0) with_bullet = 0;
        else if (strcmp(optarg, "bullet") == 0) with_bullet = 1;
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
  if (with_bullet && !fb_engine_available(FB_ENGINE_BULLET))
    return fb_cli_fail("impact", 2, "--engine bullet: Bullet is not in this build: %s",
                       FB_BULLET_HOWTO);
  d.law.mass = d.mass;
  d.h = 1.0; /* checked below once the default is known */
  fb_diag diag;
  if (fb_impact_check(&d, &diag) != FB_OK) return fb_cli_fail("impact", 2, "%s", diag.msg);
  const double t_est = fb_impact_duration_estimate(&d);
  if (h < 0.0) return fb_cli_fail("impact", 2, "--h-s %g: the step size must be positive", h);
  d.h = h > 0.0 ? h : t_est / 200.0;
  if (fb_impact_check(&d, &diag) != FB_OK) return fb_cli_fail("impact", 2, "%s", diag.msg);

  fb_impact_result ode, ref, cf;
  if (fb_impact_reference(&ref, &d, &diag) != FB_OK) return fb_cli_fail("impact", 1, "%s", diag.msg);
  fb_status st = fb_impact_ode(&ode, &d, &diag);
  int has_cf = fb_impact_closed_form(&cf, &d);
  fb_impact_result btr;
  fb_diag bdiag;
  fb_status bst = FB_ERR_ARG;
  memset(&btr, 0, sizeof btr);
#if FB_HAVE_BULLET
  if (with_bullet) bst = fb_impact_bullet(&btr, &d, &bt, &bdiag);
#endif
  const double h_omega = d.h * M_PI / ref.contact_duration;
  if (json) {
    json_t *o = json_object();
    json_object_set_new(o, "law", json_string(fb_law_name(d.law.kind)));
    json_object_set_new(o, "stiffness", json_real(d.law.stiffness));
    json_object_set_new(o, "exponent", json_real(d.law.exponent));
    json_object_set_new(o, "restitution_target", json_real(d.law.restitution));
    json_object_set_new(o, "mass_kg", json_real(d.mass));
    json_object_set_new(o, "speed_m_s", json_real(d.speed));
    json_object_set_new(o, "h_s", json_real(d.h));
    json_object_set_new(o, "h_omega", json_real(h_omega));
    json_object_set_new(o, "stepper", json_string(d.stepper == FB_STEPPER_WORLD ? "world" : "quick"));
    json_object_set_new(o, "mapping", json_string(fb_mapping_name(d.mapping)));
    json_object_set_new(o, "status", json_string(st == FB_OK ? "ok" : diag.msg));
    json_object_set_new(o, "ode", st == FB_OK ? result_json(&ode) : json_null());
    json_object_set_new(o, "reference", result_json(&ref));
    json_object_set_new(o, "closed_form", has_cf ? result_json(&cf) : json_null());
    json_object_set_new(o, "error_vs_reference", st == FB_OK ? error_json(&ode, &ref) : json_null());
    json_object_set_new(o, "error_vs_closed_form",
                        st == FB_OK && has_cf ? error_json(&ode, &cf) : json_null());
    if (with_bullet) {
      json_object_set_new(o, "bullet_solver", json_string(fb_bullet_solver_name(bt.solver)));
      json_object_set_new(o, "bullet_iterations", json_integer(bt.iterations));
      json_object_set_new(o, "bullet_status", json_string(bst == FB_OK ? "ok" : bdiag.msg));
      json_object_set_new(o, "bullet", bst == FB_OK ? result_json(&btr) : json_null());
      json_object_set_new(o, "bullet_error_vs_reference",
                          bst == FB_OK ? error_json(&btr, &ref) : json_null());
    }
    json_dumpf(o, stdout, JSON_INDENT(2) | JSON_REAL_PRECISION(10));
    fputc('\n', stdout);
    json_decref(o);
    return st == FB_OK && (!with_bullet || bst == FB_OK) ? 0 : 1;
  }
  printf("%s law, K = %g, n = %g, cr = %g, m = %g kg, v0 = %g m/s; ODE %s, %s mapping, "
         "h = %.4g s (h omega_c = %.3g, omega_c = pi / contact duration)\n\n",
         fb_law_name(d.law.kind), d.law.stiffness, d.law.exponent, d.law.restitution, d.mass,
         d.speed, d.stepper == FB_STEPPER_WORLD ? "dWorldStep" : "dWorldQuickStep",
         fb_mapping_name(d.mapping), d.h, h_omega);
  printf("%-12s %16s %16s %14s %12s %10s\n", "", "penetration_m", "duration_s", "force_max_n",
         "restitution", "steps");
  const fb_impact_result *rows[4] = {&ode, with_bullet && bst == FB_OK ? &btr : NULL, &ref,
                                     has_cf ? &cf : NULL};
  const char *names[4] = {"ode", "bullet", "reference", "closed form"};
  for (int i = 0; i < 4; i++) {
    if (!rows[i] || (i == 0 && st != FB_OK)) continue;
    printf("%-12s %16.8e %16.8e %14.6e %12.6f %10zu\n", names[i], rows[i]->penetration_max,
           rows[i]->contact_duration, rows[i]->force_max, rows[i]->restitution, rows[i]->steps);
  }
  if (st != FB_OK) return fb_cli_fail("impact", 1, "%s", diag.msg);
  printf("\nODE relative error vs reference: penetration %+.3e, duration %+.3e, force %+.3e, "
         "restitution %+.3e\n",
         rel(ode.penetration_max, ref.penetration_max), rel(ode.contact_duration, ref.contact_duration),
         rel(ode.force_max, ref.force_max), rel(ode.restitution, ref.restitution));
  if (with_bullet) {
    if (bst != FB_OK) return fb_cli_fail("impact", 1, "%s", bdiag.msg);
    printf("Bullet (%s, %d iterations) relative error vs reference: penetration %+.3e, "
           "duration %+.3e, force %+.3e, restitution %+.3e\n",
           fb_bullet_solver_name(bt.solver), bt.iterations,
           rel(btr.penetration_max, ref.penetration_max),
           rel(btr.contact_duration, ref.contact_duration), rel(btr.force_max, ref.force_max),
           rel(btr.restitution, ref.restitution));
  }
  return 0;
}
