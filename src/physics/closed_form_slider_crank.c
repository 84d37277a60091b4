/* The offset slider-crank's closed forms as the family's table
 * (closed_form.h): its exact kinematics (slider_crank.h) with peaks by a
 * grid and Brent's method, inverse dynamics (slider_crank_invdyn.h), start
 * states (start.h), tolerance outputs (the rod's and the slider's peaks,
 * the smallest transmission angle, the stroke), the reference's
 * minimal-coordinate model (slider_crank_dynamics.h) and the checks a
 * slider-crank case needs. */
#include "closed_form.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_math.h>
#include <gsl/gsl_min.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "slider_crank_invdyn.h"

/* ---- kinematics ----------------------------------------------------------- */

static fb_status solve(double out[FB_MECH_MAX_OUTPUTS][3], const fb_linkage *lk,
                       fb_branch branch, double theta2, double omega2, double alpha2,
                       fb_diag *diag) {
  (void)branch;
  const fb_slider_crank sc = fb_slider_crank_of(lk);
  fb_slider_crank_state s;
  fb_status st = fb_slider_crank_solve(&s, &sc, theta2, omega2, alpha2, diag);
  if (st != FB_OK) return st;
  const double v[2][3] = {{s.coupler_angle, s.coupler_omega, s.coupler_alpha},
                          {s.slider_x, s.slider_v, s.slider_a}};
  memcpy(out, v, sizeof v);
  return FB_OK;
}

static fb_status check_lengths(const fb_linkage *lk, fb_diag *diag) {
  const fb_slider_crank sc = fb_slider_crank_of(lk);
  return fb_slider_crank_require_full_turn(&sc, diag);
}

typedef struct {
  fb_slider_crank sc;
  double omega2;
  int body, q; /* output body, FB_Q_VEL or FB_Q_ACC */
  double sign; /* +1 finds a minimum, -1 a maximum */
} sc_peak;

static double sc_value(const sc_peak *p, double theta2) {
  double v[FB_MECH_MAX_OUTPUTS][3];
  fb_linkage lk = {{p->sc.crank, p->sc.coupler, p->sc.offset, 0.0}};
  if (solve(v, &lk, FB_BRANCH_OPEN, theta2, p->omega2, 0.0, NULL) != FB_OK)
    return NAN;
  return v[p->body][p->q];
}

static double sc_objective(double theta2, void *params) {
  const sc_peak *p = params;
  const double v = sc_value(p, theta2);
  return isfinite(v) ? p->sign * v : GSL_POSINF;
}

/* the minimum of sign * value over one revolution, refined by Brent's
 * method inside the two neighbours of the grid's smallest value fbest at
 * index best (returned as value, its crank angle [rad] in *at) */
static double sc_refine(sc_peak *p, int best, double fbest, double *at) {
  const int n = FB_ANALYTIC_PEAK_SAMPLES;
  const double step = 2.0 * M_PI / n;
  const double lo = (best - 1) * step, mid = best * step, hi = (best + 1) * step;
  double fmin = fbest;
  *at = mid;
  gsl_min_fminimizer *m = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
  gsl_function F = {sc_objective, p};
  const double flo = sc_objective(lo, p), fhi = sc_objective(hi, p);
  if (m && fbest < flo && fbest < fhi &&
      gsl_min_fminimizer_set_with_values(m, &F, mid, fbest, lo, flo, hi, fhi) == GSL_SUCCESS) {
    for (int it = 0; it < 100; it++) {
      if (gsl_min_fminimizer_iterate(m) != GSL_SUCCESS) break;
      const double a = gsl_min_fminimizer_x_lower(m), b = gsl_min_fminimizer_x_upper(m);
      if (gsl_min_test_interval(a, b, 1e-12, 0.0) == GSL_SUCCESS) break;
    }
    if (gsl_min_fminimizer_f_minimum(m) < fmin) {
      *at = gsl_min_fminimizer_x_minimum(m);
      fmin = gsl_min_fminimizer_f_minimum(m);
    }
  }
  if (m) gsl_min_fminimizer_free(m);
  return p->sign * fmin;
}

