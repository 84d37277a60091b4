/* fourbar contact-params below the command: translation, rows, the largest
 * faithful step, at_step and the verification (contact_params.h). */
#include "contact_params.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "engine.h"
#include "planar_resolution.h"
#include "planar_run.h"
#include "resolution.h"
#include "units.h"

const double fb_cp_onset_phases[FB_CP_ONSET_PHASES] = {0.0, 0.25, 0.5, 0.75, 0.999};

/* MuJoCo's default solimp, what users paste with a naive solref */
static const double solimp_default[5] = {0.9, 0.95, 0.001, 0.5, 2.0};

static int is_hertz_family(fb_law_kind k) {
  return k == FB_LAW_HERTZ || k == FB_LAW_LANKARANI_NIKRAVESH || k == FB_LAW_HUNT_CROSSLEY ||
         k == FB_LAW_FLORES || k == FB_LAW_GONTHIER;
}

static int is_damped_hertz(fb_law_kind k) { return is_hertz_family(k) && k != FB_LAW_HERTZ; }

void fb_cp_request_default(fb_cp_request *q) {
  memset(q, 0, sizeof *q);
  q->law = FB_LAW_RESTITUTION;
  q->stiffness = 1e7;
  q->exponent = NAN;
  q->restitution = NAN;
  q->damping = NAN;
  q->mass_min = q->mass_max = 0.1;
  q->h = NAN;
  q->speed = 1.0;
  q->load = NAN;
  q->verify = 1;
  q->engine_steps = 0;
}

/* the request with its defaults filled: cr 0.9 for the restitution and
 * damped Hertz laws, n 1.5 for the Hertz laws, 1 for the linear ones */
static fb_cp_request resolved(const fb_cp_request *q) {
  fb_cp_request r = *q;
  if (isnan(r.exponent)) r.exponent = is_hertz_family(r.law) ? 1.5 : 1.0;
  if (isnan(r.restitution) && (r.law == FB_LAW_RESTITUTION || is_damped_hertz(r.law)))
    r.restitution = 0.9;
  if (isnan(r.damping)) r.damping = 0.0;
  return r;
}

/* an impact definition of law (kind, K, n, c, cr) on mass m at speed v */
static fb_impact_def impact_def(fb_law_kind kind, double K, double n, double c, double cr,
                                double m, double v, double h) {
  fb_impact_def d;
  memset(&d, 0, sizeof d);
  d.law = fb_contact_law_default();
  d.law.kind = kind;
  d.law.stiffness = K;
  d.law.exponent = n;
  d.law.damping = c;
  d.law.restitution = isnan(cr) ? 0.9 : cr;
  d.law.mass = m;
  d.mass = m;
  d.speed = v;
  d.h = h;
  d.stepper = FB_STEPPER_WORLD;
  d.quick_iterations = 20;
  d.mapping = FB_MAPPING_MATCHED;
  return d;
}

static fb_impact_def linear_def(double k, double c, double m, double v, double h) {
  return impact_def(FB_LAW_LINEAR, k, 1.0, c, NAN, m, v, h);
}

/* the linear contact (k, c) at m0 before the undamped floor; *dop the
 * operating point's penetration (hertz) */
static void linear_contact(const fb_cp_request *r, double m0, double *k, double *c, double *dop) {
  *dop = NAN;
  *k = r->stiffness;
  *c = 0.0;
  if (r->law == FB_LAW_RESTITUTION) *c = fb_params_damper_for_restitution(*k, m0, r->restitution);
  if (r->law == FB_LAW_LINEAR) *c = r->damping;
  if (r->law == FB_LAW_HERTZ) {
    const double K = r->stiffness, n = r->exponent;
    if (!isnan(r->load)) {
      /* tangent stiffness n K delta^(n-1) at the static penetration of the load */
      *dop = pow(r->load / K, 1.0 / n);
      *k = n * K * pow(*dop, n - 1.0);
    } else {
      /* the spring whose impact of m0 at v reaches the law's peak penetration
       * ((n + 1) m v^2 / (2 K))^(1/(n+1)) (energy balance) */
      *dop = pow((n + 1.0) * m0 * r->speed * r->speed / (2.0 * K), 1.0 / (n + 1.0));
      *k = m0 * r->speed * r->speed / (*dop * *dop);
    }
    /* with a restitution: the spring-damper of that restitution whose peak
     * penetration is still the elastic law's */
    fb_diag dg;
    if (!isnan(r->restitution) && isnan(r->load) &&
        fb_params_linear_equivalent(r->restitution, *dop, m0, r->speed, k, c, &dg) != FB_OK)
      *k = *c = NAN;
    if (!isnan(r->restitution) && !isnan(r->load))
      *c = fb_params_damper_for_restitution(*k, m0, r->restitution);
  }
}

/* cr standing for 0 in a law's impact as cr -> 0 (Lankarani-Nikravesh,
 * Hunt-Crossley: their damping factors are finite there) */
#define LAW_CR_ZERO 1e-9
/* Flores and Gonthier at cr >= 0.5 leave at >= 0.47 (measured), far above
 * e^-2: their smallest cr is searched only below */
#define LAW_CR_CHECKED 0.5

/* the restitution of the law's own impact at cr (scale-free: it depends on
 * cr and the exponent n alone, so K, m and v are 1) */
static double law_restitution_at(fb_law_kind law, double n, double cr) {
  fb_impact_def d = impact_def(law, 1.0, n, 0.0, cr, 1.0, 1.0, 1.0);
  fb_impact_result r;
  fb_diag dg;
  return fb_impact_reference(&r, &d, &dg) == FB_OK ? r.restitution : NAN;
}

