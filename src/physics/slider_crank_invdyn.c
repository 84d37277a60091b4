#include "slider_crank_invdyn.h"

#include <math.h>

const char *fb_sc_joint_name(fb_sc_joint j) {
  switch (j) {
    case FB_SC_JOINT_GROUND_CRANK: return "ground-crank";
    case FB_SC_JOINT_CRANK_COUPLER: return "crank-coupler";
    case FB_SC_JOINT_COUPLER_SLIDER: return "coupler-slider";
    case FB_SC_JOINT_SLIDER_GROUND: return "slider-ground";
    default: return "?";
  }
}

fb_status fb_slider_crank_mass_check(const fb_slider_crank_mass *m, fb_diag *diag) {
  const struct {
    const char *name, *unit;
    double v;
    int fraction;
  } f[7] = {{"crank mass", "kg", m->crank_mass, 0},
            {"crank inertia", "kg m^2", m->crank_inertia, 0},
            {"crank centre-of-mass fraction", "", m->crank_com_fraction, 1},
            {"coupler mass", "kg", m->coupler_mass, 0},
            {"coupler inertia", "kg m^2", m->coupler_inertia, 0},
            {"coupler centre-of-mass fraction", "", m->coupler_com_fraction, 1},
            {"slider mass", "kg", m->slider_mass, 0}};
  for (int i = 0; i < 7; i++) {
    if (f[i].fraction && !(f[i].v >= 0.0 && f[i].v <= 1.0))
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "%s = %g: the centre of mass must lie between the link's joints "
                         "(0 to 1)",
                         f[i].name, f[i].v);
    if (!f[i].fraction && !(isfinite(f[i].v) && f[i].v >= 0.0))
      return fb_diag_set(diag, FB_ERR_RANGE, "%s = %g %s: must be finite and not negative",
                         f[i].name, f[i].v, f[i].unit);
  }
  return FB_OK;
}

/* z component of the planar cross product p x q */
static double cross(const double p[2], const double q[2]) { return p[0] * q[1] - p[1] * q[0]; }

fb_status fb_slider_crank_invdyn(fb_slider_crank_reactions *out, const fb_slider_crank *sc,
                                 const fb_slider_crank_mass *m, double gravity, double theta2,
                                 double omega2, double alpha2, fb_diag *diag) {
  fb_status st = fb_slider_crank_mass_check(m, diag);
  if (st != FB_OK) return st;
  fb_slider_crank_state s;
  st = fb_slider_crank_solve(&s, sc, theta2, omega2, alpha2, diag);
  if (st != FB_OK) return st;
  const double *B = s.b, *C = s.c;
  const double f2 = m->crank_com_fraction, f3 = m->coupler_com_fraction;
  const double w3 = s.coupler_omega, a3 = s.coupler_alpha;
  /* accelerations: B on the crank about the fixed A; G2 = f2 B; G3 on the rod */
  const double aB[2] = {-alpha2 * B[1] - omega2 * omega2 * B[0],
                        alpha2 * B[0] - omega2 * omega2 * B[1]};
  const double G2[2] = {f2 * B[0], f2 * B[1]};
  const double aG2[2] = {f2 * aB[0], f2 * aB[1]};
  const double r3[2] = {f3 * (C[0] - B[0]), f3 * (C[1] - B[1])}; /* G3 - B */
  const double G3[2] = {B[0] + r3[0], B[1] + r3[1]};
  const double aG3[2] = {aB[0] - a3 * r3[1] - w3 * w3 * r3[0],
                         aB[1] + a3 * r3[0] - w3 * w3 * r3[1]};
  /* slider: F_Cx from its acceleration along the guide */
  double FC[2];
  FC[0] = m->slider_mass * s.slider_a;
  /* coupler: moments about G3 with F_B eliminated */
  const double P[2] = {m->coupler_mass * aG3[0], m->coupler_mass * (aG3[1] + gravity)};
  const double BG3[2] = {B[0] - G3[0], B[1] - G3[1]};
  const double d[2] = {B[0] - C[0], B[1] - C[1]}; /* d[0] = -coupler cos theta3 < 0 */
  FC[1] = (m->coupler_inertia * a3 - cross(BG3, P) + d[1] * FC[0]) / d[0];
  const double FB[2] = {P[0] + FC[0], P[1] + FC[1]};
  /* crank */
  const double FA[2] = {m->crank_mass * aG2[0] + FB[0],
                        m->crank_mass * (aG2[1] + gravity) + FB[1]};
  const double AG2[2] = {-G2[0], -G2[1]}, BG2[2] = {B[0] - G2[0], B[1] - G2[1]};
  const double T = m->crank_inertia * alpha2 - cross(AG2, FA) + cross(BG2, FB);

  const double *F[FB_SC_PIN_COUNT] = {FA, FB, FC};
  const double ang[FB_SC_PIN_COUNT] = {theta2, theta2, s.coupler_angle};
  for (int j = 0; j < FB_SC_PIN_COUNT; j++) {
    out->force[j][0] = F[j][0];
    out->force[j][1] = F[j][1];
    const double u[2] = {cos(ang[j]), sin(ang[j])};
    out->radial[j] = F[j][0] * u[0] + F[j][1] * u[1];
    out->tangential[j] = -F[j][0] * u[1] + F[j][1] * u[0];
  }
  out->guide_force = m->slider_mass * gravity - FC[1];
  out->drive_torque = T;
  return FB_OK;
}

fb_status fb_slider_crank_invdyn_peaks(double force_max[FB_SC_PIN_COUNT], double *guide_max,
                                       double *torque_max, const fb_slider_crank *sc,
                                       const fb_slider_crank_mass *m, double gravity,
                                       double omega2, int n, fb_diag *diag) {
  if (n < 1)
    return fb_diag_set(diag, FB_ERR_ARG, "%d crank angles: at least one is needed", n);
  fb_status st = fb_slider_crank_require_full_turn(sc, diag);
  if (st != FB_OK) return st;
  double fm[FB_SC_PIN_COUNT] = {0}, nm = 0.0, tm = 0.0;
  for (int k = 0; k < n; k++) {
    fb_slider_crank_reactions r;
    st = fb_slider_crank_invdyn(&r, sc, m, gravity, 2.0 * M_PI * k / n, omega2, 0.0, diag);
    if (st != FB_OK) return st;
    for (int j = 0; j < FB_SC_PIN_COUNT; j++)
      fm[j] = fmax(fm[j], hypot(r.force[j][0], r.force[j][1]));
    nm = fmax(nm, fabs(r.guide_force));
    tm = fmax(tm, fabs(r.drive_torque));
  }
  if (force_max)
    for (int j = 0; j < FB_SC_PIN_COUNT; j++) force_max[j] = fm[j];
  if (guide_max) *guide_max = nm;
  if (torque_max) *torque_max = tm;
  return FB_OK;
}

fb_slider_crank_mass fb_slider_crank_mass_of(const fb_link_mass link[3]) {
  return (fb_slider_crank_mass){link[0].mass, link[0].inertia, link[0].com_fraction,
                                link[1].mass, link[1].inertia, link[1].com_fraction,
                                link[2].mass};
}
