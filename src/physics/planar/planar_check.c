/* The checks of a planar description (planar_check.h). */
#include "planar_check.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "planar_constraints.h"
#include "planar_kinematics.h"
#include "planar_path.h"

/* every body reached from the ground through joints; the first that is
 * not, or -1 */
static int unconnected(const fb_planar *m) {
  unsigned char *seen = calloc((size_t)m->nbodies, 1);
  if (!seen) return -1;
  seen[FB_PLANAR_GROUND] = 1;
  for (int grew = 1; grew;) {
    grew = 0;
    for (int j = 0; j < m->njoints; j++) {
      const int a = m->joint[j].body[0], b = m->joint[j].body[1];
      if (seen[a] != seen[b]) {
        seen[a] = seen[b] = 1;
        grew = 1;
      }
    }
  }
  int first = -1;
  for (int b = m->nbodies - 1; b > 0; b--)
    if (!seen[b]) first = b;
  free(seen);
  return first;
}

/* the singular values (largest first) of rows x nq matrix a (row-major),
 * and the right singular vector of the smallest into v (nq) when v is not
 * NULL; rows <= nq. Returns 0 when out of memory. */
static int svd(double *s, double *v, const double *a, int rows, int nq) {
  /* GSL wants M >= N: factorise a^T (nq x rows) = U S V^T, so a = V S U^T
   * and a's right singular vectors are U's columns */
  gsl_matrix *at = gsl_matrix_alloc((size_t)nq, (size_t)rows);
  gsl_matrix *vv = gsl_matrix_alloc((size_t)rows, (size_t)rows);
  gsl_vector *sv = gsl_vector_alloc((size_t)rows), *work = gsl_vector_alloc((size_t)rows);
  const int ok = at && vv && sv && work;
  if (ok) {
    for (int r = 0; r < rows; r++)
      for (int c = 0; c < nq; c++) gsl_matrix_set(at, (size_t)c, (size_t)r, a[r * nq + c]);
    gsl_linalg_SV_decomp(at, vv, sv, work);
    for (int r = 0; r < rows; r++) s[r] = gsl_vector_get(sv, (size_t)r);
    if (v)
      for (int c = 0; c < nq; c++) v[c] = gsl_matrix_get(at, (size_t)c, (size_t)(rows - 1));
  }
  if (at) gsl_matrix_free(at);
  if (vv) gsl_matrix_free(vv);
  if (sv) gsl_vector_free(sv);
  if (work) gsl_vector_free(work);
  return ok;
}

/* Phi_q of the first `joints` joints (and the drive's row when drive) at q,
 * scaled: angle rows times the size, angle columns times the size, so that
 * every entry compares lengths with lengths; returns its rows */
static int scaled_jacobian(double *a, const fb_planar *m, const double *q, int joints, int drive) {
  unsigned char *off = calloc((size_t)m->njoints, 1);
  if (!off) return -1;
  for (int j = joints; j < m->njoints; j++) off[j] = 1;
  const fb_planar_drive d = {0.0, 0.0, 0.0};
  const int rows = fb_planar_rows(m, off, drive), nq = fb_planar_nq(m);
  fb_planar_constraints(NULL, a, NULL, m, off, drive ? &d : NULL, q, NULL);
  const double size = fb_planar_size(m);
  int r = 0;
  for (int j = 0; j < joints; j++, r += 2)
    if (m->joint[j].kind == FB_KIND_PRISMATIC)
      for (int c = 0; c < nq; c++) a[r * nq + c] *= size;
  if (drive)
    for (int c = 0; c < nq; c++) a[r * nq + c] *= size;
  for (int rr = 0; rr < rows; rr++)
    for (int c = 2; c < nq; c += 3) a[rr * nq + c] /= size;
  free(off);
  return rows;
}

/* the body with the largest scaled motion in v other than `not`, or -1 */
static int moving_most(const fb_planar *m, const double *v, int not) {
  int best = -1;
  double big = 1e-6; /* a body that moves 1e-6 of the largest does not move */
  for (int b = 1; b < m->nbodies; b++) {
    if (b == not) continue;
    const double *x = v + 3 * (b - 1);
    const double mag = fmax(fmax(fabs(x[0]), fabs(x[1])), fabs(x[2]));
    if (mag > big) {
      big = mag;
      best = b;
    }
  }
  return best;
}

