/* The dimensions of a planar stack-up (planar_dims.h). */
#include "planar_dims.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "iso2768.h"
#include "planar_case.h"
#include "planar_constraints.h"
#include "planar_kinematics.h"
#include "planar_outputs.h"
#include "planar_path.h"
#include "planar_spec.h"
#include "units.h"

/* revolute points of one body the stack-up keeps: three vary by their
 * distances, a fourth is only counted (to refuse the body) */
#define BODY_POINTS 4

/* An offset this small is a line through its datum [m]: ISO 2768-1's
 * Table 1 starts at 0.5 mm. */
#define OFFSET_MIN_M 0.5e-3

/* An offset below this is a line through its datum written to the last
 * digit, its rest rounding [m]. */
#define NOISE_M 1e-12

/* the distinct revolute points of body b in its frame (at most
 * BODY_POINTS kept; the count returned may exceed it), with one joint at
 * each */
static int body_points(double p[BODY_POINTS][2], int joint[BODY_POINTS], const fb_planar *m,
                       int b) {
  int n = 0;
  for (int j = 0; j < m->njoints; j++)
    for (int s = 0; s < 2; s++) {
      if (m->joint[j].body[s] != b || m->joint[j].kind != FB_KIND_REVOLUTE) continue;
      const double *x = m->joint[j].point[s];
      int seen = 0;
      for (int i = 0; i < n && i < BODY_POINTS; i++)
        seen |= hypot(x[0] - p[i][0], x[1] - p[i][1]) < FB_PLANAR_SAME_POINT_M;
      if (seen) continue;
      if (n < BODY_POINTS) {
        p[n][0] = x[0];
        p[n][1] = x[1];
        joint[n] = j;
      }
      n++;
    }
  return n;
}

/* 1 when body b of n points is a line (planar.h on_one_bar) */
static int line_body(const fb_planar *m, int b, int n) { return n >= 3 && m->body[b].on_one_bar; }

/* the number of body b's distances at n points */
static int body_distances(const fb_planar *m, int b, int n) {
  return line_body(m, b, n) ? n - 1 : n * (n - 1) / 2;
}

/* a line body's frame: its datum d, the first in order of the two points
 * farthest apart, u along the line towards the other, v across it;
 * returns d */
static int line_frame(double u[2], double v[2], double p[BODY_POINTS][2], int n) {
  int d, e;
  const double far = fb_planar_farthest_pair((const double (*)[2])p, n, &d, &e);
  u[0] = (p[e][0] - p[d][0]) / far;
  u[1] = (p[e][1] - p[d][1]) / far;
  v[0] = -u[1];
  v[1] = u[0];
  return d;
}

/* A body's datum in its frame: the point its rebuild keeps and, when it
 * has one, the direction it keeps. */
typedef struct {
  int has_point, has_dir;
  double at[2];  /* [m] */
  double dir[2]; /* unit */
  int joint;     /* the joint at the point; -1 with the ground's +x */
  int dir_joint; /* the joint the direction points to (-1: the ground's +x) */
  double leg;    /* the direction's length between its two points [m]; 0: the ground's */
} datum;

static datum datum_of(const fb_planar *m, int b) {
  double p[BODY_POINTS][2];
  int joint[BODY_POINTS];
  const int n = body_points(p, joint, m, b);
  datum d = {0, 0, {0, 0}, {1, 0}, -1, -1, 0.0};
  if (n < 1 || n > 3) return d;
  int k = 0, e = 1; /* a line's datum and end as its rebuild keeps them (line_frame) */
  if (line_body(m, b, n)) fb_planar_farthest_pair((const double (*)[2])p, n, &k, &e);
  d.has_point = 1;
  d.at[0] = p[k][0], d.at[1] = p[k][1];
  d.joint = joint[k];
  if (b == FB_PLANAR_GROUND) { /* the ground's frame is the world's: lines from +x */
    d.has_dir = 1;
    return d;
  }
  if (n < 2) return d;
  d.leg = hypot(p[e][0] - p[k][0], p[e][1] - p[k][1]);
  d.dir[0] = (p[e][0] - p[k][0]) / d.leg, d.dir[1] = (p[e][1] - p[k][1]) / d.leg;
  d.has_dir = 1;
  d.dir_joint = joint[e];
  return d;
}

