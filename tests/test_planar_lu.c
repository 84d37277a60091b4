/* The sparse LU of the planar core (planar_lu.h) against GSL's dense LU
 * with partial pivoting: the same solutions, transposed solutions and
 * determinant signs on random sparse matrices (small ones as a loop
 * closure's, banded ones as a chain's Jacobian, and scattered ones) and on the four-bar's and six-bar's square
 * sets over a revolution (planar_sparse.h); a pivot that degrades
 * triggers a new analysis; a singular matrix is refused. */
#include <gsl/gsl_linalg.h>
#include <string.h>

#include "casefile.h"
#include "fb_test.h"
#include "planar_case.h"
#include "planar_kinematics.h"
#include "planar_lu.h"
#include "planar_path.h"
#include "planar_sparse.h"

/* Solutions against GSL's: both backward stable, so each differs from the
 * exact one by ~cond x 1e-16; the random matrices below have condition
 * numbers up to ~1e4 (their diagonal is not dominant), the mechanisms'
 * ~1e3: 1e-10 relative to the solution's largest entry holds with a
 * factor of ~100 (measured: FB_TEST_VERBOSE). */
#define SOLVE_REL_TOL 1e-10
/* The square set's sparse Phi, gamma and Jacobian against the dense forms
 * of planar_constraints.c: the same products, the trig taken once per
 * body rather than once per joint point, so equal to the rounding of a
 * product: entries of ~0.3 m and ~1e2 1/s^2 carry ~1e-16 of themselves
 * (measured 2.8e-17; 1e-14 leaves the larger entries their rounding). */
#define SPARSE_TOL 1e-14

/* a reproducible stream of uniform numbers in [-1, 1) */
static double uni(unsigned long *s) {
  *s = *s * 6364136223846793005UL + 1442695040888963407UL;
  return (double)(*s >> 11) / 4503599627370496.0 - 1.0;
}

/* x against GSL's dense solution of a x = b (or a^T x = b), relative to
 * the largest |entry| */
static double against_gsl(const double *a, int n, const double *b, const double *x, int trans,
                          int *sign) {
  gsl_matrix *m = gsl_matrix_alloc((size_t)n, (size_t)n);
  gsl_permutation *p = gsl_permutation_alloc((size_t)n);
  gsl_vector *v = gsl_vector_alloc((size_t)n);
  for (int i = 0; i < n; i++) {
    gsl_vector_set(v, (size_t)i, b[i]);
    for (int j = 0; j < n; j++) gsl_matrix_set(m, (size_t)i, (size_t)j, trans ? a[j * n + i] : a[i * n + j]);
  }
  int s;
  gsl_linalg_LU_decomp(m, p, &s);
  if (sign) *sign = gsl_linalg_LU_sgndet(m, s) < 0 ? -1 : 1;
  gsl_linalg_LU_svx(m, p, v);
  double big = 0.0, diff = 0.0;
  for (int i = 0; i < n; i++) {
    big = fmax(big, fabs(gsl_vector_get(v, (size_t)i)));
    diff = fmax(diff, fabs(gsl_vector_get(v, (size_t)i) - x[i]));
  }
  gsl_matrix_free(m);
  gsl_permutation_free(p);
  gsl_vector_free(v);
  return diff / big;
}

/* one random n x n matrix with band half-width hb (or scattered, hb < 0)
 * of seed s, factorised and solved both ways against GSL */
