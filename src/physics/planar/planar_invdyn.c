/* Joint reactions and drive torque from the Lagrange multipliers
 * (planar_invdyn.h). */
#include "planar_invdyn.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "planar_path.h"

/* the force and moment about its centre that rows r, r + 1 with
 * multipliers lam put on body b: -(Phi_q rows, b's columns)^T lambda */
static void on_body(double f[3], const double *jac, int nq, int r, int b, const double *lam) {
  f[0] = f[1] = f[2] = 0.0;
  if (!b) return;
  for (int k = 0; k < 3; k++)
    for (int i = 0; i < 2; i++) f[k] -= jac[(r + i) * nq + 3 * (b - 1) + k] * lam[r + i];
}

/* Q - M q'' of m at the accelerations qdd into rhs (fb_planar_nq) */
static void applied_less_inertial(double *rhs, const fb_planar *m, const double *qdd,
                                  double gravity) {
  for (int b = 1; b < m->nbodies; b++) {
    const fb_planar_body *bb = &m->body[b];
    const int c = 3 * (b - 1);
    rhs[c] = -bb->mass * qdd[c];
    rhs[c + 1] = -bb->mass * gravity - bb->mass * qdd[c + 1];
    rhs[c + 2] = -bb->inertia * qdd[c + 2];
  }
}

/* every joint's reaction and the drive torque from the multipliers lam of
 * the Jacobian jac (n x n) at q; FB_ERR_ASSEMBLY when one is not finite */
static fb_status reactions_of(fb_planar_reaction *out, double *drive_torque, const fb_planar *m,
                              const double *q, const double *jac, const double *lam,
                              fb_diag *diag) {
  const int n = fb_planar_nq(m);
  for (int i = 0; i < n; i++)
    if (!isfinite(lam[i]))
      return fb_diag_set(diag, FB_ERR_ASSEMBLY, "inverse dynamics: the Jacobian is singular (a "
                         "locked position): the reactions are not determined there");
  for (int j = 0; j < m->njoints; j++) {
    const fb_planar_joint *jt_ = &m->joint[j];
    /* on body[1]; when that is the ground, minus what body[0] gets */
    const int on_second = jt_->body[1] != FB_PLANAR_GROUND;
    const int b = jt_->body[on_second ? 1 : 0];
    const double sign = on_second ? 1.0 : -1.0;
    double f[3];
    on_body(f, jac, n, 2 * j, b, lam);
    double pt[2];
    fb_planar_point(pt, m, q, b, jt_->point[on_second ? 1 : 0]);
    const double arm[2] = {pt[0] - q[3 * (b - 1)], pt[1] - q[3 * (b - 1) + 1]};
    out[j].force[0] = sign * f[0];
    out[j].force[1] = sign * f[1];
    out[j].moment = sign * (f[2] - (arm[0] * f[1] - arm[1] * f[0]));
  }
  /* the drive's row has +1 in the driven body's angle */
  if (drive_torque) *drive_torque = -lam[n - 1];
  return FB_OK;
}

/* FB_ERR_ARG unless m is driven and of one degree of freedom */
static fb_status invdyn_takes(const fb_planar *m, fb_diag *diag) {
  if (m->drive < 0 || fb_planar_gruebler(m) != 1)
    return fb_diag_set(diag, FB_ERR_ARG, "inverse dynamics needs a driven mechanism of one "
                       "degree of freedom");
  return FB_OK;
}

