/* A sparse LU factorisation of the planar core's square Jacobians (the
 * kinematics' square set, planar_sparse.h; a loop closure's,
 * planar_tree.h), refactorised at every evaluation in the pivot order of
 * its last analysis.
 *
 * The matrix is n x n with a fixed pattern (a joint's row touches its two
 * bodies' columns). The analysis eliminates it with Markowitz pivoting
 * under a threshold (Duff, Erisman and Reid, Direct Methods for Sparse
 * Matrices, 2nd ed. 2017, sec. 7.2 and 9.3): at each step, among the
 * entries at least FB_PLANAR_LU_THRESHOLD of their column's largest, the
 * one whose row and column hold the fewest others, so that a chain of
 * loops keeps its band and the translations' +-1 entries pivot first. A
 * refactorisation replays that order on new values, the same operations
 * on the same places (as SuiteSparse's klu_refactor does), and analyses
 * again only when a pivot has fallen below FB_PLANAR_LU_KEEP of its
 * column's largest. All storage is allocated once, in fb_planar_lu_new: a
 * dense n x n array holds the factors in place, the operations' lists
 * are bounded by n^2, and the work of a refactorisation or a solve is
 * that of the factors' entries (linear in a chain's length).
 *
 * Why not a library: on these matrices (9 to 51 rows) a refactorisation
 * and a solve by SuiteSparse's KLU cost about three times this one's, by
 * LAPACK's banded or GSL's dense LU ten times or more, the calls' fixed
 * work outweighing the products (tests/bench_planar_lu.c,
 * docs/performance.md). */
#ifndef FB_PLANAR_LU_H
#define FB_PLANAR_LU_H

#include "status.h"

/* An analysis takes a pivot at least this fraction of its column's
 * largest entry: the threshold of UMFPACK's default (0.1), which keeps
 * the growth of the factors within 11^n in theory and near 1 in practice
 * while leaving room to choose sparse pivots. */
#define FB_PLANAR_LU_THRESHOLD 0.1

/* A refactorisation keeps the analysis's order while each pivot stays at
 * least this fraction of its column's largest entry; below it the matrix
 * is analysed again (a joint's geometry has turned far from where the
 * order was chosen). */
#define FB_PLANAR_LU_KEEP 0.01

/* The factorisation's workspace. */
typedef struct fb_planar_lu fb_planar_lu;

/* A workspace for an n x n matrix with nnz entries at (row[e], col[e])
 * (0-based, no position twice). Errors: FB_ERR_ARG for an entry outside
 * the matrix or twice; FB_ERR_NOMEM. */
fb_status fb_planar_lu_new(fb_planar_lu **out, int n, int nnz, const int *row, const int *col,
                           fb_diag *diag);

void fb_planar_lu_free(fb_planar_lu *lu);

/* The matrix's values (nnz, in the pattern's order): set them, then
 * factorise. */
double *fb_planar_lu_values(fb_planar_lu *lu);

/* Factorises the values: 1, or 0 when the matrix is singular (a column
 * with no usable pivot). */
int fb_planar_lu_factor(fb_planar_lu *lu);

/* x (n) = A^-1 b (b: n; x may be b) with the last factorisation. */
void fb_planar_lu_solve(fb_planar_lu *lu, const double *b, double *x);

/* x = A^-1 b for nrhs right-hand sides, column by column (b, x: n x
 * nrhs, column c at b + c n; x may be b). */
void fb_planar_lu_solve_many(fb_planar_lu *lu, const double *b, double *x, int nrhs);

/* x (n) = A^-T b (b: n; x may be b). */
void fb_planar_lu_solve_transposed(fb_planar_lu *lu, const double *b, double *x);

/* The sign of det A (+1, -1) at the last factorisation. */
int fb_planar_lu_sign(const fb_planar_lu *lu);

/* log |det A| at the last factorisation (a conditioning measure to
 * compare matrices of one shape). */
double fb_planar_lu_log_abs_det(const fb_planar_lu *lu);

/* Analyses made so far (the first included): a count for tests. */
long fb_planar_lu_analyses(const fb_planar_lu *lu);

#endif
