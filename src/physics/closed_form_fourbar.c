/* The four-bar's closed forms as the family's table (closed_form.h):
 * its exact kinematics (linkage.h, analytic.h), inverse dynamics
 * (invdyn.h), start states (start.h), tolerance outputs (tolerance.h, whose
 * four-bar functions are defined here) and the checks a four-bar case
 * needs. */
#include "closed_form.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "invdyn.h"

/* ---- kinematics ----------------------------------------------------------- */

static fb_status solve(double out[FB_MECH_MAX_OUTPUTS][3], const fb_linkage *lk,
                       fb_branch branch, double theta2, double omega2, double alpha2,
                       fb_diag *diag) {
  fb_linkage_state s;
  fb_status st = fb_linkage_solve(&s, lk, branch, theta2, omega2, alpha2, diag);
  if (st != FB_OK) return st;
  const double v[2][3] = {{s.coupler_angle, s.coupler_omega, s.coupler_alpha},
                          {s.follower_angle, s.follower_omega, s.follower_alpha}};
  memcpy(out, v, sizeof v);
  return FB_OK;
}

/* the four-bar's output bodies rotate: no position extremes */
static void no_positions(fb_peaks *out) {
  for (int b = 0; b < FB_MECH_MAX_OUTPUTS; b++) out->body[b].pos_max = out->body[b].pos_min = NAN;
}

static fb_status peaks_where(fb_peaks *out, double where[8], const fb_linkage *lk,
                             fb_branch branch, double omega2, fb_diag *diag) {
  fb_status st = fb_analytic_peaks_where(out, where, lk, branch, omega2, diag);
  no_positions(out);
  return st;
}


static fb_status reactions(double force[4][2], double *drive_torque, const fb_linkage *lk,
                           fb_branch branch, const fb_link_mass link[3], double gravity,
                           double theta2, double omega2, fb_diag *diag) {
  fb_reactions r;
  fb_status st = fb_invdyn_solve(&r, lk, branch, link, gravity, theta2, omega2, diag);
  if (st != FB_OK) return st;
  memcpy(force, r.force, sizeof r.force);
  if (drive_torque) *drive_torque = r.drive_torque;
  return FB_OK;
}

static fb_status reaction_peaks(double force_max[4], const fb_linkage *lk, fb_branch branch,
                                const fb_link_mass link[3], double gravity, double omega2, int n,
                                fb_diag *diag) {
  return fb_invdyn_peaks(force_max, NULL, lk, branch, link, gravity, omega2, n, diag);
}

static fb_status mechanism_at(fb_mechanism *out, const fb_linkage *lk, fb_branch branch,
                              const fb_link_mass link[3], double theta2, int clearance_mask,
                              fb_diag *diag) {
  fb_linkage_state ls;
  fb_status st = fb_linkage_solve(&ls, lk, branch, theta2, 0.0, 0.0, diag);
  if (st != FB_OK) return st;
  fb_mechanism_from_state(out, lk, &ls, link, clearance_mask);
  return FB_OK;
}

/* ---- start states ------------------------------------------------------- */

static fb_status start_steady(fb_start_state *out, const fb_linkage *lk, fb_branch branch,
                              double theta0, double omega2, fb_diag *diag) {
  fb_linkage_state ls;
  fb_status rc = fb_linkage_solve(&ls, lk, branch, theta0, omega2, 0.0, diag);
  if (rc != FB_OK) return rc;
  memset(out, 0, sizeof *out);
  out->crank_angle = ls.crank_angle;
  out->crank_omega = omega2;
  out->coupler_angle = ls.coupler_angle;
  out->coupler_omega = ls.coupler_omega;
  out->follower_angle = ls.follower_angle;
  out->follower_omega = ls.follower_omega;
  for (int k = 0; k < 2; k++) {
    out->pin[FB_JOINT_B][k] = out->hole[FB_JOINT_B][k] = ls.b[k];
    out->pin[FB_JOINT_C][k] = out->hole[FB_JOINT_C][k] = ls.c[k];
  }
  out->pin[FB_JOINT_D][0] = out->hole[FB_JOINT_D][0] = lk->length[FB_GROUND];
  out->coupler_b_vel[0] = -omega2 * ls.b[1];
  out->coupler_b_vel[1] = omega2 * ls.b[0];
  return FB_OK;
}

