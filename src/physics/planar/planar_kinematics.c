/* Newton position analysis, velocity and acceleration analysis
 * (planar_kinematics.h). */
#include "planar_kinematics.h"

#include <gsl/gsl_blas.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_permute_vector.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

struct fb_planar_kin {
  const fb_planar *m;
  int n;                  /* coordinates = rows */
  double size;            /* fb_planar_size [m] */
  double *jac;            /* n x n */
  double *phi, *rhs, *x;  /* n each */
  gsl_permutation *perm;
};

fb_status fb_planar_kin_new(fb_planar_kin **out, const fb_planar *m, fb_diag *diag) {
  *out = NULL;
  if (m->drive < 0)
    return fb_diag_set(diag, FB_ERR_ARG, "the mechanism has no drive: name its driven joint "
                       "([drive] joint)");
  const int f = fb_planar_gruebler(m);
  if (f != 1)
    return fb_diag_set(diag, FB_ERR_ARG,
                       "the mechanism has %d degrees of freedom by the Gruebler-Kutzbach count "
                       "3 (n - 1) - 2 j = 3 x %d - 2 x %d; one drive moves a mechanism of 1",
                       f, m->nbodies - 1, m->njoints);
  fb_planar_kin *k = calloc(1, sizeof *k);
  const int n = fb_planar_nq(m);
  if (k) {
    k->m = m;
    k->n = n;
    k->size = fb_planar_size(m);
    k->jac = calloc((size_t)n * (size_t)n, sizeof *k->jac);
    k->phi = calloc((size_t)n, sizeof *k->phi);
    k->rhs = calloc((size_t)n, sizeof *k->rhs);
    k->x = calloc((size_t)n, sizeof *k->x);
    k->perm = gsl_permutation_alloc((size_t)n);
  }
  if (!k || !k->jac || !k->phi || !k->rhs || !k->x || !k->perm) {
    fb_planar_kin_free(k);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the kinematics of %d coordinates",
                       n);
  }
  *out = k;
  return FB_OK;
}

void fb_planar_kin_free(fb_planar_kin *k) {
  if (!k) return;
  free(k->jac);
  free(k->phi);
  free(k->rhs);
  free(k->x);
  if (k->perm) gsl_permutation_free(k->perm);
  free(k);
}

/* 1 when row i of the full set (every joint, then the drive) is an angle:
 * the drive's and a prismatic joint's first */
static int row_is_angle(const fb_planar_kin *k, int i) {
  return i == k->n - 1 || (i % 2 == 0 && k->m->joint[i / 2].kind == FB_KIND_PRISMATIC);
}

const fb_planar *fb_planar_kin_mech(const fb_planar_kin *k) { return k->m; }

/* largest |v_i| with lengths divided by the size: of coordinates (coords =
 * 1: x, y are lengths, theta an angle) or of rows */
static double scaled_norm(const fb_planar_kin *k, const double *v, int coords) {
  double big = 0.0;
  for (int i = 0; i < k->n; i++) {
    const int angle = coords ? i % 3 == 2 : row_is_angle(k, i);
    big = fmax(big, fabs(v[i]) / (angle ? 1.0 : k->size));
  }
  return big;
}

/* factorises the Jacobian at q (held in k->jac); 0 when singular */
static int factorise(fb_planar_kin *k, int *sign) {
  gsl_matrix_view a = gsl_matrix_view_array(k->jac, (size_t)k->n, (size_t)k->n);
  int s = 0;
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  const int rc = gsl_linalg_LU_decomp(&a.matrix, k->perm, &s);
  gsl_set_error_handler(old);
  if (rc != GSL_SUCCESS) return 0;
  for (int i = 0; i < k->n; i++)
    if (!(fabs(k->jac[i * k->n + i]) > 0.0) || !isfinite(k->jac[i * k->n + i])) return 0;
  if (sign) *sign = gsl_linalg_LU_sgndet(&a.matrix, s) < 0 ? -1 : 1;
  return 1;
}

/* x = J^-1 rhs with the factorised Jacobian */
static void solve(fb_planar_kin *k, const double *rhs, double *x) {
  gsl_matrix_view a = gsl_matrix_view_array(k->jac, (size_t)k->n, (size_t)k->n);
  gsl_vector_const_view b = gsl_vector_const_view_array(rhs, (size_t)k->n);
  gsl_vector_view xv = gsl_vector_view_array(x, (size_t)k->n);
  gsl_linalg_LU_solve(&a.matrix, k->perm, &b.vector, &xv.vector);
}

