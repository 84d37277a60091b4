#include "start.h"

#include <math.h>
#include <string.h>

#include "invdyn.h"
#include "series.h"
#include "slider_crank_invdyn.h"

const char *fb_start_name(fb_start s) { return s == FB_START_REST ? "rest" : "steady"; }

const char *fb_pin_start_name(fb_pin_start p) {
  return p == FB_PIN_RESTING ? "resting" : (p == FB_PIN_ANGLE ? "angle" : "centred");
}

/* each joint's force on its second body with the crank held at theta0 under
 * gravity alone (inverse dynamics at zero speed); a slider-crank's guide
 * (slider-ground) carries none that a pin could lean on */
static fb_status static_load(double force[4][2], const fb_case *c, const fb_linkage *lk,
                             fb_diag *diag) {
  memset(force, 0, 4 * sizeof force[0]);
  if (c->mechanism == FB_MECH_SLIDER_CRANK) {
    const fb_slider_crank sc = fb_slider_crank_of(lk);
    const fb_slider_crank_mass m = fb_slider_crank_mass_of(c->link);
    fb_slider_crank_reactions r;
    fb_status st = fb_slider_crank_invdyn(&r, &sc, &m, c->gravity, c->crank_angle0, 0.0, 0.0, diag);
    if (st != FB_OK) return st;
    memcpy(force, r.force, sizeof r.force);
    return FB_OK;
  }
  fb_reactions r;
  fb_status st = fb_invdyn_solve(&r, lk, c->branch, c->link, c->gravity, c->crank_angle0, 0.0,
                                 diag);
  if (st != FB_OK) return st;
  memcpy(force, r.force, 4 * sizeof force[0]);
  return FB_OK;
}

/* eccentricity of every clearance joint from the case's pin_start */
static fb_status eccentricities(double ecc[4][2], const fb_case *c, const fb_linkage *lk,
                                int mask, fb_diag *diag) {
  memset(ecc, 0, 4 * sizeof ecc[0]);
  /* an ensemble member's perturbation (ensemble.h), on top of the pin start */
  for (int j = 0; j < 4; j++)
    if (mask & (1 << j)) ecc[j][0] = c->pin_start_offset[0], ecc[j][1] = c->pin_start_offset[1];
  if (!mask || c->pin_start == FB_PIN_CENTRED) return FB_OK;
  double dir[4][2];
  if (c->pin_start == FB_PIN_ANGLE) {
    for (int j = 0; j < 4; j++) dir[j][0] = cos(c->pin_start_angle), dir[j][1] = sin(c->pin_start_angle);
  } else {
    /* static load at zero speed; fb_reactions gives each force on the
     * joint's second body. The contact pushes the hole body along +e and
     * the pin body along -e: at B and C the second body holds the hole
     * (e along the force), at A and D it holds the pin (e against it). */
    double force[4][2];
    fb_status st = static_load(force, c, lk, diag);
    if (st != FB_OK) return st;
    const double sign[4] = {-1.0, 1.0, 1.0, -1.0};
    for (int j = 0; j < 4; j++) {
      const double f = hypot(force[j][0], force[j][1]);
      /* no load (zero gravity): the wall below the hole, an arbitrary choice */
      dir[j][0] = f > 0.0 ? sign[j] * force[j][0] / f : 0.0;
      dir[j][1] = f > 0.0 ? sign[j] * force[j][1] / f : -1.0;
    }
  }
  for (int j = 0; j < 4; j++)
    if (mask & (1 << j)) {
      ecc[j][0] += c->radial_clearance * dir[j][0];
      ecc[j][1] += c->radial_clearance * dir[j][1];
    }
  return FB_OK;
}

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

/* fb_start_resolve for the slider-crank: the rod and slider of the ideal
 * slider-crank whose guide is moved by the piston pin's e_y */
static fb_status sc_resolve(fb_start_state *out, const fb_case *c, const fb_linkage *lk,
                            int clearance_mask, fb_diag *diag) {
  double ecc[4][2];
  fb_status st = eccentricities(ecc, c, lk, clearance_mask, diag);
  if (st != FB_OK) return st;
  const double *e = ecc[FB_SC_JOINT_COUPLER_SLIDER];
  fb_slider_crank shifted = fb_slider_crank_of(lk);
  shifted.offset += e[1];
  fb_slider_crank_state s;
  fb_diag inner;
  st = fb_slider_crank_solve(&s, &shifted, c->crank_angle0, fb_case_omega2(c), 0.0, &inner);
  if (st != FB_OK)
    return fb_diag_set(diag, FB_ERR_ASSEMBLY,
                       "start: with the piston pin at its start position the slider-crank does "
                       "not assemble at crank angle %.6g deg: %s",
                       c->crank_angle0 * 180.0 / M_PI, inner.msg);
  sc_fill(out, &s, e, fb_case_omega2(c), c->start == FB_START_REST && clearance_mask != 0);
  return FB_OK;
}

fb_status fb_start_steady(fb_start_state *out, fb_mech_type t, const fb_linkage *lk,
                          fb_branch branch, double theta0, double omega2, fb_diag *diag) {
  if (t == FB_MECH_SLIDER_CRANK) {
    const fb_slider_crank sc = fb_slider_crank_of(lk);
    fb_slider_crank_state s;
    fb_status st = fb_slider_crank_solve(&s, &sc, theta0, omega2, 0.0, diag);
    if (st != FB_OK) return st;
    sc_fill(out, &s, (const double[2]){0.0, 0.0}, omega2, 0);
    return FB_OK;
  }
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

fb_status fb_start_resolve(fb_start_state *out, const fb_case *c, const fb_linkage *lk,
                           int clearance_mask, fb_diag *diag) {
  if (c->mechanism == FB_MECH_SLIDER_CRANK) return sc_resolve(out, c, lk, clearance_mask, diag);
  const double omega2 = fb_case_omega2(c), theta2 = c->crank_angle0;
  double ecc[4][2];
  fb_status st = eccentricities(ecc, c, lk, clearance_mask, diag);
  if (st != FB_OK) return st;
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
  const int centred = memcmp(ecc, (double[4][2]){{0}}, sizeof ecc) == 0;
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
