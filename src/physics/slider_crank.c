#include "slider_crank.h"

#include <math.h>

const char *fb_sc_class_name(fb_sc_class k) {
  switch (k) {
    case FB_SC_FULL_TURN: return "full-turn";
    case FB_SC_CHANGE_POINT: return "change-point";
    case FB_SC_ROCKER: return "rocker";
  }
  return "?";
}

const char *fb_sc_param_name(fb_sc_param p) {
  switch (p) {
    case FB_SC_PARAM_CRANK: return "crank";
    case FB_SC_PARAM_COUPLER: return "coupler";
    case FB_SC_PARAM_OFFSET: return "offset";
    default: return "?";
  }
}

fb_status fb_slider_crank_check(const fb_slider_crank *sc, fb_diag *diag) {
  const double len[2] = {sc->crank, sc->coupler};
  const char *name[2] = {"crank", "coupler"};
  for (int i = 0; i < 2; i++)
    if (!isfinite(len[i]) || len[i] <= 0.0)
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "%s length = %g m: a link length must be positive and finite", name[i],
                         len[i]);
  if (!isfinite(sc->offset))
    return fb_diag_set(diag, FB_ERR_RANGE, "offset = %g m: the guide's offset must be finite",
                       sc->offset);
  return FB_OK;
}

fb_sc_class fb_slider_crank_class(const fb_slider_crank *sc) {
  const double reach = sc->crank + fabs(sc->offset);
  const double scale = sc->crank + sc->coupler + fabs(sc->offset);
  if (fabs(sc->coupler - reach) <= FB_SC_CHANGE_POINT_REL_TOL * scale) return FB_SC_CHANGE_POINT;
  return sc->coupler > reach ? FB_SC_FULL_TURN : FB_SC_ROCKER;
}

fb_status fb_slider_crank_require_full_turn(const fb_slider_crank *sc, fb_diag *diag) {
  fb_status st = fb_slider_crank_check(sc, diag);
  if (st != FB_OK) return st;
  const double a = sc->crank, b = sc->coupler, e = sc->offset;
  switch (fb_slider_crank_class(sc)) {
    case FB_SC_FULL_TURN: return FB_OK;
    case FB_SC_CHANGE_POINT:
      return fb_diag_set(diag, FB_ERR_ASSEMBLY,
                         "crank %.9g m, coupler %.9g m, offset %.9g m: a change point "
                         "(coupler = crank + |offset|): the rod stands perpendicular to the "
                         "guide at crank angle %g deg, where the slider's velocity is undefined "
                         "and it may leave its branch; make the coupler longer than crank + "
                         "|offset|",
                         a, b, e, e >= 0.0 ? -90.0 : 90.0);
    case FB_SC_ROCKER:
      break;
  }
  return fb_diag_set(diag, FB_ERR_ASSEMBLY,
                     "crank %.9g m, coupler %.9g m, offset %.9g m: the crank cannot turn fully "
                     "(coupler < crank + |offset| = %.9g m): the loop opens where |offset - "
                     "crank sin theta2| > coupler",
                     a, b, e, a + fabs(e));
}

fb_status fb_slider_crank_solve(fb_slider_crank_state *out, const fb_slider_crank *sc,
                                double theta2, double omega2, double alpha2, fb_diag *diag) {
  fb_status st = fb_slider_crank_check(sc, diag);
  if (st != FB_OK) return st;
  const double a = sc->crank, b = sc->coupler, e = sc->offset;
  const double s2 = sin(theta2), c2 = cos(theta2);
  /* position: u = b sin theta3 (the rod's rise from B to the guide), w = b cos theta3 */
  const double u = e - a * s2;
  if (!(fabs(u) <= b))
    return fb_diag_set(diag, FB_ERR_ASSEMBLY,
                       "crank angle %.6g deg: the guide is %.9g m from the crank pin B, farther "
                       "than the coupler %.9g m, so the slider-crank cannot be assembled there",
                       theta2 * 180.0 / M_PI, fabs(u), b);
  const double w = sqrt((b - u) * (b + u)); /* factored: no cancellation near |u| = b */
  if (w <= FB_SC_PERPENDICULAR_TOL * b)
    return fb_diag_set(diag, FB_ERR_ASSEMBLY,
                       "crank angle %.6g deg: the rod stands perpendicular to the guide (dead "
                       "position), velocities are undefined",
                       theta2 * 180.0 / M_PI);
  const double s3 = u / b, c3 = w / b;
  /* velocity: d/dt of both loop components */
  const double w3 = -a * c2 * omega2 / w;
  const double v = -a * s2 * omega2 - u * w3;
  /* acceleration: second time derivatives */
  const double a3 = (a * (s2 * omega2 * omega2 - c2 * alpha2) + u * w3 * w3) / w;
  const double acc = -a * (c2 * omega2 * omega2 + s2 * alpha2) - w * w3 * w3 - u * a3;

  out->crank_angle = theta2;
  out->crank_omega = omega2;
  out->crank_alpha = alpha2;
  out->coupler_angle = atan2(s3, c3);
  out->coupler_omega = w3;
  out->coupler_alpha = a3;
  out->slider_x = a * c2 + w;
  out->slider_v = v;
  out->slider_a = acc;
  out->transmission_angle = acos(fabs(s3) > 1.0 ? 1.0 : fabs(s3));
  out->b[0] = a * c2;
  out->b[1] = a * s2;
  out->c[0] = a * c2 + w;
  out->c[1] = e;
  return FB_OK;
}

