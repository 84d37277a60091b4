/* The transmission angle of a planar description (planar_transmission.h). */
#include "planar_transmission.h"

#include <math.h>
#include <string.h>

#include "planar_constraints.h"

/* the joints of body b, at most two, into j; returns how many it has */
static int joints_of(const fb_planar *m, int b, int j[2]) {
  int n = 0;
  for (int k = 0; k < m->njoints; k++)
    if (m->joint[k].body[0] == b || m->joint[k].body[1] == b) {
      if (n < 2) j[n] = k;
      n++;
    }
  return n;
}

static int other(const fb_planar_joint *j, int b) { return j->body[0] == b ? j->body[1] : j->body[0]; }

int fb_planar_transmissions(fb_planar_transmission *out, int max, const fb_planar *m) {
  if (m->drive < 0 || m->nbodies > 64) return 0;
  int from, to, dist[64];
  fb_planar_drive_bodies(m, &from, &to);
  for (int b = 0; b < m->nbodies; b++) dist[b] = -1;
  dist[to] = 0; /* joints between a body and the driven one, the ground not counted */
  for (int grown = 1; grown;) {
    grown = 0;
    for (int k = 0; k < m->njoints; k++) {
      const int a = m->joint[k].body[0], c = m->joint[k].body[1];
      if (a == FB_PLANAR_GROUND || c == FB_PLANAR_GROUND) continue;
      if (dist[a] >= 0 && (dist[c] < 0 || dist[c] > dist[a] + 1)) dist[c] = dist[a] + 1, grown = 1;
      if (dist[c] >= 0 && (dist[a] < 0 || dist[a] > dist[c] + 1)) dist[a] = dist[c] + 1, grown = 1;
    }
  }
  int n = 0;
  for (int k = 0; k < m->njoints && n < max; k++)
    for (int side = 0; side < 2 && n < max; side++) {
      const int link = m->joint[k].body[side], driven = m->joint[k].body[1 - side];
      int j[2];
      if (link == FB_PLANAR_GROUND || link == to || driven == FB_PLANAR_GROUND) continue;
      if (joints_of(m, link, j) != 2 || m->joint[j[0]].kind != FB_KIND_REVOLUTE ||
          m->joint[j[1]].kind != FB_KIND_REVOLUTE || m->joint[k].kind != FB_KIND_REVOLUTE)
        continue;
      if (!(dist[link] >= 0 && dist[driven] > dist[link])) continue;
      const int far = j[0] == k ? j[1] : j[0];
      if (hypot(m->joint[far].at[0] - m->joint[k].at[0], m->joint[far].at[1] - m->joint[k].at[1]) == 0.0)
        continue; /* no line */
      out[n++] = (fb_planar_transmission){link, k, driven, far};
    }
  return n;
}

/* joint k's point on body b in the world at q */
static void joint_point(double out[2], const fb_planar *m, const double *q, int k, int b) {
  const fb_planar_joint *j = &m->joint[k];
  fb_planar_point(out, m, q, b, j->point[j->body[0] == b ? 0 : 1]);
}

double fb_planar_transmission_angle(const fb_planar *m, const fb_planar_transmission *t,
                                    const double *q, const double *qd) {
  double pj[2], pf[2], v[2] = {NAN, NAN};
  joint_point(pj, m, q, t->joint, t->link);
  joint_point(pf, m, q, t->from, t->link);
  const double f[2] = {pj[0] - pf[0], pj[1] - pf[1]}; /* the link's line */
  for (int k = 0; k < m->njoints && !isfinite(v[0]); k++) {
    const fb_planar_joint *j = &m->joint[k];
    if (k == t->joint || (j->body[0] != t->driven && j->body[1] != t->driven) ||
        other(j, t->driven) != FB_PLANAR_GROUND)
      continue;
    if (j->kind == FB_KIND_REVOLUTE) { /* about its ground pivot */
      double g[2];
      joint_point(g, m, q, k, t->driven);
      v[0] = -(pj[1] - g[1]), v[1] = pj[0] - g[0];
    } else { /* along its ground guide: the axis turns with body[0], at rest */
      const int b0 = j->body[0];
      const double th = b0 == FB_PLANAR_GROUND ? 0.0 : q[3 * (b0 - 1) + 2];
      v[0] = cos(th) * j->axis[0] - sin(th) * j->axis[1];
      v[1] = sin(th) * j->axis[0] + cos(th) * j->axis[1];
    }
  }
  if (!isfinite(v[0])) /* D moves freely: its point's instantaneous velocity */
    fb_planar_point_velocity(v, m, q, qd, t->driven, m->joint[t->joint].point
                                                     [m->joint[t->joint].body[0] == t->driven ? 0 : 1]);
  const double along = fabs(f[0] * v[0] + f[1] * v[1]), across = fabs(f[0] * v[1] - f[1] * v[0]);
  if (!(hypot(v[0], v[1]) > 1e-12 * hypot(f[0], f[1]))) return NAN;
  return atan2(along, across);
}
