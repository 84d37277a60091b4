/* The constrained inverse mass: accelerations under forces, projection onto
 * the constraints, effective mass (planar_mass.h). */
#include "planar_mass.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "effective_mass.h"
#include "planar_kinematics.h"

struct fb_planar_cmass {
  const fb_planar *m;
  unsigned char *off; /* (njoints) */
  int nq, rows;
  int drive_row;      /* 1: the description's drive is a row of the set */
  double *minv;       /* (nq) diagonal of M^-1 */
  double *g;          /* rows x nq */
  double *s;          /* rows x rows: S, then its Cholesky factor */
  double *x, *z;      /* rows each */
  double *phi;        /* rows */
  double *jr;         /* 2 x nq */
  double *zt;         /* 2 x rows */
  int *nz, *nnz;      /* rows x nq: each row's nonzero columns of g, first nnz[row] */
  double *jc;         /* FB_PLANAR_CMASS_MAX_CONTACTS x nq: contact rows */
};

fb_status fb_planar_cmass_new(fb_planar_cmass **out, const fb_planar *m,
                              const unsigned char *off, fb_diag *diag) {
  *out = NULL;
  fb_planar_cmass *c = calloc(1, sizeof *c);
  if (!c) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  c->m = m;
  c->nq = fb_planar_nq(m);
  c->drive_row = m->drive >= 0; /* an undriven description has no drive row */
  c->rows = fb_planar_rows(m, off, c->drive_row);
  const size_t nq = (size_t)c->nq, rows = (size_t)c->rows;
  c->off = calloc((size_t)m->njoints, 1);
  c->minv = calloc(nq, sizeof *c->minv);
  c->g = calloc(rows * nq, sizeof *c->g);
  c->s = calloc(rows * rows, sizeof *c->s);
  c->x = calloc(rows, sizeof *c->x);
  c->z = calloc(rows, sizeof *c->z);
  c->phi = calloc(rows, sizeof *c->phi);
  c->jr = calloc(2 * nq, sizeof *c->jr);
  c->zt = calloc(2 * rows, sizeof *c->zt);
  c->nz = calloc(rows * nq + rows, sizeof *c->nz);
  c->nnz = c->nz ? c->nz + rows * nq : NULL;
  c->jc = calloc(FB_PLANAR_CMASS_MAX_CONTACTS * nq, sizeof *c->jc);
  if (!c->off || !c->minv || !c->g || !c->s || !c->x || !c->z || !c->phi || !c->jr || !c->zt ||
      !c->nz || !c->jc) {
    fb_planar_cmass_free(c);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for %zu constraint rows", rows);
  }
  if (off) memcpy(c->off, off, (size_t)m->njoints);
  for (int b = 1; b < m->nbodies; b++) {
    c->minv[3 * (b - 1)] = c->minv[3 * (b - 1) + 1] = 1.0 / m->body[b].mass;
    c->minv[3 * (b - 1) + 2] = 1.0 / m->body[b].inertia;
  }
  *out = c;
  return FB_OK;
}

void fb_planar_cmass_free(fb_planar_cmass *c) {
  if (!c) return;
  free(c->off);
  free(c->minv);
  free(c->g);
  free(c->s);
  free(c->x);
  free(c->z);
  free(c->phi);
  free(c->jr);
  free(c->zt);
  free(c->nz);
  free(c->jc);
  free(c);
}

int fb_planar_cmass_rows(const fb_planar_cmass *c) { return c->rows; }

fb_status fb_planar_cmass_factor(fb_planar_cmass *c, const double *q, double reg,
                                 fb_diag *diag) {
  const fb_planar_drive d = {0.0, 0.0, 0.0};
  fb_planar_constraints(NULL, c->g, NULL, c->m, c->off, c->drive_row ? &d : NULL, q, NULL);
  const int nq = c->nq, rows = c->rows;
  /* a row touches its joint's two bodies, 6 of the nq columns: S's sums
   * skip the others' exact zero products (the same sums, bit for bit;
   * the six-bar's right-hand side: this loop was 29 % of its time) */
  for (int a = 0; a < rows; a++) {
    int n = 0;
    for (int i = 0; i < nq; i++)
      if (c->g[a * nq + i] != 0.0) c->nz[a * nq + n++] = i;
    c->nnz[a] = n;
  }
  double smax = 0.0;
  for (int a = 0; a < rows; a++)
    for (int b = 0; b <= a; b++) {
      double v = 0.0;
      for (int k = 0; k < c->nnz[a]; k++) {
        const int i = c->nz[a * nq + k];
        v += c->g[a * nq + i] * c->minv[i] * c->g[b * nq + i];
      }
      c->s[a * rows + b] = c->s[b * rows + a] = v;
      if (a == b) smax = fmax(smax, v);
    }
  for (int a = 0; a < rows; a++) c->s[a * rows + a] += reg * smax;
  gsl_matrix_view sv = gsl_matrix_view_array(c->s, (size_t)rows, (size_t)rows);
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  const int rc = gsl_linalg_cholesky_decomp1(&sv.matrix);
  gsl_set_error_handler(old);
  if (rc != GSL_SUCCESS)
    return fb_diag_set(diag, FB_ERR_NUMERIC, "the constraints' G M^-1 G^T is not positive "
                       "definite at this position (a redundant or singular set: %s)",
                       gsl_strerror(rc));
  return FB_OK;
}