static double random_case(int n, int hb, unsigned long s) {
  double *a = calloc((size_t)n * (size_t)n, sizeof *a);
  int *row = malloc((size_t)n * (size_t)n * 2 * sizeof *row), *col = row + n * n;
  int nnz = 0;
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++) {
      const int in = hb >= 0 ? abs(i - j) <= hb : (i == (j * 7 + 3) % n || uni(&s) > 0.6);
      if (!in) continue;
      a[i * n + j] = uni(&s);
      row[nnz] = i, col[nnz] = j, nnz++;
    }
  fb_planar_lu *lu;
  fb_diag d;
  assert_int_equal(fb_planar_lu_new(&lu, n, nnz, row, col, &d), FB_OK);
  for (int e = 0; e < nnz; e++) fb_planar_lu_values(lu)[e] = a[row[e] * n + col[e]];
  double worst = 0.0;
  for (int again = 0; again < 2; again++) { /* the analysis, then a refactorisation */
    assert_true(fb_planar_lu_factor(lu));
    double b[64], x[64];
    for (int i = 0; i < n; i++) b[i] = uni(&s);
    int sign;
    fb_planar_lu_solve(lu, b, x);
    worst = fmax(worst, against_gsl(a, n, b, x, 0, &sign));
    assert_int_equal(fb_planar_lu_sign(lu), sign);
    fb_planar_lu_solve_transposed(lu, b, x);
    worst = fmax(worst, against_gsl(a, n, b, x, 1, NULL));
    memcpy(x, b, (size_t)n * sizeof *x); /* in place */
    fb_planar_lu_solve(lu, x, x);
    worst = fmax(worst, against_gsl(a, n, b, x, 0, NULL));
    /* three right-hand sides at once, in place: each as alone */
    double bb[3 * 64], xx[3 * 64];
    for (int i = 0; i < 3 * n; i++) bb[i] = xx[i] = uni(&s);
    fb_planar_lu_solve_many(lu, xx, xx, 3);
    for (int c = 0; c < 3; c++) worst = fmax(worst, against_gsl(a, n, bb + c * n, xx + c * n, 0, NULL));
  }
  assert_int_equal(fb_planar_lu_analyses(lu), 1);
  fb_planar_lu_free(lu);
  free(a);
  free(row);
  return worst;
}

static void test_random(void **state) {
  (void)state;
  double worst = 0.0;
  for (unsigned long s = 1; s <= 20; s++) {
    worst = fmax(worst, random_case(3, 1, s));
    worst = fmax(worst, random_case(6, -1, s));
    worst = fmax(worst, random_case(9, 2, s));
    worst = fmax(worst, random_case(40, 3, s));
    worst = fmax(worst, random_case(25, -1, s));
  }
  report_residual("random sparse: solutions vs GSL (rel)", worst, SOLVE_REL_TOL);
  assert_true(worst <= SOLVE_REL_TOL);
}

/* a pivot that falls below FB_PLANAR_LU_KEEP of its column makes a new
 * analysis; a singular matrix is refused: a 2 x 2 block alone and with
 * the identity of order n - 2 beside it */
static void block(int n) {
  int row[64], col[64], k = 0;
  const int r4[4] = {0, 0, 1, 1}, c4[4] = {0, 1, 0, 1};
  for (int e = 0; e < 4; e++) row[k] = r4[e], col[k++] = c4[e];
  for (int i = 2; i < n; i++) row[k] = col[k] = i, k++;
  fb_planar_lu *lu;
  fb_diag d;
  assert_int_equal(fb_planar_lu_new(&lu, n, k, row, col, &d), FB_OK);
  double *v = fb_planar_lu_values(lu);
  for (int e = 4; e < k; e++) v[e] = 1.0;
  v[0] = 4.0, v[1] = 1.0, v[2] = 1.0, v[3] = 3.0; /* pivot (0, 0) */
  assert_true(fb_planar_lu_factor(lu));
  v[0] = 1e-4, v[2] = 1.0; /* (0, 0) now 1e-4 of its column */
  assert_true(fb_planar_lu_factor(lu));
  assert_int_equal(fb_planar_lu_analyses(lu), 2);
  double b[16] = {1.0, 2.0}, x[16];
  fb_planar_lu_solve(lu, b, x);
  assert_true(fabs(v[0] * x[0] + v[1] * x[1] - b[0]) < 1e-14);
  assert_true(fabs(v[2] * x[0] + v[3] * x[1] - b[1]) < 1e-14);
  v[0] = 1.0, v[1] = 2.0, v[2] = 2.0, v[3] = 4.0; /* rank 1 */
  assert_false(fb_planar_lu_factor(lu));
  fb_planar_lu_free(lu);
}

static void test_reanalysis_and_singular(void **state) {
  (void)state;
  block(2);
  block(10);
  fb_diag d;
  const int twice[2] = {0, 0};
  fb_planar_lu *bad;
  assert_int_equal(fb_planar_lu_new(&bad, 2, 2, twice, twice, &d), FB_ERR_ARG);
}

/* the square set of a shipped description over a revolution: the sparse
 * values against planar_constraints.h's dense Jacobian, and solutions
 * against GSL's */