/* start.h's loop through the offsets: A_hole = 0 .. D_hole = (g, 0) */
static fb_status start_resolve(fb_start_state *out, const fb_case *c, const fb_linkage *lk,
                               const double ecc[4][2], int clearance_mask, fb_diag *diag) {
  const double omega2 = fb_case_omega2(c), theta2 = c->crank_angle0;
  fb_status st;
  memset(out, 0, sizeof *out);
  memcpy(out->ecc, ecc, sizeof out->ecc);
  out->crank_angle = theta2;
  out->crank_omega = omega2;
  const double a = lk->length[FB_CRANK], b = lk->length[FB_COUPLER];
  const double f = lk->length[FB_FOLLOWER], g = lk->length[FB_GROUND];
  const double u2[2] = {cos(theta2), sin(theta2)};
  /* A and B from the crank side */
  out->hole[FB_JOINT_A][0] = out->hole[FB_JOINT_A][1] = 0.0;
  for (int k = 0; k < 2; k++) {
    out->pin[FB_JOINT_A][k] = ecc[FB_JOINT_A][k];
    out->pin[FB_JOINT_B][k] = out->pin[FB_JOINT_A][k] + a * u2[k];
    out->hole[FB_JOINT_B][k] = out->pin[FB_JOINT_B][k] - ecc[FB_JOINT_B][k];
  }
  const int centred = memcmp(ecc, (double[4][2]){{0}}, sizeof out->ecc) == 0;
  double th3, th4, w3, w4, cpt[2] = {0, 0};
  if (centred) {
    /* the ideal mechanism itself: bit-identical to the steady start before
     * start states existed */
    fb_linkage_state s;
    st = fb_linkage_solve(&s, lk, c->branch, theta2, omega2, 0.0, diag);
    if (st != FB_OK) return st;
    th3 = s.coupler_angle;
    th4 = s.follower_angle;
    w3 = s.coupler_omega;
    w4 = s.follower_omega;
    out->hole[FB_JOINT_B][0] = out->pin[FB_JOINT_B][0] = s.b[0];
    out->hole[FB_JOINT_B][1] = out->pin[FB_JOINT_B][1] = s.b[1];
    cpt[0] = s.c[0];
    cpt[1] = s.c[1];
  } else {
    /* a four-bar whose crank tip is P = B_hole - e_C - e_D: circle(P, b)
     * meets circle(D, f), on the case's branch as in fb_linkage_solve */
    const double P[2] = {out->hole[FB_JOINT_B][0] - ecc[FB_JOINT_C][0] - ecc[FB_JOINT_D][0],
                         out->hole[FB_JOINT_B][1] - ecc[FB_JOINT_C][1] - ecc[FB_JOINT_D][1]};
    const double dx = g - P[0], dy = -P[1];
    const double d = hypot(dx, dy);
    if (!(d >= fabs(b - f) && d <= b + f) || d == 0.0)
      return fb_diag_set(diag, FB_ERR_ASSEMBLY,
                         "start: with the pins at their start positions the loop does not "
                         "close at crank angle %.6g deg",
                         theta2 * 180.0 / M_PI);
    double cphi = (b * b + d * d - f * f) / (2.0 * b * d);
    cphi = cphi > 1.0 ? 1.0 : (cphi < -1.0 ? -1.0 : cphi);
    const double psi = atan2(dy, dx), phi = acos(cphi);
    th3 = c->branch == FB_BRANCH_OPEN ? psi + phi : psi - phi;
    const double Cx = P[0] + b * cos(th3), Cy = P[1] + b * sin(th3);
    th4 = atan2(Cy, Cx - g);
    th3 = atan2(sin(th3), cos(th3));
    /* velocities with the offsets fixed: the crank tip moves at
     * omega2 x (B_pin - A_pin) = a omega2 u2'; same 2x2 system */
    const double s2 = u2[1], c2 = u2[0], s3 = sin(th3), c3 = cos(th3), s4 = sin(th4), c4 = cos(th4);
    const double det = b * f * sin(th3 - th4);
    if (fabs(det) <= 1e-14 * b * f)
      return fb_diag_set(diag, FB_ERR_ASSEMBLY,
                         "start: coupler and follower are aligned at crank angle %.6g deg",
                         theta2 * 180.0 / M_PI);
    const double r1 = a * s2 * omega2, r2 = -a * c2 * omega2;
    w3 = (r1 * (-f * c4) - f * s4 * r2) / det;
    w4 = ((-b * s3) * r2 - b * c3 * r1) / det;
  }
  const double u3[2] = {cos(th3), sin(th3)}, u4[2] = {cos(th4), sin(th4)};
  for (int k = 0; k < 2; k++) {
    out->pin[FB_JOINT_C][k] = out->hole[FB_JOINT_B][k] + b * u3[k];
    out->hole[FB_JOINT_C][k] = out->pin[FB_JOINT_C][k] - ecc[FB_JOINT_C][k];
    out->pin[FB_JOINT_D][k] = out->hole[FB_JOINT_C][k] - f * u4[k];
  }
  out->hole[FB_JOINT_D][0] = g;
  out->hole[FB_JOINT_D][1] = 0.0;
  if (centred) { /* C and D exactly as the ideal solve placed them */
    for (int k = 0; k < 2; k++) out->pin[FB_JOINT_C][k] = out->hole[FB_JOINT_C][k] = cpt[k];
    out->pin[FB_JOINT_D][0] = g;
    out->pin[FB_JOINT_D][1] = 0.0;
  }
  out->coupler_angle = th3;
  out->follower_angle = th4;
  const int rest = c->start == FB_START_REST && clearance_mask != 0;
  out->coupler_omega = rest ? 0.0 : w3;
  out->follower_omega = rest ? 0.0 : w4;
  if (!rest) {
    const double rb[2] = {out->pin[FB_JOINT_B][0] - out->pin[FB_JOINT_A][0],
                          out->pin[FB_JOINT_B][1] - out->pin[FB_JOINT_A][1]};
    out->coupler_b_vel[0] = -omega2 * rb[1];
    out->coupler_b_vel[1] = omega2 * rb[0];
  }
  return FB_OK;
}