/* prismatic joint j's guide (its side and body), the line's point and
 * direction in the guide's frame */
static int guide_line(double P[2], double a[2], const fb_planar *m, int j) {
  const fb_planar_joint *J = &m->joint[j];
  const int side = fb_planar_guide_side(J->body[0], J->body[1]);
  const int g = J->body[side];
  P[0] = J->point[side][0], P[1] = J->point[side][1];
  fb_planar_rotate(a, m->body[J->body[0]].angle0 - m->body[g].angle0, J->axis);
  return side;
}

/* the line's offset from datum d, signed (across a, to the left) [m] */
static double signed_offset(const datum *d, const double P[2], const double a[2]) {
  return (P[0] - d->at[0]) * -a[1] + (P[1] - d->at[1]) * a[0];
}

/* the line's angle from d's direction, in [0, pi) [rad] */
static double line_angle(const datum *d, const double a[2]) {
  double t = atan2(d->dir[0] * a[1] - d->dir[1] * a[0], d->dir[0] * a[0] + d->dir[1] * a[1]);
  if (t < 0.0) t += M_PI;          /* a line has no sense: [0, pi] */
  if (t > M_PI - 1e-12) t -= M_PI; /* and pi is 0 */
  return fabs(t) < 1e-15 ? 0.0 : t;
}

/* 1 when joint j is prismatic and body b guides it (fb_planar_guide_side) */
static int guides(const fb_planar *m, int b, int j) {
  const fb_planar_joint *J = &m->joint[j];
  return J->kind == FB_KIND_PRISMATIC && J->body[fb_planar_guide_side(J->body[0], J->body[1])] == b;
}

/* the number of dimensions of body b's lines (offsets and angles) */
static int line_dims(const fb_planar *m, int b) {
  const datum d = datum_of(m, b);
  int count = 0;
  for (int j = 0; j < m->njoints; j++)
    if (guides(m, b, j)) count += d.has_point + (d.has_point && d.has_dir);
  return count;
}

int fb_planar_dims_count(const fb_planar *m) {
  int count = 0;
  for (int b = 0; b < m->nbodies; b++) {
    double p[BODY_POINTS][2];
    int joint[BODY_POINTS];
    count += body_distances(m, b, body_points(p, joint, m, b)) + line_dims(m, b);
  }
  return count;
}

/* the range error of dimension L on body b, named */
static fb_status named(fb_diag *diag, const fb_planar *m, const fb_planar_length *L,
                       const fb_diag *inner) {
  const char *what = L->kind == FB_PLANAR_DIM_DISTANCE ? "distance"
                     : L->kind == FB_PLANAR_DIM_OFFSET ? "offset of the line of"
                                                       : "angle of the line of";
  return fb_diag_set(diag, FB_ERR_RANGE, "body '%s', %s '%s' from '%s': %s",
                     m->body[L->body].name, what, m->joint[L->joint[1]].name,
                     L->joint[0] >= 0 ? m->joint[L->joint[0]].name : "+x", inner->msg);
}

/* body b's lines' dimensions from out (n filled so far) */
static fb_status lines_of(fb_planar_length *out, int *n, const fb_planar *m, int b, char cls,
                          const double *travel, fb_diag *diag) {
  const datum d = datum_of(m, b);
  if (!d.has_point) return FB_OK;
  fb_diag inner;
  for (int j = 0; j < m->njoints; j++) {
    if (!guides(m, b, j)) continue;
    double P[2], a[2];
    guide_line(P, a, m, j);
    fb_planar_length *L = &out[(*n)++];
    *L = (fb_planar_length){FB_PLANAR_DIM_OFFSET, b, {d.joint, j}, 0, 0, FB_PLANAR_SENS_STEP, ""};
    L->nominal = fabs(signed_offset(&d, P, a));
    if (L->nominal < NOISE_M) L->nominal = 0.0;
    if (L->nominal < OFFSET_MIN_M)
      snprintf(L->source, sizeof L->source, "none: a line through its datum (ISO 2768-1 starts "
               "at 0.5 mm)");
    else if (fb_iso2768_linear(&L->plus_minus, cls, L->nominal, L->source, sizeof L->source,
                               &inner) != FB_OK)
      return named(diag, m, L, &inner);
    if (!d.has_dir) continue;
    const double t = travel ? travel[j] : 0.0;
    const double leg = d.leg > 0.0 && (t <= 0.0 || d.leg < t) ? d.leg : t > 0.0 ? t : 1e-3;
    L = &out[(*n)++];
    *L = (fb_planar_length){FB_PLANAR_DIM_ANGLE, b, {d.dir_joint, j}, line_angle(&d, a), 0,
                            FB_PLANAR_SENS_STEP / leg, ""};
    if (fb_iso2768_angular(&L->plus_minus, cls, leg, L->source, sizeof L->source, &inner) != FB_OK)
      return named(diag, m, L, &inner);
  }
  return FB_OK;
}

