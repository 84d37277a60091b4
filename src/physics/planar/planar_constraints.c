/* The constraint equations, their Jacobian and gamma (planar_constraints.h). */
#include "planar_constraints.h"

#include <math.h>
#include <string.h>

int fb_planar_rows(const fb_planar *m, const unsigned char *off, int with_drive) {
  int rows = with_drive ? 1 : 0;
  for (int j = 0; j < m->njoints; j++)
    if (!off || !off[j]) rows += 2;
  return rows;
}

double fb_planar_angle(const double *q, int b) { return b ? q[3 * (b - 1) + 2] : 0.0; }

static double rate_of(const double *qd, int b) { return b ? qd[3 * (b - 1) + 2] : 0.0; }

/* out = [c -sn; sn c] s, the one formula of a rotation */
static void turn(double out[2], double c, double sn, const double s[2]) {
  out[0] = c * s[0] - sn * s[1];
  out[1] = sn * s[0] + c * s[1];
}

void fb_planar_rotate(double out[2], double theta, const double s[2]) {
  turn(out, cos(theta), sin(theta), s);
}

void fb_planar_rotation(double cs[2], const double *q, int b) {
  const double a = fb_planar_angle(q, b);
  cs[0] = b ? cos(a) : 1.0; /* the ground's: cos 0, sin 0 exactly */
  cs[1] = b ? sin(a) : 0.0;
}

void fb_planar_point_at(double out[2], const double *q, int b, const double s[2],
                        const double cs[2]) {
  double as[2];
  turn(as, cs[0], cs[1], s);
  out[0] = as[0] + (b ? q[3 * (b - 1)] : 0.0);
  out[1] = as[1] + (b ? q[3 * (b - 1) + 1] : 0.0);
}

void fb_planar_point(double out[2], const fb_planar *m, const double *q, int b,
                     const double s[2]) {
  (void)m;
  double cs[2];
  fb_planar_rotation(cs, q, b);
  fb_planar_point_at(out, q, b, s, cs);
}

void fb_planar_point_velocity(double out[2], const fb_planar *m, const double *q,
                              const double *qd, int b, const double s[2]) {
  (void)m;
  out[0] = out[1] = 0.0;
  if (!b) return;
  double as[2];
  fb_planar_rotate(as, fb_planar_angle(q, b), s);
  const double w = qd[3 * (b - 1) + 2];
  out[0] = qd[3 * (b - 1)] - w * as[1];
  out[1] = qd[3 * (b - 1) + 1] + w * as[0];
}

void fb_planar_point_motion(double x[2], double v[2], const fb_planar *m, const double *q,
                            const double *qd, int b, const double s[2]) {
  (void)m;
  double cs[2];
  fb_planar_rotation(cs, q, b);
  fb_planar_point_motion_at(x, v, q, qd, b, s, cs);
}

void fb_planar_point_motion_at(double x[2], double v[2], const double *q, const double *qd,
                               int b, const double s[2], const double cs[2]) {
  double as[2];
  turn(as, cs[0], cs[1], s);
  x[0] = as[0] + (b ? q[3 * (b - 1)] : 0.0);
  x[1] = as[1] + (b ? q[3 * (b - 1) + 1] : 0.0);
  const double w = b ? qd[3 * (b - 1) + 2] : 0.0;
  v[0] = b ? qd[3 * (b - 1)] - w * as[1] : 0.0;
  v[1] = b ? qd[3 * (b - 1) + 1] + w * as[0] : 0.0;
}

void fb_planar_point_jacobian(double *rows, const fb_planar *m, const double *q, int b,
                              const double s[2], double sign) {
  if (!b) return;
  const int nq = fb_planar_nq(m), c = 3 * (b - 1);
  double as[2];
  fb_planar_rotate(as, fb_planar_angle(q, b), s);
  rows[c] += sign;
  rows[c + 2] += -sign * as[1];
  rows[nq + c + 1] += sign;
  rows[nq + c + 2] += sign * as[0];
}

/* adds v to row r's angle column of body b */
static void add_angle(double *jac, int nq, int r, int b, double v) {
  if (b) jac[r * nq + 3 * (b - 1) + 2] += v;
}

/* a revolute joint's two rows from row r */
static void revolute(double *phi, double *jac, double *gamma, int r, const fb_planar *m,
                     const fb_planar_joint *j, const double *q, const double *qd) {
  const int nq = fb_planar_nq(m);
  const int i = j->body[0], k = j->body[1];
  if (phi) {
    double pi[2], pk[2];
    fb_planar_point(pi, m, q, i, j->point[0]);
    fb_planar_point(pk, m, q, k, j->point[1]);
    phi[r] = pi[0] - pk[0];
    phi[r + 1] = pi[1] - pk[1];
  }
  if (jac) {
    fb_planar_point_jacobian(jac + r * nq, m, q, i, j->point[0], 1.0);
    fb_planar_point_jacobian(jac + r * nq, m, q, k, j->point[1], -1.0);
  }
  if (gamma) {
    double ai[2], ak[2];
    fb_planar_rotate(ai, fb_planar_angle(q, i), j->point[0]);
    fb_planar_rotate(ak, fb_planar_angle(q, k), j->point[1]);
    const double wi = rate_of(qd, i), wk = rate_of(qd, k);
    gamma[r] = ai[0] * wi * wi - ak[0] * wk * wk;
    gamma[r + 1] = ai[1] * wi * wi - ak[1] * wk * wk;
  }
}

