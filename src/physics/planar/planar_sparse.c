/* The square constraint set in sparse form (planar_sparse.h). */
#include "planar_sparse.h"

#include <math.h>

void fb_planar_sq_angle_bodies(const fb_planar *m, int aj, int *from, int *to) {
  const fb_planar_joint *j = &m->joint[aj];
  const int swap = j->body[1] == FB_PLANAR_GROUND;
  *from = j->body[swap ? 1 : 0];
  *to = j->body[swap ? 0 : 1];
}

/* body b's column c (0: x, 1: y, 2: theta), -1 for the ground */
static int col_of(int b, int c) { return b ? 3 * (b - 1) + c : -1; }

/* The entries of every row, in one walk: the pattern (row, col not NULL)
 * or the values (val not NULL, at q with trig cs). The order is the
 * pattern's: joint by joint, each row's entries body[0] then body[1], the
 * angle row last. */
static int walk(const fb_planar *m, int aj, int *row, int *col, double *val, const double *q,
                const double *cs, int only) {
  int e = 0;
#define PUT(r, b, c, v)                                                                         \
  do {                                                                                          \
    if ((b) != 0) {                                                                             \
      if (row) row[e] = (r), col[e] = col_of((b), (c));                                         \
      if (val) val[e] = (v);                                                                    \
      e++;                                                                                      \
    }                                                                                           \
  } while (0)
  for (int j = only >= 0 ? only : 0; j < (only >= 0 ? only + 1 : m->njoints); j++) {
    const fb_planar_joint *jt = &m->joint[j];
    const int i = jt->body[0], k = jt->body[1], r = 2 * j;
    double ai[2] = {0, 0}, ak[2] = {0, 0};
    if (val) {
      const double *ci = cs + 2 * i, *ck = cs + 2 * k;
      ai[0] = ci[0] * jt->point[0][0] - ci[1] * jt->point[0][1];
      ai[1] = ci[1] * jt->point[0][0] + ci[0] * jt->point[0][1];
      ak[0] = ck[0] * jt->point[1][0] - ck[1] * jt->point[1][1];
      ak[1] = ck[1] * jt->point[1][0] + ck[0] * jt->point[1][1];
    }
    if (jt->kind != FB_KIND_PRISMATIC) {
      PUT(r, i, 0, 1.0);
      PUT(r, i, 2, -ai[1]);
      PUT(r, k, 0, -1.0);
      PUT(r, k, 2, ak[1]);
      PUT(r + 1, i, 1, 1.0);
      PUT(r + 1, i, 2, ai[0]);
      PUT(r + 1, k, 1, -1.0);
      PUT(r + 1, k, 2, -ak[0]);
      continue;
    }
    double n[2] = {0, 0}, d[2] = {0, 0};
    if (val) {
      const double *ci = cs + 2 * i;
      const double nb[2] = {-jt->axis[1], jt->axis[0]};
      n[0] = ci[0] * nb[0] - ci[1] * nb[1];
      n[1] = ci[1] * nb[0] + ci[0] * nb[1];
      const double ri[2] = {i ? q[3 * (i - 1)] : 0.0, i ? q[3 * (i - 1) + 1] : 0.0};
      const double rk[2] = {k ? q[3 * (k - 1)] : 0.0, k ? q[3 * (k - 1) + 1] : 0.0};
      d[0] = rk[0] + ak[0] - ri[0] - ai[0];
      d[1] = rk[1] + ak[1] - ri[1] - ai[1];
    }
    const double pn[2] = {-n[1], n[0]};
    PUT(r, i, 2, -1.0);
    PUT(r, k, 2, 1.0);
    PUT(r + 1, i, 0, -n[0]);
    PUT(r + 1, i, 1, -n[1]);
    PUT(r + 1, i, 2, pn[0] * d[0] + pn[1] * d[1] - (n[0] * -ai[1] + n[1] * ai[0]));
    PUT(r + 1, k, 0, n[0]);
    PUT(r + 1, k, 1, n[1]);
    PUT(r + 1, k, 2, n[0] * -ak[1] + n[1] * ak[0]);
  }
  if (only >= 0) return e;
  int from, to;
  fb_planar_sq_angle_bodies(m, aj, &from, &to);
  PUT(2 * m->njoints, from, 2, -1.0);
  PUT(2 * m->njoints, to, 2, 1.0);
#undef PUT
  return e;
}

