/* The planar core's sparse LU (planar_lu.h) against the libraries it
 * stands in for, on the square sets (planar_sparse.h) of shipped planar
 * cases over a revolution of positions: a refactorisation and a solve of
 * each (a benchmark, never a test: `meson test -C build --benchmark
 * planar_lu`, or ./build/tests/bench_planar_lu CASE...; built when
 * SuiteSparse's KLU and LAPACK are found). CPU time of this process per
 * refactorisation and solve, best of BEST_OF repeats:
 *   planar_lu  fb_planar_lu_factor (the analysis's order) + fb_planar_lu_solve
 *   KLU        klu_refactor (klu_analyze and klu_factor once) + klu_solve
 *   LAPACK     dgbtrf + dgbtrs on the band (the pattern's kl, ku in the
 *              square set's natural order: joints' rows, bodies' columns)
 *   GSL        gsl_linalg_LU_decomp + gsl_linalg_LU_solve (dense)
 * Each solution is checked against GSL's (relative 1e-9). For instruction
 * counts run it under `valgrind --tool=callgrind`. */
#include <gsl/gsl_linalg.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <suitesparse/klu.h>
#include <time.h>

#include "casefile.h"
#include "planar_case.h"
#include "planar_kinematics.h"
#include "planar_lu.h"
#include "planar_path.h"
#include "planar_sparse.h"

#define BEST_OF 5
#define POSES 360

/* LAPACK's banded LU (Fortran interface) */
void dgbtrf_(const int *m, const int *n, const int *kl, const int *ku, double *ab, const int *ldab,
             int *ipiv, int *info);
void dgbtrs_(const char *trans, const int *n, const int *kl, const int *ku, const int *nrhs,
             const double *ab, const int *ldab, const int *ipiv, double *b, const int *ldb,
             int *info);

