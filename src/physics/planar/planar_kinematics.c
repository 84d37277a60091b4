/* Newton position analysis, velocity and acceleration analysis
 * (planar_kinematics.h). */
#include "planar_kinematics.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "planar_lu.h"
#include "planar_sparse.h"

struct fb_planar_kin {
  const fb_planar *m;
  int n;                  /* coordinates = rows */
  double size;            /* fb_planar_size [m] */
  fb_planar_lu *lu;       /* the square set's Jacobian (planar_sparse.h), factorised */
  double *cs;             /* (2 nbodies) the bodies' cosines and sines */
  double *phi, *rhs, *x;  /* n each */
  double *scratch;        /* 5 n: fb_planar_kin_scratch */
  double *mult;           /* 2 n: fb_planar_kin_jacobian's caller's multipliers */
  int *col, *rowptr;      /* the pattern: entry e's column; row r's entries from rowptr[r] */
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
  const int n = fb_planar_nq(m), nnz = fb_planar_sq_nnz(m, m->drive);
  int *pat = malloc(2 * (size_t)nnz * sizeof *pat);
  fb_status rc = k && pat ? FB_OK : fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  if (rc == FB_OK) {
    k->m = m;
    k->n = n;
    k->size = fb_planar_size(m);
    fb_planar_sq_pattern(m, m->drive, pat, pat + nnz);
    rc = fb_planar_lu_new(&k->lu, n, nnz, pat, pat + nnz, diag);
  }
  if (rc == FB_OK) {
    k->cs = calloc(2 * (size_t)m->nbodies, sizeof *k->cs);
    k->phi = calloc(10 * (size_t)n, sizeof *k->phi);
    k->col = malloc(((size_t)nnz + (size_t)n + 1) * sizeof *k->col);
    if (!k->cs || !k->phi || !k->col)
      rc = fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the kinematics of %d coordinates",
                       n);
  }
  if (rc == FB_OK) { /* the pattern is row by row (planar_sparse.h) */
    k->rowptr = k->col + nnz;
    memcpy(k->col, pat + nnz, (size_t)nnz * sizeof *k->col);
    for (int r = 0, e = 0; r <= n; r++) {
      while (e < nnz && pat[e] < r) e++;
      k->rowptr[r] = e;
    }
  }
  free(pat);
  if (rc != FB_OK) {
    fb_planar_kin_free(k);
    return rc;
  }
  k->rhs = k->phi + n;
  k->x = k->rhs + n;
  k->scratch = k->x + n;
  k->mult = k->scratch + 5 * n;
  *out = k;
  return FB_OK;
}

void fb_planar_kin_free(fb_planar_kin *k) {
  if (!k) return;
  fb_planar_lu_free(k->lu);
  free(k->cs);
  free(k->phi);
  free(k->col);
  free(k);
}

double *fb_planar_kin_scratch(fb_planar_kin *k) { return k->scratch; }

const double *fb_planar_kin_jacobian(fb_planar_kin *k, const int **col, const int **rowptr,
                                     double **mult) {
  *col = k->col;
  *rowptr = k->rowptr;
  if (mult) *mult = k->mult;
  return fb_planar_lu_values(k->lu);
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

/* Phi at q with the drive at angle into k->phi (k->cs: q's trig) */
static void residual(fb_planar_kin *k, const double *q, double angle) {
  fb_planar_sq_phi(k->phi, k->m, k->m->drive, q, k->cs);
  k->phi[k->n - 1] -= angle;
}

/* factorises the Jacobian at q (k->cs: q's trig); 0 when singular */
static int factorise(fb_planar_kin *k, const double *q, int *sign) {
  fb_planar_sq_values(fb_planar_lu_values(k->lu), k->m, k->m->drive, q, k->cs);
  if (!fb_planar_lu_factor(k->lu)) return 0;
  if (sign) *sign = fb_planar_lu_sign(k->lu);
  return 1;
}

void fb_planar_kin_solve_transposed(fb_planar_kin *k, const double *rhs, double *x) {
  fb_planar_lu_solve_transposed(k->lu, rhs, x);
}

int fb_planar_worst_joint(fb_planar_kin *k, const double *q, double angle, double *residual_out) {
  fb_planar_sq_trig(k->cs, k->m, q);
  residual(k, q, angle);
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
  if (residual_out) *residual_out = worst >= 0 && k->m->joint[worst].kind == FB_KIND_REVOLUTE
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
  int it = 0, last = 0;
  for (; it < FB_PLANAR_NEWTON_MAX && !last; it++) {
    fb_planar_sq_trig(k->cs, k->m, q);
    residual(k, q, angle);
    if (!(scaled_norm(k, k->phi, 0) < 1e3)) break; /* diverged (or not finite) */
    if (!factorise(k, q, NULL)) {
      if (iterations) *iterations = it;
      return not_closed(k, q, angle, "singular Jacobian", diag);
    }
    for (int i = 0; i < k->n; i++) k->rhs[i] = -k->phi[i];
    fb_planar_lu_solve(k->lu, k->rhs, k->x);
    for (int i = 0; i < k->n; i++) q[i] += k->x[i];
    last = scaled_norm(k, k->x, 1) <= FB_PLANAR_NEWTON_STOP;
  }
  if (iterations) *iterations = it;
  fb_planar_sq_trig(k->cs, k->m, q);
  residual(k, q, angle);
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
  fb_planar_sq_trig(k->cs, k->m, q);
  if (!factorise(k, q, sign))
    return fb_diag_set(diag, FB_ERR_ASSEMBLY, "the Jacobian is singular: the mechanism is at a "
                       "locked or change-point position, where its velocities are undefined");
  double *v = qd ? qd : k->x;
  memset(k->rhs, 0, (size_t)k->n * sizeof *k->rhs);
  k->rhs[k->n - 1] = d->omega;
  fb_planar_lu_solve(k->lu, k->rhs, v);
  if (qdd) {
    fb_planar_sq_gamma(k->rhs, k->m, k->m->drive, q, v, k->cs);
    k->rhs[k->n - 1] = d->alpha;
    fb_planar_lu_solve(k->lu, k->rhs, qdd);
  }
  return FB_OK;
}
