#include "effective_mass.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <math.h>
#include <string.h>

#define NQ 9   /* planar coordinates of three bodies */
#define NG_MAX 9 /* 4 hinges x 2 + the drive */

/* bodies of each joint: pin (first), hole (second); -1 is ground */
static const int joint_body[4][2] = {{0, -1}, {0, 1}, {1, 2}, {2, -1}};

void fb_mechanism_from_state(fb_mechanism *out, const fb_linkage *lengths,
                             const fb_linkage_state *st, const fb_link_mass link[3],
                             int clearance_mask) {
  memset(out, 0, sizeof *out);
  const double a[2] = {0.0, 0.0}, d[2] = {lengths->length[FB_GROUND], 0.0};
  const double *from[3] = {a, st->b, d}, *to[3] = {st->b, st->c, st->c};
  for (int i = 0; i < 3; i++) {
    out->mass[i] = link[i].mass;
    out->inertia[i] = link[i].inertia;
    for (int q = 0; q < 2; q++)
      out->com[i][q] = from[i][q] + link[i].com_fraction * (to[i][q] - from[i][q]);
  }
  for (int q = 0; q < 2; q++) {
    out->joint[0][q] = a[q];
    out->joint[1][q] = st->b[q];
    out->joint[2][q] = st->c[q];
    out->joint[3][q] = d[q];
  }
  out->clearance_mask = clearance_mask;
  out->crank_driven = 1;
}

void fb_mechanism_from_slider_crank(fb_mechanism *out, const fb_slider_crank_state *st,
                                    const fb_link_mass link[3], int clearance_mask) {
  memset(out, 0, sizeof *out);
  const double a[2] = {0.0, 0.0};
  const double *from[3] = {a, st->b, st->c}, *to[3] = {st->b, st->c, st->c};
  for (int i = 0; i < 3; i++) {
    out->mass[i] = link[i].mass;
    out->inertia[i] = link[i].inertia;
    const double f = i == 2 ? 0.0 : link[i].com_fraction; /* the slider's centre: the pin */
    for (int q = 0; q < 2; q++) out->com[i][q] = from[i][q] + f * (to[i][q] - from[i][q]);
  }
  for (int q = 0; q < 2; q++) {
    out->joint[0][q] = a[q];
    out->joint[1][q] = st->b[q];
    out->joint[2][q] = st->c[q];
    out->joint[3][q] = st->c[q];
  }
  out->clearance_mask = clearance_mask;
  out->prismatic_mask = 1 << FB_JOINT_D;
  out->crank_driven = 1;
}

/* adds the velocity rows of point p on body i (sign s) to rows r, r + 1 */
static void point_rows(double rows[][NQ], int r, const fb_mechanism *m, int i, const double p[2],
                       double s) {
  if (i < 0) return;
  rows[r][3 * i + 0] += s;
  rows[r][3 * i + 2] += -s * (p[1] - m->com[i][1]);
  rows[r + 1][3 * i + 1] += s;
  rows[r + 1][3 * i + 2] += s * (p[0] - m->com[i][0]);
}

/* the paper's case: a driven crank and one clearance joint, B (crank pin in
 * the coupler's hole). The crank is then held (the drive and hinge A) and
 * what moves is the coupler-follower chain hinged at C and D: coordinates
 * (omega_follower, omega_coupler), generalised mass M (2 x 2) from the
 * kinetic energy, T = 1/2 I_D w4^2 + 1/2 m3 |w4 perp(a) + w3 perp(r3)|^2
 * + 1/2 I3 w3^2 with a = C - D, r3 = com3 - C, I_D the follower's inertia
 * about D; the hole point p on the coupler moves at v = J (w4, w3)^T with
 * J = [perp(a), perp(p - C)] (2 x 2), and W = J M^-1 J^T. The same tensor
 * as the general KKT form (test_effective_mass cross-checks them); no
 * factorisation, about 60 flops. */