static double cpu_s(void) {
  struct timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static volatile double sink;

typedef struct {
  int n, nnz;
  int *row, *col;
  double *val; /* POSES x nnz: the Jacobian at each pose */
  double *b;   /* n: a right-hand side */
} poses;

static int load(poses *P, const char *path) {
  fb_case c;
  fb_diag d;
  if (fb_casefile_load_planar(&c, path, NULL, 0, &d) != FB_OK) {
    fprintf(stderr, "%s\n", d.msg);
    return 0;
  }
  fb_planar *m;
  fb_planar_kin *k;
  if (fb_planar_of_case(&m, &c, &c.nominal, &d) != FB_OK || fb_planar_kin_new(&k, m, &d) != FB_OK) {
    fprintf(stderr, "%s\n", d.msg);
    return 0;
  }
  P->n = fb_planar_nq(m);
  P->nnz = fb_planar_sq_nnz(m, m->drive);
  P->row = malloc(2 * (size_t)P->nnz * sizeof *P->row);
  P->col = P->row + P->nnz;
  P->val = malloc((size_t)POSES * (size_t)P->nnz * sizeof *P->val);
  P->b = malloc((size_t)P->n * sizeof *P->b);
  double *q = malloc((size_t)P->n * sizeof *q), *cs = malloc(2 * (size_t)m->nbodies * sizeof *cs);
  fb_planar_sq_pattern(m, m->drive, P->row, P->col);
  fb_planar_assembly(m, q);
  if (fb_planar_position(k, q, 0.0, NULL, &d) != FB_OK) return 0;
  for (int i = 0; i < POSES; i++) {
    fb_path_end end;
    const double a = 2.0 * M_PI * i / POSES;
    if (i > 0 && fb_planar_follow(k, q, 2.0 * M_PI * (i - 1) / POSES, a, NULL, &end, &d) != FB_OK)
      return 0;
    fb_planar_sq_trig(cs, m, q);
    fb_planar_sq_values(P->val + (size_t)i * P->nnz, m, m->drive, q, cs);
  }
  for (int i = 0; i < P->n; i++) P->b[i] = 1.0 + 0.1 * i;
  free(q);
  free(cs);
  fb_planar_kin_free(k);
  fb_planar_free(m);
  return 1;
}

/* GSL's dense solution at pose i into x */
static void gsl_solution(const poses *P, int i, double *x) {
  const int n = P->n;
  gsl_matrix *a = gsl_matrix_calloc((size_t)n, (size_t)n);
  gsl_permutation *p = gsl_permutation_alloc((size_t)n);
  for (int e = 0; e < P->nnz; e++)
    gsl_matrix_set(a, (size_t)P->row[e], (size_t)P->col[e], P->val[(size_t)i * P->nnz + e]);
  int s;
  gsl_linalg_LU_decomp(a, p, &s);
  gsl_vector_const_view bv = gsl_vector_const_view_array(P->b, (size_t)n);
  gsl_vector_view xv = gsl_vector_view_array(x, (size_t)n);
  gsl_linalg_LU_solve(a, p, &bv.vector, &xv.vector);
  gsl_matrix_free(a);
  gsl_permutation_free(p);
}

static void check(const poses *P, int i, const double *x, const char *who) {
  double *g = malloc((size_t)P->n * sizeof *g), big = 0.0, diff = 0.0;
  gsl_solution(P, i, g);
  for (int k = 0; k < P->n; k++) big = fmax(big, fabs(g[k])), diff = fmax(diff, fabs(g[k] - x[k]));
  if (!(diff <= 1e-9 * big)) fprintf(stderr, "%s: pose %d off GSL's by %.3g\n", who, i, diff / big);
  free(g);
}

static double bench_planar_lu(const poses *P) {
  fb_planar_lu *lu;
  if (fb_planar_lu_new(&lu, P->n, P->nnz, P->row, P->col, NULL) != FB_OK) exit(1);
  double *x = malloc((size_t)P->n * sizeof *x), best = 1e30;
  for (int r = 0; r < BEST_OF; r++) {
    const double t0 = cpu_s();
    for (int i = 0; i < POSES; i++) {
      memcpy(fb_planar_lu_values(lu), P->val + (size_t)i * P->nnz, (size_t)P->nnz * sizeof *x);
      fb_planar_lu_factor(lu);
      fb_planar_lu_solve(lu, P->b, x);
      sink = x[0];
    }
    best = fmin(best, cpu_s() - t0);
  }
  check(P, POSES - 1, x, "planar_lu");
  free(x);
  fb_planar_lu_free(lu);
  return best / POSES;
}

static double bench_klu(const poses *P) {
  const int n = P->n, nnz = P->nnz;
  /* compressed columns */
  int *ap = calloc((size_t)n + 1, sizeof *ap), *ai = malloc((size_t)nnz * sizeof *ai);
  int *map = malloc((size_t)nnz * sizeof *map), *fill = calloc((size_t)n, sizeof *fill);
  double *ax = malloc((size_t)nnz * sizeof *ax), *x = malloc((size_t)n * sizeof *x);
  for (int e = 0; e < nnz; e++) ap[P->col[e] + 1]++;
  for (int c = 0; c < n; c++) ap[c + 1] += ap[c];
  for (int e = 0; e < nnz; e++) {
    const int k = ap[P->col[e]] + fill[P->col[e]]++;
    ai[k] = P->row[e];
    map[e] = k;
  }
  klu_common common;
  klu_defaults(&common);
  klu_symbolic *sym = klu_analyze(n, ap, ai, &common);
  for (int e = 0; e < nnz; e++) ax[map[e]] = P->val[e];
  klu_numeric *num = klu_factor(ap, ai, ax, sym, &common);
  double best = 1e30;
  for (int r = 0; r < BEST_OF; r++) {
    const double t0 = cpu_s();
    for (int i = 0; i < POSES; i++) {
      for (int e = 0; e < nnz; e++) ax[map[e]] = P->val[(size_t)i * nnz + e];
      klu_refactor(ap, ai, ax, sym, num, &common);
      memcpy(x, P->b, (size_t)n * sizeof *x);
      klu_solve(sym, num, n, 1, x, &common);
      sink = x[0];
    }
    best = fmin(best, cpu_s() - t0);
  }
  check(P, POSES - 1, x, "KLU");
  klu_free_numeric(&num, &common);
  klu_free_symbolic(&sym, &common);
  free(ap), free(ai), free(map), free(fill), free(ax), free(x);
  return best / POSES;
}

static double bench_lapack(const poses *P) {
  const int n = P->n, nnz = P->nnz;
  int kl = 0, ku = 0;
  for (int e = 0; e < nnz; e++) {
    kl = P->row[e] - P->col[e] > kl ? P->row[e] - P->col[e] : kl;
    ku = P->col[e] - P->row[e] > ku ? P->col[e] - P->row[e] : ku;
  }
  const int ldab = 2 * kl + ku + 1, one = 1;
  double *ab = malloc((size_t)ldab * (size_t)n * sizeof *ab), *x = malloc((size_t)n * sizeof *x);
  int *ipiv = malloc((size_t)n * sizeof *ipiv), info;
  double best = 1e30;
  for (int r = 0; r < BEST_OF; r++) {
    const double t0 = cpu_s();
    for (int i = 0; i < POSES; i++) {
      memset(ab, 0, (size_t)ldab * (size_t)n * sizeof *ab);
      for (int e = 0; e < nnz; e++) /* AB(kl + ku + 1 + i - j, j), 1-based */
        ab[(size_t)P->col[e] * ldab + (size_t)(kl + ku + P->row[e] - P->col[e])] =
            P->val[(size_t)i * nnz + e];
      dgbtrf_(&n, &n, &kl, &ku, ab, &ldab, ipiv, &info);
      memcpy(x, P->b, (size_t)n * sizeof *x);
      dgbtrs_("N", &n, &kl, &ku, &one, ab, &ldab, ipiv, x, &n, &info);
      sink = x[0];
    }
    best = fmin(best, cpu_s() - t0);
  }
  check(P, POSES - 1, x, "LAPACK");
  printf("  (band: kl %d, ku %d)\n", kl, ku);
  free(ab), free(x), free(ipiv);
  return best / POSES;
}

static double bench_gsl(const poses *P) {
  const int n = P->n;
  gsl_matrix *a = gsl_matrix_alloc((size_t)n, (size_t)n);
  gsl_permutation *p = gsl_permutation_alloc((size_t)n);
  double *x = malloc((size_t)n * sizeof *x), best = 1e30;
  for (int r = 0; r < BEST_OF; r++) {
    const double t0 = cpu_s();
    for (int i = 0; i < POSES; i++) {
      gsl_matrix_set_zero(a);
      for (int e = 0; e < P->nnz; e++)
        gsl_matrix_set(a, (size_t)P->row[e], (size_t)P->col[e], P->val[(size_t)i * P->nnz + e]);
      int s;
      gsl_linalg_LU_decomp(a, p, &s);
      gsl_vector_const_view bv = gsl_vector_const_view_array(P->b, (size_t)n);
      gsl_vector_view xv = gsl_vector_view_array(x, (size_t)n);
      gsl_linalg_LU_solve(a, p, &bv.vector, &xv.vector);
      sink = x[0];
    }
    best = fmin(best, cpu_s() - t0);
  }
  check(P, POSES - 1, x, "GSL");
  gsl_matrix_free(a);
  gsl_permutation_free(p);
  free(x);
  return best / POSES;
}

int main(int argc, char **argv) {
  const char *dir = getenv("FOURBAR_CASES_DIR");
  char fourbar[4096], sixbar[4096];
  snprintf(fourbar, sizeof fourbar, "%s/templates/planar_fourbar.ini", dir ? dir : "cases");
  snprintf(sixbar, sizeof sixbar, "%s/watt_sixbar.ini", dir ? dir : "cases");
  const char *deflt[2] = {fourbar, sixbar};
  const int ncase = argc > 1 ? argc - 1 : 2;
  printf("CPU time of a refactorisation and a solve [us], best of %d over %d poses\n", BEST_OF,
         POSES);
  for (int i = 0; i < ncase; i++) {
    const char *path = argc > 1 ? argv[i + 1] : deflt[i];
    poses P;
    if (!load(&P, path)) return 1;
    printf("%s: %d x %d, %d entries\n", path, P.n, P.n, P.nnz);
    const double a = bench_planar_lu(&P), b = bench_klu(&P), c = bench_lapack(&P), d = bench_gsl(&P);
    printf("  planar_lu %.3f  KLU %.3f  LAPACK dgbtrf %.3f  GSL dense %.3f\n", 1e6 * a, 1e6 * b,
           1e6 * c, 1e6 * d);
    free(P.row), free(P.val), free(P.b);
  }
  return 0;
}