/* a prismatic joint's two rows from row r */
static void prismatic(double *phi, double *jac, double *gamma, int r, const fb_planar *m,
                      const fb_planar_joint *j, const double *q, const double *qd) {
  const int nq = fb_planar_nq(m);
  const int i = j->body[0], k = j->body[1];
  const double ti = fb_planar_angle(q, i), tk = fb_planar_angle(q, k);
  double pi[2], pk[2], ai[2], ak[2], n[2];
  fb_planar_point(pi, m, q, i, j->point[0]);
  fb_planar_point(pk, m, q, k, j->point[1]);
  fb_planar_rotate(ai, ti, j->point[0]);
  fb_planar_rotate(ak, tk, j->point[1]);
  const double nb[2] = {-j->axis[1], j->axis[0]};
  fb_planar_rotate(n, ti, nb);
  const double d[2] = {pk[0] - pi[0], pk[1] - pi[1]};
  const double pn[2] = {-n[1], n[0]};
  if (phi) {
    phi[r] = tk - ti - (m->body[k].angle0 - m->body[i].angle0);
    phi[r + 1] = n[0] * d[0] + n[1] * d[1];
  }
  if (jac) {
    add_angle(jac, nq, r, k, 1.0);
    add_angle(jac, nq, r, i, -1.0);
    double *row = jac + (r + 1) * nq;
    if (i) {
      const int c = 3 * (i - 1);
      row[c] -= n[0];
      row[c + 1] -= n[1];
      /* d n / d theta_i = perp(n); d p_i / d theta_i = perp(A_i s_i) */
      row[c + 2] += pn[0] * d[0] + pn[1] * d[1] - (n[0] * -ai[1] + n[1] * ai[0]);
    }
    if (k) {
      const int c = 3 * (k - 1);
      row[c] += n[0];
      row[c + 1] += n[1];
      row[c + 2] += n[0] * -ak[1] + n[1] * ak[0];
    }
  }
  if (gamma) {
    const double wi = rate_of(qd, i), wk = rate_of(qd, k);
    double vi[2], vk[2];
    fb_planar_point_velocity(vi, m, q, qd, i, j->point[0]);
    fb_planar_point_velocity(vk, m, q, qd, k, j->point[1]);
    const double dd[2] = {vk[0] - vi[0], vk[1] - vi[1]};
    gamma[r] = 0.0;
    gamma[r + 1] = (n[0] * d[0] + n[1] * d[1]) * wi * wi - 2.0 * wi * (pn[0] * dd[0] + pn[1] * dd[1]) +
                   n[0] * (ak[0] * wk * wk - ai[0] * wi * wi) + n[1] * (ak[1] * wk * wk - ai[1] * wi * wi);
  }
}

void fb_planar_constraints(double *phi, double *jac, double *gamma, const fb_planar *m,
                           const unsigned char *off, const fb_planar_drive *drive,
                           const double *q, const double *qd) {
  const int nq = fb_planar_nq(m);
  const int rows = fb_planar_rows(m, off, drive != NULL);
  if (jac) memset(jac, 0, (size_t)rows * (size_t)nq * sizeof *jac);
  int r = 0;
  for (int j = 0; j < m->njoints; j++) {
    if (off && off[j]) continue;
    if (m->joint[j].kind == FB_KIND_PRISMATIC)
      prismatic(phi, jac, gamma, r, m, &m->joint[j], q, qd);
    else
      revolute(phi, jac, gamma, r, m, &m->joint[j], q, qd);
    r += 2;
  }
  if (!drive) return;
  int from, to;
  fb_planar_drive_bodies(m, &from, &to);
  if (phi)
    phi[r] = fb_planar_angle(q, to) - fb_planar_angle(q, from) - (m->body[to].angle0 - m->body[from].angle0) -
             drive->angle;
  if (jac) {
    add_angle(jac, nq, r, to, 1.0);
    add_angle(jac, nq, r, from, -1.0);
  }
  if (gamma) gamma[r] = drive->alpha;
}

void fb_planar_add_force(double *force, const double *q, int b, const double p[2],
                         const double f[2]) {
  if (!b) return;
  const int c = 3 * (b - 1);
  force[c] += f[0];
  force[c + 1] += f[1];
  force[c + 2] += (p[0] - q[c]) * f[1] - (p[1] - q[c + 1]) * f[0];
}
