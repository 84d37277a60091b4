/* fourbar contact-params: argument parsing, dispatch and printing only; the
 * translations are src/physics/engine_params.c, the verification runs are
 * the single-impact engines of impact.h. */
#include <getopt.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "case.h"
#include "casefile.h"
#include "cli.h"
#include "contact.h"
#include "engine_params.h"
#include "fb_config.h"
#include "impact.h"
#include "model_table.h"
#include "resolution.h"
#include "units.h"

static const char params_help[] =
    "usage: fourbar contact-params [--law linear|restitution|hertz] [--stiffness K]\n"
    "         [--exponent n] [--damping-n-s-m c | --restitution cr]\n"
    "         [--mass-kg m | --mass-kg A:B] [--h-s h] [--speed-m-s v]\n"
    "         [--load-n F] [--verify] [--json]\n"
    "       fourbar contact-params --case CASE [--joint NAME]\n"
    "         [--law restitution|hertz] [--h-s h] [--speed-m-s v]\n"
    "         [--verify] [--json]\n"
    "\n"
    "The engine parameters that make a soft contact behave like a given physical\n"
    "contact at step h: ODE (per-contact ERP/CFM), Gazebo (SDF kp, kd, max_vel,\n"
    "min_depth), MuJoCo 2.2 (solref/solimp, direct and standard form) and Bullet\n"
    "(contact stiffness and damping), each in the engine's own units and syntax.\n"
    "With --verify, each is simulated on a single impact of the given mass and\n"
    "speed and compared with the continuous law (docs/contact-params.md).\n"
    "\n"
    "  --law          restitution (default: a linear spring with the damper\n"
    "                 that gives coefficient of restitution cr), linear (spring\n"
    "                 and damper), hertz (K delta^n, undamped: turned into a\n"
    "                 linear spring at an operating point, see --load-n)\n"
    "  --stiffness    k [N/m] (hertz: K [N/m^n]); default 1e7\n"
    "  --exponent     n of the hertz law (default 1.5)\n"
    "  --restitution  cr of the restitution law, in (0.135, 1] (default 0.9)\n"
    "  --damping-n-s-m  c of the linear law [N s/m] (default 0)\n"
    "  --mass-kg      effective mass along the contact normal [kg], or a range A:B\n"
    "                 (the rows are designed at the geometric mean and verified\n"
    "                 at both ends); default 0.1\n"
    "  --h-s          step size [s]; default: h omega_c = 0.1 at the smallest mass\n"
    "  --speed-m-s    impact speed for --verify and the hertz operating point\n"
    "                 (default 1)\n"
    "  --load-n       hertz only: linearise at the static penetration of this\n"
    "                 load (tangent stiffness) instead of the impact at\n"
    "                 --speed-m-s (the linear spring with the same peak\n"
    "                 penetration)\n"
    "  --case         take the contact from a case file (a path, or a shipped\n"
    "                 case's name): the law of its clearance-restitution models\n"
    "                 (--law restitution: k, cr) or of its clearance-impact models\n"
    "                 (--law hertz: K, n, linearised at the joint's expected\n"
    "                 force; its damper is not carried), the joint's\n"
    "                 effective-mass range over a revolution and every\n"
    "                 direction, and the run's step (unless --h-s)\n"
    "  --joint        the case's clearance joint (crank-coupler,\n"
    "                 coupler-follower, ...); needed when the case has several\n"
    "  --verify       simulate each engine's parameters on one impact\n"
    "  --json         one JSON object: params per engine and verify (see docs)\n"
    "Exit status: 0 ok, 1 a verification failed to run, 2 bad input.\n";

/* Largest effective-mass ratio A:B may span: beyond it no single row can be
 * faithful, and a user has mistyped a unit. */
#define MASS_RATIO_MAX 1e4
/* Default h omega_c when --h-s is not given: the single-impact accuracy
 * point of the issue (h omega_c = 0.1, about 31 steps per contact). */
#define DEFAULT_H_OMEGA 0.1
/* --verify runs each row until the body leaves, or for this many contact
 * durations of the continuous law (a row that never lets go fails there). */
#define VERIFY_DURATIONS 100.0
/* The max_vel / contact_max_correcting_vel printed: this multiple of the
 * largest correcting velocity the row asks for at the law's peak
 * penetration, so that no impact up to twice the speed is cut. */
#define MAX_VEL_MARGIN 2.0

typedef struct {
  fb_law_kind law;
  double K, n, c, cr;
  double m_min, m_max, m0;
  double h, v, load;
  int has_load, verify, json;
  /* --case: the file, the joint and the law's model */
  char case_path[4096];
  int joint;
} request;

static double rel(double x, double ref) { return ref != 0.0 ? (x - ref) / fabs(ref) : x - ref; }

/* the linear contact the engines get at mass m; for hertz, also the
 * operating-point penetration [m] */