/* Flores, Gonthier: the cr at which the law's own impact leaves at e^-2
 * (FB_RESTITUTION_MIN), by bisection on [FB_IMPACT_CR_MIN_DIVERGENT,
 * LAW_CR_CHECKED] to 1e-4 (the restitution rises with cr) */
static double law_cr_min(fb_law_kind law, double n) {
  double lo = FB_IMPACT_CR_MIN_DIVERGENT, hi = LAW_CR_CHECKED;
  if (law_restitution_at(law, n, lo) > FB_RESTITUTION_MIN) return lo;
  while (hi - lo > 1e-4) {
    const double mid = 0.5 * (lo + hi);
    if (law_restitution_at(law, n, mid) > FB_RESTITUTION_MIN) hi = mid;
    else lo = mid;
  }
  return hi;
}

/* what names each input of q in a message: the flags, or the case's keys
 * for a contact taken from a case (never a flag the user did not give) */
static const fb_impact_names *request_names(const fb_cp_request *q) {
  static const fb_impact_names from_case = {
      "the case's contact stiffness ([clearance] keys)", "[clearance] restitution",
      "--damping-n-s-m", "the joint's effective mass (from the case's [mass] keys and lengths)",
      "--speed-m-s", "[solver] h_s"};
  static fb_impact_names flags_h_case;
  if (!q->case_path) return &fb_impact_flag_names;
  if (q->h_from_case) return &from_case;
  flags_h_case = from_case;
  flags_h_case.h = "--h-s";
  return &flags_h_case;
}

