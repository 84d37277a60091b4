/* Gravity, springs and loads as generalised forces (planar_loads.h). */
#include "planar_loads.h"

#include <math.h>

#include "planar_constraints.h"
#include "planar_outputs.h"

int fb_planar_has_loads(const fb_planar *m) {
  return m->nsprings > 0 || m->nloads > 0 || m->torque_joint >= 0;
}

/* spring s's ends, unit direction u (a to b; zero when they meet) and
 * state (length, rate, tension) */
static void spring_at(double pa[2], double pb[2], double u[2], double out[3], const fb_planar *m,
                      int s, const double *q, const double *qd) {
  const fb_planar_spring *sp = &m->spring[s];
  double va[2], vb[2];
  fb_planar_point_motion(pa, va, m, q, qd, sp->body[0], sp->point[0]);
  fb_planar_point_motion(pb, vb, m, q, qd, sp->body[1], sp->point[1]);
  const double d[2] = {pb[0] - pa[0], pb[1] - pa[1]}, l = hypot(d[0], d[1]);
  u[0] = l > 0.0 ? d[0] / l : 0.0;
  u[1] = l > 0.0 ? d[1] / l : 0.0;
  const double rate = u[0] * (vb[0] - va[0]) + u[1] * (vb[1] - va[1]);
  out[0] = l;
  out[1] = rate;
  out[2] = sp->stiffness * (l - sp->free_length) + sp->damping * rate;
}

void fb_planar_spring_state(double out[3], const fb_planar *m, int s, const double *q,
                            const double *qd) {
  double pa[2], pb[2], u[2];
  spring_at(pa, pb, u, out, m, s, q, qd);
}

int fb_planar_load_acts(const fb_planar *m, int l, const double *q, const double *qd) {
  const fb_planar_load *ld = &m->load[l];
  if (ld->active == FB_PLANAR_LOAD_ALWAYS) return 1;
  const double rate = fb_planar_slide_rate(m, ld->stroke, q, qd);
  return ld->active == FB_PLANAR_LOAD_OUTSTROKE ? rate > 0.0 : rate < 0.0;
}

void fb_planar_applied(double *Q, const fb_planar *m, const double *q, const double *qd,
                       double gravity) {
  for (int b = 1; b < m->nbodies; b++) {
    const int i = 3 * (b - 1);
    Q[i] = 0.0;
    Q[i + 1] = -m->body[b].mass * gravity;
    Q[i + 2] = 0.0;
  }
  for (int s = 0; s < m->nsprings; s++) {
    double pa[2], pb[2], u[2], st[3];
    spring_at(pa, pb, u, st, m, s, q, qd);
    const double fa[2] = {st[2] * u[0], st[2] * u[1]}, fb[2] = {-fa[0], -fa[1]};
    fb_planar_add_force(Q, q, m->spring[s].body[0], pa, fa);
    fb_planar_add_force(Q, q, m->spring[s].body[1], pb, fb);
  }
  for (int l = 0; l < m->nloads; l++) {
    if (!fb_planar_load_acts(m, l, q, qd)) continue;
    const fb_planar_load *ld = &m->load[l];
    double p[2];
    fb_planar_point(p, m, q, ld->body, ld->point);
    fb_planar_add_force(Q, q, ld->body, p, ld->force);
    Q[3 * (ld->body - 1) + 2] += ld->torque;
  }
  if (m->torque_joint >= 0) { /* the torque drive: +T on body[1], -T on body[0] */
    const fb_planar_joint *jt = &m->joint[m->torque_joint];
    if (jt->body[1] != FB_PLANAR_GROUND) Q[3 * (jt->body[1] - 1) + 2] += m->drive_torque;
    if (jt->body[0] != FB_PLANAR_GROUND) Q[3 * (jt->body[0] - 1) + 2] -= m->drive_torque;
  }
}