fb_status fb_planar_dims(fb_planar_length *out, int *n, const fb_planar *m, char cls,
                         const double *travel, fb_diag *diag) {
  *n = 0;
  for (int b = 0; b < m->nbodies; b++) {
    double p[BODY_POINTS][2];
    int joint[BODY_POINTS];
    const int np = body_points(p, joint, m, b);
    if (np > 3)
      return fb_diag_set(diag, FB_ERR_ARG, "body '%s' has %d distinct revolute joint points: "
                         "their distances over-determine it, and the stack-up varies bodies of 2 "
                         "or 3 points", m->body[b].name, np);
    const int line = line_body(m, b, np);
    double u[2] = {1.0, 0.0}, v[2];
    const int d = line ? line_frame(u, v, p, np) : 0;
    for (int i = 0; i < np; i++)
      for (int k = i + 1; k < np; k++) {
        if (line && i != d && k != d) continue; /* a line's distances: from its datum */
        fb_planar_length *L = &out[(*n)++];
        *L = (fb_planar_length){FB_PLANAR_DIM_DISTANCE, b, {joint[i], joint[k]}, 0, 0,
                                FB_PLANAR_SENS_STEP, ""};
        L->nominal = line ? fabs((p[k][0] - p[i][0]) * u[0] + (p[k][1] - p[i][1]) * u[1])
                          : hypot(p[k][0] - p[i][0], p[k][1] - p[i][1]);
        fb_diag inner;
        if (fb_iso2768_linear(&L->plus_minus, cls, L->nominal, L->source, sizeof L->source,
                              &inner) != FB_OK)
          return fb_diag_set(diag, FB_ERR_RANGE, "body '%s', '%s' to '%s' (%.6g mm): %s",
                             m->body[b].name, m->joint[joint[i]].name, m->joint[joint[k]].name,
                             L->nominal / FB_M_PER_MM, inner.msg);
      }
    const fb_status st = lines_of(out, n, m, b, cls, travel, diag);
    if (st != FB_OK) return st;
  }
  return FB_OK;
}

/* body b's points rebuilt from its distances len: the first stays, the
 * second along the nominal direction, the third on the nominal side of
 * the first two; a line body's datum stays and each other point is at its
 * length along the line from it, on its nominal side, its small offset
 * across the line kept. Returns 0 when the three lengths of a triangle do
 * not close one (a length longer than the other two's sum), else 1. */
static int rebuild(double q[3][2], double p[BODY_POINTS][2], int n, int line, const double *len) {
  memcpy(q, p, (size_t)n * sizeof q[0]);
  if (line) {
    double u[2], v[2];
    const int d = line_frame(u, v, p, n);
    for (int k = 0, at = 0; k < n; k++) {
      if (k == d) continue;
      const double dx = p[k][0] - p[d][0], dy = p[k][1] - p[d][1];
      const double along = dx * u[0] + dy * u[1], across = dx * v[0] + dy * v[1];
      const double l = along >= 0.0 ? len[at] : -len[at];
      at++;
      q[k][0] = p[d][0] + l * u[0] + across * v[0];
      q[k][1] = p[d][1] + l * u[1] + across * v[1];
    }
    return 1;
  }
  if (n < 2) return 1;
  const double d01 = hypot(p[1][0] - p[0][0], p[1][1] - p[0][1]);
  const double u[2] = {(p[1][0] - p[0][0]) / d01, (p[1][1] - p[0][1]) / d01};
  q[1][0] = p[0][0] + len[0] * u[0];
  q[1][1] = p[0][1] + len[0] * u[1];
  if (n < 3) return 1;
  const double l02 = len[1], l12 = len[2], d = len[0];
  const double a = (l02 * l02 - l12 * l12 + d * d) / (2.0 * d);
  const double h2 = l02 * l02 - a * a;
  if (h2 < 0.0) return 0; /* no triangle: never clamped to a flat one */
  const double h = sqrt(h2);
  const double side = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) -
                      (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
  const double sg = side >= 0.0 ? 1.0 : -1.0;
  q[2][0] = q[0][0] + a * u[0] - sg * h * u[1];
  q[2][1] = q[0][1] + a * u[1] + sg * h * u[0];
  return 1;
}