fb_status fb_cp_request_check(const fb_cp_request *q, fb_diag *diag) {
  const fb_law_kind law = q->law;
  if (!(law == FB_LAW_RESTITUTION || law == FB_LAW_LINEAR || is_hertz_family(law)))
    return fb_diag_set(diag, FB_ERR_ARG, "--law %s: must be restitution, linear, hertz, "
                       "lankarani-nikravesh, hunt-crossley, flores or gonthier", fb_law_name(law));
  const fb_impact_names *names = request_names(q);
  if (!(q->stiffness > 0.0) || !isfinite(q->stiffness) || q->stiffness > 1e20)
    return fb_diag_set(diag, FB_ERR_RANGE, "%s %s: must be positive, at most 1e20 (N/m, "
                       "or N/m^n for the Hertz laws)", names->stiffness, FB_NUM(q->stiffness));
  if (!(q->mass_min >= FB_MASS_MIN_KG) || !(q->mass_max >= q->mass_min) ||
      !isfinite(q->mass_max) || q->mass_max > FB_CP_MASS_RATIO_MAX * q->mass_min ||
      q->mass_max > FB_MASS_MAX_KG) {
    if (q->case_path) /* no flag of the user's: the case's masses and lengths */
      return fb_diag_set(diag, FB_ERR_RANGE, "--case %s: the joint's effective mass over a "
                         "revolution, %.6g to %.6g kg (from the case's [mass] keys and link "
                         "lengths), lies outside what a single impact is verified for: %g kg to "
                         "%g kg, the largest at most %g times the smallest; check the case's "
                         "masses (kg) and lengths (mm)", q->case_path, q->mass_min, q->mass_max,
                         FB_MASS_MIN_KG, FB_MASS_MAX_KG, FB_CP_MASS_RATIO_MAX);
    return fb_diag_set(diag, FB_ERR_RANGE, "--mass-kg %s:%s: need %g kg <= A <= B <= %g kg and "
                       "B/A <= %g", FB_NUM(q->mass_min), FB_NUM(q->mass_max), FB_MASS_MIN_KG, FB_MASS_MAX_KG,
                       FB_CP_MASS_RATIO_MAX);
  }
  if (!(q->speed > 0.0) || q->speed > FB_IMPACT_SPEED_MAX_M_S)
    return fb_diag_set(diag, FB_ERR_RANGE, "--speed-m-s %s: must lie in (0, %g] m/s", FB_NUM(q->speed),
                       FB_IMPACT_SPEED_MAX_M_S);
  if (!isnan(q->h) && (!(q->h > 0.0) || !isfinite(q->h)))
    return fb_diag_set(diag, FB_ERR_RANGE, "%s %s: the step size must be positive and finite",
                       names->h, FB_NUM(q->h));
  if (is_hertz_family(law)) {
    if (!isnan(q->exponent) && !(q->exponent >= 1.0 && q->exponent <= 3.0))
      return fb_diag_set(diag, FB_ERR_RANGE, "--exponent %s: must lie in [1, 3]", FB_NUM(q->exponent));
    if (!isnan(q->damping))
      return fb_diag_set(diag, FB_ERR_ARG, "--damping-n-s-m with --law %s: the Hertz laws' "
                         "damping follows from --restitution (cr); give --law linear for a "
                         "damper of your own", fb_law_name(law));
  } else {
    if (!isnan(q->exponent) && q->exponent != 1.0)
      return fb_diag_set(diag, FB_ERR_RANGE, "--exponent %s: the %s law is linear (n = 1)",
                         FB_NUM(q->exponent), fb_law_name(law));
  }
  if (!isnan(q->load) && law != FB_LAW_HERTZ)
    return fb_diag_set(diag, FB_ERR_ARG, "--load-n: only for --law hertz");
  if (!isnan(q->load) && !(q->load > 0.0 && isfinite(q->load)))
    return fb_diag_set(diag, FB_ERR_RANGE, "--load-n %s: must be positive and finite", FB_NUM(q->load));
  /* a flag the law does not use is refused, never ignored */
  if (law == FB_LAW_RESTITUTION && !isnan(q->damping))
    return fb_diag_set(diag, FB_ERR_ARG, "--damping-n-s-m with the restitution law: its damper "
                       "follows from --restitution (cr); give --law linear for a damper of your "
                       "own");
  if (law == FB_LAW_LINEAR && !isnan(q->restitution))
    return fb_diag_set(diag, FB_ERR_ARG, "--restitution with --law linear: the linear law's "
                       "damper is --damping-n-s-m; drop --law linear for the restitution law (cr)");
  if (law == FB_LAW_LINEAR && !isnan(q->damping) && (!(q->damping >= 0.0) || !isfinite(q->damping)))
    return fb_diag_set(diag, FB_ERR_RANGE, "--damping-n-s-m %s: must be >= 0 and finite",
                       FB_NUM(q->damping));
  if ((law == FB_LAW_RESTITUTION || law == FB_LAW_HERTZ) && !isnan(q->restitution) &&
      !(q->restitution > FB_RESTITUTION_MIN && q->restitution <= 1.0))
    return fb_diag_set(diag, FB_ERR_RANGE, "--restitution %s: cr must lie in (0.135, 1] (below "
                       "e^-2 the spring-damper is over-damped)", FB_NUM(q->restitution));
  if (is_damped_hertz(law) && !isnan(q->restitution) &&
      !(q->restitution > 0.0 && q->restitution <= 1.0))
    return fb_diag_set(diag, FB_ERR_RANGE, "--restitution %s: a coefficient of restitution lies "
                       "in (0, 1]", FB_NUM(q->restitution));
  /* Flores and Gonthier reach any restitution, but the rows translate the
   * law into a linear spring-damper, which leaves no slower than at e^-2:
   * a cr whose law leaves slower is refused before any row */
  if ((law == FB_LAW_FLORES || law == FB_LAW_GONTHIER) && !isnan(q->restitution) &&
      q->restitution < LAW_CR_CHECKED) {
    const fb_cp_request r = resolved(q);
    const double cr_min = law_cr_min(law, r.exponent);
    if (q->restitution <= cr_min)
      return fb_diag_set(diag, FB_ERR_RANGE, "%s %s with --law %s: the law's impact would leave "
                         "at a restitution below e^-2 = %.4f (the least a linear spring-damper, "
                         "which every engine row is, reaches: at critical damping), which it "
                         "does for cr <= %.3g at exponent %g: give %s > %.3g",
                         request_names(q)->restitution, FB_NUM(q->restitution), fb_law_name(law),
                         FB_RESTITUTION_MIN, cr_min, r.exponent, request_names(q)->restitution,
                         cr_min);
  }
  /* the impacts the inputs describe, at both ends of the mass range: the
   * law's own and the linear contact the engines get, each a contact a
   * double can follow in at most FB_IMPACT_MAX_STEPS steps of h (impact.h);
   * a verified row runs for up to FB_CP_VERIFY_DURATIONS contact durations */
  const fb_cp_request r = resolved(q);
  const double m0 = sqrt(r.mass_min * r.mass_max);
  double k, c, dop;
  linear_contact(&r, m0, &k, &c, &dop);
  const double h_probe = isnan(r.h) ? 1.0 : r.h;
  for (int e = 0; e < 2; e++) {
    const double m = e ? r.mass_max : r.mass_min;
    fb_impact_def d[2];
    d[0] = impact_def(is_hertz_family(law) ? law : FB_LAW_LINEAR, r.stiffness, r.exponent,
                      law == FB_LAW_LINEAR ? r.damping : 0.0, r.restitution, m, r.speed, h_probe);
    d[1] = linear_def(k, c, m, r.speed, h_probe);
    for (int i = 0; i < 2; i++) {
      d[i].names = names;
      fb_status st = fb_impact_check(&d[i], diag);
      if (st != FB_OK) {
        char msg[FB_DIAG_SIZE];
        snprintf(msg, sizeof msg, "%s", diag->msg);
        return fb_diag_set(diag, st, "%s (the %s at %g kg, %g m/s)", msg,
                           i ? "linear contact the engines get" : "law's impact", m, r.speed);
      }
      fb_impact_result cf;
      const double T = fb_impact_closed_form(&cf, &d[i]) ? cf.contact_duration
                                                         : fb_impact_duration_estimate(&d[i]);
      if (!isnan(r.h) && r.verify && FB_CP_VERIFY_DURATIONS * T / r.h + 10.0 > FB_IMPACT_MAX_STEPS)
        return fb_diag_set(diag, FB_ERR_RANGE, "%s %g with verification: each row runs for "
                           "up to %g contact durations (%.3g s at %g kg), %.3g steps, more than "
                           "%.0e: give h >= %.2g s (or --no-verify)", names->h, r.h, FB_CP_VERIFY_DURATIONS,
                           T, m, FB_CP_VERIFY_DURATIONS * T / r.h, FB_IMPACT_MAX_STEPS,
                           FB_CP_VERIFY_DURATIONS * T / FB_IMPACT_MAX_STEPS);
    }
  }
  return FB_OK;
}

/* ---- rows ---------------------------------------------------------------- */

/* the continuous linear contact's impact at mass m: closed form (exact), or
 * the reference integration when over-damped at that mass */
static void continuous(double k, double c, double m, double v, double h, double *pen, double *dur,
                       double *res, double *force) {
  fb_impact_def d = linear_def(k, c, m, v, h);
  fb_impact_result r;
  fb_diag dg;
  if (!fb_impact_closed_form(&r, &d) && fb_impact_reference(&r, &d, &dg) != FB_OK) {
    *pen = *dur = *res = *force = NAN;
    return;
  }
  *pen = r.penetration_max;
  *dur = r.contact_duration;
  *res = r.restitution;
  if (force) *force = r.force_max;
}