/* the joint between bodies a and b, or -1 */
static int joint_between(const fb_planar *m, int a, int b) {
  for (int j = 0; j < m->njoints; j++)
    if ((m->joint[j].body[0] == a && m->joint[j].body[1] == b) ||
        (m->joint[j].body[0] == b && m->joint[j].body[1] == a))
      return j;
  return -1;
}

/* what moves at a singular position q: "bodies 'a' and 'b' (at joint 'j')"
 * into text, from the right singular vector of the smallest singular
 * value (a motion the joints and the held drive allow to first order) */
static void singular_motion(char *text, size_t size, const fb_planar *m, const double *q,
                            fb_planar_where *where) {
  const int nq = fb_planar_nq(m);
  double *a = calloc((size_t)nq * (size_t)nq + 2 * (size_t)nq, sizeof *a);
  text[0] = '\0';
  if (!a) return;
  double *s = a + nq * nq, *v = s + nq;
  scaled_jacobian(a, m, q, m->njoints, 1);
  if (svd(s, v, a, nq, nq)) {
    int b1 = moving_most(m, v, -1), b2 = moving_most(m, v, b1);
    const int j = b2 > 0 ? joint_between(m, b1, b2) : -1;
    if (b2 > 0 && b2 < b1) { /* named in the description's order */
      const int t = b1;
      b1 = b2;
      b2 = t;
    }
    if (b1 > 0) where->body = b1;
    if (j >= 0) where->joint = j;
    if (b1 > 0 && b2 > 0)
      snprintf(text, size, ": bodies '%s' and '%s'%s%s%s can move there with the drive held "
               "(the Jacobian's smallest singular value is %.2g of its largest)",
               m->body[b1].name, m->body[b2].name, j >= 0 ? " (at joint '" : "",
               j >= 0 ? m->joint[j].name : "", j >= 0 ? "')" : "", s[nq - 1] / s[0]);
    else if (b1 > 0)
      snprintf(text, size, ": body '%s' can move there with the drive held", m->body[b1].name);
  }
  free(a);
}

/* the first joint whose rows add less than their number to the rank of
 * the rows before it at q, or -1 (then the drive's row is the one) */
static int redundant_joint(const fb_planar *m, const double *q) {
  const int nq = fb_planar_nq(m);
  double *a = calloc((size_t)(2 * m->njoints + 1) * (size_t)nq + 2 * (size_t)nq + 2, sizeof *a);
  if (!a) return -1;
  double *s = a + (size_t)(2 * m->njoints + 1) * nq;
  int found = -1, rank = 0;
  for (int j = 1; j <= m->njoints && found < 0; j++) {
    const int rows = scaled_jacobian(a, m, q, j, 0);
    if (rows > nq || !svd(s, NULL, a, rows, nq)) break;
    int r = 0;
    for (int i = 0; i < rows; i++) r += s[i] > FB_PLANAR_RANK_TOL * s[0];
    if (r < rank + 2) found = j - 1;
    rank = r;
  }
  free(a);
  return found;
}

static fb_status check_rank(const fb_planar *m, const double *q, fb_planar_where *where,
                            fb_diag *diag) {
  const int nq = fb_planar_nq(m);
  double *a = calloc((size_t)nq * (size_t)nq + (size_t)nq, sizeof *a);
  if (!a) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  double *s = a + nq * nq;
  scaled_jacobian(a, m, q, m->njoints, 1);
  const int ok = svd(s, NULL, a, nq, nq);
  const double ratio = s[nq - 1] / s[0];
  free(a);
  if (!ok) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  if (ratio > FB_PLANAR_RANK_TOL) return FB_OK;
  const int j = redundant_joint(m, q);
  char motion[512];
  singular_motion(motion, sizeof motion, m, q, where);
  if (j >= 0) where->joint = j;
  return fb_diag_set(diag, FB_ERR_ARG,
                     "the joints' equations are dependent at the assembly configuration (the "
                     "Gruebler count is right, but the Jacobian with the drive is singular)%s; "
                     "%s%s%s: a redundant joint, or a mechanism assembled at a toggle or "
                     "change-point position", motion, j >= 0 ? "joint '" : "the drive",
                     j >= 0 ? m->joint[j].name : " adds no constraint to the joints",
                     j >= 0 ? "' adds no constraint the joints before it do not already impose"
                            : "");
}