void fb_planar_kin_solve_transposed(fb_planar_kin *k, const double *rhs, double *x) {
  gsl_matrix_view a = gsl_matrix_view_array(k->jac, (size_t)k->n, (size_t)k->n);
  gsl_vector_view xv = gsl_vector_view_array(x, (size_t)k->n);
  memcpy(x, rhs, (size_t)k->n * sizeof *x);
  gsl_blas_dtrsv(CblasUpper, CblasTrans, CblasNonUnit, &a.matrix, &xv.vector); /* U^T y = rhs */
  gsl_blas_dtrsv(CblasLower, CblasTrans, CblasUnit, &a.matrix, &xv.vector);    /* L^T z = y */
  gsl_permute_vector_inverse(k->perm, &xv.vector);                              /* P x = z */
}

int fb_planar_worst_joint(fb_planar_kin *k, const double *q, double angle, double *residual) {
  const fb_planar_drive d = {angle, 0.0, 0.0};
  fb_planar_constraints(k->phi, NULL, NULL, k->m, NULL, &d, q, NULL);
  int worst = -1;
  double big = fabs(k->phi[k->n - 1]);
  for (int j = 0; j < k->m->njoints; j++) {
    const int prism = k->m->joint[j].kind == FB_KIND_PRISMATIC;
    /* a prismatic joint's first row is an angle */
    const double r = prism ? fmax(fabs(k->phi[2 * j]), fabs(k->phi[2 * j + 1]) / k->size)
                           : hypot(k->phi[2 * j], k->phi[2 * j + 1]) / k->size;
    if (r > big) {
      big = r;
      worst = j;
    }
  }
  if (residual) *residual = worst >= 0 && k->m->joint[worst].kind == FB_KIND_REVOLUTE
                                ? big * k->size
                                : big;
  return worst;
}

static fb_status not_closed(fb_planar_kin *k, const double *q, double angle, const char *why,
                            fb_diag *diag) {
  double r;
  const int j = fb_planar_worst_joint(k, q, angle, &r);
  if (j < 0)
    return fb_diag_set(diag, FB_ERR_ASSEMBLY, "the loop equations have no solution at drive "
                       "angle %.6g deg from the assembly configuration (%s)", angle * 180.0 / M_PI,
                       why);
  const int rev = k->m->joint[j].kind == FB_KIND_REVOLUTE;
  return fb_diag_set(diag, FB_ERR_ASSEMBLY,
                     "the loop equations have no solution at drive angle %.6g deg from the "
                     "assembly configuration (%s): joint '%s' stays %.3g %s apart", angle * 180.0 / M_PI,
                     why, k->m->joint[j].name, rev ? r * 1e3 : r, rev ? "mm" : "(scaled)");
}

fb_status fb_planar_position(fb_planar_kin *k, double *q, double angle, int *iterations,
                             fb_diag *diag) {
  const fb_planar_drive d = {angle, 0.0, 0.0};
  int it = 0, last = 0;
  for (; it < FB_PLANAR_NEWTON_MAX && !last; it++) {
    fb_planar_constraints(k->phi, k->jac, NULL, k->m, NULL, &d, q, NULL);
    if (!(scaled_norm(k, k->phi, 0) < 1e3)) break; /* diverged (or not finite) */
    if (!factorise(k, NULL)) {
      if (iterations) *iterations = it;
      return not_closed(k, q, angle, "singular Jacobian", diag);
    }
    for (int i = 0; i < k->n; i++) k->rhs[i] = -k->phi[i];
    solve(k, k->rhs, k->x);
    for (int i = 0; i < k->n; i++) q[i] += k->x[i];
    last = scaled_norm(k, k->x, 1) <= FB_PLANAR_NEWTON_STOP;
  }
  if (iterations) *iterations = it;
  fb_planar_constraints(k->phi, NULL, NULL, k->m, NULL, &d, q, NULL);
  int finite = 1;
  for (int i = 0; i < k->n; i++) finite &= isfinite(q[i]) != 0;
  if (!finite) return not_closed(k, q, angle, "Newton diverged", diag);
  if (!last) return not_closed(k, q, angle, "Newton did not converge", diag);
  if (!(scaled_norm(k, k->phi, 0) <= FB_PLANAR_CLOSE_TOL))
    return not_closed(k, q, angle, "residual above the closing tolerance", diag);
  return FB_OK;
}

fb_status fb_planar_motion(fb_planar_kin *k, double *qd, double *qdd, const double *q,
                           const fb_planar_drive *d, int *sign, fb_diag *diag) {
  fb_planar_constraints(NULL, k->jac, NULL, k->m, NULL, d, q, NULL);
  if (!factorise(k, sign))
    return fb_diag_set(diag, FB_ERR_ASSEMBLY, "the Jacobian is singular: the mechanism is at a "
                       "locked or change-point position, where its velocities are undefined");
  double *v = qd ? qd : k->x;
  memset(k->rhs, 0, (size_t)k->n * sizeof *k->rhs);
  k->rhs[k->n - 1] = d->omega;
  solve(k, k->rhs, v);
  if (qdd) {
    fb_planar_constraints(NULL, NULL, k->rhs, k->m, NULL, d, q, v);
    solve(k, k->rhs, qdd);
  }
  return FB_OK;
}