static void mechanism_sweep(const char *name, int planar) {
  fb_case c;
  fb_diag d;
  if ((planar ? fb_test_shipped_case_planar(&c, name, &d)
              : fb_test_shipped_case(&c, name, NULL, 0, &d)) != FB_OK)
    fail_msg("%s", d.msg);
  fb_planar *m;
  if (fb_planar_of_case(&m, &c, &c.nominal, &d) != FB_OK) fail_msg("%s", d.msg);
  const int n = fb_planar_nq(m), nnz = fb_planar_sq_nnz(m, m->drive);
  int *row = malloc(2 * (size_t)nnz * sizeof *row), *col = row + nnz;
  fb_planar_sq_pattern(m, m->drive, row, col);
  fb_planar_lu *lu;
  assert_int_equal(fb_planar_lu_new(&lu, n, nnz, row, col, &d), FB_OK);
  fb_planar_kin *k;
  assert_int_equal(fb_planar_kin_new(&k, m, &d), FB_OK);
  double *q = calloc(4 * (size_t)n + 2 * (size_t)m->nbodies + (size_t)n * (size_t)n, sizeof *q);
  double *b = q + n, *x = b + n, *dense = x + n, *cs = dense + n * n;
  fb_planar_assembly(m, q);
  assert_int_equal(fb_planar_position(k, q, 0.0, NULL, &d), FB_OK);
  double worst = 0.0, jac = 0.0;
  unsigned long s = 7;
  for (int i = 0; i < 36; i++) {
    fb_path_end end;
    if (i > 0 && fb_planar_follow(k, q, (i - 1) * M_PI / 18, i * M_PI / 18, NULL, &end, &d) != FB_OK)
      fail_msg("%s", d.msg);
    /* Phi, gamma (at rates of a random motion) and the Jacobian: sparse
     * against planar_constraints.h's dense forms, the drive's angle 0 */
    const fb_planar_drive dr = {0.0, 0.0, 0.0};
    for (int r = 0; r < n; r++) x[r] = uni(&s);
    fb_planar_constraints(b, dense, NULL, m, NULL, &dr, q, NULL);
    fb_planar_sq_trig(cs, m, q);
    double *v = fb_planar_lu_values(lu), phi[64], g[64], gd[64];
    fb_planar_sq_phi(phi, m, m->drive, q, cs);
    fb_planar_sq_gamma(g, m, m->drive, q, x, cs);
    fb_planar_constraints(NULL, NULL, gd, m, NULL, &dr, q, x);
    for (int r = 0; r < n; r++) jac = fmax(jac, fmax(fabs(phi[r] - b[r]), fabs(g[r] - gd[r])));
    fb_planar_sq_values(v, m, m->drive, q, cs);
    for (int e = 0; e < nnz; e++) jac = fmax(jac, fabs(v[e] - dense[row[e] * n + col[e]]));
    assert_true(fb_planar_lu_factor(lu));
    for (int r = 0; r < n; r++) b[r] = uni(&s);
    int sign;
    fb_planar_lu_solve(lu, b, x);
    worst = fmax(worst, against_gsl(dense, n, b, x, 0, &sign));
    assert_int_equal(fb_planar_lu_sign(lu), sign);
    fb_planar_lu_solve_transposed(lu, b, x);
    worst = fmax(worst, against_gsl(dense, n, b, x, 1, NULL));
  }
  if (fb_test_verbose())
    fprintf(stderr, "  %s: %d x %d, %d entries, %ld analyses over the revolution\n", name, n, n,
            nnz, fb_planar_lu_analyses(lu));
  report_residual("square set: sparse vs dense Phi, gamma, Jacobian", jac, SPARSE_TOL);
  assert_true(jac <= SPARSE_TOL);
  report_residual("square set: solutions vs GSL (rel)", worst, SOLVE_REL_TOL);
  assert_true(worst <= SOLVE_REL_TOL);
  free(q);
  free(row);
  fb_planar_kin_free(k);
  fb_planar_lu_free(lu);
  fb_planar_free(m);
}

static void test_mechanisms(void **state) {
  (void)state;
  mechanism_sweep("paper_crank_rocker.ini", 0);
  mechanism_sweep("watt_sixbar.ini", 1);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_random),
      cmocka_unit_test(test_reanalysis_and_singular),
      cmocka_unit_test(test_mechanisms),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
