#include "invdyn.h"

#include <gsl/gsl_linalg.h>
#include <math.h>

fb_status fb_invdyn_solve(fb_reactions *out, const fb_linkage *lk, fb_branch branch,
                          const fb_link_mass link[3], double gravity, double theta2,
                          double omega2, fb_diag *diag) {
  fb_linkage_state s;
  fb_status st = fb_linkage_solve(&s, lk, branch, theta2, omega2, 0.0, diag);
  if (st != FB_OK) return st;
  const double A[2] = {0, 0}, D[2] = {lk->length[FB_GROUND], 0};
  const double *P[3] = {A, s.b, D}; /* first joint of each link */
  const double *Q[3] = {s.b, s.c, s.c};
  const double w[3] = {omega2, s.coupler_omega, s.follower_omega};
  const double al[3] = {0.0, s.coupler_alpha, s.follower_alpha};
  /* acceleration of each first joint: A and D fixed; B on the crank */
  double aP[3][2] = {{0, 0}, {-omega2 * omega2 * s.b[0], -omega2 * omega2 * s.b[1]}, {0, 0}};
  double G[3][2], aG[3][2];
  for (int i = 0; i < 3; i++) {
    double r[2] = {link[i].com_fraction * (Q[i][0] - P[i][0]),
                   link[i].com_fraction * (Q[i][1] - P[i][1])};
    G[i][0] = P[i][0] + r[0];
    G[i][1] = P[i][1] + r[1];
    /* a_G = a_P + alpha x r - omega^2 r */
    aG[i][0] = aP[i][0] - al[i] * r[1] - w[i] * w[i] * r[0];
    aG[i][1] = aP[i][1] + al[i] * r[0] - w[i] * w[i] * r[1];
  }
  /* unknowns x = [FAx FAy FBx FBy FCx FCy FDx FDy T]
   * crank:    FA - FB + m1 g = m1 aG1;  T + (A-G1) x FA - (B-G1) x FB = I1 al1
   * coupler:  FB - FC + m2 g = m2 aG2;  (B-G2) x FB - (C-G2) x FC = I2 al2
   * follower: FC + FD + m3 g = m3 aG3;  (C-G3) x FC + (D-G3) x FD = I3 al3 */
  double M[81] = {0}, rhs[9];
#define E(r, c) M[(r) * 9 + (c)]
  /* body b, joint j (0..3), sign: adds sign * F_j to body b's equations */
  struct {
    int b, j;
    double sign;
    const double *at;
  } terms[6] = {{0, 0, +1, A}, {0, 1, -1, s.b}, {1, 1, +1, s.b},
                {1, 2, -1, s.c}, {2, 2, +1, s.c}, {2, 3, +1, D}};
  for (int t = 0; t < 6; t++) {
    int b = terms[t].b, j = terms[t].j;
    double sg = terms[t].sign;
    double r[2] = {terms[t].at[0] - G[b][0], terms[t].at[1] - G[b][1]};
    E(3 * b + 0, 2 * j + 0) += sg;
    E(3 * b + 1, 2 * j + 1) += sg;
    /* r x F = r0 Fy - r1 Fx */
    E(3 * b + 2, 2 * j + 0) += -sg * r[1];
    E(3 * b + 2, 2 * j + 1) += sg * r[0];
  }
  E(2, 8) = 1.0; /* drive torque on the crank */
#undef E
  for (int b = 0; b < 3; b++) {
    rhs[3 * b + 0] = link[b].mass * aG[b][0];
    rhs[3 * b + 1] = link[b].mass * (aG[b][1] + gravity);
    rhs[3 * b + 2] = link[b].inertia * al[b];
  }
  gsl_matrix_view m = gsl_matrix_view_array(M, 9, 9);
  gsl_vector_view bv = gsl_vector_view_array(rhs, 9);
  double xs[9];
  gsl_vector_view xv = gsl_vector_view_array(xs, 9);
  gsl_permutation *perm = gsl_permutation_alloc(9);
  if (!perm) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  int sgn;
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  int rc = gsl_linalg_LU_decomp(&m.matrix, perm, &sgn);
  if (rc == GSL_SUCCESS) rc = gsl_linalg_LU_solve(&m.matrix, perm, &bv.vector, &xv.vector);
  gsl_set_error_handler(old);
  gsl_permutation_free(perm);
  if (rc != GSL_SUCCESS || !isfinite(xs[8]))
    return fb_diag_set(diag, FB_ERR_NUMERIC,
                       "inverse dynamics singular at crank angle %g deg", theta2 * 180.0 / M_PI);
  for (int j = 0; j < 4; j++) {
    out->force[j][0] = xs[2 * j];
    out->force[j][1] = xs[2 * j + 1];
  }
  out->drive_torque = xs[8];
  /* components in the frame of the link carrying each pin */
  const double ang[4] = {theta2, theta2, s.follower_angle, s.follower_angle};
  for (int j = 0; j < 4; j++) {
    double u[2] = {cos(ang[j]), sin(ang[j])};
    out->radial[j] = out->force[j][0] * u[0] + out->force[j][1] * u[1];
    out->tangential[j] = -out->force[j][0] * u[1] + out->force[j][1] * u[0];
  }
  return FB_OK;
}

fb_status fb_invdyn_peaks(double force_max[4], double tangential_max[4], const fb_linkage *lk,
                          fb_branch branch, const fb_link_mass link[3], double gravity,
                          double omega2, int n, fb_diag *diag) {
  double fm[4] = {0}, tm[4] = {0};
  for (int k = 0; k < n; k++) {
    fb_reactions r;
    fb_status st =
        fb_invdyn_solve(&r, lk, branch, link, gravity, 2.0 * M_PI * k / n, omega2, diag);
    if (st != FB_OK) return st;
    for (int j = 0; j < 4; j++) {
      fm[j] = fmax(fm[j], hypot(r.force[j][0], r.force[j][1]));
      tm[j] = fmax(tm[j], fabs(r.tangential[j]));
    }
  }
  for (int j = 0; j < 4; j++) {
    if (force_max) force_max[j] = fm[j];
    if (tangential_max) tangential_max[j] = tm[j];
  }
  return FB_OK;
}