/* prismatic joint j's line in copy x placed at offset off (>= 0, on its
 * nominal side) and turned by turn [rad] about the datum point of m's
 * guide body */
static void place_line(fb_planar *x, const fb_planar *m, int j, double off, double turn) {
  double P[2], a[2];
  const int side = guide_line(P, a, m, j);
  const datum d = datum_of(m, m->joint[j].body[side]);
  const double off0 = signed_offset(&d, P, a);
  const double along = (P[0] - d.at[0]) * a[0] + (P[1] - d.at[1]) * a[1];
  const double s = off0 < 0.0 ? -off : off;
  double a1[2];
  fb_planar_rotate(a1, turn, a);
  x->joint[j].point[side][0] = d.at[0] + along * a1[0] - s * a1[1];
  x->joint[j].point[side][1] = d.at[1] + along * a1[1] + s * a1[0];
  fb_planar_rotate(x->joint[j].axis, turn, m->joint[j].axis);
}

fb_planar *fb_planar_dims_apply(const fb_planar *m, const fb_planar_length *dim, int n,
                                const double *len, int *open) {
  *open = -1;
  fb_planar *x = fb_planar_new(m->nbodies - 1, m->njoints);
  if (!x) return NULL;
  memcpy(x->body, m->body, (size_t)m->nbodies * sizeof *m->body);
  memcpy(x->joint, m->joint, (size_t)m->njoints * sizeof *m->joint);
  x->nbodies = m->nbodies;
  x->njoints = m->njoints;
  x->drive = m->drive;
  for (int b = 0, at = 0; b < m->nbodies; b++) {
    double p[BODY_POINTS][2], q[3][2];
    int joint[BODY_POINTS];
    const int np = body_points(p, joint, m, b);
    if (!rebuild(q, p, np, line_body(m, b, np), len + at) && *open < 0) *open = b;
    at += body_distances(m, b, np) + line_dims(m, b);
    for (int j = 0; j < m->njoints; j++)
      for (int side = 0; side < 2; side++) {
        const fb_planar_joint *J = &m->joint[j];
        if (J->body[side] != b) continue;
        if (J->kind == FB_KIND_PRISMATIC && side == fb_planar_guide_side(J->body[0], J->body[1]))
          continue; /* a line: placed by its offset and angle below */
        for (int i = 0; i < np; i++)
          if (hypot(J->point[side][0] - p[i][0], J->point[side][1] - p[i][1]) <
              FB_PLANAR_SAME_POINT_M) {
            x->joint[j].point[side][0] = q[i][0];
            x->joint[j].point[side][1] = q[i][1];
          }
      }
  }
  for (int k = 0; k < n; k++) {
    if (dim[k].kind != FB_PLANAR_DIM_OFFSET) continue;
    const int turn = k + 1 < n && dim[k + 1].kind == FB_PLANAR_DIM_ANGLE;
    place_line(x, m, dim[k].joint[1], len[k], turn ? len[k + 1] - dim[k + 1].nominal : 0.0);
  }
  return x;
}

void fb_planar_dims_at(double *len, const fb_planar_length *dim, int n, const char *at) {
  for (int k = 0; k < n; k++)
    len[k] = dim[k].nominal +
             (at[k] == '+' ? 1.0 : at[k] == '-' ? -1.0 : 0.0) * dim[k].plus_minus;
}

/* fb_planar_quantity of the slides' positions: index i is slide i's
 * (planar_outputs.h's row: 3 per slide after the points' 6) */
static double slide_position(const fb_planar *m, const double *q, const double *qd,
                             const double *qdd, const double *w1, int i, void *ctx) {
  (void)w1;
  double *row = ctx;
  fb_planar_outputs(row, m, q, qd, qdd);
  return row[FB_PLANAR_POINT_QUANTITIES * m->npoints + 3 * i];
}