/* the extremes the slider-crank's peaks take, in the order of `where`
 * (fb_mech_peaks_where): per output body omega (v) max, min, alpha (a) max,
 * min; then the rod's angle max and min */
enum { SC_NEXT = 10 };
static const struct {
  int body, q;
  double sign; /* -1 a maximum, +1 a minimum */
} sc_ext[SC_NEXT] = {{0, FB_Q_VEL, -1.0}, {0, FB_Q_VEL, +1.0}, {0, FB_Q_ACC, -1.0},
                     {0, FB_Q_ACC, +1.0}, {1, FB_Q_VEL, -1.0}, {1, FB_Q_VEL, +1.0},
                     {1, FB_Q_ACC, -1.0}, {1, FB_Q_ACC, +1.0}, {0, FB_Q_POS, -1.0},
                     {0, FB_Q_POS, +1.0}};

/* every extreme of sc_ext: one pass over the grid of FB_ANALYTIC_PEAK_SAMPLES
 * crank angles finds each one's smallest grid value (the first on a tie),
 * then Brent refines each; value[i] and its crank angle at[i] [rad] */
static void sc_extremes(double value[SC_NEXT], double at[SC_NEXT], const fb_slider_crank *sc,
                        double omega2) {
  const int n = FB_ANALYTIC_PEAK_SAMPLES;
  const double step = 2.0 * M_PI / n;
  int best[SC_NEXT] = {0};
  double fbest[SC_NEXT];
  for (int i = 0; i < SC_NEXT; i++) fbest[i] = GSL_POSINF;
  const fb_linkage lk = {{sc->crank, sc->coupler, sc->offset, 0.0}};
  for (int k = 0; k < n; k++) {
    double v[FB_MECH_MAX_OUTPUTS][3];
    const int ok = solve(v, &lk, FB_BRANCH_OPEN, k * step, omega2, 0.0, NULL) == FB_OK;
    for (int i = 0; i < SC_NEXT; i++) {
      const double x = ok ? v[sc_ext[i].body][sc_ext[i].q] : NAN;
      const double f = isfinite(x) ? sc_ext[i].sign * x : GSL_POSINF;
      if (f < fbest[i]) fbest[i] = f, best[i] = k;
    }
  }
  for (int i = 0; i < SC_NEXT; i++) {
    sc_peak p = {*sc, omega2, sc_ext[i].body, sc_ext[i].q, sc_ext[i].sign};
    value[i] = sc_refine(&p, best[i], fbest[i], &at[i]);
  }
}

static fb_status peaks_where(fb_peaks *out, double where[8], const fb_linkage *lk,
                             fb_branch branch, double omega2, fb_diag *diag) {
  (void)branch; /* one assembly: the slider on the +x side */
  const fb_slider_crank sc = fb_slider_crank_of(lk);
  fb_slider_crank_limits lim;
  fb_status st = fb_slider_crank_limit_positions(&lim, &sc, diag);
  if (st != FB_OK) return st;
  double v[SC_NEXT], at[SC_NEXT];
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  sc_extremes(v, at, &sc, omega2);
  gsl_set_error_handler(old);
  for (int b = 0; b < 2; b++) {
    fb_body_peaks *o = &out->body[b];
    o->omega_max = v[4 * b], o->omega_min = v[4 * b + 1];
    o->alpha_max = v[4 * b + 2], o->alpha_min = v[4 * b + 3];
  }
  if (where) memcpy(where, at, 8 * sizeof *where);
  /* the rod's angle swings through +-asin((crank + |offset|) / coupler)
   * about the guide: its extremes from the same search */
  out->body[0].pos_max = v[8];
  out->body[0].pos_min = v[9];
  out->body[1].pos_max = lim.x_max;
  out->body[1].pos_min = lim.x_min;
  return FB_OK;
}