fb_status fb_cp_rows_make(fb_cp_rows *rows, double k, double c, double m_min, double m_max,
                          double h, double v, fb_diag *diag) {
  memset(rows, 0, sizeof *rows);
  const double m0 = sqrt(m_min * m_max);
  fb_linear_contact lc = {k, c, m0, h};
  fb_status st = fb_linear_contact_check(&lc, diag);
  if (st != FB_OK) return st;
  rows->lc = lc;
  rows->h_omega_c = h * sqrt(k / m_min);
  rows->omega_d_h = fb_contact_omega_d_h(h, k, c, m_min);
  if ((st = fb_params_ode_matched(&lc, &rows->ode, diag)) != FB_OK) return st;
  if ((st = fb_params_ode_standard(&lc, &rows->ode_standard, diag)) != FB_OK) return st;
  fb_params_spring_damper_of_row(&rows->ode, h, &rows->gazebo);
  if ((st = fb_params_row_of_spring_damper(&rows->gazebo, h, &rows->gazebo_row, diag)) != FB_OK)
    return st;
  rows->gazebo_naive.kp = k;
  rows->gazebo_naive.kd = c;
  if ((st = fb_params_row_of_spring_damper(&rows->gazebo_naive, h, &rows->gazebo_naive_row,
                                           diag)) != FB_OK)
    return st;
  fb_params_mujoco_direct_matched(&lc, &rows->mj_direct);
  fb_params_mujoco_direct_continuous(&lc, &rows->mj_continuous);
  rows->mj_naive = rows->mj_continuous;
  rows->mj_naive.solref[0] = -k / m0;
  rows->mj_naive.solref[1] = -c / m0;
  memcpy(rows->mj_naive.solimp, solimp_default, sizeof solimp_default);
  fb_diag sd;
  rows->has_standard = fb_params_mujoco_standard(&lc, &rows->mj_standard, &sd) == FB_OK;
  if (!rows->has_standard) snprintf(rows->standard_note, sizeof rows->standard_note, "%s", sd.msg);
  rows->n_masses = m_min == m_max ? 1 : 3;
  rows->masses[0] = rows->n_masses == 1 ? m0 : m_min;
  rows->masses[1] = m0;
  rows->masses[2] = m_max;
  double pen_max = 0.0;
  for (int i = 0; i < rows->n_masses; i++) {
    fb_linear_contact lm = lc;
    lm.m = rows->masses[i];
    fb_params_mujoco_direct_matched(&lm, &rows->mj_at[i]);
    continuous(k, c, lm.m, v, h, &rows->penetration[i], &rows->duration[i],
               &rows->restitution[i], NULL);
    pen_max = fmax(pen_max, rows->penetration[i]);
  }
  /* max_vel: twice the larger of the correcting velocity the row asks for at
   * the deepest peak penetration of the range and the impact speed, so that
   * no impact up to twice the speed is cut */
  rows->max_vel = 2.0 * fmax(fb_params_correcting_velocity(&rows->ode, h, pen_max), v);
  return FB_OK;
}

/* ---- verification -------------------------------------------------------- */

/* whose single impact verifies a row: ODE (also Gazebo's rows), MuJoCo, Bullet */
typedef enum { KIND_ODE, KIND_MUJOCO, KIND_BULLET } row_kind;

typedef struct {
  const char *engine, *form;
  row_kind kind;
  int recommended;
  int mass_index;               /* -1: every mass; else only masses[i] */
  const fb_ode_row *row;        /* KIND_ODE */
  double max_vel;               /* KIND_ODE */
  const fb_mujoco_params *mj;   /* KIND_MUJOCO */
  const fb_spring_damper *sd;   /* KIND_BULLET */
} row_spec;

/* the engine that verifies rows of kind k by single impacts (its impact
 * op's row), or NULL when this build has none (why in diag) */
static const fb_engine_impact *row_engine(row_kind k, fb_diag *diag) {
  static const fb_engine_id id[3] = {FB_ENGINE_ODE, FB_ENGINE_MUJOCO, FB_ENGINE_BULLET};
  const fb_engine *e = fb_engine_get(id[k], diag);
  if (!e) return NULL;
  if (!e->impact || !e->impact->row) {
    fb_diag_set(diag, FB_ERR_ARG, "engine '%s' has no single impact", e->name);
    return NULL;
  }
  return e->impact;
}

/* 1 when this build verifies rows of kind k */
static int row_kind_built(row_kind k) {
  fb_diag dg;
  return row_engine(k, &dg) != NULL;
}

/* the engines whose rows this build cannot verify, with how to get them */
static void unverified(fb_cp_result *o) {
  static const struct {
    row_kind kind;
    fb_engine_id id;
  } optional[2] = {{KIND_MUJOCO, FB_ENGINE_MUJOCO}, {KIND_BULLET, FB_ENGINE_BULLET}};
  o->n_unverified = 0;
  for (int i = 0; i < 2; i++)
    if (!row_kind_built(optional[i].kind)) {
      o->unverified[o->n_unverified].engine = fb_engine_name(optional[i].id);
      o->unverified[o->n_unverified++].howto = fb_engine_howto(optional[i].id);
    }
}