static void tensor_crank_pin(double w[2][2], const fb_mechanism *m) {
  const double *c = m->joint[FB_JOINT_C], *d = m->joint[FB_JOINT_D], *p = m->joint[FB_JOINT_B];
  const double a[2] = {c[0] - d[0], c[1] - d[1]};
  const double r3[2] = {m->com[FB_COUPLER][0] - c[0], m->com[FB_COUPLER][1] - c[1]};
  const double r4[2] = {m->com[FB_FOLLOWER][0] - d[0], m->com[FB_FOLLOWER][1] - d[1]};
  const double m3 = m->mass[FB_COUPLER], m4 = m->mass[FB_FOLLOWER];
  const double m11 = m->inertia[FB_FOLLOWER] + m4 * (r4[0] * r4[0] + r4[1] * r4[1]) +
                     m3 * (a[0] * a[0] + a[1] * a[1]);
  const double m12 = m3 * (a[0] * r3[0] + a[1] * r3[1]);
  const double m22 = m->inertia[FB_COUPLER] + m3 * (r3[0] * r3[0] + r3[1] * r3[1]);
  const double det = m11 * m22 - m12 * m12;
  /* M^-1 */
  const double i11 = m22 / det, i12 = -m12 / det, i22 = m11 / det;
  /* columns of J: perp(a) for w4, perp(p - C) for w3 */
  const double j0[2] = {-a[1], a[0]}, j1[2] = {-(p[1] - c[1]), p[0] - c[0]};
  for (int r = 0; r < 2; r++)
    for (int q = 0; q < 2; q++)
      w[r][q] = j0[r] * (i11 * j0[q] + i12 * j1[q]) + j1[r] * (i12 * j0[q] + i22 * j1[q]);
  const double off = 0.5 * (w[0][1] + w[1][0]);
  w[0][1] = w[1][0] = off;
}

/* the slider-crank's piston pin C with the crank driven (A and B held):
 * the rod turns about B and the slider slides along x, two coordinates
 * (omega_rod, v_slider) with no inertial coupling, generalised masses
 * I_B = I3 + m3 |G3 - B|^2 and m_slider; the pin point on the rod moves at
 * omega_rod perp(C - B), the hole on the slider at (v_slider, 0), so
 * W = p p^T / I_B + x x^T / m_slider with p = perp(C - B), x = (1, 0):
 * the mass matrix of slider_crank_dynamics.h's minimal coordinates, and the
 * general KKT form's (test_effective_mass cross-checks them) */
static void tensor_piston_pin(double w[2][2], const fb_mechanism *m) {
  const double *b = m->joint[FB_JOINT_B], *c = m->joint[FB_JOINT_C];
  const double g[2] = {m->com[FB_COUPLER][0] - b[0], m->com[FB_COUPLER][1] - b[1]};
  const double i_b = m->inertia[FB_COUPLER] + m->mass[FB_COUPLER] * (g[0] * g[0] + g[1] * g[1]);
  const double p[2] = {-(c[1] - b[1]), c[0] - b[0]};
  w[0][0] = p[0] * p[0] / i_b + 1.0 / m->mass[2];
  w[0][1] = w[1][0] = p[0] * p[1] / i_b;
  w[1][1] = p[1] * p[1] / i_b;
}

static fb_status check_inertia(const fb_mechanism *m, fb_diag *diag) {
  for (int i = 0; i < 3; i++)
    if (!(m->mass[i] > 0.0) || !(m->inertia[i] > 0.0) || !isfinite(m->mass[i]) ||
        !isfinite(m->inertia[i]))
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "body %d: mass %g kg, inertia %g kg m^2: both must be positive and "
                         "finite",
                         i, m->mass[i], m->inertia[i]);
  return FB_OK;
}

fb_status fb_effective_mass_tensor(double w[4][2][2], const fb_mechanism *m, fb_diag *diag) {
  if (m->crank_driven && m->prismatic_mask == (1 << FB_JOINT_D) &&
      m->clearance_mask == (1 << FB_JOINT_C)) {
    fb_status st = check_inertia(m, diag);
    if (st != FB_OK) return st;
    memset(w, 0, 4 * sizeof w[0]);
    tensor_piston_pin(w[FB_JOINT_C], m);
    return FB_OK;
  }
  if (m->crank_driven && !m->prismatic_mask && m->clearance_mask == (1 << FB_JOINT_B)) {
    fb_status st = check_inertia(m, diag);
    if (st != FB_OK) return st;
    memset(w, 0, 4 * sizeof w[0]);
    tensor_crank_pin(w[FB_JOINT_B], m);
    /* a chain at its dead point (C on the line D-B with no inertia to spare)
     * leaves M singular: the general form regularises it */
    if (isfinite(w[FB_JOINT_B][0][0]) && isfinite(w[FB_JOINT_B][1][1])) return FB_OK;
  }
  return fb_effective_mass_tensor_kkt(w, m, diag);
}