static fb_linear_contact linear_of(const request *q, double m, double *delta_op) {
  fb_linear_contact lc = {q->K, q->c, m, q->h};
  *delta_op = NAN;
  if (q->law == FB_LAW_RESTITUTION) lc.c = fb_params_damper_for_restitution(q->K, q->m0, q->cr);
  if (q->law == FB_LAW_HERTZ) {
    if (q->has_load) {
      /* tangent stiffness n K delta^(n-1) at the static penetration of the load */
      *delta_op = pow(q->load / q->K, 1.0 / q->n);
      lc.k = q->n * q->K * pow(*delta_op, q->n - 1.0);
    } else {
      /* the linear spring whose impact of m0 at v reaches the law's peak
       * penetration ((n + 1) m v^2 / (2 K))^(1/(n+1)) (energy balance) */
      *delta_op = pow((q->n + 1.0) * q->m0 * q->v * q->v / (2.0 * q->K), 1.0 / (q->n + 1.0));
      lc.k = q->m0 * q->v * q->v / (*delta_op * *delta_op);
    }
    lc.c = 0.0;
  }
  return lc;
}

/* the continuous law's single impact of mass m at speed v (the target),
 * as the reference integrates it */
static void target_def(const request *q, double m, fb_impact_def *out) {
  fb_impact_def d;
  memset(&d, 0, sizeof d);
  d.law = fb_contact_law_default();
  d.law.kind = q->law == FB_LAW_HERTZ ? FB_LAW_HERTZ : FB_LAW_LINEAR;
  d.law.stiffness = q->K;
  d.law.exponent = q->law == FB_LAW_HERTZ ? q->n : 1.0;
  double dop;
  d.law.damping = q->law == FB_LAW_HERTZ ? 0.0 : linear_of(q, m, &dop).c;
  d.law.mass = m;
  d.mass = m;
  d.speed = q->v;
  d.h = q->h;
  d.stepper = FB_STEPPER_WORLD;
  d.quick_iterations = 20;
  d.mapping = FB_MAPPING_MATCHED;
  *out = d;
}

static fb_status target(const request *q, double m, fb_impact_result *out, fb_diag *diag) {
  fb_impact_def d;
  target_def(q, m, &d);
  fb_status st = fb_impact_check(&d, diag);
  if (st != FB_OK) return st;
  return fb_impact_reference(out, &d, diag);
}

static json_t *row_json(const fb_ode_row *r) {
  json_t *o = json_object();
  json_object_set_new(o, "erp", json_real(r->erp));
  json_object_set_new(o, "cfm_m_n_s", json_real(r->cfm));
  return o;
}

static json_t *mujoco_json(const fb_mujoco_params *p, const char *form) {
  json_t *o = json_object();
  json_object_set_new(o, "form", json_string(form));
  json_object_set_new(o, "solref", json_pack("[f,f]", p->solref[0], p->solref[1]));
  json_object_set_new(o, "solimp", json_pack("[f,f,f,f,f]", p->solimp[0], p->solimp[1],
                                             p->solimp[2], p->solimp[3], p->solimp[4]));
  json_object_set_new(o, "stiffness_per_mass_1_s2", json_real(p->kappa));
  json_object_set_new(o, "damping_per_mass_1_s", json_real(p->beta));
  return o;
}

typedef struct {
  const char *engine, *form;
  double mass, restitution, restitution_target, penetration, penetration_target;
  double force, force_target;
  int ok;
  char why[1024];
} check_row;

static int parse_mass(const char *s, request *q) {
  char *end;
  q->m_min = strtod(s, &end);
  q->m_max = q->m_min;
  if (*end == ':') q->m_max = strtod(end + 1, &end);
  if (*end != '\0' || end == s) return 0;
  return 1;
}

