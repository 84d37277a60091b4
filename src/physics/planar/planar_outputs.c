/* Output points' and slides' motion (planar_outputs.h). */
#include "planar_outputs.h"

#include <math.h>

int fb_planar_slide_count(const fb_planar *m) {
  int n = 0;
  for (int j = 0; j < m->njoints; j++) n += m->joint[j].kind == FB_KIND_PRISMATIC;
  return n;
}

int fb_planar_output_count(const fb_planar *m) {
  return FB_PLANAR_POINT_QUANTITIES * m->npoints +
         FB_PLANAR_SLIDE_QUANTITIES * fb_planar_slide_count(m);
}

/* the world position, velocity and acceleration of point s of body b
 * (the ground's: s itself, at rest); qdd NULL: accelerations zero */
static void point_motion(double x[2], double v[2], double a[2], const double *q,
                         const double *qd, const double *qdd, int b, const double s[2]) {
  if (b == FB_PLANAR_GROUND) {
    x[0] = s[0], x[1] = s[1];
    v[0] = v[1] = a[0] = a[1] = 0.0;
    return;
  }
  const int i = 3 * (b - 1);
  const double c = cos(q[i + 2]), sn = sin(q[i + 2]);
  const double r[2] = {c * s[0] - sn * s[1], sn * s[0] + c * s[1]}; /* A s */
  const double w = qd[i + 2], al = qdd ? qdd[i + 2] : 0.0;
  const double ax = qdd ? qdd[i] : 0.0, ay = qdd ? qdd[i + 1] : 0.0;
  x[0] = q[i] + r[0], x[1] = q[i + 1] + r[1];
  v[0] = qd[i] - w * r[1], v[1] = qd[i + 1] + w * r[0];
  a[0] = ax - al * r[1] - w * w * r[0];
  a[1] = ay + al * r[0] - w * w * r[1];
}

int fb_planar_slide_guide(const fb_planar *m, int j, double datum[2]) {
  const fb_planar_joint *pj = &m->joint[j];
  datum[0] = datum[1] = 0.0;
  const int side = fb_planar_guide_side(pj->body[0], pj->body[1]);
  if (pj->body[side] == FB_PLANAR_GROUND) return side;
  const int g = pj->body[side];
  int first = -1; /* the guide's joint with the ground, else its first joint */
  for (int k = 0; k < m->njoints && first < 0; k++)
    if ((m->joint[k].body[0] == g || m->joint[k].body[1] == g) &&
        (m->joint[k].body[0] == FB_PLANAR_GROUND || m->joint[k].body[1] == FB_PLANAR_GROUND))
      first = k;
  for (int k = 0; k < m->njoints && first < 0; k++)
    if (m->joint[k].body[0] == g || m->joint[k].body[1] == g) first = k;
  const fb_planar_joint *f = &m->joint[first];
  const int at = f->body[0] == g ? 0 : 1;
  datum[0] = f->point[at][0];
  datum[1] = f->point[at][1];
  return side;
}

/* prismatic joint j's slide, its rate and acceleration into out (3);
 * qdd NULL: the acceleration is not meaningful */
static void slide(double out[3], const fb_planar *m, int j, const double *q, const double *qd,
                  const double *qdd) {
  const fb_planar_joint *pj = &m->joint[j];
  double datum[2];
  const int gk = fb_planar_slide_guide(m, j, datum), g = pj->body[gk], k = pj->body[1 - gk];
  double p[3][2], d[3][2];
  point_motion(p[0], p[1], p[2], q, qd, qdd, k, pj->point[1 - gk]);
  point_motion(d[0], d[1], d[2], q, qd, qdd, g, datum);
  /* the axis in the world: body[0]'s frame turned (both bodies turn together) */
  const int b0 = pj->body[0];
  const double th = b0 == FB_PLANAR_GROUND ? 0.0 : q[3 * (b0 - 1) + 2];
  const double w = g == FB_PLANAR_GROUND ? 0.0 : qd[3 * (g - 1) + 2];
  const double al = g == FB_PLANAR_GROUND || !qdd ? 0.0 : qdd[3 * (g - 1) + 2];
  const double c = cos(th), sn = sin(th);
  const double u[2] = {c * pj->axis[0] - sn * pj->axis[1], sn * pj->axis[0] + c * pj->axis[1]};
  const double up[2] = {-u[1], u[0]};
  const double r[2] = {p[0][0] - d[0][0], p[0][1] - d[0][1]};
  const double rv[2] = {p[1][0] - d[1][0], p[1][1] - d[1][1]};
  const double ra[2] = {p[2][0] - d[2][0], p[2][1] - d[2][1]};
  out[0] = r[0] * u[0] + r[1] * u[1];
  out[1] = rv[0] * u[0] + rv[1] * u[1] + w * (r[0] * up[0] + r[1] * up[1]);
  out[2] = ra[0] * u[0] + ra[1] * u[1] + 2.0 * w * (rv[0] * up[0] + rv[1] * up[1]) +
           r[0] * (al * up[0] - w * w * u[0]) + r[1] * (al * up[1] - w * w * u[1]);
}

double fb_planar_slide_rate(const fb_planar *m, int j, const double *q, const double *qd) {
  double out[3];
  slide(out, m, j, q, qd, NULL);
  return out[1];
}

void fb_planar_outputs(double *out, const fb_planar *m, const double *q, const double *qd,
                       const double *qdd) {
  int n = 0;
  for (int k = 0; k < m->npoints; k++, n += FB_PLANAR_POINT_QUANTITIES) {
    double x[2], v[2], a[2];
    point_motion(x, v, a, q, qd, qdd, m->point[k].body, m->point[k].point);
    const double row[FB_PLANAR_POINT_QUANTITIES] = {x[0], x[1], v[0], v[1], a[0], a[1]};
    for (int c = 0; c < FB_PLANAR_POINT_QUANTITIES; c++) out[n + c] = row[c];
  }
  for (int j = 0; j < m->njoints; j++)
    if (m->joint[j].kind == FB_KIND_PRISMATIC) {
      slide(out + n, m, j, q, qd, qdd);
      n += FB_PLANAR_SLIDE_QUANTITIES;
    }
}

int fb_planar_body_turns(const fb_planar *m, int b) {
  /* the bodies whose angle prismatic joints tie to the ground's, grown
   * from it until no joint adds one */
  unsigned long long held = 1ull << FB_PLANAR_GROUND;
  for (int grown = 1; grown;) {
    grown = 0;
    for (int j = 0; j < m->njoints; j++) {
      const fb_planar_joint *pj = &m->joint[j];
      if (pj->kind != FB_KIND_PRISMATIC || pj->body[0] >= 64 || pj->body[1] >= 64) continue;
      const unsigned long long both = (1ull << pj->body[0]) | (1ull << pj->body[1]);
      if ((held & both) && (held & both) != both) held |= both, grown = 1;
    }
  }
  return b >= 64 || !(held & (1ull << b));
}