static fb_status reactions(double force[4][2], double *drive_torque, const fb_linkage *lk,
                           fb_branch branch, const fb_link_mass link[3], double gravity,
                           double theta2, double omega2, fb_diag *diag) {
  (void)branch;
  const fb_slider_crank sc = fb_slider_crank_of(lk);
  const fb_slider_crank_mass m = fb_slider_crank_mass_of(link);
  fb_slider_crank_reactions r;
  fb_status st = fb_slider_crank_invdyn(&r, &sc, &m, gravity, theta2, omega2, 0.0, diag);
  if (st != FB_OK) return st;
  memcpy(force, r.force, sizeof r.force);
  force[FB_SC_JOINT_SLIDER_GROUND][0] = 0.0;
  force[FB_SC_JOINT_SLIDER_GROUND][1] = -r.guide_force;
  if (drive_torque) *drive_torque = r.drive_torque;
  return FB_OK;
}

/* the pins' largest forces and at the guide, slider-ground, the largest |N| */
static fb_status reaction_peaks(double force_max[4], const fb_linkage *lk, fb_branch branch,
                                const fb_link_mass link[3], double gravity, double omega2, int n,
                                fb_diag *diag) {
  (void)branch;
  const fb_slider_crank sc = fb_slider_crank_of(lk);
  const fb_slider_crank_mass m = fb_slider_crank_mass_of(link);
  double pins[FB_SC_PIN_COUNT], guide;
  fb_status st = fb_slider_crank_invdyn_peaks(pins, &guide, NULL, &sc, &m, gravity, omega2, n, diag);
  if (st != FB_OK) return st;
  for (int j = 0; j < FB_SC_PIN_COUNT; j++) force_max[j] = pins[j];
  force_max[FB_SC_JOINT_SLIDER_GROUND] = guide;
  return FB_OK;
}

static fb_status mechanism_at(fb_mechanism *out, const fb_linkage *lk, fb_branch branch,
                              const fb_link_mass link[3], double theta2, int clearance_mask,
                              fb_diag *diag) {
  (void)branch;
  const fb_slider_crank sc = fb_slider_crank_of(lk);
  fb_slider_crank_state s;
  fb_status st = fb_slider_crank_solve(&s, &sc, theta2, 0.0, 0.0, diag);
  if (st != FB_OK) return st;
  fb_mechanism_from_slider_crank(out, &s, link, clearance_mask);
  return FB_OK;
}

/* ---- start states ------------------------------------------------------- */

/* the slider-crank's joint points from its exact solution s (with the
 * piston pin's eccentricity e: P = s.c, H = P - e) and its velocities */
static void sc_fill(fb_start_state *out, const fb_slider_crank_state *s, const double e[2],
                    double omega2, int slider_at_rest) {
  memset(out, 0, sizeof *out);
  out->crank_angle = s->crank_angle;
  out->crank_omega = omega2;
  out->coupler_angle = s->coupler_angle;
  out->coupler_omega = s->coupler_omega;
  for (int k = 0; k < 2; k++) {
    out->pin[FB_SC_JOINT_CRANK_COUPLER][k] = out->hole[FB_SC_JOINT_CRANK_COUPLER][k] = s->b[k];
    out->pin[FB_SC_JOINT_COUPLER_SLIDER][k] = s->c[k];
    out->hole[FB_SC_JOINT_COUPLER_SLIDER][k] = s->c[k] - e[k];
    out->ecc[FB_SC_JOINT_COUPLER_SLIDER][k] = e[k];
    out->pin[FB_SC_JOINT_SLIDER_GROUND][k] = out->hole[FB_SC_JOINT_SLIDER_GROUND][k] =
        out->hole[FB_SC_JOINT_COUPLER_SLIDER][k];
  }
  out->body[1][FB_Q_POS] = out->hole[FB_SC_JOINT_COUPLER_SLIDER][0];
  out->body[1][FB_Q_VEL] = slider_at_rest ? 0.0 : s->slider_v;
  out->coupler_b_vel[0] = -omega2 * s->b[1];
  out->coupler_b_vel[1] = omega2 * s->b[0];
}

