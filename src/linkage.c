#include "linkage.h"

#include <math.h>

static const char *const link_names[FB_LINK_COUNT] = {"crank", "coupler",
                                                      "follower", "ground"};

const char *fb_link_name(fb_link link) {
  return (link >= 0 && link < FB_LINK_COUNT) ? link_names[link] : "?";
}

const char *fb_grashof_name(fb_grashof g) {
  switch (g) {
    case FB_GRASHOF_CRANK_ROCKER: return "crank-rocker";
    case FB_GRASHOF_DOUBLE_CRANK: return "double-crank";
    case FB_GRASHOF_DOUBLE_ROCKER: return "double-rocker";
    case FB_GRASHOF_ROCKER_CRANK: return "rocker-crank";
    case FB_GRASHOF_CHANGE_POINT: return "change-point";
    case FB_GRASHOF_NON_GRASHOF: return "non-Grashof";
  }
  return "?";
}

fb_status fb_linkage_check(const fb_linkage *lk, fb_diag *diag) {
  for (int i = 0; i < FB_LINK_COUNT; i++) {
    double v = lk->length[i];
    if (!isfinite(v) || v <= 0.0)
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "%s length = %g m: a link length must be positive and finite",
                         link_names[i], v);
  }
  return FB_OK;
}

fb_grashof fb_linkage_grashof(const fb_linkage *lk) {
  int s = 0, l = 0;
  double sum = 0.0;
  for (int i = 0; i < FB_LINK_COUNT; i++) {
    if (lk->length[i] < lk->length[s]) s = i;
    if (lk->length[i] > lk->length[l]) l = i;
    sum += lk->length[i];
  }
  double sl = lk->length[s] + lk->length[l];
  double pq = sum - sl;
  if (fabs(sl - pq) <= FB_GRASHOF_REL_TOL * sum) return FB_GRASHOF_CHANGE_POINT;
  if (sl > pq) return FB_GRASHOF_NON_GRASHOF;
  switch ((fb_link)s) {
    case FB_CRANK: return FB_GRASHOF_CRANK_ROCKER;
    case FB_GROUND: return FB_GRASHOF_DOUBLE_CRANK;
    case FB_COUPLER: return FB_GRASHOF_DOUBLE_ROCKER;
    default: return FB_GRASHOF_ROCKER_CRANK;
  }
}

fb_status fb_linkage_solve(fb_linkage_state *out, const fb_linkage *lk,
                           fb_branch branch, double theta2, double omega2,
                           double alpha2, fb_diag *diag) {
  fb_status st = fb_linkage_check(lk, diag);
  if (st != FB_OK) return st;
  const double a = lk->length[FB_CRANK], b = lk->length[FB_COUPLER];
  const double c = lk->length[FB_FOLLOWER], g = lk->length[FB_GROUND];

  /* position: C is the intersection of circle(B, b) and circle(D, c) */
  const double bx = a * cos(theta2), by = a * sin(theta2);
  const double dx = g - bx, dy = -by; /* vector B->D */
  const double f = hypot(dx, dy);
  if (!(f >= fabs(b - c) && f <= b + c) || f == 0.0)
    return fb_diag_set(diag, FB_ERR_ASSEMBLY,
                       "crank angle %.6g deg: |BD| = %.9g m is outside "
                       "[|coupler - follower|, coupler + follower] = [%.9g, %.9g] m, "
                       "so the linkage cannot be assembled there",
                       theta2 * 180.0 / M_PI, f, fabs(b - c), b + c);
  /* angle at B between B->D and B->C (law of cosines), clamped for roundoff */
  double cphi = (b * b + f * f - c * c) / (2.0 * b * f);
  cphi = cphi > 1.0 ? 1.0 : (cphi < -1.0 ? -1.0 : cphi);
  const double phi = acos(cphi);
  const double psi = atan2(dy, dx);
  const double th3 = branch == FB_BRANCH_OPEN ? psi + phi : psi - phi;
  const double cx = bx + b * cos(th3), cy = by + b * sin(th3);
  const double th4 = atan2(cy, cx - g);

  /* velocity: d/dt of loop closure, a 2x2 system in (omega3, omega4)
   *   -b s3 w3 + c s4 w4 =  a s2 w2
   *    b c3 w3 - c c4 w4 = -a c2 w2        det = b c sin(th3 - th4) */
  const double s2 = sin(theta2), c2 = cos(theta2);
  const double s3 = sin(th3), c3 = cos(th3), s4 = sin(th4), c4 = cos(th4);
  const double det = b * c * sin(th3 - th4);
  if (fabs(det) <= 1e-14 * b * c)
    return fb_diag_set(diag, FB_ERR_ASSEMBLY,
                       "crank angle %.6g deg: coupler and follower are aligned "
                       "(toggle position), velocities are undefined",
                       theta2 * 180.0 / M_PI);
  /* Cramer's rule on M = [[-b s3, c s4], [b c3, -c c4]] */
  const double r1 = a * s2 * omega2, r2 = -a * c2 * omega2;
  const double w3 = (r1 * (-c * c4) - c * s4 * r2) / det;
  const double w4 = ((-b * s3) * r2 - b * c3 * r1) / det;

  /* acceleration: d^2/dt^2 of loop closure, same matrix, new right side
   *   -b s3 a3 + c s4 a4 =  a (s2 al2 + c2 w2^2) + b c3 w3^2 - c c4 w4^2
   *    b c3 a3 - c c4 a4 = -a (c2 al2 - s2 w2^2) + b s3 w3^2 - c s4 w4^2 */
  const double q1 = a * (s2 * alpha2 + c2 * omega2 * omega2) + b * c3 * w3 * w3 -
                    c * c4 * w4 * w4;
  const double q2 = -a * (c2 * alpha2 - s2 * omega2 * omega2) + b * s3 * w3 * w3 -
                    c * s4 * w4 * w4;
  const double a3 = (q1 * (-c * c4) - c * s4 * q2) / det;
  const double a4 = ((-b * s3) * q2 - b * c3 * q1) / det;

  double cmu = (b * b + c * c - f * f) / (2.0 * b * c);
  cmu = cmu > 1.0 ? 1.0 : (cmu < -1.0 ? -1.0 : cmu);

  out->crank_angle = theta2;
  out->crank_omega = omega2;
  out->crank_alpha = alpha2;
  out->coupler_angle = atan2(sin(th3), cos(th3));
  out->coupler_omega = w3;
  out->coupler_alpha = a3;
  out->follower_angle = th4;
  out->follower_omega = w4;
  out->follower_alpha = a4;
  out->transmission_angle = acos(cmu);
  out->b[0] = bx;
  out->b[1] = by;
  out->c[0] = cx;
  out->c[1] = cy;
  return FB_OK;
}