/* x = S^-1 x in place */
static void s_solve(fb_planar_cmass *c, double *x) {
  gsl_matrix_view sv = gsl_matrix_view_array(c->s, (size_t)c->rows, (size_t)c->rows);
  gsl_vector_view xv = gsl_vector_view_array(x, (size_t)c->rows);
  gsl_linalg_cholesky_svx(&sv.matrix, &xv.vector);
}

/* out (nq) = M^-1 (f - G^T x), f may be NULL (zero) */
static void back(const fb_planar_cmass *c, double *out, const double *f, const double *x) {
  for (int i = 0; i < c->nq; i++) {
    double v = f ? f[i] : 0.0;
    for (int a = 0; a < c->rows; a++) v -= c->g[a * c->nq + i] * x[a];
    out[i] = c->minv[i] * v;
  }
}

void fb_planar_cmass_accel(fb_planar_cmass *c, double *qdd, double *lambda, const double *force,
                           const double *gamma) {
  for (int a = 0; a < c->rows; a++) {
    double v = -gamma[a];
    for (int i = 0; i < c->nq; i++) v += c->g[a * c->nq + i] * c->minv[i] * force[i];
    c->x[a] = v;
  }
  s_solve(c, c->x);
  back(c, qdd, force, c->x);
  if (lambda) memcpy(lambda, c->x, (size_t)c->rows * sizeof *lambda);
}

void fb_planar_cmass_tensor(fb_planar_cmass *c, double w[2][2], int j, const double *q) {
  const fb_planar_joint *jt = &c->m->joint[j];
  fb_planar_cmass_tensor_points(c, w, jt->body[0], jt->point[0], jt->body[1], jt->point[1], q);
}

void fb_planar_cmass_tensor_points(fb_planar_cmass *c, double w[2][2], int b0, const double s0[2],
                                   int b1, const double s1[2], const double *q) {
  const int nq = c->nq, rows = c->rows;
  memset(c->jr, 0, 2 * (size_t)nq * sizeof *c->jr);
  fb_planar_point_jacobian(c->jr, c->m, q, b0, s0, 1.0);
  fb_planar_point_jacobian(c->jr, c->m, q, b1, s1, -1.0);
  for (int r = 0; r < 2; r++) {
    double *z = c->zt + r * rows;
    for (int a = 0; a < rows; a++) {
      double v = 0.0;
      for (int i = 0; i < nq; i++) v += c->g[a * nq + i] * c->minv[i] * c->jr[r * nq + i];
      z[a] = v;
    }
  }
  for (int r = 0; r < 2; r++) {
    memcpy(c->x, c->zt + r * rows, (size_t)rows * sizeof *c->x);
    s_solve(c, c->x);
    for (int k = 0; k < 2; k++) {
      double v = 0.0;
      for (int i = 0; i < nq; i++) v += c->jr[r * nq + i] * c->minv[i] * c->jr[k * nq + i];
      for (int a = 0; a < rows; a++) v -= c->zt[k * rows + a] * c->x[a];
      w[r][k] = v;
    }
  }
  /* symmetric by construction; average the rounding away */
  const double off = 0.5 * (w[0][1] + w[1][0]);
  w[0][1] = w[1][0] = off;
}

/* largest |v| of the rows that are lengths (angle rows: a prismatic joint's
 * first, the drive's) */
static double length_rows_max(const fb_planar_cmass *c, const double *v) {
  double big = 0.0;
  int r = 0;
  for (int j = 0; j < c->m->njoints; j++) {
    if (c->off[j]) continue;
    const int prism = c->m->joint[j].kind == FB_KIND_PRISMATIC;
    big = fmax(big, fmax(prism ? 0.0 : fabs(v[r]), fabs(v[r + 1])));
    r += 2;
  }
  return big;
}

