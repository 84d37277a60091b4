/* The free start of an undriven description (planar_start.h). */
#include "planar_start.h"

#include <gsl/gsl_linalg.h>
#include <math.h>
#include <stdlib.h>

#include "planar_constraints.h"

/* singular values below this fraction of the largest count as zero: the
 * joints leave that combination of linear rates free */
#define RANK_TOL 1e-12

/* x (cols) = least-squares minimum-norm solution of a (rows x cols) x = b */
static int least_squares(double *x, const double *a, const double *b, int rows, int cols) {
  const int n = rows > cols ? rows : cols;
  gsl_matrix *u = gsl_matrix_calloc((size_t)n, (size_t)cols);
  gsl_matrix *v = gsl_matrix_alloc((size_t)cols, (size_t)cols);
  gsl_vector *s = gsl_vector_alloc((size_t)cols), *work = gsl_vector_alloc((size_t)cols);
  int ok = u && v && s && work;
  if (ok) {
    for (int r = 0; r < rows; r++)
      for (int c = 0; c < cols; c++) gsl_matrix_set(u, (size_t)r, (size_t)c, a[r * cols + c]);
    ok = gsl_linalg_SV_decomp(u, v, s, work) == GSL_SUCCESS;
  }
  if (ok) {
    const double smax = gsl_vector_get(s, 0);
    for (int c = 0; c < cols; c++) x[c] = 0.0;
    for (int k = 0; k < cols; k++) {
      const double sk = gsl_vector_get(s, (size_t)k);
      if (!(sk > RANK_TOL * smax)) continue;
      double ub = 0.0;
      for (int r = 0; r < rows; r++) ub += gsl_matrix_get(u, (size_t)r, (size_t)k) * b[r];
      for (int c = 0; c < cols; c++) x[c] += gsl_matrix_get(v, (size_t)c, (size_t)k) * ub / sk;
    }
  }
  gsl_matrix_free(u);
  gsl_matrix_free(v);
  gsl_vector_free(s);
  gsl_vector_free(work);
  return ok;
}

fb_status fb_planar_free_start(double *y0, const fb_planar *m, const unsigned char *off,
                               const double *omega0, fb_diag *diag) {
  const int nq = fb_planar_nq(m), nb = m->nbodies - 1, rows = fb_planar_rows(m, off, 0);
  double wmax = 0.0;
  for (int b = 1; b < m->nbodies; b++) {
    if (!isfinite(omega0[b]))
      return fb_diag_set(diag, FB_ERR_RANGE, "body '%s': initial angular velocity %g rad/s is "
                         "not finite", m->body[b].name, omega0[b]);
    wmax = fmax(wmax, fabs(omega0[b]));
  }
  double *q = y0, *qd = y0 + nq;
  fb_planar_assembly(m, q);
  for (int i = 0; i < nq; i++) qd[i] = 0.0;
  for (int b = 1; b < m->nbodies; b++) qd[3 * (b - 1) + 2] = omega0[b];
  if (rows == 0) return FB_OK;
  double *g = malloc(((size_t)rows * (size_t)(nq + 2 * nb + 2) + 2 * (size_t)nb) * sizeof *g);
  if (!g) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  double *gv = g + (size_t)rows * nq, *rhs = gv + (size_t)rows * 2 * nb, *res = rhs + rows,
         *v = res + rows;
  fb_planar_constraints(NULL, g, NULL, m, off, NULL, q, NULL);
  /* G_v v = -G_w w */
  for (int r = 0; r < rows; r++) {
    rhs[r] = 0.0;
    for (int b = 0; b < nb; b++) {
      gv[r * 2 * nb + 2 * b] = g[r * nq + 3 * b];
      gv[r * 2 * nb + 2 * b + 1] = g[r * nq + 3 * b + 1];
      rhs[r] -= g[r * nq + 3 * b + 2] * omega0[b + 1];
    }
  }
  fb_status st = least_squares(v, gv, rhs, rows, 2 * nb)
                     ? FB_OK
                     : fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  for (int b = 0; b < nb && st == FB_OK; b++) {
    qd[3 * b] = v[2 * b];
    qd[3 * b + 1] = v[2 * b + 1];
  }
  /* the residual G q', joint by joint */
  if (st == FB_OK) {
    const double scale = fmax(fb_planar_size(m) * wmax, 1e-300);
    int worst = -1, r = 0;
    double big = FB_PLANAR_START_TOL;
    for (int j = 0; j < m->njoints; j++) {
      if (off && off[j]) continue;
      for (int k = 0; k < 2; k++, r++) {
        double e = 0.0;
        for (int i = 0; i < nq; i++) e += g[r * nq + i] * qd[i];
        /* a prismatic joint's first row is an angle rate: to a length rate by the size */
        const double rel = fabs(e) * (m->joint[j].kind == FB_KIND_PRISMATIC && k == 0
                                          ? fb_planar_size(m) : 1.0) / scale;
        if (rel > big) big = rel, worst = j, res[0] = e;
      }
    }
    if (worst >= 0)
      st = fb_diag_set(diag, FB_ERR_ARG, "the initial angular velocities cannot be held by the "
                       "joints: joint '%s' would open at %.6g %s (%.3g of the size times the "
                       "largest rate; allowed %g); give rates the joints allow, or let the "
                       "bodies' rates follow one another (docs/planar.md, a free start)",
                       m->joint[worst].name, fabs(res[0]),
                       m->joint[worst].kind == FB_KIND_PRISMATIC ? "rad/s or m/s" : "m/s", big,
                       FB_PLANAR_START_TOL);
  }
  free(g);
  return st;
}
