#include "linkage.h"

#include <math.h>
#include <stdio.h>

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

void fb_linkage_grashof_sums(const fb_linkage *lk, double *sl, double *pq, int *shortest,
                             int *longest) {
  int s = 0, l = 0;
  double sum = 0.0;
  for (int i = 0; i < FB_LINK_COUNT; i++) {
    if (lk->length[i] < lk->length[s]) s = i;
    if (lk->length[i] > lk->length[l]) l = i;
    sum += lk->length[i];
  }
  *sl = lk->length[s] + lk->length[l];
  *pq = sum - *sl;
  if (shortest) *shortest = s;
  if (longest) *longest = l;
}

int fb_linkage_fold_angles(const fb_linkage *lk, double out[2]) {
  const double a = lk->length[FB_CRANK], b = lk->length[FB_COUPLER];
  const double c = lk->length[FB_FOLLOWER], g = lk->length[FB_GROUND];
  const double tol = FB_GRASHOF_REL_TOL * (a + b + c + g);
  /* B on the ground line: |BD| = |g - a| at theta2 = 0, g + a at pi */
  const double bd[2] = {fabs(g - a), g + a}, th[2] = {0.0, M_PI};
  int n = 0;
  for (int k = 0; k < 2; k++)
    if (fabs(bd[k] - fabs(b - c)) <= tol || fabs(bd[k] - (b + c)) <= tol) out[n++] = th[k];
  return n;
}

void fb_linkage_grashof_text(char *out, size_t size, const fb_linkage *lk) {
  double sl, pq;
  int s, l;
  fb_linkage_grashof_sums(lk, &sl, &pq, &s, &l);
  const fb_grashof g = fb_linkage_grashof(lk);
  const double mm = 1e3;
  if (g == FB_GRASHOF_CHANGE_POINT) {
    double th[2];
    const int n = fb_linkage_fold_angles(lk, th);
    snprintf(out, size,
             "Grashof change-point: s + l = %.6g + %.6g = %.6g mm equals p + q: the links fold flat "
             "(all four pivots on one line) at crank angle %s%s, where it can switch between "
             "its open and crossed assemblies and the velocities are undefined",
             lk->length[s] * mm, lk->length[l] * mm, sl * mm,
             n == 0 ? "?" : th[0] == 0.0 ? "0 deg" : "180 deg", n == 2 ? " and 180 deg" : "");
    return;
  }
  static const char *const turns[] = {
      [FB_GRASHOF_CRANK_ROCKER] = "the crank, the shortest link, turns fully; the follower rocks",
      [FB_GRASHOF_DOUBLE_CRANK] = "the ground is the shortest link: crank and follower both turn "
                                  "fully",
      [FB_GRASHOF_DOUBLE_ROCKER] = "the coupler is the shortest link and turns fully; crank and "
                                   "follower rock",
      [FB_GRASHOF_ROCKER_CRANK] = "the follower is the shortest link and turns fully; the crank "
                                  "rocks",
      [FB_GRASHOF_NON_GRASHOF] = "no link turns fully (a triple rocker)"};
  snprintf(out, size, "%s%s: s + l = %.6g + %.6g = %.6g mm %s p + q = %.6g mm (margin %.4g mm): %s",
           g == FB_GRASHOF_NON_GRASHOF ? "" : "Grashof ", fb_grashof_name(g), lk->length[s] * mm,
           lk->length[l] * mm, sl * mm, sl < pq ? "<" : ">", pq * mm, (pq - sl) * mm, turns[g]);
}