int fb_cmd_contact_params(int argc, char **argv) {
  static const struct option opts[] = {
      {"law", required_argument, 0, 'L'},       {"stiffness", required_argument, 0, 'k'},
      {"exponent", required_argument, 0, 'n'},  {"restitution", required_argument, 0, 'e'},
      {"damping-n-s-m", required_argument, 0, 'c'}, {"mass-kg", required_argument, 0, 'm'},
      {"h-s", required_argument, 0, 'H'},       {"speed-m-s", required_argument, 0, 'v'},
      {"load-n", required_argument, 0, 'F'},    {"verify", no_argument, 0, 'V'},
      {"json", no_argument, 0, 'j'},            {"help", no_argument, 0, 'h'},
      {"case", required_argument, 0, 'C'},      {"joint", required_argument, 0, 'J'},
      {0, 0, 0, 0}};
  request q = {.law = FB_LAW_RESTITUTION, .K = 1e7, .n = 1.5, .c = 0.0, .cr = 0.9,
               .m_min = 0.1, .m_max = 0.1, .h = 0.0, .v = 1.0};
  int ch, cr_given = 0, c_given = 0, n_given = 0, k_given = 0, m_given = 0, law_given = 0;
  int h_given = 0; /* --h-s given: its value is checked, never replaced by the default */
  const char *case_arg = NULL, *joint_arg = NULL;
  const char *P = "contact-params";
  optind = 1;
  while ((ch = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
    switch (ch) {
      case 'L':
        if (strcmp(optarg, "linear") == 0) q.law = FB_LAW_LINEAR;
        else if (strcmp(optarg, "restitution") == 0) q.law = FB_LAW_RESTITUTION;
        else if (strcmp(optarg, "hertz") == 0) q.law = FB_LAW_HERTZ;
        else return fb_cli_fail(P, 2, "--law '%s': must be linear, restitution or hertz", optarg);
        law_given = 1;
        break;
      case 'k': if (!fb_cli_double(P, "--stiffness", optarg, &q.K)) return 2; k_given = 1; break;
      case 'n': if (!fb_cli_double(P, "--exponent", optarg, &q.n)) return 2; n_given = 1; break;
      case 'e': if (!fb_cli_double(P, "--restitution", optarg, &q.cr)) return 2; cr_given = 1; break;
      case 'c': if (!fb_cli_double(P, "--damping-n-s-m", optarg, &q.c)) return 2; c_given = 1; break;
      case 'm':
        if (!parse_mass(optarg, &q))
          return fb_cli_fail(P, 2, "--mass-kg '%s': a mass in kg or a range A:B", optarg);
        m_given = 1;
        break;
      case 'C': case_arg = optarg; break;
      case 'J': joint_arg = optarg; break;
      case 'H': if (!fb_cli_double(P, "--h-s", optarg, &q.h)) return 2; h_given = 1; break;
      case 'v': if (!fb_cli_double(P, "--speed-m-s", optarg, &q.v)) return 2; break;
      case 'F': if (!fb_cli_double(P, "--load-n", optarg, &q.load)) return 2; q.has_load = 1; break;
      case 'V': q.verify = 1; break;
      case 'j': q.json = 1; break;
      case 'h': fputs(params_help, stdout); return 0;
      default: return fb_cli_fail(P, 2, "unknown option '%s'; see fourbar contact-params --help",
                                  argv[optind - 1]);
    }
  }
  if (optind < argc) return fb_cli_fail(P, 2, "unexpected argument '%s'", argv[optind]);
  (void)law_given;
  fb_case_contact cc;
  q.joint = -1;
  if (joint_arg && !case_arg)
    return fb_cli_fail(P, 2, "--joint %s: names a joint of a case; give --case too", joint_arg);
  if (case_arg) {
    if (k_given || cr_given || c_given || n_given || m_given || q.has_load)
      return fb_cli_fail(P, 2, "--case takes the stiffness, exponent, damping or restitution, "
                         "effective mass and operating point from the case: drop %s",
                         k_given ? "--stiffness" : cr_given ? "--restitution"
                         : c_given ? "--damping-n-s-m" : n_given ? "--exponent"
                         : m_given ? "--mass-kg" : "--load-n");
    if (q.law == FB_LAW_LINEAR)
      return fb_cli_fail(P, 2, "--law linear with --case: a case's clearance models use the "
                         "restitution law (--law restitution, the default) and the impact law "
                         "(--law hertz)");
    fb_cli_case_path(q.case_path, sizeof q.case_path, case_arg);
    fb_case cs;
    fb_diag cd;
    if (fb_casefile_load(&cs, q.case_path, NULL, 0, &cd) != FB_OK)
      return fb_cli_fail(P, 2, "%s", cd.msg);
    if (joint_arg) {
      for (int j = 0; j < 4; j++)
        if (strcmp(joint_arg, fb_joint_name(j)) == 0) q.joint = j;
      if (q.joint < 0)
        return fb_cli_fail(P, 2, "--joint '%s': must be ground-crank, crank-coupler, "
                           "coupler-follower or follower-ground", joint_arg);
    } else {
      int n = 0;
      for (int j = 0; j < 4; j++)
        if (cs.clearance.mask & (1 << j)) q.joint = j, n++;
      if (n > 1)
        return fb_cli_fail(P, 2, "--case %s has %d clearance joints: name one with --joint",
                           q.case_path, n);
    }
    if (fb_case_contact_of(&cc, &cs, q.joint, &cd) != FB_OK)
      return fb_cli_fail(P, 2, "--case %s: %s", q.case_path, cd.msg);
    if (q.law == FB_LAW_HERTZ) {
      q.K = cc.impact.stiffness;
      q.n = cc.impact.exponent;
      /* the operating point: the joint's expected force (resolution.h) */
      q.load = cc.est.force_expected;
      q.has_load = 1;
    } else {
      q.K = cc.restitution.stiffness;
      q.cr = cc.restitution.restitution;
      cr_given = 1;
    }
    q.m_min = cc.est.m_eff_min;
    q.m_max = cc.est.m_eff_max;
    if (!h_given) q.h = cc.h;
  }
  /* every parameter with its range and unit */
  if (!(q.K > 0.0) || !isfinite(q.K) || q.K > 1e20)
    return fb_cli_fail(P, 2, "--stiffness %s: must be positive, at most 1e20 (N/m, or N/m^n "
                       "for hertz)", FB_NUM(q.K));
  /* the effective mass a single impact can take (impact.h, --verify's and
   * impact --mass-kg's range) */
  if (!(q.m_min >= FB_MASS_MIN_KG) || !(q.m_max >= q.m_min) || !isfinite(q.m_max) ||
      q.m_max > MASS_RATIO_MAX * q.m_min || q.m_max > FB_MASS_MAX_KG)
    return fb_cli_fail(P, 2, "--mass-kg %s:%s: need %g kg <= A <= B <= %g kg and B/A <= %g",
                       FB_NUM(q.m_min), FB_NUM(q.m_max), FB_MASS_MIN_KG, FB_MASS_MAX_KG,
                       MASS_RATIO_MAX);
  if (!(q.v > 0.0) || q.v > FB_IMPACT_SPEED_MAX_M_S)
    return fb_cli_fail(P, 2, "--speed-m-s %s: must lie in (0, %g] m/s", FB_NUM(q.v),
                       FB_IMPACT_SPEED_MAX_M_S);
  if (q.law == FB_LAW_HERTZ) {
    if (cr_given || c_given)
      return fb_cli_fail(P, 2, "--law hertz is undamped here: give a linear or restitution law "
                         "for a damped contact (or drop --restitution/--damping-n-s-m)");
    if (!(q.n >= 1.0 && q.n <= 3.0))
      return fb_cli_fail(P, 2, "--exponent %s: must lie in [1, 3]", FB_NUM(q.n));
  } else {
    if (n_given && q.n != 1.0)
      return fb_cli_fail(P, 2, "--exponent %s: the %s law is linear (n = 1)", FB_NUM(q.n),
                         q.law == FB_LAW_LINEAR ? "linear" : "restitution");
    if (q.has_load) return fb_cli_fail(P, 2, "--load-n: only for --law hertz");
    q.n = 1.0;
  }
  /* a flag the law does not use is refused, never ignored */
  if (q.law == FB_LAW_RESTITUTION && c_given)
    return fb_cli_fail(P, 2, "--damping-n-s-m with the restitution law: its damper follows from "
                       "--restitution (cr); give --law linear for a damper of your own");
  if (q.law == FB_LAW_LINEAR && cr_given)
    return fb_cli_fail(P, 2, "--restitution with --law linear: the linear law's damper is "
                       "--damping-n-s-m; drop --law linear for the restitution law (cr)");
  if (q.law == FB_LAW_RESTITUTION && !(q.cr > exp(-2.0) && q.cr <= 1.0))
    return fb_cli_fail(P, 2, "--restitution %s: cr must lie in (0.135, 1] (below e^-2 the "
                       "spring-damper is over-damped)", FB_NUM(q.cr));
  if (q.law == FB_LAW_LINEAR && (!(q.c >= 0.0) || !isfinite(q.c)))
    return fb_cli_fail(P, 2, "--damping-n-s-m %s: must be >= 0 and finite", FB_NUM(q.c));
  if (q.has_load && !(q.load > 0.0 && isfinite(q.load)))
    return fb_cli_fail(P, 2, "--load-n %s: must be positive and finite", FB_NUM(q.load));
  q.m0 = sqrt(q.m_min * q.m_max);
  double dop;
  {
    const double h_keep = q.h;
    q.h = 1.0;
    fb_linear_contact lmin = linear_of(&q, q.m_min, &dop);
    const double h_auto = DEFAULT_H_OMEGA / sqrt(lmin.k / q.m_min);
    q.h = h_keep;
    if (h_given && (!(q.h > 0.0) || !isfinite(q.h)))
      return fb_cli_fail(P, 2, "--h-s %s: the step size must be positive", FB_NUM(q.h));
    if (!h_given && !(q.h > 0.0)) q.h = h_auto;
  }
  fb_diag diag;
  fb_linear_contact lc = linear_of(&q, q.m0, &dop);
  if (fb_linear_contact_check(&lc, &diag) != FB_OK) return fb_cli_fail(P, 2, "%s", diag.msg);
  /* the impacts these parameters describe, at both ends of the mass range:
   * the law's own and the linear contact the engines get, each a contact a
   * double can follow in at most FB_IMPACT_MAX_STEPS steps of h (impact.h);
   * --verify steps each row up to 100 contact durations, so there every
   * duration must fit in FB_IMPACT_MAX_STEPS / 100 steps */
  for (int e = 0; e < 2; e++) {
    const double m = e ? q.m_max : q.m_min;
    fb_impact_def d[2];
    target_def(&q, m, &d[0]);
    d[1] = d[0];
    double dm;
    const fb_linear_contact lm = linear_of(&q, m, &dm);
    d[1].law.kind = FB_LAW_LINEAR;
    d[1].law.exponent = 1.0;
    d[1].law.stiffness = lm.k;
    d[1].law.damping = lm.c;
    for (int k = 0; k < 2; k++) {
      if (fb_impact_check(&d[k], &diag) != FB_OK)
        return fb_cli_fail(P, 2, "%s (the %s at %s kg, %s m/s)", diag.msg,
                           k ? "linear contact the engines get" : "law's impact", FB_NUM(m),
                           FB_NUM(q.v));
      fb_impact_result cf;
      const double T = fb_impact_closed_form(&cf, &d[k]) ? cf.contact_duration
                                                         : fb_impact_duration_estimate(&d[k]);
      if (q.verify && VERIFY_DURATIONS * T / q.h + 10.0 > FB_IMPACT_MAX_STEPS)
        return fb_cli_fail(P, 2, "--h-s %s with --verify: each row runs for up to %g contact "
                           "durations (%.3g s at %s kg), %.3g steps, more than %.0e: give h >= "
                           "%.2g s", FB_NUM(q.h), VERIFY_DURATIONS, T, FB_NUM(m),
                           VERIFY_DURATIONS * T / q.h, FB_IMPACT_MAX_STEPS,
                           VERIFY_DURATIONS * T / FB_IMPACT_MAX_STEPS);
    }
  }
  const double h_omega_max = q.h * sqrt(lc.k / q.m_min);
  const double omega_d_h = fb_contact_omega_d_h(q.h, lc.k, lc.c, q.m_min);
  if (omega_d_h > FB_MATCHED_ALIAS_BOUND)
    return fb_cli_fail(P, 2, "--h-s %g: omega_d h = %.3g at the smallest mass passes %.3g (the "
                       "step aliases the contact's oscillation); use h <= %.3g s",
                       q.h, omega_d_h, FB_MATCHED_ALIAS_BOUND,
                       q.h * FB_MATCHED_ALIAS_BOUND / omega_d_h);

  fb_ode_row matched, standard, gz_row;
  if (fb_params_ode_matched(&lc, &matched, &diag) != FB_OK ||
      fb_params_ode_standard(&lc, &standard, &diag) != FB_OK)
    return fb_cli_fail(P, 2, "%s", diag.msg);
  fb_spring_damper gz;
  fb_params_spring_damper_of_row(&matched, q.h, &gz);
  if (fb_params_row_of_spring_damper(&gz, q.h, &gz_row, &diag) != FB_OK)
    return fb_cli_fail(P, 2, "%s", diag.msg);
  /* the law's peak penetration at the heaviest mass and the speed (undamped
   * linear estimate), for the correcting-velocity limits */
  const double delta_peak = q.v * sqrt(q.m_max / lc.k);
  const double max_vel =
      MAX_VEL_MARGIN * fmax(fb_params_correcting_velocity(&matched, q.h, delta_peak), q.v);
  fb_mujoco_params mj_direct, mj_cont, mj_std;
  fb_params_mujoco_direct_matched(&lc, &mj_direct);
  fb_params_mujoco_direct_continuous(&lc, &mj_cont);
  /* what users commonly paste: solref (-k/m, -c/m) with MuJoCo's default
   * solimp (0.9 0.95 0.001 0.5 2) */
  fb_mujoco_params mj_naive = mj_cont;
  mj_naive.solref[0] = -lc.k / lc.m;
  mj_naive.solref[1] = -lc.c / lc.m;
  const double solimp_default[5] = {0.9, 0.95, 0.001, 0.5, 2.0};
  memcpy(mj_naive.solimp, solimp_default, sizeof solimp_default);
  /* and Gazebo's kp, kd set to the law's k, c: the standard row */
  const fb_spring_damper gz_naive = {lc.k, lc.c};
  fb_ode_row gz_naive_row;
  if (fb_params_row_of_spring_damper(&gz_naive, q.h, &gz_naive_row, &diag) != FB_OK)
    return fb_cli_fail(P, 2, "%s", diag.msg);
  fb_diag std_diag;
  const int has_std = fb_params_mujoco_standard(&lc, &mj_std, &std_diag) == FB_OK;

  /* ---- verification ------------------------------------------------------ */
  check_row rows[64];
  int nrows = 0, failed = 0;
  if (q.verify) {
    double masses[3] = {q.m_min, q.m0, q.m_max};
    const int nm = q.m_min == q.m_max ? 1 : 3;
    if (nm == 1) masses[0] = q.m0;
    for (int i = 0; i < nm; i++) {
      const double m = masses[i];
      fb_impact_result ref;
      if (target(&q, m, &ref, &diag) != FB_OK) return fb_cli_fail(P, 1, "%s", diag.msg);
      const double t_max = VERIFY_DURATIONS * ref.contact_duration + 10.0 * q.h;
      /* MuJoCo's parameters are per unit of effective mass: the direct form
       * recomputed at this mass (what a per-contact update would hand it) */
      double dm;
      fb_linear_contact lm = linear_of(&q, m, &dm);
      fb_mujoco_params mj_at_mass;
      fb_params_mujoco_direct_matched(&lm, &mj_at_mass);
      struct {
        const char *engine, *form;
        int kind; /* 0 ODE row, 1 MuJoCo, 2 Bullet's contact stiffness and damping */
        const fb_ode_row *row;
        const fb_mujoco_params *mj;
        const fb_spring_damper *sd;
      } runs[] = {{"ode", "matched", 0, &matched, NULL, NULL},
                  {"ode", "standard", 0, &standard, NULL, NULL},
                  {"gazebo", "matched", 0, &gz_row, NULL, NULL},
                  {"gazebo", "naive", 0, &gz_naive_row, NULL, NULL},
                  {"mujoco", "direct", 1, NULL, &mj_direct, NULL},
                  {"mujoco", "direct-at-mass", 1, NULL, nm > 1 ? &mj_at_mass : NULL, NULL},
                  {"mujoco", "direct-continuous", 1, NULL, &mj_cont, NULL},
                  {"mujoco", "standard", 1, NULL, has_std ? &mj_std : NULL, NULL},
                  {"mujoco", "naive", 1, NULL, &mj_naive, NULL},
                  /* the printed stiffness and damping, and the law's k, c pasted as they are */
                  {"bullet", "matched", 2, NULL, NULL, &gz},
                  {"bullet", "naive", 2, NULL, NULL, &gz_naive}};
      for (size_t r = 0; r < sizeof runs / sizeof runs[0]; r++) {
        if (runs[r].kind == 1 && !runs[r].mj) continue;
        if (runs[r].kind == 1 && !FB_HAVE_MUJOCO) continue;
        if (runs[r].kind == 2 && !FB_HAVE_BULLET) continue;
        check_row *x = &rows[nrows++];
        memset(x, 0, sizeof *x);
        x->engine = runs[r].engine;
        x->form = runs[r].form;
        x->mass = m;
        x->restitution_target = ref.restitution;
        x->penetration_target = ref.penetration_max;
        x->force_target = ref.force_max;
        fb_impact_result res;
        fb_status st;
        if (runs[r].kind == 0)
          st = fb_impact_ode_row(&res, m, q.v, q.h, runs[r].row->erp, runs[r].row->cfm,
                                 strcmp(x->engine, "gazebo") == 0 ? max_vel : INFINITY, t_max,
                                 &diag);
        else if (runs[r].kind == 1)
          st = fb_impact_mujoco(&res, m, q.v, q.h, runs[r].mj->solref, runs[r].mj->solimp, t_max,
                                &diag);
        else
#if FB_HAVE_BULLET
          st = fb_impact_bullet_contact(&res, m, q.v, q.h, runs[r].sd->kp, runs[r].sd->kd, t_max,
                                        &diag);
#else
          st = FB_ERR_ARG; /* not reached: skipped above */
#endif
        x->ok = st == FB_OK;
        if (!x->ok) {
          snprintf(x->why, sizeof x->why, "%s", diag.msg);
          failed = 1;
          continue;
        }
        x->restitution = res.restitution;
        x->penetration = res.penetration_max;
        x->force = res.force_max;
      }
    }
  }

  if (q.json) {
    json_t *o = json_object();
    json_t *c = json_object();
    json_object_set_new(c, "law", json_string(q.law == FB_LAW_HERTZ ? "hertz"
                                              : q.law == FB_LAW_LINEAR ? "linear" : "restitution"));
    json_object_set_new(c, "stiffness", json_real(q.K));
    json_object_set_new(c, "stiffness_unit", json_string(q.law == FB_LAW_HERTZ ? "N/m^n" : "N/m"));
    json_object_set_new(c, "exponent", json_real(q.n));
    json_object_set_new(c, "restitution", q.law == FB_LAW_RESTITUTION ? json_real(q.cr) : json_null());
    json_object_set_new(c, "linear_stiffness_n_m", json_real(lc.k));
    json_object_set_new(c, "linear_damping_n_s_m", json_real(lc.c));
    json_object_set_new(c, "operating_point",
                        q.law != FB_LAW_HERTZ ? json_null()
                        : json_pack("{s:s,s:f}", "rule",
                                    q.has_load ? "tangent at the static penetration of the load"
                                               : "equal peak penetration of the impact",
                                    "penetration_m", dop));
    json_object_set_new(o, "contact", c);
    json_object_set_new(o, "case",
                        q.joint < 0 ? json_null()
                                    : json_pack("{s:s,s:s,s:s}", "file", q.case_path, "joint",
                                                fb_joint_name(q.joint), "model",
                                                q.law == FB_LAW_HERTZ ? "clearance-impact"
                                                                      : "clearance-restitution"));
    json_object_set_new(o, "mass_kg", json_pack("{s:f,s:f,s:f}", "min", q.m_min, "max", q.m_max,
                                                "design", q.m0));
    json_object_set_new(o, "h_s", json_real(q.h));
    json_object_set_new(o, "h_omega_c_max", json_real(h_omega_max));
    json_object_set_new(o, "speed_m_s", json_real(q.v));
    json_t *p = json_object();
    json_t *ode = json_object();
    json_object_set_new(ode, "matched", row_json(&matched));
    json_object_set_new(ode, "standard", row_json(&standard));
    json_object_set_new(ode, "contact_max_correcting_vel_m_s", json_real(max_vel));
    json_object_set_new(ode, "contact_surface_layer_m", json_real(0.0));
    json_object_set_new(p, "ode", ode);
    json_object_set_new(p, "gazebo", json_pack("{s:f,s:f,s:f,s:f,s:f}", "kp", gz.kp, "kd", gz.kd,
                                               "max_vel", max_vel, "min_depth", 0.0,
                                               "max_step_size", q.h));
    json_t *mj = json_object();
    json_object_set_new(mj, "direct", mujoco_json(&mj_direct, "direct"));
    json_object_set_new(mj, "direct_continuous", mujoco_json(&mj_cont, "direct-continuous"));
    json_object_set_new(mj, "standard", has_std ? mujoco_json(&mj_std, "standard") : json_null());
    json_object_set_new(mj, "standard_note", has_std ? json_null() : json_string(std_diag.msg));
    json_object_set_new(mj, "integrator", json_string("Euler"));
    json_object_set_new(p, "mujoco", mj);
    json_object_set_new(p, "bullet", json_pack("{s:f,s:f}", "contact_stiffness", gz.kp,
                                               "contact_damping", gz.kd));
    json_object_set_new(o, "params", p);
    json_t *v = json_array();
    for (int i = 0; i < nrows; i++) {
      const check_row *x = &rows[i];
      json_t *e = json_object();
      json_object_set_new(e, "engine", json_string(x->engine));
      json_object_set_new(e, "form", json_string(x->form));
      json_object_set_new(e, "mass_kg", json_real(x->mass));
      json_object_set_new(e, "status", json_string(x->ok ? "ok" : x->why));
      json_object_set_new(e, "restitution", x->ok ? json_real(x->restitution) : json_null());
      json_object_set_new(e, "restitution_target", json_real(x->restitution_target));
      json_object_set_new(e, "restitution_rel",
                          x->ok ? json_real(rel(x->restitution, x->restitution_target)) : json_null());
      json_object_set_new(e, "penetration_max_m", x->ok ? json_real(x->penetration) : json_null());
      json_object_set_new(e, "penetration_target_m", json_real(x->penetration_target));
      json_object_set_new(e, "penetration_rel",
                          x->ok ? json_real(rel(x->penetration, x->penetration_target)) : json_null());
      json_object_set_new(e, "force_max_n", x->ok ? json_real(x->force) : json_null());
      json_object_set_new(e, "force_target_n", json_real(x->force_target));
      json_array_append_new(v, e);
    }
    json_object_set_new(o, "verify", q.verify ? v : json_null());
    if (!q.verify) json_decref(v);
    json_dumpf(o, stdout, JSON_INDENT(2) | JSON_REAL_PRECISION(10));
    fputc('\n', stdout);
    json_decref(o);
    return failed ? 1 : 0;
  }

  if (q.joint >= 0)
    printf("case %s, joint %s: the law of its clearance-%s models%s; effective mass over a "
           "revolution and every direction\n",
           q.case_path, fb_joint_name(q.joint), q.law == FB_LAW_HERTZ ? "impact" : "restitution",
           q.law == FB_LAW_HERTZ ? " (its damper not carried), linearised at the joint's "
                                   "expected force"
                                 : "");
  printf("contact: %s law, ", q.law == FB_LAW_HERTZ ? "hertz"
                             : q.law == FB_LAW_LINEAR ? "linear" : "restitution");
  if (q.law == FB_LAW_HERTZ)
    printf("K = %g N/m^%g, undamped; linear spring k = %.6g N/m at %s (penetration %.4g m)\n",
           q.K, q.n, lc.k,
           q.has_load ? "the tangent of the static penetration of the load"
                      : "equal peak penetration of the impact",
           dop);
  else if (q.law == FB_LAW_RESTITUTION)
    printf("k = %g N/m, cr = %g: damper c = %.6g N s/m at the design mass\n", q.K, q.cr, lc.c);
  else
    printf("k = %g N/m, c = %g N s/m\n", q.K, q.c);
  printf("effective mass %g to %g kg, rows designed at %.4g kg; step h = %.4g s "
         "(h omega_c up to %.3g)\n\n",
         q.m_min, q.m_max, q.m0, q.h, h_omega_max);
  printf("ODE (per contact, every step):\n"
         "  contact.surface.mode = dContactSoftERP | dContactSoftCFM;\n"
         "  contact.surface.soft_erp = %.10g;  contact.surface.soft_cfm = %.10g;\n"
         "  dWorldSetContactMaxCorrectingVel(world, %.4g);  dWorldSetContactSurfaceLayer(world, 0);\n"
         "  (standard mapping, for comparison: soft_erp = %.6g, soft_cfm = %.6g)\n\n",
         matched.erp, matched.cfm, max_vel, standard.erp, standard.cfm);
  printf("Gazebo (SDFormat, ODE physics, <max_step_size>%.6g</max_step_size>):\n"
         "  <surface><contact><ode><kp>%.10g</kp><kd>%.10g</kd>"
         "<max_vel>%.4g</max_vel><min_depth>0</min_depth></ode></contact></surface>\n"
         "  <physics><ode><constraints><contact_max_correcting_vel>%.4g"
         "</contact_max_correcting_vel><contact_surface_layer>0</contact_surface_layer>"
         "</constraints></ode></physics>\n",
         q.h, gz.kp, gz.kd, max_vel, max_vel);
  if (gz.kd < 0.0)
    printf("  kd < 0: the matched row's ERP exceeds 1 (it takes back the damper h kp that the\n"
           "  kp/kd -> ERP/CFM formula adds); a Gazebo that clamps kd at 0 gives the standard\n"
           "  row's restitution loss instead (the gazebo naive row of --verify shows it)\n");
  printf("\nMuJoCo 2.2 (<option timestep=\"%.6g\" integrator=\"Euler\"/>, stiffness per unit of "
         "the true effective mass):\n"
         "  <geom ... condim=\"1\" solref=\"%.10g %.10g\" solimp=\"%g %g %g %g %g\"/>   (direct)\n",
         q.h, mj_direct.solref[0], mj_direct.solref[1], mj_direct.solimp[0], mj_direct.solimp[1],
         mj_direct.solimp[2], mj_direct.solimp[3], mj_direct.solimp[4]);
  if (has_std)
    printf("  <geom ... condim=\"1\" solref=\"%.10g %.10g\" solimp=\"%g %g %g %g %g\"/>   (standard)\n",
           mj_std.solref[0], mj_std.solref[1], mj_std.solimp[0], mj_std.solimp[1],
           mj_std.solimp[2], mj_std.solimp[3], mj_std.solimp[4]);
  else
    printf("  standard form: %s\n", std_diag.msg);
  printf("\nBullet (btCollisionObject::setContactStiffnessAndDamping at fixed step h = %.6g s):\n"
         "  body.setContactStiffnessAndDamping(%.10g, %.10g);\n"
         "  other.setContactStiffnessAndDamping(BT_LARGE_FLOAT, 0);  (Bullet combines the two in\n"
         "    series for stiffness and adds the dampers: the default 0.1 N s/m would be added)\n"
         "  solverInfo.m_splitImpulse = 0; m_linearSlop = 0; m_sor = 1  (split impulse turns the\n"
         "    spring's position term into a position fix with no force)\n",
         q.h, gz.kp, gz.kd);
  if (!q.verify) return 0;
  printf("\nverification: one impact at %g m/s per mass, against the continuous law "
         "(rel = engine / law - 1)\n", q.v);
  printf("%-8s %-18s %9s %12s %10s %14s %10s %12s %10s\n", "engine", "form", "mass_kg",
         "restitution", "rel", "penetration_m", "rel", "force_max_n", "rel");
  for (int i = 0; i < nrows; i++) {
    const check_row *x = &rows[i];
    if (!x->ok) {
      printf("%-8s %-18s %9.4g  failed: %s\n", x->engine, x->form, x->mass, x->why);
      continue;
    }
    printf("%-8s %-18s %9.4g %12.6f %+10.2e %14.6e %+10.2e %12.5g %+10.2e\n", x->engine,
           x->form, x->mass, x->restitution, rel(x->restitution, x->restitution_target),
           x->penetration, rel(x->penetration, x->penetration_target), x->force,
           rel(x->force, x->force_target));
  }
  /* an engine this build lacks: named, with how to get it */
  if (!FB_HAVE_MUJOCO) printf("(mujoco not verified: %s)\n", fb_engine_howto(FB_ENGINE_MUJOCO));
  if (!FB_HAVE_BULLET) printf("(bullet not verified: %s)\n", fb_engine_howto(FB_ENGINE_BULLET));
  return failed ? 1 : 0;
}