static fb_status start_steady(fb_start_state *out, const fb_linkage *lk, fb_branch branch,
                              double theta0, double omega2, fb_diag *diag) {
  (void)branch;
  const fb_slider_crank sc = fb_slider_crank_of(lk);
  fb_slider_crank_state s;
  fb_status st = fb_slider_crank_solve(&s, &sc, theta0, omega2, 0.0, diag);
  if (st != FB_OK) return st;
  sc_fill(out, &s, (const double[2]){0.0, 0.0}, omega2, 0);
  return FB_OK;
}

/* start.h's slider-crank: the rod and slider of the ideal slider-crank
 * whose guide is moved by the piston pin's e_y */
static fb_status start_resolve(fb_start_state *out, const fb_case *c, const fb_linkage *lk,
                               const double ecc[4][2], int clearance_mask, fb_diag *diag) {
  const double *e = ecc[FB_SC_JOINT_COUPLER_SLIDER];
  fb_slider_crank shifted = fb_slider_crank_of(lk);
  shifted.offset += e[1];
  fb_slider_crank_state s;
  fb_diag inner;
  fb_status st = fb_slider_crank_solve(&s, &shifted, c->crank_angle0, fb_case_omega2(c), 0.0, &inner);
  if (st != FB_OK)
    return fb_diag_set(diag, FB_ERR_ASSEMBLY,
                       "start: with the piston pin at its start position the slider-crank does "
                       "not assemble at crank angle %.6g deg: %s",
                       c->crank_angle0 * 180.0 / M_PI, inner.msg);
  sc_fill(out, &s, e, fb_case_omega2(c), c->start == FB_START_REST && clearance_mask != 0);
  return FB_OK;
}

/* ---- tolerance outputs -------------------------------------------------- */

/* the slider-crank's, in the same slots: the second output body's peaks are
 * the slider's (fb_mech_output_key's names, as summary.json's
 * models[].slider), slot 9 its stroke */
static const char *const sc_out_names[FB_TOL_NOUT] = {
    "coupler_omega_max_rad_s",      "coupler_omega_min_rad_s",      "coupler_alpha_max_rad_s2",
    "coupler_alpha_min_rad_s2",     "slider_velocity_max_m_s",      "slider_velocity_min_m_s",
    "slider_acceleration_max_m_s2", "slider_acceleration_min_m_s2", "transmission_angle_min_rad",
    "stroke_m"};

static fb_status sc_outputs(double out[FB_TOL_NOUT], double where[8], const fb_linkage *lk,
                            double omega2, fb_diag *diag) {
  const fb_slider_crank sc = fb_slider_crank_of(lk);
  fb_slider_crank_limits lim;
  fb_status st = fb_slider_crank_limit_positions(&lim, &sc, diag);
  fb_peaks p;
  if (st == FB_OK)
    st = peaks_where(&p, where, lk, FB_BRANCH_OPEN, omega2, diag);
  if (st != FB_OK) return st;
  fb_tol_outputs_from_peaks(out, &p);
  out[8] = lim.transmission_min;
  out[9] = lim.stroke;
  return FB_OK;
}

/* the outputs (tolerance.h fb_tol_outputs_of) */
static fb_status tol_outputs(double out[FB_TOL_NOUT], const fb_linkage *lk, fb_branch branch,
                             double omega2, fb_diag *diag) {
  (void)branch;
  return sc_outputs(out, NULL, lk, omega2, diag);
}

/* d(output)/d(crank, coupler, offset) into columns FB_CRANK, FB_COUPLER,
 * FB_LENGTH_OFFSET (the fourth column 0): the peaks' from the exact
 * sensitivities at each peak's crank angle (envelope theorem); the smallest
 * transmission angle acos(u), u = (crank + |offset|) / coupler, and the
 * stroke sqrt((coupler + crank)^2 - offset^2) - sqrt((coupler - crank)^2 -
 * offset^2) differentiated in closed form. At offset 0 the transmission
 * angle has a corner (|offset|): its offset column is then the one-sided
 * derivative toward +offset (fb_tol_sensitivities_of). */