fb_grashof fb_linkage_grashof(const fb_linkage *lk) {
  int s;
  double sl, pq, sum = 0.0;
  for (int i = 0; i < FB_LINK_COUNT; i++) sum += lk->length[i];
  fb_linkage_grashof_sums(lk, &sl, &pq, &s, NULL);
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

/* solves [[m11, m12], [m21, m22]] x = r */
static void solve2(const double m[2][2], const double r[2], double x[2]) {
  const double det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
  x[0] = (r[0] * m[1][1] - m[0][1] * r[1]) / det;
  x[1] = (m[0][0] * r[1] - m[1][0] * r[0]) / det;
}

fb_status fb_linkage_sensitivity(double out[4][FB_LINK_COUNT], const fb_linkage *lk,
                                 fb_branch branch, double theta2, double omega2, fb_diag *diag) {
  fb_linkage_state st;
  fb_status rc = fb_linkage_solve(&st, lk, branch, theta2, omega2, 0.0, diag);
  if (rc != FB_OK) return rc;
  const double b = lk->length[FB_COUPLER], c = lk->length[FB_FOLLOWER];
  const double s2 = sin(theta2), c2 = cos(theta2);
  const double s3 = sin(st.coupler_angle), c3 = cos(st.coupler_angle);
  const double s4 = sin(st.follower_angle), c4 = cos(st.follower_angle);
  const double w2 = omega2, w3 = st.coupler_omega, w4 = st.follower_omega;
  const double a3 = st.coupler_alpha, a4 = st.follower_alpha;
  /* J = d(loop)/d(theta3, theta4); J w = r and J alpha = q (see fb_linkage_solve) */
  const double J[2][2] = {{-b * s3, c * s4}, {b * c3, -c * c4}};
  /* explicit partials of the loop vector with respect to a, b, c, g */
  const double dphi[FB_LINK_COUNT][2] = {{c2, s2}, {c3, s3}, {-c4, -s4}, {-1.0, 0.0}};
  for (int k = 0; k < FB_LINK_COUNT; k++) {
    const double da = k == FB_CRANK, db = k == FB_COUPLER, dc = k == FB_FOLLOWER;
    double dth[2];
    const double mphi[2] = {-dphi[k][0], -dphi[k][1]};
    solve2(J, mphi, dth); /* d(theta3, theta4)/dL */
    /* dJ = explicit + via the angles */
    const double dJ[2][2] = {{-db * s3 - b * c3 * dth[0], dc * s4 + c * c4 * dth[1]},
                             {db * c3 - b * s3 * dth[0], -dc * c4 + c * s4 * dth[1]}};
    const double dr[2] = {da * s2 * w2, -da * c2 * w2};
    double rhs[2] = {dr[0] - (dJ[0][0] * w3 + dJ[0][1] * w4),
                     dr[1] - (dJ[1][0] * w3 + dJ[1][1] * w4)};
    double dw[2];
    solve2(J, rhs, dw);
    /* q = (a c2 w2^2 + b c3 w3^2 - c c4 w4^2, a s2 w2^2 + b s3 w3^2 - c s4 w4^2) */
    const double dq[2] = {
        da * c2 * w2 * w2 + db * c3 * w3 * w3 + b * (-s3 * dth[0] * w3 * w3 + 2.0 * c3 * w3 * dw[0]) -
            dc * c4 * w4 * w4 - c * (-s4 * dth[1] * w4 * w4 + 2.0 * c4 * w4 * dw[1]),
        da * s2 * w2 * w2 + db * s3 * w3 * w3 + b * (c3 * dth[0] * w3 * w3 + 2.0 * s3 * w3 * dw[0]) -
            dc * s4 * w4 * w4 - c * (c4 * dth[1] * w4 * w4 + 2.0 * s4 * w4 * dw[1])};
    rhs[0] = dq[0] - (dJ[0][0] * a3 + dJ[0][1] * a4);
    rhs[1] = dq[1] - (dJ[1][0] * a3 + dJ[1][1] * a4);
    double dal[2];
    solve2(J, rhs, dal);
    out[0][k] = dw[0];
    out[1][k] = dw[1];
    out[2][k] = dal[0];
    out[3][k] = dal[1];
  }
  return FB_OK;
}