int fb_planar_sq_nnz(const fb_planar *m, int aj) {
  return walk(m, aj, NULL, NULL, NULL, NULL, NULL, -1);
}

void fb_planar_sq_pattern(const fb_planar *m, int aj, int *row, int *col) {
  walk(m, aj, row, col, NULL, NULL, NULL, -1);
}

void fb_planar_sq_values(double *val, const fb_planar *m, int aj, const double *q,
                         const double *cs) {
  double *v = val;
  for (int j = 0; j < m->njoints; j++) {
    const fb_planar_joint *jt = &m->joint[j];
    const int i = jt->body[0], k = jt->body[1];
    const double *ci = cs + 2 * i, *ck = cs + 2 * k;
    const double ai[2] = {ci[0] * jt->point[0][0] - ci[1] * jt->point[0][1],
                          ci[1] * jt->point[0][0] + ci[0] * jt->point[0][1]};
    const double ak[2] = {ck[0] * jt->point[1][0] - ck[1] * jt->point[1][1],
                          ck[1] * jt->point[1][0] + ck[0] * jt->point[1][1]};
    if (jt->kind != FB_KIND_PRISMATIC) { /* walk's order: row x (i, k), row y (i, k) */
      if (i) *v++ = 1.0, *v++ = -ai[1];
      if (k) *v++ = -1.0, *v++ = ak[1];
      if (i) *v++ = 1.0, *v++ = ai[0];
      if (k) *v++ = -1.0, *v++ = -ak[0];
      continue;
    }
    v += walk(m, aj, NULL, NULL, v, q, cs, j);
  }
  int from, to;
  fb_planar_sq_angle_bodies(m, aj, &from, &to);
  if (from) *v++ = -1.0;
  if (to) *v++ = 1.0;
}

void fb_planar_sq_trig(double *cs, const fb_planar *m, const double *q) {
  cs[0] = 1.0;
  cs[1] = 0.0;
  for (int b = 1; b < m->nbodies; b++) {
    const double t = q[3 * (b - 1) + 2];
    cs[2 * b] = cos(t);
    cs[2 * b + 1] = sin(t);
  }
}

/* A s of body b (cs its trig) into out */
static void rot(double out[2], const double *cs, int b, const double s[2]) {
  const double c = cs[2 * b], sn = cs[2 * b + 1];
  out[0] = c * s[0] - sn * s[1];
  out[1] = sn * s[0] + c * s[1];
}

static double pos_of(const double *q, int b, int c) { return b ? q[3 * (b - 1) + c] : 0.0; }

void fb_planar_sq_joint_phi(double out[2], const fb_planar *m, int j, const double *q,
                            const double *cs) {
  const fb_planar_joint *jt = &m->joint[j];
  const int i = jt->body[0], k = jt->body[1];
  double ai[2], ak[2];
  rot(ai, cs, i, jt->point[0]);
  rot(ak, cs, k, jt->point[1]);
  const double d[2] = {pos_of(q, k, 0) + ak[0] - pos_of(q, i, 0) - ai[0],
                       pos_of(q, k, 1) + ak[1] - pos_of(q, i, 1) - ai[1]};
  if (jt->kind != FB_KIND_PRISMATIC) {
    out[0] = -d[0];
    out[1] = -d[1];
    return;
  }
  double n[2];
  const double nb[2] = {-jt->axis[1], jt->axis[0]};
  rot(n, cs, i, nb);
  out[0] = pos_of(q, k, 2) - pos_of(q, i, 2) - (m->body[k].angle0 - m->body[i].angle0);
  out[1] = n[0] * d[0] + n[1] * d[1];
}