static fb_status sc_sensitivities(double out[FB_TOL_NOUT][FB_LINK_COUNT], const fb_linkage *lk,
                                  fb_branch branch, double omega2, fb_diag *diag) {
  (void)branch;
  const fb_slider_crank sc = fb_slider_crank_of(lk);
  double o[FB_TOL_NOUT], where[8];
  fb_status st = sc_outputs(o, where, lk, omega2, diag);
  if (st != FB_OK) return st;
  memset(out, 0, FB_TOL_NOUT * sizeof out[0]);
  static const int col[FB_SC_PARAM_COUNT] = {FB_CRANK, FB_COUPLER, FB_LENGTH_OFFSET};
  /* output i: body i / 4 (rod, slider), quantity (i % 4) / 2 (velocity, acceleration) */
  static const int row[8] = {FB_SC_SENS_OMEGA3, FB_SC_SENS_OMEGA3, FB_SC_SENS_ALPHA3,
                             FB_SC_SENS_ALPHA3, FB_SC_SENS_V,      FB_SC_SENS_V,
                             FB_SC_SENS_A,      FB_SC_SENS_A};
  for (int i = 0; i < 8; i++) {
    double s[FB_SC_SENS_COUNT][FB_SC_PARAM_COUNT];
    st = fb_slider_crank_sensitivity(s, &sc, where[i], omega2, 0.0, diag);
    if (st != FB_OK) return st;
    for (int k = 0; k < FB_SC_PARAM_COUNT; k++) out[i][col[k]] = s[row[i]][k];
  }
  const double a = sc.crank, b = sc.coupler, e = sc.offset;
  const double sgn = e < 0.0 ? -1.0 : 1.0; /* d|e|/de, +1 at e = 0 (one-sided) */
  const double u = (a + fabs(e)) / b;
  const double k = -1.0 / sqrt(1.0 - u * u); /* d acos(u) / du */
  out[8][FB_CRANK] = k / b;
  out[8][FB_COUPLER] = -k * u / b;
  out[8][FB_LENGTH_OFFSET] = k * sgn / b;
  const double p = sqrt((b + a) * (b + a) - e * e), m = sqrt((b - a) * (b - a) - e * e);
  out[9][FB_CRANK] = (b + a) / p + (b - a) / m;
  out[9][FB_COUPLER] = (b + a) / p - (b - a) / m;
  out[9][FB_LENGTH_OFFSET] = -e / p + e / m;
  return FB_OK;
}

/* ---- the reference and the case ----------------------------------------- */

/* the minimal-coordinate model (rod angle, slider x) the reference
 * integrates for case c */
static fb_status reference_model(fb_sc_dyn_model *out, const fb_case *c, const fb_linkage *lk,
                                 const fb_contact_law *law, double impact_velocity,
                                 fb_diag *diag) {
  out->geometry = fb_slider_crank_of(lk);
  out->mass = fb_slider_crank_mass_of(c->link);
  out->gravity = c->gravity;
  out->clearance = c->radial_clearance;
  out->law = *law;
  out->impact_velocity = impact_velocity;
  out->theta0 = c->crank_angle0;
  out->omega2 = fb_case_omega2(c);
  return fb_sc_dyn_check(out, diag);
}

static fb_status planar(fb_planar **out, const fb_linkage *lk, fb_branch branch,
                        const fb_link_mass link[3], double theta0, fb_diag *diag) {
  (void)branch;
  return fb_planar_slider_crank(out, lk, link, theta0, diag);
}

/* the slider-crank's counterpart of the Grashof line: its class by
 * coupler against crank + |offset|, the stroke and the dead centres, the
 * smallest transmission angle */
static void class_text(const fb_case *c, char *out, size_t size) {
  const fb_slider_crank sc = fb_slider_crank_of(&c->nominal);
  const double sum = sc.crank + fabs(sc.offset);
  const size_t n = (size_t)snprintf(
      out, size, "slider-crank, %s: coupler %.6g mm against crank + |offset| = %.6g mm (margin %.4g mm)",
      fb_sc_class_name(fb_slider_crank_class(&sc)), sc.coupler * 1e3, sum * 1e3,
      (sc.coupler - sum) * 1e3);
  fb_slider_crank_limits lim;
  if (n < size && fb_slider_crank_limit_positions(&lim, &sc, NULL) == FB_OK)
    snprintf(out + n, size - n, "; stroke %.6g mm between the dead centres x = %.6g and %.6g mm; "
             "smallest transmission angle %.4g deg", lim.stroke * 1e3, lim.x_min * 1e3,
             lim.x_max * 1e3, lim.transmission_min * 180.0 / M_PI);
}