/* one row at one mass over the onset phases into x; returns x->faithful */
static int check_row(fb_cp_check *x, const fb_cp_rows *rows, const row_spec *r, int im, double v) {
  const double m = rows->masses[im], h = rows->lc.h;
  memset(x, 0, sizeof *x);
  x->engine = r->engine;
  x->form = r->form;
  x->mass = m;
  x->recommended = r->recommended;
  x->ran = 1;
  double dur, res, pen, force;
  continuous(rows->lc.k, rows->lc.c, m, v, h, &pen, &dur, &res, &force);
  x->restitution_target = res;
  x->penetration_target = pen;
  x->force_target = force;
  if (!isfinite(pen) || !isfinite(dur)) {
    x->ran = 0;
    snprintf(x->why, sizeof x->why, "the continuous contact's impact could not be integrated");
    return 0;
  }
  const double t_max = FB_CP_VERIFY_DURATIONS * dur + 10.0 * h;
  x->faithful = 1;
  for (int p = 0; p < FB_CP_ONSET_PHASES; p++) {
    const double phase = fb_cp_onset_phases[p];
    fb_impact_result o;
    fb_diag dg;
    fb_impact_row row;
    memset(&row, 0, sizeof row);
    row.mass = m;
    row.speed = v;
    row.h = h;
    row.t_max = t_max;
    row.onset_phase = phase;
    if (r->kind == KIND_ODE) {
      row.ode = *r->row;
      row.max_vel = r->max_vel;
    } else if (r->kind == KIND_MUJOCO) {
      row.mujoco = r->mass_index < 0 && r->mj == NULL ? rows->mj_at[im] : *r->mj;
    } else {
      row.bullet = *r->sd;
    }
    const fb_engine_impact *e = row_engine(r->kind, &dg);
    if (e && e->version) x->engine_version = e->version();
    const fb_status st = e ? e->row(&o, &row, &dg) : FB_ERR_ARG;
    if (st != FB_OK) {
      x->ran = 0;
      x->faithful = 0;
      snprintf(x->why, sizeof x->why, "onset phase %g: %s", phase, dg.msg);
      return 0;
    }
    const double er = (o.restitution - res) / fabs(res);
    const double ep = (o.penetration_max - pen) / pen;
    if (p == 0 || fabs(er) > fabs(x->restitution_rel)) {
      x->restitution_rel = er;
      x->restitution = o.restitution;
      x->restitution_phase = phase;
    }
    if (p == 0 || fabs(ep) > fabs(x->penetration_rel)) {
      x->penetration_rel = ep;
      x->penetration = o.penetration_max;
      x->penetration_phase = phase;
    }
    if (p == 0) x->force = o.force_max;
    if (!(fabs(er) <= FB_CP_RESTITUTION_TOL && fabs(ep) <= FB_CP_PENETRATION_TOL))
      x->faithful = 0;
  }
  return x->faithful;
}

/* the rows of a step as specs; with comparisons the rows users commonly
 * paste too */
static int row_specs(row_spec *s, const fb_cp_rows *rows, int recommended, int comparisons) {
  int n = 0;
  const int range = rows->n_masses > 1;
  s[n++] = (row_spec){"ode", "matched", KIND_ODE, recommended, -1, &rows->ode, INFINITY, 0, 0};
  s[n++] = (row_spec){"gazebo", "matched", KIND_ODE, recommended, -1, &rows->gazebo_row,
                      rows->max_vel, 0, 0};
  if (row_kind_built(KIND_MUJOCO)) {
    if (range) {
      s[n++] = (row_spec){"mujoco", "direct-at-mass", KIND_MUJOCO, recommended, -1, 0, 0, NULL, 0};
    } else {
      s[n++] = (row_spec){"mujoco", "direct", KIND_MUJOCO, recommended, -1, 0, 0, &rows->mj_direct,
                          0};
      if (rows->has_standard)
        s[n++] = (row_spec){"mujoco", "standard", KIND_MUJOCO, recommended, -1, 0, 0,
                            &rows->mj_standard, 0};
    }
  }
  if (row_kind_built(KIND_BULLET))
    s[n++] = (row_spec){"bullet", "matched", KIND_BULLET, recommended, -1, 0, 0, 0, &rows->gazebo};
  if (!comparisons) return n;
  s[n++] = (row_spec){"ode", "standard", KIND_ODE, 0, -1, &rows->ode_standard, INFINITY, 0, 0};
  s[n++] = (row_spec){"gazebo", "naive", KIND_ODE, 0, -1, &rows->gazebo_naive_row, rows->max_vel,
                      0, 0};
  if (row_kind_built(KIND_MUJOCO)) {
    if (range)
      s[n++] = (row_spec){"mujoco", "direct", KIND_MUJOCO, 0, -1, 0, 0, &rows->mj_direct, 0};
    s[n++] = (row_spec){"mujoco", "direct-continuous", KIND_MUJOCO, 0, -1, 0, 0,
                        &rows->mj_continuous, 0};
    s[n++] = (row_spec){"mujoco", "naive", KIND_MUJOCO, 0, -1, 0, 0, &rows->mj_naive, 0};
  }
  if (row_kind_built(KIND_BULLET))
    s[n++] = (row_spec){"bullet", "naive", KIND_BULLET, 0, -1, 0, 0, 0, &rows->gazebo_naive};
  return n;
}

/* fb_cp_verify's rows, or (engine not NULL) that engine's recommended
 * rows alone */
static int verify_rows(fb_cp_step *st, double speed, int recommended, const char *engine) {
  row_spec s[16];
  const int ns = row_specs(s, &st->rows, recommended, !engine);
  int failed = 0;
  st->n_checks = 0;
  for (int i = 0; i < ns; i++) {
    if (engine && strcmp(s[i].engine, engine) != 0) continue;
    for (int im = 0; im < st->rows.n_masses && st->n_checks < FB_CP_CHECKS_MAX; im++) {
      fb_cp_check *x = &st->checks[st->n_checks++];
      if (!check_row(x, &st->rows, &s[i], im, speed) && x->recommended) failed++;
    }
  }
  return failed;
}