fb_status fb_planar_cmass_project(fb_planar_cmass *c, double *q, double *qd,
                                  const fb_planar_drive *d, double *dq_max, double *dv_max,
                                  fb_diag *diag) {
  const int nq = c->nq, rows = c->rows;
  const double size = fb_planar_size(c->m);
  double *dq = c->jr; /* (2 nq of scratch) */
  for (int it = 0; it < 4; it++) {
    fb_planar_constraints(c->phi, NULL, NULL, c->m, c->off, c->drive_row ? d : NULL, q, NULL);
    if (it == 0 && dq_max) *dq_max = length_rows_max(c, c->phi);
    fb_status rc = fb_planar_cmass_factor(c, q, 0.0, diag);
    if (rc != FB_OK) return rc;
    memcpy(c->x, c->phi, (size_t)rows * sizeof *c->x);
    s_solve(c, c->x);
    back(c, dq, NULL, c->x);
    double big = 0.0;
    for (int i = 0; i < nq; i++) {
      q[i] += dq[i];
      big = fmax(big, fabs(dq[i]) / (i % 3 == 2 ? 1.0 : size));
    }
    if (big <= FB_PLANAR_NEWTON_STOP) break;
  }
  fb_status rc = fb_planar_cmass_factor(c, q, 0.0, diag);
  if (rc != FB_OK) return rc;
  for (int a = 0; a < rows; a++) {
    double v = c->drive_row && a == rows - 1 ? -d->omega : 0.0;
    for (int i = 0; i < nq; i++) v += c->g[a * nq + i] * qd[i];
    c->x[a] = v;
  }
  if (dv_max) *dv_max = length_rows_max(c, c->x);
  s_solve(c, c->x);
  back(c, dq, NULL, c->x);
  for (int i = 0; i < nq; i++) qd[i] += dq[i];
  return FB_OK;
}

fb_status fb_planar_effective_mass_tensor(double w[2][2], const fb_planar *m, const double *q,
                                          const unsigned char *off, int j, fb_diag *diag) {
  if (j < 0 || j >= m->njoints || !off || !off[j])
    return fb_diag_set(diag, FB_ERR_ARG, "effective mass at joint %d: it must be one of the "
                       "joints left out of the set (a clearance joint)", j);
  fb_planar_cmass *c;
  fb_status rc = fb_planar_cmass_new(&c, m, off, diag);
  if (rc != FB_OK) return rc;
  rc = fb_planar_cmass_factor(c, q, FB_EFFECTIVE_MASS_REG, diag);
  if (rc == FB_OK) fb_planar_cmass_tensor(c, w, j, q);
  fb_planar_cmass_free(c);
  return rc;
}

void fb_planar_cmass_delassus(fb_planar_cmass *c, double *d, int k, const int *b0,
                              const double (*s0)[2], const int *b1, const double (*s1)[2],
                              const double (*n)[2], const double *q) {
  const int nq = c->nq, rows = c->rows;
  /* row r: n_r^T (J(b0_r, s0_r) - J(b1_r, s1_r)) */
  for (int r = 0; r < k; r++) {
    memset(c->jr, 0, 2 * (size_t)nq * sizeof *c->jr);
    fb_planar_point_jacobian(c->jr, c->m, q, b0[r], s0[r], 1.0);
    fb_planar_point_jacobian(c->jr, c->m, q, b1[r], s1[r], -1.0);
    for (int i = 0; i < nq; i++) c->jc[r * nq + i] = n[r][0] * c->jr[i] + n[r][1] * c->jr[nq + i];
  }
  /* D = J M^-1 J^T - (G M^-1 J^T)^T S^-1 (G M^-1 J^T) */
  for (int r = 0; r < k; r++) {
    for (int a = 0; a < rows; a++) {
      double v = 0.0;
      for (int i = 0; i < nq; i++) v += c->g[a * nq + i] * c->minv[i] * c->jc[r * nq + i];
      c->x[a] = v;
    }
    s_solve(c, c->x);
    for (int l = 0; l < k; l++) {
      double v = 0.0;
      for (int i = 0; i < nq; i++) v += c->jc[r * nq + i] * c->minv[i] * c->jc[l * nq + i];
      for (int a = 0; a < rows; a++) {
        double z = 0.0;
        for (int i = 0; i < nq; i++) z += c->g[a * nq + i] * c->minv[i] * c->jc[l * nq + i];
        v -= z * c->x[a];
      }
      d[r * k + l] = v;
    }
  }
}

double fb_planar_joint_law_mass(const fb_planar *m, int j) {
  const double a = m->body[m->joint[j].body[0]].mass, b = m->body[m->joint[j].body[1]].mass;
  return a > 0.0 && b > 0.0 ? a * b / (a + b) : fmax(a, b);
}