/* ---- tolerance outputs -------------------------------------------------- */

static const char *const out_names[FB_TOL_NOUT] = {
    "coupler_omega_max_rad_s",   "coupler_omega_min_rad_s",    "coupler_alpha_max_rad_s2",
    "coupler_alpha_min_rad_s2",  "follower_omega_max_rad_s",   "follower_omega_min_rad_s",
    "follower_alpha_max_rad_s2", "follower_alpha_min_rad_s2",  "transmission_angle_min_rad",
    "transmission_angle_max_rad"};

const char *fb_tol_output_name(int i) { return (i >= 0 && i < FB_TOL_NOUT) ? out_names[i] : "?"; }

int fb_tol_output_parse(const char *name) {
  size_t n = strlen(name);
  for (int i = 0; i < FB_TOL_NOUT; i++) {
    if (strcmp(name, out_names[i]) == 0) return i;
    /* without the unit suffix: the name is a prefix followed by "_rad" */
    if (strncmp(name, out_names[i], n) == 0 && strncmp(out_names[i] + n, "_rad", 4) == 0) return i;
  }
  return -1;
}

void fb_tol_outputs_from_peaks(double out[FB_TOL_NOUT], const fb_peaks *p) {
  out[0] = p->coupler.omega_max;
  out[1] = p->coupler.omega_min;
  out[2] = p->coupler.alpha_max;
  out[3] = p->coupler.alpha_min;
  out[4] = p->follower.omega_max;
  out[5] = p->follower.omega_min;
  out[6] = p->follower.alpha_max;
  out[7] = p->follower.alpha_min;
}

fb_status fb_tol_outputs(double out[FB_TOL_NOUT], const fb_linkage *lk, fb_branch branch,
                         double omega2, fb_diag *diag) {
  fb_peaks p;
  fb_status st = fb_analytic_peaks(&p, lk, branch, omega2, diag);
  if (st != FB_OK) return st;
  fb_tol_outputs_from_peaks(out, &p);
  return fb_linkage_transmission_range(lk, &out[8], &out[9], diag);
}

fb_status fb_tol_sensitivities(double out[FB_TOL_NOUT][FB_LINK_COUNT], const fb_linkage *lk,
                               fb_branch branch, double omega2, fb_diag *diag) {
  fb_peaks p;
  double where[8];
  fb_status st = fb_analytic_peaks_where(&p, where, lk, branch, omega2, diag);
  if (st != FB_OK) return st;
  for (int i = 0; i < 8; i++) {
    double s[4][FB_LINK_COUNT];
    st = fb_linkage_sensitivity(s, lk, branch, where[i], omega2, diag);
    if (st != FB_OK) return st;
    /* output i: body i / 4 (coupler, follower), quantity (i % 4) / 2 (omega, alpha) */
    const int row = (i % 4 < 2 ? 0 : 2) + (i < 4 ? 0 : 1);
    for (int k = 0; k < FB_LINK_COUNT; k++) out[i][k] = s[row][k];
  }
  /* transmission angle at theta2 = 0 (f = g - a) and pi (f = g + a) */
  const double a = lk->length[FB_CRANK], b = lk->length[FB_COUPLER];
  const double c = lk->length[FB_FOLLOWER], g = lk->length[FB_GROUND];
  for (int e = 0; e < 2; e++) {
    const double sgn = e == 0 ? -1.0 : 1.0; /* f = g + sgn a */
    const double f = g + sgn * a;
    const double u = (b * b + c * c - f * f) / (2.0 * b * c);
    const double k = -1.0 / sqrt(1.0 - u * u); /* d acos(u) / du */
    const double du_df = -f / (b * c);
    out[8 + e][FB_CRANK] = k * du_df * sgn;
    out[8 + e][FB_GROUND] = k * du_df;
    out[8 + e][FB_COUPLER] = k * (1.0 / c - u / b);
    out[8 + e][FB_FOLLOWER] = k * (1.0 / b - u / c);
  }
  return FB_OK;
}