int fb_cp_verify(fb_cp_step *st, double speed, int recommended) {
  return verify_rows(st, speed, recommended, NULL);
}

/* 1 when every recommended row of (k, c) at step h is faithful at every
 * mass and onset phase (stops at the first that is not) */
static int faithful_at(double k, double c, double m_min, double m_max, double h, double v) {
  fb_cp_rows rows;
  fb_diag dg;
  if (fb_cp_rows_make(&rows, k, c, m_min, m_max, h, v, &dg) != FB_OK) return 0;
  if (rows.h_omega_c > FB_H_OMEGA_C_BOUND * (1.0 + 1e-12)) return 0;
  row_spec s[16];
  const int ns = row_specs(s, &rows, 1, 0);
  for (int im = 0; im < rows.n_masses; im++)
    for (int i = 0; i < ns; i++) {
      fb_cp_check x;
      if (!check_row(&x, &rows, &s[i], im, v)) return 0;
    }
  return 1;
}

/* the largest faithful step of (k, c) over the range: the rule's step when
 * faithful, else halving to a faithful one and bisecting in log h */
static double largest_step(double k, double c, double m_min, double m_max, double v,
                           const char **limited_by) {
  const double omega_c = sqrt(k / m_min);
  double hi = FB_H_OMEGA_C_BOUND / omega_c;
  *limited_by = "rule";
  if (faithful_at(k, c, m_min, m_max, hi, v)) return hi;
  *limited_by = "verification";
  double lo = 0.5 * hi;
  while (!faithful_at(k, c, m_min, m_max, lo, v)) {
    hi = lo;
    lo *= 0.5;
    if (lo * omega_c < FB_CP_H_OMEGA_MIN) return NAN;
  }
  while (hi / lo > 1.0 + FB_CP_STEP_REL) {
    const double mid = sqrt(lo * hi);
    if (faithful_at(k, c, m_min, m_max, mid, v)) lo = mid;
    else hi = mid;
  }
  return lo;
}

/* ---- the per-step mapping of a nonlinear law ---------------------------- */

static void per_step(fb_cp_result *o, const fb_cp_request *r) {
  fb_cp_per_step *ps = &o->per_step;
  memset(ps, 0, sizeof *ps);
  if (!is_hertz_family(r->law) || !isnan(r->load)) return;
  if (r->law == FB_LAW_HERTZ && !isnan(r->restitution)) return; /* no law with that damper */
  ps->present = 1;
  const double kt = r->exponent * r->stiffness * pow(o->law_penetration, r->exponent - 1.0);
  ps->h_omega_t = r->h * sqrt(kt / r->mass_min);
  ps->recommended = o->given.recommended && isfinite(o->largest_h_omega) &&
                    ps->h_omega_t <= o->largest_h_omega;
  fb_cp_check *x = &ps->check;
  x->engine = "ode";
  x->form = "per-step";
  x->mass = o->m0;
  x->recommended = ps->recommended;
  x->restitution_target = o->law_restitution;
  x->penetration_target = o->law_penetration;
  x->force_target = o->law_force;
  /* beyond the run's rule the row is not shown as verified (no numbers of a
   * step that cannot resolve the contact) */
  if (!r->verify || ps->h_omega_t > FB_H_OMEGA_C_BOUND) {
    snprintf(x->why, sizeof x->why, "not verified: h omega_t = %.3g passes %g", ps->h_omega_t,
             FB_H_OMEGA_C_BOUND);
    return;
  }
  fb_impact_def d = impact_def(r->law, r->stiffness, r->exponent, 0.0, r->restitution, o->m0,
                               r->speed, r->h);
  fb_impact_result res;
  fb_diag dg;
  const fb_impact_opts io = {fb_bullet_opts_default()};
  const fb_engine *ode = fb_engine_get(FB_ENGINE_ODE, &dg);
  x->ran = ode->impact->law(&res, &d, &io, &dg) == FB_OK;
  if (!x->ran) {
    snprintf(x->why, sizeof x->why, "%s", dg.msg);
    return;
  }
  x->restitution = res.restitution;
  x->penetration = res.penetration_max;
  x->force = res.force_max;
  x->restitution_rel = (res.restitution - o->law_restitution) / o->law_restitution;
  x->penetration_rel = (res.penetration_max - o->law_penetration) / o->law_penetration;
  x->faithful = fabs(x->restitution_rel) <= FB_CP_RESTITUTION_TOL &&
                fabs(x->penetration_rel) <= FB_CP_PENETRATION_TOL;
}

/* ---- the whole command --------------------------------------------------- */

/* the stiffest contact of o's restitution faithful at step h: o's contact
 * with h omega moved to that of the largest faithful step (k' = k s^2,
 * c' = c s, s = largest_step / h), its rows at h, recommended */
static fb_status at_step(fb_cp_step *out, double *k, double *c, const fb_cp_result *o,
                         const fb_cp_request *r, double h, fb_diag *diag) {
  const double s = o->largest_step / h;
  *k = o->k * s * s;
  *c = o->c * s;
  memset(out, 0, sizeof *out);
  fb_status st = fb_cp_rows_make(&out->rows, *k, *c, r->mass_min, r->mass_max, h, r->speed, diag);
  if (st != FB_OK) return st;
  out->recommended = 1;
  return FB_OK;
}