/* a slider-crank's lengths, nominal and at the stack-up corner */
static fb_status check_case(const fb_case *c, fb_diag *diag) {
  fb_linkage su;
  fb_case_stackup_lengths(c, &su);
  const fb_linkage *lk[2] = {&c->nominal, &su};
  static const char *const which[2] = {"nominal", "stack-up"};
  for (int k = 0; k < 2; k++) {
    fb_diag inner;
    if (check_lengths(lk[k], &inner) != FB_OK)
      return fb_diag_set(diag, FB_ERR_ASSEMBLY,
                         "%s slider-crank ([linkage] crank_mm = %g, coupler_mm = %g, offset_mm = "
                         "%g): %s; a crank driven at constant speed needs coupler > crank + "
                         "|offset|",
                         which[k], lk[k]->length[FB_CRANK] * 1e3, lk[k]->length[FB_COUPLER] * 1e3,
                         lk[k]->length[FB_LENGTH_OFFSET] * 1e3, inner.msg);
  }
  return FB_OK;
}

/* its one clearance joint (the piston pin) and the options it refuses (the
 * paper's penalty, the worst corner) */
static fb_status check_options(const fb_case *c, fb_diag *diag) {
  /* the joints the description lets carry clearance: the piston pin */
  const fb_mech_desc *mech = fb_case_mech(c);
  for (int j = 0; j < mech->njoints; j++)
    if ((c->clearance.mask & (1 << j)) && !mech->joint[j].clearance_ok)
      return fb_diag_set(diag, FB_ERR_ARG,
                         "[clearance] joints names %s: a slider-crank's clearance joint is its "
                         "piston pin, %s (the models and the reference take it there; "
                         "ground-crank and crank-coupler are ideal, and the prismatic "
                         "slider-ground is a guide, not a pin): set joints = %s or none",
                         mech->joint[j].name, mech->joint[mech->reference_joint].name,
                         mech->joint[mech->reference_joint].name);
  if (c->clearance.mask && c->clearance.penalty == FB_PENALTY_SOURCE_PAPER)
    return fb_diag_set(diag, FB_ERR_ARG,
                       "[clearance] penalty = paper: the paper's stiffness recipe (its Tables II "
                       "and III) is the four-bar's, from its coupler and follower accelerations; "
                       "for a slider-crank use penalty = physical, goldsmith or explicit");
  if (c->stackup.worst)
    return fb_diag_set(diag, FB_ERR_ARG,
                       "[tolerance] stackup = worst: the worst corner is searched for the "
                       "four-bar only; give a slider-crank's corner as max, min, nominal or "
                       "its characters (crank, coupler, offset, then any)");
  return FB_OK;
}

const fb_closed_form fb_closed_form_slider_crank = {
    .solve = solve,
    .check_lengths = check_lengths,
    .peaks_where = peaks_where,
    .sample = NULL,
    .reactions = reactions,
    .reaction_peaks = reaction_peaks,
    .mechanism_at = mechanism_at,
    .start_steady = start_steady,
    .start_resolve = start_resolve,
    .tol_names = sc_out_names,
    .tol_outputs = tol_outputs,
    .tol_sensitivities = sc_sensitivities,
    .paper_refusal =
        "the paper's Tables I to III are its four-bar's recipe (F = k max|alpha| of the "
        "four-bar's two rocking links, with the paper's constants): they do not apply to a "
        "slider-crank; --mode physical gives Kc, P and the approach from its joints' reactions",
    .ideal_reference = 0,
    .reference_model = reference_model,
    .planar = planar,
    .class_text = class_text,
    .check_case = check_case,
    .tolerances_checked = 2, /* the offset, any sign, may be smaller than its tolerance */
    .check_options = check_options,
    .check_drivable = NULL,
};
