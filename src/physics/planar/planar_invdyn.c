/* Joint reactions and drive torque from the Lagrange multipliers
 * (planar_invdyn.h). */
#include "planar_invdyn.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "planar_loads.h"
#include "planar_path.h"

/* the force and moment about its centre that rows r, r + 1 with
 * multipliers lam put on body b: -(Phi_q rows, b's columns)^T lambda, from
 * the sparse Jacobian's values val, columns col and rows' starts rowptr */
static void on_body(double f[3], const double *val, const int *col, const int *rowptr, int r,
                    int b, const double *lam) {
  f[0] = f[1] = f[2] = 0.0;
  if (!b) return;
  for (int i = 0; i < 2; i++)
    for (int e = rowptr[r + i]; e < rowptr[r + i + 1]; e++)
      if (col[e] / 3 == b - 1) f[col[e] % 3] -= val[e] * lam[r + i];
}

/* Q - M q'' of m at q, qd and the accelerations qdd into rhs
 * (fb_planar_nq): gravity, springs and loads (planar_loads.h) less the
 * bodies' inertia */
static void applied_less_inertial(double *rhs, const fb_planar *m, const double *q,
                                  const double *qd, const double *qdd, double gravity) {
  fb_planar_applied(rhs, m, q, qd, gravity);
  for (int b = 1; b < m->nbodies; b++) {
    const fb_planar_body *bb = &m->body[b];
    const int c = 3 * (b - 1);
    rhs[c] -= bb->mass * qdd[c];
    rhs[c + 1] -= bb->mass * qdd[c + 1];
    rhs[c + 2] -= bb->inertia * qdd[c + 2];
  }
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
  fb_status st = invdyn_takes(m, diag);
  if (st != FB_OK) return st;
  fb_planar_kin *k;
  st = fb_planar_kin_new(&k, m, diag);
  if (st != FB_OK) return st;
  const fb_planar_drive d = {0.0, 0.0, 0.0};
  if (fb_planar_motion(k, NULL, NULL, q, &d, NULL, NULL) != FB_OK)
    st = fb_diag_set(diag, FB_ERR_ASSEMBLY, "inverse dynamics: the Jacobian is singular (a "
                     "locked position): the reactions are not determined there");
  if (st == FB_OK) st = fb_planar_invdyn_kin(out, drive_torque, k, q, qd, qdd, gravity, diag);
  fb_planar_kin_free(k);
  return st;
}

fb_status fb_planar_invdyn_kin(fb_planar_reaction *out, double *drive_torque, fb_planar_kin *k,
                               const double *q, const double *qd, const double *qdd,
                               double gravity, fb_diag *diag) {
  const fb_planar *m = fb_planar_kin_mech(k);
  const int n = fb_planar_nq(m);
  const int *col, *rowptr;
  double *rhs;
  const double *val = fb_planar_kin_jacobian(k, &col, &rowptr, &rhs);
  double *lam = rhs + n;
  applied_less_inertial(rhs, m, q, qd, qdd, gravity);
  fb_planar_kin_solve_transposed(k, rhs, lam);
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
    on_body(f, val, col, rowptr, 2 * j, b, lam);
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

fb_status fb_planar_reactions_over(fb_planar_reaction *out, int n, const fb_planar *m,
                                   double omega, double gravity, fb_diag *diag) {
  const int nq = fb_planar_nq(m), nj = m->njoints;
  double *q = malloc((3 * (size_t)nq) * sizeof *q);
  fb_planar_kin *k = NULL;
  fb_status st = q ? fb_planar_kin_new(&k, m, diag) : fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  double *qd = q + nq, *qdd = qd + nq;
  if (st == FB_OK) {
    fb_planar_assembly(m, q);
    st = fb_planar_position(k, q, 0.0, NULL, diag);
  }
  const double da = 2.0 * M_PI / n;
  for (int i = 0; i < n && st == FB_OK; i++) {
    fb_path_end end;
    if (i > 0) st = fb_planar_follow(k, q, (i - 1) * da, i * da, NULL, &end, diag);
    const fb_planar_drive d = {i * da, omega, 0.0};
    if (st == FB_OK) st = fb_planar_motion(k, qd, qdd, q, &d, NULL, diag);
    if (st == FB_OK)
      st = fb_planar_invdyn_kin(out + (size_t)i * nj, NULL, k, q, qd, qdd, gravity, diag);
  }
  fb_planar_kin_free(k);
  free(q);
  return st;
}

fb_status fb_planar_reaction_max(double *most, const fb_planar *m, double omega, double gravity,
                                 fb_diag *diag) {
  const int nj = m->njoints, n = FB_PLANAR_PEAK_SAMPLES;
  fb_planar_reaction *r = malloc((size_t)n * (size_t)nj * sizeof *r);
  fb_status st = r ? fb_planar_reactions_over(r, n, m, omega, gravity, diag)
                   : fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  for (int j = 0; j < nj; j++) most[j] = 0.0;
  for (size_t i = 0; i < (size_t)n * (size_t)nj && st == FB_OK; i++)
    most[i % (size_t)nj] = fmax(most[i % (size_t)nj], hypot(r[i].force[0], r[i].force[1]));
  free(r);
  return st;
}