fb_status fb_cp_request_from_case(fb_cp_request *q, const fb_case *c, int j, fb_diag *diag) {
  fb_case_contact cc;
  fb_status st = fb_case_contact_of(&cc, c, j, diag);
  if (st != FB_OK) return st;
  if (q->law == FB_LAW_HERTZ) {
    q->stiffness = cc.impact.stiffness;
    q->exponent = cc.impact.exponent;
    q->load = cc.est.force_expected; /* the operating point: the joint's expected force */
  } else {
    q->stiffness = cc.restitution.stiffness;
    q->restitution = cc.restitution.restitution;
  }
  q->mass_min = cc.est.m_eff_min;
  q->mass_max = cc.est.m_eff_max;
  q->h_from_case = isnan(q->h);
  if (isnan(q->h)) q->h = cc.h;
  if (!q->case_path) q->case_path = "(the case)"; /* the caller names the file */
  return FB_OK;
}

fb_status fb_cp_request_from_planar(fb_cp_request *q, const fb_case *c, const fb_planar *m, int j,
                                    fb_diag *diag) {
  fb_planar_contact_estimate *est = malloc(2 * (size_t)m->njoints * sizeof *est);
  if (!est) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  int n = 0;
  fb_status st = fb_planar_contact_estimates(est, &n, c, m, diag);
  const int impact = q->law == FB_LAW_HERTZ;
  const fb_planar_contact_estimate *e = NULL;
  for (int k = 0; k < n && st == FB_OK; k++)
    if (est[k].joint == j && est[k].impact == impact) e = &est[k];
  if (st == FB_OK && !e)
    st = fb_diag_set(diag, FB_ERR_ARG, "joint '%s' is not a revolute clearance joint of the case "
                     "([clearance] joints): a pin in its hole is what the contact is taken from",
                     m->joint[j].name);
  if (st == FB_OK) {
    q->stiffness = e->law.stiffness;
    if (impact) {
      q->exponent = e->law.exponent;
      q->load = e->force_expected; /* the operating point: the joint's expected force */
    } else {
      q->restitution = e->law.restitution;
    }
    q->mass_min = e->m_eff_min;
    q->mass_max = e->m_eff_max;
    q->h_from_case = isnan(q->h);
    if (isnan(q->h)) q->h = fb_planar_run_step(c); /* the step a run of the case takes */
    if (!q->case_path) q->case_path = "(the case)";
  }
  free(est);
  return st;
}