fb_status fb_planar_invdyn(fb_planar_reaction *out, double *drive_torque, const fb_planar *m,
                           const double *q, const double *qd, const double *qdd, double gravity,
                           fb_diag *diag) {
  (void)qd; /* the velocities enter through q'' alone */
  fb_status st = invdyn_takes(m, diag);
  if (st != FB_OK) return st;
  const int n = fb_planar_nq(m);
  double *jac = calloc((size_t)n * (size_t)n + 2 * (size_t)n, sizeof *jac);
  gsl_matrix *jt = gsl_matrix_alloc((size_t)n, (size_t)n);
  gsl_permutation *p = gsl_permutation_alloc((size_t)n);
  if (!jac || !jt || !p) {
    free(jac);
    if (jt) gsl_matrix_free(jt);
    if (p) gsl_permutation_free(p);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  }
  double *rhs = jac + n * n, *lam = rhs + n;
  const fb_planar_drive d = {0.0, 0.0, 0.0};
  fb_planar_constraints(NULL, jac, NULL, m, NULL, &d, q, NULL);
  for (int r = 0; r < n; r++)
    for (int c = 0; c < n; c++) gsl_matrix_set(jt, (size_t)c, (size_t)r, jac[r * n + c]);
  applied_less_inertial(rhs, m, qdd, gravity);
  int s;
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  gsl_linalg_LU_decomp(jt, p, &s);
  gsl_vector_view bv = gsl_vector_view_array(rhs, (size_t)n), xv = gsl_vector_view_array(lam, (size_t)n);
  const int rc = gsl_linalg_LU_solve(jt, p, &bv.vector, &xv.vector);
  gsl_set_error_handler(old);
  if (rc != GSL_SUCCESS) lam[0] = NAN; /* reactions_of's singular Jacobian */
  st = reactions_of(out, drive_torque, m, q, jac, lam, diag);
  free(jac);
  gsl_matrix_free(jt);
  gsl_permutation_free(p);
  return st;
}

fb_status fb_planar_invdyn_kin(fb_planar_reaction *out, double *drive_torque, fb_planar_kin *k,
                               const double *q, const double *qdd, double gravity, fb_diag *diag) {
  const fb_planar *m = fb_planar_kin_mech(k);
  const int n = fb_planar_nq(m);
  double *jac = calloc((size_t)n * (size_t)n + 2 * (size_t)n, sizeof *jac);
  if (!jac) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  double *rhs = jac + n * n, *lam = rhs + n;
  const fb_planar_drive d = {0.0, 0.0, 0.0};
  fb_planar_constraints(NULL, jac, NULL, m, NULL, &d, q, NULL);
  applied_less_inertial(rhs, m, qdd, gravity);
  fb_planar_kin_solve_transposed(k, rhs, lam);
  const fb_status st = reactions_of(out, drive_torque, m, q, jac, lam, diag);
  free(jac);
  return st;
}

fb_status fb_planar_reaction_max(double *most, const fb_planar *m, double omega, double gravity,
                                 fb_diag *diag) {
  const int nq = fb_planar_nq(m), nj = m->njoints;
  double *q = malloc((3 * (size_t)nq) * sizeof *q);
  fb_planar_reaction *r = malloc((size_t)nj * sizeof *r);
  fb_planar_kin *k = NULL;
  fb_status st = q && r ? fb_planar_kin_new(&k, m, diag)
                        : fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  double *qd = q + nq, *qdd = qd + nq;
  if (st == FB_OK) {
    fb_planar_assembly(m, q);
    st = fb_planar_position(k, q, 0.0, NULL, diag);
  }
  for (int j = 0; j < nj; j++) most[j] = 0.0;
  const double da = 2.0 * M_PI / FB_PLANAR_PEAK_SAMPLES;
  for (int i = 0; i < FB_PLANAR_PEAK_SAMPLES && st == FB_OK; i++) {
    fb_path_end end;
    if (i > 0) st = fb_planar_follow(k, q, (i - 1) * da, i * da, NULL, &end, diag);
    const fb_planar_drive d = {i * da, omega, 0.0};
    if (st == FB_OK) st = fb_planar_motion(k, qd, qdd, q, &d, NULL, diag);
    if (st == FB_OK) st = fb_planar_invdyn(r, NULL, m, q, qd, qdd, gravity, diag);
    for (int j = 0; j < nj && st == FB_OK; j++)
      most[j] = fmax(most[j], hypot(r[j].force[0], r[j].force[1]));
  }
  fb_planar_kin_free(k);
  free(q);
  free(r);
  return st;
}