/* ---- case checks -------------------------------------------------------- */

static fb_status check_drivable(const fb_linkage *lk, const char *which, fb_diag *diag) {
  double lo, hi;
  int full;
  fb_diag inner;
  fb_status st = fb_linkage_crank_range(lk, &lo, &hi, &full, &inner);
  if (st != FB_OK)
    return fb_diag_set(diag, st, "%s linkage cannot be assembled: %s", which, inner.msg);
  /* (by the class's tolerance: the strict test alone can pass on roundoff) */
  if (fb_linkage_grashof(lk) == FB_GRASHOF_CHANGE_POINT) {
    char g[512];
    fb_linkage_grashof_text(g, sizeof g, lk);
    return fb_diag_set(diag, FB_ERR_ASSEMBLY,
                       "%s linkage: %s; a crank driven at constant speed cannot pass a fold: "
                       "make s + l differ from p + q (s + l < p + q for a crank-rocker) with "
                       "[linkage] crank_mm, coupler_mm, follower_mm, ground_mm",
                       which, g);
  }
  if (!full)
    return fb_diag_set(diag, FB_ERR_ASSEMBLY,
                       "%s linkage (%s): the crank cannot turn fully, but it is driven "
                       "at constant speed: it reaches only crank angles with |theta2| in "
                       "[%.3f, %.3f] deg; "
                       "a driven crank needs coupler + follower > crank + ground and "
                       "|coupler - follower| < |ground - crank|",
                       which, fb_grashof_name(fb_linkage_grashof(lk)), lo * 180.0 / M_PI,
                       hi * 180.0 / M_PI);
  return FB_OK;
}

/* the Grashof line of the nominal lengths, the class at the stack-up
 * corner when it differs, and how near the tolerances bring the change
 * point */
static void class_text(const fb_case *c, char *out, size_t size) {
  fb_linkage_grashof_text(out, size, &c->nominal);
  size_t n = strlen(out);
  fb_linkage su;
  fb_case_stackup_lengths(c, &su);
  const fb_grashof gn = fb_linkage_grashof(&c->nominal), gs = fb_linkage_grashof(&su);
  if (gs != gn && n < size)
    n += (size_t)snprintf(out + n, size - n, "; at the stack-up corner: %s", fb_grashof_name(gs));
  double sl, pq, tol = 0.0;
  fb_linkage_grashof_sums(&c->nominal, &sl, &pq, NULL, NULL);
  for (int i = 0; i < FB_LINK_COUNT; i++) tol += c->plus_minus[i];
  if (gn != FB_GRASHOF_CHANGE_POINT && tol > 0.0 && fabs(pq - sl) <= tol && n < size)
    snprintf(out + n, size - n, "; within the length tolerances (+- %.4g mm summed) the linkage "
             "can reach the change point, %.4g mm away", tol * 1e3, fabs(pq - sl) * 1e3);
}

/* the nominal lengths make a four-bar */
static fb_status check_case(const fb_case *c, fb_diag *diag) {
  return fb_linkage_check(&c->nominal, diag);
}

/* the nominal and the stack-up four-bar turn fully at constant crank speed */
static fb_status check_drivable_case(const fb_case *c, fb_diag *diag) {
  fb_status st = check_drivable(&c->nominal, "nominal", diag);
  if (st != FB_OK) return st;
  fb_linkage su;
  fb_case_stackup_lengths(c, &su);
  return check_drivable(&su, "stack-up", diag);
}

const fb_closed_form fb_closed_form_fourbar = {
    .solve = solve,
    .check_lengths = fb_linkage_check,
    .peaks_where = peaks_where,
    .sample = fb_analytic_sample,
    .reactions = reactions,
    .reaction_peaks = reaction_peaks,
    .mechanism_at = mechanism_at,
    .start_steady = start_steady,
    .start_resolve = start_resolve,
    .tol_names = out_names,
    .tol_outputs = fb_tol_outputs,
    .tol_sensitivities = fb_tol_sensitivities,
    .paper_refusal = NULL,
    .ideal_reference = 1,
    .reference_model = NULL,
    .planar = fb_planar_fourbar,
    .class_text = class_text,
    .check_case = check_case,
    .tolerances_checked = FB_LINK_COUNT,
    .check_options = NULL,
    .check_drivable = check_drivable_case,
};