fb_status fb_slider_crank_limit_positions(fb_slider_crank_limits *out, const fb_slider_crank *sc,
                                          fb_diag *diag) {
  fb_status st = fb_slider_crank_require_full_turn(sc, diag);
  if (st != FB_OK) return st;
  const double a = sc->crank, b = sc->coupler, e = sc->offset;
  const double r_out = b + a, r_in = b - a; /* |C - A| at the two dead centres */
  out->x_max = sqrt((r_out - e) * (r_out + e));
  out->x_min = sqrt((r_in - e) * (r_in + e));
  out->stroke = out->x_max - out->x_min;
  out->theta_outer = asin(e / r_out);
  out->theta_inner = M_PI + asin(e / r_in);
  out->outstroke_angle = M_PI + asin(e / r_out) - asin(e / r_in);
  out->transmission_min = acos((a + fabs(e)) / b);
  return FB_OK;
}

fb_status fb_slider_crank_sensitivity(double out[FB_SC_SENS_COUNT][FB_SC_PARAM_COUNT],
                                      const fb_slider_crank *sc, double theta2, double omega2,
                                      double alpha2, fb_diag *diag) {
  fb_slider_crank_state s;
  fb_status st = fb_slider_crank_solve(&s, sc, theta2, omega2, alpha2, diag);
  if (st != FB_OK) return st;
  const double a = sc->crank, b = sc->coupler, e = sc->offset;
  const double s2 = sin(theta2), c2 = cos(theta2);
  const double u = e - a * s2, w = sqrt((b - u) * (b + u));
  const double w3 = s.coupler_omega, a3 = s.coupler_alpha;
  const double o2 = omega2 * omega2;
  for (int k = 0; k < FB_SC_PARAM_COUNT; k++) {
    /* derivatives of the parameters themselves */
    const double da = k == FB_SC_PARAM_CRANK, db = k == FB_SC_PARAM_COUPLER;
    const double de = k == FB_SC_PARAM_OFFSET;
    const double du = de - s2 * da;
    const double dw = (b * db - u * du) / w;
    const double dx = c2 * da + dw;
    const double dth3 = (du - u * db / b) / w; /* theta3 = asin(u / b) */
    /* omega3 w = -a c2 omega2 */
    const double dw3 = (-da * c2 * omega2 - w3 * dw) / w;
    const double dv = -da * s2 * omega2 - du * w3 - u * dw3;
    /* alpha3 w = N = a (s2 omega2^2 - c2 alpha2) + u omega3^2 */
    const double dN = da * (s2 * o2 - c2 * alpha2) + du * w3 * w3 + 2.0 * u * w3 * dw3;
    const double da3 = (dN - a3 * dw) / w;
    const double dacc = -da * (c2 * o2 + s2 * alpha2) - dw * w3 * w3 - 2.0 * w * w3 * dw3 -
                        du * a3 - u * da3;
    out[FB_SC_SENS_X][k] = dx;
    out[FB_SC_SENS_V][k] = dv;
    out[FB_SC_SENS_A][k] = dacc;
    out[FB_SC_SENS_THETA3][k] = dth3;
    out[FB_SC_SENS_OMEGA3][k] = dw3;
    out[FB_SC_SENS_ALPHA3][k] = da3;
  }
  return FB_OK;
}

fb_slider_crank fb_slider_crank_of(const fb_linkage *lk) {
  return (fb_slider_crank){lk->length[FB_CRANK], lk->length[FB_COUPLER],
                           lk->length[FB_LENGTH_OFFSET]};
}