void fb_planar_sq_joint_apply(double out[2], const fb_planar *m, int j, const double *q,
                              const double *cs, const double *x) {
  const fb_planar_joint *jt = &m->joint[j];
  const int i = jt->body[0], k = jt->body[1];
  double ai[2], ak[2];
  rot(ai, cs, i, jt->point[0]);
  rot(ak, cs, k, jt->point[1]);
  const double wi = pos_of(x, i, 2), wk = pos_of(x, k, 2);
  /* the points' rates x + w perp(A s) */
  const double vi[2] = {pos_of(x, i, 0) - wi * ai[1], pos_of(x, i, 1) + wi * ai[0]};
  const double vk[2] = {pos_of(x, k, 0) - wk * ak[1], pos_of(x, k, 1) + wk * ak[0]};
  if (jt->kind != FB_KIND_PRISMATIC) {
    out[0] = vi[0] - vk[0];
    out[1] = vi[1] - vk[1];
    return;
  }
  double n[2];
  const double nb[2] = {-jt->axis[1], jt->axis[0]};
  rot(n, cs, i, nb);
  const double d[2] = {pos_of(q, k, 0) + ak[0] - pos_of(q, i, 0) - ai[0],
                       pos_of(q, k, 1) + ak[1] - pos_of(q, i, 1) - ai[1]};
  out[0] = wk - wi;
  out[1] = n[0] * (vk[0] - vi[0]) + n[1] * (vk[1] - vi[1]) + wi * (-n[1] * d[0] + n[0] * d[1]);
}

void fb_planar_sq_joint_gamma(double out[2], const fb_planar *m, int j, const double *q,
                              const double *qd, const double *cs) {
  const fb_planar_joint *jt = &m->joint[j];
  const int i = jt->body[0], k = jt->body[1];
  double ai[2], ak[2];
  rot(ai, cs, i, jt->point[0]);
  rot(ak, cs, k, jt->point[1]);
  const double wi = pos_of(qd, i, 2), wk = pos_of(qd, k, 2);
  if (jt->kind != FB_KIND_PRISMATIC) {
    out[0] = ai[0] * wi * wi - ak[0] * wk * wk;
    out[1] = ai[1] * wi * wi - ak[1] * wk * wk;
    return;
  }
  double n[2];
  const double nb[2] = {-jt->axis[1], jt->axis[0]};
  rot(n, cs, i, nb);
  const double pn[2] = {-n[1], n[0]};
  const double d[2] = {pos_of(q, k, 0) + ak[0] - pos_of(q, i, 0) - ai[0],
                       pos_of(q, k, 1) + ak[1] - pos_of(q, i, 1) - ai[1]};
  /* the points' velocities r' + w perp(A s) */
  const double vi[2] = {pos_of(qd, i, 0) - wi * ai[1], pos_of(qd, i, 1) + wi * ai[0]};
  const double vk[2] = {pos_of(qd, k, 0) - wk * ak[1], pos_of(qd, k, 1) + wk * ak[0]};
  const double dd[2] = {vk[0] - vi[0], vk[1] - vi[1]};
  out[0] = 0.0;
  out[1] = (n[0] * d[0] + n[1] * d[1]) * wi * wi - 2.0 * wi * (pn[0] * dd[0] + pn[1] * dd[1]) +
           n[0] * (ak[0] * wk * wk - ai[0] * wi * wi) + n[1] * (ak[1] * wk * wk - ai[1] * wi * wi);
}

void fb_planar_sq_phi(double *phi, const fb_planar *m, int aj, const double *q, const double *cs) {
  for (int j = 0; j < m->njoints; j++) fb_planar_sq_joint_phi(phi + 2 * j, m, j, q, cs);
  int from, to;
  fb_planar_sq_angle_bodies(m, aj, &from, &to);
  phi[2 * m->njoints] = pos_of(q, to, 2) - pos_of(q, from, 2) -
                        (m->body[to].angle0 - m->body[from].angle0);
}

void fb_planar_sq_gamma(double *gamma, const fb_planar *m, int aj, const double *q,
                        const double *qd, const double *cs) {
  (void)aj;
  for (int j = 0; j < m->njoints; j++) fb_planar_sq_joint_gamma(gamma + 2 * j, m, j, q, qd, cs);
  gamma[2 * m->njoints] = 0.0;
}