/* after a revolution, the body farthest from its start, or -1 */
static int off_start(const fb_planar *m, const double *q, const double *q0, double *by) {
  const double size = fb_planar_size(m);
  int worst = -1;
  double big = FB_PLANAR_RETURN_TOL;
  for (int b = 1; b < m->nbodies; b++) {
    const double *x = q + 3 * (b - 1), *x0 = q0 + 3 * (b - 1);
    const double turns = (x[2] - x0[2]) / (2.0 * M_PI);
    const double d = fmax(hypot(x[0] - x0[0], x[1] - x0[1]) / size,
                          fabs(turns - nearbyint(turns)) * 2.0 * M_PI);
    if (d > big) {
      big = d;
      worst = b;
      *by = hypot(x[0] - x0[0], x[1] - x0[1]);
    }
  }
  return worst;
}

static fb_status check_turn(const fb_planar *m, double *q, fb_planar_where *where,
                            fb_diag *diag) {
  fb_planar_kin *k;
  fb_status rc = fb_planar_kin_new(&k, m, diag);
  if (rc != FB_OK) return rc;
  const int nq = fb_planar_nq(m);
  double *q0 = calloc((size_t)nq, sizeof *q0);
  if (!q0) {
    fb_planar_kin_free(k);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  }
  fb_diag inner;
  rc = fb_planar_position(k, q, 0.0, NULL, &inner);
  if (rc != FB_OK) {
    where->joint = fb_planar_worst_joint(k, q, 0.0, NULL);
    rc = fb_diag_set(diag, rc, "the description does not close: %s", inner.msg);
  }
  memcpy(q0, q, (size_t)nq * sizeof *q);
  double reached;
  fb_path_end end;
  if (rc == FB_OK && (rc = fb_planar_follow(k, q, 0.0, 2.0 * M_PI, &reached, &end, &inner)) != FB_OK) {
    char motion[512];
    singular_motion(motion, sizeof motion, m, q, where);
    rc = fb_diag_set(diag, rc, "the drive ('%s') cannot turn a full revolution: %s%s",
                     m->joint[m->drive].name, inner.msg, motion);
  }
  double by = 0.0;
  const int b = rc == FB_OK ? off_start(m, q, q0, &by) : -1;
  if (b > 0) {
    where->body = b;
    rc = fb_diag_set(diag, FB_ERR_ASSEMBLY,
                     "after one revolution of the drive ('%s') body '%s' is not back at its "
                     "assembly position (%.3g mm away, or turned): the mechanism switched "
                     "assembly branch on the way", m->joint[m->drive].name, m->body[b].name,
                     by * 1e3);
  }
  free(q0);
  fb_planar_kin_free(k);
  return rc;
}

fb_status fb_planar_check_structure(const fb_planar *m, fb_planar_where *where, fb_diag *diag) {
  fb_planar_where none = {-1, -1};
  if (!where) where = &none;
  *where = none;
  const int lone = unconnected(m);
  if (lone > 0) {
    where->body = lone;
    return fb_diag_set(diag, FB_ERR_ARG, "body '%s' is not joined to the ground through the "
                       "joints: every moving body needs a chain of joints to the ground",
                       m->body[lone].name);
  }
  const int f = fb_planar_gruebler(m);
  if (f != 1) {
    const int more = f > 1;
    return fb_diag_set(diag, FB_ERR_ARG,
                       "the mechanism has %d degrees of freedom by the Gruebler-Kutzbach count "
                       "for planar mechanisms, 3 (n - 1) - 2 j = 3 x (%d - 1) - 2 x %d with n "
                       "bodies (the ground included) and j joints (revolute or prismatic); one "
                       "drive moves a mechanism of 1: %s", f, m->nbodies, m->njoints,
                       more ? "a joint is missing (or a body too many): with the drive held it "
                              "could still move"
                            : "it is over-constrained (a joint too many, or a body missing): "
                              "it could not move");
  }
  return FB_OK;
}

fb_status fb_planar_check(const fb_planar *m, fb_planar_where *where, fb_diag *diag) {
  fb_planar_where none = {-1, -1};
  if (!where) where = &none;
  fb_status rc = fb_planar_check_structure(m, where, diag);
  if (rc != FB_OK) return rc;
  const int nq = fb_planar_nq(m);
  double *q = calloc((size_t)nq, sizeof *q);
  if (!q) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  fb_planar_assembly(m, q);
  /* an undriven description (a free start): the rank and the turn are the drive's */
  rc = m->drive < 0 ? FB_OK : check_rank(m, q, where, diag);
  if (rc == FB_OK && m->drive >= 0) rc = check_turn(m, q, where, diag);
  free(q);
  return rc;
}