fb_status fb_effective_mass_tensor_kkt(double w[4][2][2], const fb_mechanism *m, fb_diag *diag) {
  fb_status st = check_inertia(m, diag);
  if (st != FB_OK) return st;
  double minv[NQ];
  for (int i = 0; i < 3; i++) {
    minv[3 * i] = minv[3 * i + 1] = 1.0 / m->mass[i];
    minv[3 * i + 2] = 1.0 / m->inertia[i];
  }
  /* constraint rows G (ng x 9) */
  double g[NG_MAX][NQ];
  memset(g, 0, sizeof g);
  int ng = 0;
  for (int j = 0; j < 4; j++) {
    if (m->clearance_mask & (1 << j)) continue;
    if (m->prismatic_mask & (1 << j)) { /* a guide along the ground's x: v_y = 0, omega = 0 */
      g[ng][3 * joint_body[j][0] + 1] = 1.0;
      g[ng + 1][3 * joint_body[j][0] + 2] = 1.0;
    } else {
      point_rows(g, ng, m, joint_body[j][0], m->joint[j], 1.0);
      point_rows(g, ng, m, joint_body[j][1], m->joint[j], -1.0);
    }
    ng += 2;
  }
  if (m->crank_driven) g[ng++][2] = 1.0;
  /* S = G M^-1 G^T, regularised, factorised once */
  double s[NG_MAX * NG_MAX];
  double smax = 0.0;
  for (int a = 0; a < ng; a++)
    for (int b = 0; b < ng; b++) {
      double v = 0.0;
      for (int q = 0; q < NQ; q++) v += g[a][q] * minv[q] * g[b][q];
      s[a * ng + b] = v;
      if (a == b && v > smax) smax = v;
    }
  for (int a = 0; a < ng; a++) s[a * ng + a] += FB_EFFECTIVE_MASS_REG * smax;
  gsl_matrix_view sv = gsl_matrix_view_array(s, (size_t)(ng > 0 ? ng : 1), (size_t)(ng > 0 ? ng : 1));
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  int rc = ng > 0 ? gsl_linalg_cholesky_decomp1(&sv.matrix) : GSL_SUCCESS;
  gsl_set_error_handler(old);
  if (rc != GSL_SUCCESS)
    return fb_diag_set(diag, FB_ERR_NUMERIC,
                       "effective mass: the constraint matrix is not positive definite (%s)",
                       gsl_strerror(rc));
  for (int j = 0; j < 4; j++) {
    w[j][0][0] = w[j][0][1] = w[j][1][0] = w[j][1][1] = 0.0;
    if (!(m->clearance_mask & (1 << j))) continue;
    /* J (2 x 9): pin point velocity minus hole point velocity */
    double jr[2][NQ];
    memset(jr, 0, sizeof jr);
    point_rows(jr, 0, m, joint_body[j][0], m->joint[j], 1.0);
    point_rows(jr, 0, m, joint_body[j][1], m->joint[j], -1.0);
    /* W = J M^-1 J^T - (G M^-1 J^T)^T S^-1 (G M^-1 J^T) */
    double z[2][NG_MAX], x[2][NG_MAX];
    for (int c = 0; c < 2; c++) {
      for (int a = 0; a < ng; a++) {
        double v = 0.0;
        for (int q = 0; q < NQ; q++) v += g[a][q] * minv[q] * jr[c][q];
        z[c][a] = x[c][a] = v;
      }
      if (ng > 0) {
        gsl_vector_view xv = gsl_vector_view_array(x[c], (size_t)ng);
        gsl_linalg_cholesky_svx(&sv.matrix, &xv.vector);
      }
    }
    for (int r = 0; r < 2; r++)
      for (int c = 0; c < 2; c++) {
        double v = 0.0;
        for (int q = 0; q < NQ; q++) v += jr[r][q] * minv[q] * jr[c][q];
        for (int a = 0; a < ng; a++) v -= z[r][a] * x[c][a];
        w[j][r][c] = v;
      }
    /* symmetric by construction; average the rounding away */
    const double off = 0.5 * (w[j][0][1] + w[j][1][0]);
    w[j][0][1] = w[j][1][0] = off;
  }
  return FB_OK;
}

double fb_effective_mass_along(double w[2][2], const double n[2]) {
  const double q = n[0] * (w[0][0] * n[0] + w[0][1] * n[1]) + n[1] * (w[1][0] * n[0] + w[1][1] * n[1]);
  return q > 0.0 ? 1.0 / q : INFINITY;
}

void fb_effective_mass_range(double w[2][2], double *m_min, double *m_max) {
  const double tr = w[0][0] + w[1][1];
  const double det = w[0][0] * w[1][1] - w[0][1] * w[1][0];
  const double half = 0.5 * tr, disc = sqrt(fmax(half * half - det, 0.0));
  const double lmax = half + disc;
  const double lmin = lmax > 0.0 ? det / lmax : 0.0; /* no cancellation */
  *m_min = lmax > 0.0 ? 1.0 / lmax : INFINITY;
  *m_max = lmin > 0.0 ? 1.0 / lmin : INFINITY;
}