fb_status fb_cp_run(fb_cp_result *o, const fb_cp_request *q, fb_diag *diag) {
  memset(o, 0, sizeof *o);
  fb_status st = fb_cp_request_check(q, diag);
  if (st != FB_OK) return st;
  fb_cp_request r = resolved(q);
  o->m0 = sqrt(r.mass_min * r.mass_max);
  const double v = r.speed;
  linear_contact(&r, o->m0, &o->k, &o->c, &o->op_penetration);
  /* the law's own impact at the design mass */
  o->law_restitution = o->law_penetration = o->law_force = o->law_floor = NAN;
  if (is_damped_hertz(r.law)) {
    fb_impact_def d = impact_def(r.law, r.stiffness, r.exponent, 0.0, r.restitution, o->m0, v, 1.0);
    fb_impact_result res;
    if ((st = fb_impact_reference(&res, &d, diag)) != FB_OK) return st;
    o->law_restitution = res.restitution;
    o->law_penetration = res.penetration_max;
    o->law_force = res.force_max;
    if ((r.law == FB_LAW_LANKARANI_NIKRAVESH || r.law == FB_LAW_HUNT_CROSSLEY) &&
        fabs(res.restitution - r.restitution) > FB_CP_LAW_NOTE_REL * r.restitution) {
      /* the least restitution the law reaches: its impact as cr -> 0 */
      fb_impact_def d0 = impact_def(r.law, r.stiffness, r.exponent, 0.0, LAW_CR_ZERO, o->m0, v, 1.0);
      fb_impact_result r0;
      fb_diag dg;
      if (fb_impact_reference(&r0, &d0, &dg) == FB_OK) o->law_floor = r0.restitution;
    }
    if (!(res.restitution > FB_RESTITUTION_MIN))
      return fb_diag_set(diag, FB_ERR_RANGE, "--law %s with --restitution %g leaves with %.4g, "
                         "which no linear spring-damper reaches (at most critical damping, "
                         "e^-2 = %.4f): give a larger --restitution", fb_law_name(r.law),
                         r.restitution, res.restitution, FB_RESTITUTION_MIN);
    if ((st = fb_params_linear_equivalent(res.restitution, res.penetration_max, o->m0, v, &o->k,
                                          &o->c, diag)) != FB_OK)
      return st;
  } else if (r.law == FB_LAW_HERTZ) {
    fb_impact_def d = impact_def(FB_LAW_HERTZ, r.stiffness, r.exponent, 0.0, NAN, o->m0, v, 1.0);
    fb_impact_result res;
    fb_impact_closed_form(&res, &d);
    o->law_restitution = isnan(r.restitution) ? 1.0 : r.restitution;
    o->law_penetration = res.penetration_max;
    o->law_force = res.force_max;
  }
  /* an undamped (or nearly) contact: the damper of FB_CP_RESTITUTION_MAX */
  const double c_floor = fb_params_damper_for_restitution(o->k, o->m0, FB_CP_RESTITUTION_MAX);
  if (!(o->c >= c_floor)) {
    o->c = c_floor;
    o->damper_floored = 1;
  }
  {
    double pen, dur, res;
    continuous(o->k, o->c, o->m0, v, 1.0, &pen, &dur, &res, &o->lin_force);
  }
  /* the largest faithful step, then the step */
  o->largest_step = o->largest_h_omega = NAN;
  o->largest_limited_by = "";
  if (r.verify) {
    o->largest_step = largest_step(o->k, o->c, r.mass_min, r.mass_max, v, &o->largest_limited_by);
    o->largest_h_omega = o->largest_step * sqrt(o->k / r.mass_min);
  }
  if (isnan(r.h)) {
    r.h = FB_CP_DEFAULT_H_OMEGA / sqrt(o->k / r.mass_min);
    if (isfinite(o->largest_step)) r.h = fmin(r.h, o->largest_step);
  }
  o->q = r;
  /* the given contact at h */
  fb_cp_step *g = &o->given;
  if ((st = fb_cp_rows_make(&g->rows, o->k, o->c, r.mass_min, r.mass_max, r.h, v, diag)) != FB_OK)
    return st;
  if (g->rows.h_omega_c > FB_H_OMEGA_C_BOUND)
    snprintf(g->why_not, sizeof g->why_not, "h omega_c = %.3g at %.4g kg passes %g, the bound a "
             "run holds its contacts to (resolution.h)", g->rows.h_omega_c, r.mass_min,
             FB_H_OMEGA_C_BOUND);
  else if (r.verify && !isfinite(o->largest_step))
    snprintf(g->why_not, sizeof g->why_not, "no step down to h omega_c = %g keeps it faithful",
             FB_CP_H_OMEGA_MIN);
  else if (r.verify && !(r.h <= o->largest_step * (1.0 + 1e-12)))
    snprintf(g->why_not, sizeof g->why_not, "h = %.4g s is beyond the largest faithful step "
             "%.4g s (h omega_c %.3g)", r.h, o->largest_step, o->largest_h_omega);
  else
    g->recommended = 1;
  /* rows within the run's rule are verified and shown even when not
   * recommended (so the failure shows); beyond it they are not shown */
  if (r.verify && g->rows.h_omega_c <= FB_H_OMEGA_C_BOUND)
    o->failed += verify_rows(g, v, g->recommended, r.rows_of);
  /* at_step: the stiffest faithful contact of the same restitution at h */
  if (r.verify && isfinite(o->largest_step) && !r.rows_of) {
    o->has_at_step = 1;
    if ((st = at_step(&o->at_step, &o->at_k, &o->at_c, o, &r, r.h, diag)) != FB_OK) return st;
    o->failed += fb_cp_verify(&o->at_step, v, 1);
    /* and at the engines' default steps */
    static const struct {
      const char *engine;
      double h;
    } defaults[FB_CP_ENGINE_STEPS] = {{"mujoco", FB_CP_MUJOCO_DEFAULT_H},
                                      {"gazebo", FB_CP_GAZEBO_DEFAULT_H}};
    for (int i = 0; r.engine_steps && i < FB_CP_ENGINE_STEPS; i++) {
      o->engine_step[i].engine = defaults[i].engine;
      o->engine_step[i].h = defaults[i].h;
      if ((st = at_step(&o->engine_step[i].step, &o->engine_step[i].k, &o->engine_step[i].c, o,
                        &r, defaults[i].h, diag)) != FB_OK)
        return st;
      o->failed += fb_cp_verify(&o->engine_step[i].step, v, 1);
      o->n_engine_steps = i + 1;
    }
  }
  per_step(o, &r);
  unverified(o);
  if (o->per_step.recommended && r.verify && !o->per_step.check.faithful) o->failed++;
  return FB_OK;
}

fb_status fb_cp_case_step_check(fb_step_check *out, const fb_case *c, double h, fb_diag *diag) {
  memset(out, 0, sizeof *out);
  out->largest_step = INFINITY;
  out->faithful = 1;
  int none = 0;
  fb_cp_result *o = malloc(sizeof *o);
  if (!o) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the step's verification");
  fb_status st = FB_OK;
  for (int j = 0; j < 4 && st == FB_OK; j++) {
    if (!(c->clearance.mask & (1 << j))) continue;
    fb_cp_request q;
    fb_cp_request_default(&q);
    q.h = h;
    q.engine_steps = 0;
    q.rows_of = "ode"; /* read below: the largest faithful step and ODE's matched row */
    st = fb_cp_request_from_case(&q, c, j, diag);
    if (st == FB_OK) st = fb_cp_run(o, &q, diag);
    if (st != FB_OK) break;
    out->checked = 1;
    none |= !isfinite(o->largest_step);
    if (isfinite(o->largest_step)) out->largest_step = fmin(out->largest_step, o->largest_step);
    for (int k = 0; k < o->given.n_checks; k++) {
      const fb_cp_check *x = &o->given.checks[k];
      if (strcmp(x->engine, "ode") != 0 || strcmp(x->form, "matched") != 0 || !x->ran) continue;
      if (fabs(x->restitution_rel) > fabs(out->restitution_rel) ||
          fabs(x->penetration_rel) > fabs(out->penetration_rel))
        out->joint = j;
      if (fabs(x->restitution_rel) > fabs(out->restitution_rel)) out->restitution_rel = x->restitution_rel;
      if (fabs(x->penetration_rel) > fabs(out->penetration_rel)) out->penetration_rel = x->penetration_rel;
      out->faithful &= x->faithful;
    }
    /* beyond the run's bound the rows are not verified (fb_cp_run): not faithful */
    if (o->given.n_checks == 0) out->faithful = 0;
  }
  if (none || !isfinite(out->largest_step)) out->largest_step = NAN;
  free(o);
  return st;
}