fb_status fb_linkage_crank_range(const fb_linkage *lk, double *lo, double *hi,
                                 int *full, fb_diag *diag) {
  fb_status st = fb_linkage_check(lk, diag);
  if (st != FB_OK) return st;
  const double a = lk->length[FB_CRANK], b = lk->length[FB_COUPLER];
  const double c = lk->length[FB_FOLLOWER], g = lk->length[FB_GROUND];
  /* |BD|^2 = a^2 + g^2 - 2 a g cos(theta2) in [(b-c)^2, (b+c)^2]
   *   <=> cos(theta2) in [cos_min, cos_max] */
  const double cos_max = (a * a + g * g - (b - c) * (b - c)) / (2.0 * a * g);
  const double cos_min = (a * a + g * g - (b + c) * (b + c)) / (2.0 * a * g);
  if (cos_max < -1.0 || cos_min > 1.0 || cos_min > cos_max)
    return fb_diag_set(diag, FB_ERR_ASSEMBLY,
                       "crank %.9g m, coupler %.9g m, follower %.9g m, ground %.9g m: "
                       "no crank angle closes the loop (|BD| ranges over [%.9g, %.9g] m "
                       "but must lie in [%.9g, %.9g] m)",
                       a, b, c, g, fabs(g - a), g + a, fabs(b - c), b + c);
  *lo = cos_max >= 1.0 ? 0.0 : acos(cos_max);
  *hi = cos_min <= -1.0 ? M_PI : acos(cos_min);
  /* strict: a toggle of coupler and follower on the way is a singular point */
  *full = (b + c > a + g) && (fabs(b - c) < fabs(g - a));
  return FB_OK;
}

fb_status fb_linkage_transmission_range(const fb_linkage *lk, double *mu_min,
                                        double *mu_max, fb_diag *diag) {
  double lo, hi;
  int full;
  fb_status st = fb_linkage_crank_range(lk, &lo, &hi, &full, diag);
  if (st != FB_OK) return st;
  const double a = lk->length[FB_CRANK], b = lk->length[FB_COUPLER];
  const double c = lk->length[FB_FOLLOWER], g = lk->length[FB_GROUND];
  double mu[2];
  const double th[2] = {lo, hi};
  for (int i = 0; i < 2; i++) {
    double f2 = a * a + g * g - 2.0 * a * g * cos(th[i]);
    double cm = (b * b + c * c - f2) / (2.0 * b * c);
    cm = cm > 1.0 ? 1.0 : (cm < -1.0 ? -1.0 : cm);
    mu[i] = acos(cm);
  }
  *mu_min = mu[0];
  *mu_max = mu[1];
  return FB_OK;
}