fb_status fb_planar_slide_travel(double *travel, const fb_planar *m, double omega,
                                 fb_diag *diag) {
  for (int j = 0; j < m->njoints; j++) travel[j] = 0.0;
  const int ns = fb_planar_slide_count(m);
  if (m->drive < 0 || ns == 0) return FB_OK;
  fb_planar_kin *k;
  fb_status st = fb_planar_kin_new(&k, m, diag);
  if (st != FB_OK) return st;
  double *row = malloc(((size_t)fb_planar_output_count(m) + 1) * sizeof *row);
  fb_planar_extreme *e = malloc((size_t)ns * sizeof *e);
  st = row && e ? fb_planar_extremes_of(e, ns, slide_position, row, k, omega, diag)
                : fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  for (int j = 0, s = 0; st == FB_OK && j < m->njoints; j++)
    if (m->joint[j].kind == FB_KIND_PRISMATIC) travel[j] = e[s].max - e[s].min, s++;
  free(row);
  free(e);
  fb_planar_kin_free(k);
  return st;
}

fb_status fb_planar_dims_toleranced(fb_planar_length **out, int *n, const fb_planar *m, char cls,
                                    double omega, fb_diag *diag) {
  *n = 0;
  const int count = fb_planar_dims_count(m);
  *out = calloc(count ? (size_t)count : 1, sizeof **out);
  double *travel = calloc((size_t)m->njoints + 1, sizeof *travel);
  fb_status st = *out && travel ? fb_planar_slide_travel(travel, m, omega, diag)
                                : fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  if (st == FB_OK) st = fb_planar_dims(*out, n, m, cls, travel, diag);
  free(travel);
  if (st != FB_OK) {
    free(*out);
    *out = NULL;
    *n = 0;
  }
  return st;
}

/* what fb_planar_dims_apply does not carry: x takes m's output points,
 * springs, loads and torque drive (each in its body's frame, as m's);
 * 0 out of memory */
static int copy_rest(fb_planar *x, const fb_planar *m) {
  x->torque_joint = m->torque_joint;
  x->drive_torque = m->drive_torque;
  if (m->npoints && !(x->point = malloc((size_t)m->npoints * sizeof *x->point))) return 0;
  if (m->nsprings && !(x->spring = malloc((size_t)m->nsprings * sizeof *x->spring))) return 0;
  if (m->nloads && !(x->load = malloc((size_t)m->nloads * sizeof *x->load))) return 0;
  if (m->npoints) memcpy(x->point, m->point, (size_t)m->npoints * sizeof *x->point);
  if (m->nsprings) memcpy(x->spring, m->spring, (size_t)m->nsprings * sizeof *x->spring);
  if (m->nloads) memcpy(x->load, m->load, (size_t)m->nloads * sizeof *x->load);
  x->npoints = m->npoints;
  x->nsprings = m->nsprings;
  x->nloads = m->nloads;
  return 1;
}

fb_status fb_planar_dims_corner(fb_planar **out, const fb_planar *m, char cls, double omega,
                                const char *at, fb_diag *diag) {
  *out = NULL;
  fb_planar_length *dim;
  int n;
  fb_status st = fb_planar_dims_toleranced(&dim, &n, m, cls, omega, diag);
  if (st != FB_OK) return st;
  if ((int)strlen(at) != n) {
    free(dim);
    return fb_diag_set(diag, FB_ERR_ARG, "[tolerance] stackup = '%s': %d signs for the "
                       "description's %d dimensions (fourbar stackup lists them in order)",
                       at, (int)strlen(at), n);
  }
  double *len = malloc((n ? (size_t)n : 1) * sizeof *len);
  if (!len) {
    free(dim);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  }
  fb_planar_dims_at(len, dim, n, at);
  int open;
  *out = fb_planar_dims_apply(m, dim, n, len, &open);
  if (*out && (open >= 0 || !copy_rest(*out, m))) {
    fb_planar_free(*out);
    *out = NULL;
  }
  if (open < 0) st = *out ? FB_OK : fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  else
    st = fb_diag_set(diag, FB_ERR_ASSEMBLY, "[tolerance] stackup = '%s': body '%s': its three "
                     "joint distances close no triangle (one is longer than the other two "
                     "together)", at, m->body[open].name);
  free(len);
  free(dim);
  return st;
}
