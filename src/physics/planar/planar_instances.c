/* The four-bar and the slider-crank as instances of the planar description
 * (planar_case.h fb_planar_fourbar, fb_planar_slider_crank): their bodies and
 * joints placed from their exact solution at the start angle. */
#include "planar_case.h"

#include <math.h>
#include <string.h>

#include "effective_mass.h"
#include "linkage.h"
#include "planar_constraints.h"
#include "slider_crank.h"

/* a moving body of fb_mech_desc d (index i) at centre c and angle a */
static int add_link(fb_planar *p, const fb_mech_desc *d, int i, const fb_link_mass *lm,
                    const double from[2], const double to[2], double f, double a,
                    fb_diag *diag) {
  const double c[2] = {from[0] + f * (to[0] - from[0]), from[1] + f * (to[1] - from[1])};
  return fb_planar_add_body(p, d->body[i].name, lm->mass, lm->inertia, c, a, 0, diag);
}

/* the joints of fb_mech_desc d at positions at[j], its body indices moved
 * to the description's (the ground first), driven at its input's joint 0 */
static fb_status add_joints(fb_planar *p, const fb_mech_desc *d, const double at[][2],
                            fb_diag *diag) {
  const int ground = d->nbodies - 1; /* fb_mech_desc lists the ground last */
  for (int j = 0; j < d->njoints; j++) {
    int b[2];
    for (int k = 0; k < 2; k++)
      b[k] = d->joint[j].body[k] == ground ? FB_PLANAR_GROUND : d->joint[j].body[k] + 1;
    if (fb_planar_add_joint(p, d->joint[j].name, d->joint[j].kind, b[0], b[1], at[j], 0.0,
                            diag) < 0)
      return FB_ERR_ARG;
  }
  return fb_planar_set_drive(p, 0, diag);
}

/* one moving link of an instance: its centre at fraction f from `from` to
 * `to`, its frame at angle [rad] */
typedef struct {
  const double *from, *to;
  double f, angle;
} link_at;

/* the instance of fb_mech_desc d: its three moving links and its joints
 * at positions at[j], driven at ground-crank */
static fb_status instance(fb_planar **out, const fb_mech_desc *d, const fb_link_mass link[3],
                          const link_at la[3], const double at[][2], fb_diag *diag) {
  fb_planar *p = fb_planar_new(3, 4);
  if (!p) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for a description");
  fb_status rc = FB_OK;
  for (int i = 0; i < 3 && rc == FB_OK; i++)
    if (add_link(p, d, i, &link[i], la[i].from, la[i].to, la[i].f, la[i].angle, diag) < 0)
      rc = FB_ERR_RANGE;
  if (rc == FB_OK) rc = add_joints(p, d, at, diag);
  if (rc != FB_OK) {
    fb_planar_free(p);
    return rc;
  }
  *out = p;
  return FB_OK;
}

fb_status fb_planar_fourbar(fb_planar **out, const fb_linkage *lk, fb_branch branch,
                            const fb_link_mass link[3], double theta0, fb_diag *diag) {
  *out = NULL;
  fb_linkage_state st;
  fb_status rc = fb_linkage_solve(&st, lk, branch, theta0, 0.0, 0.0, diag);
  if (rc != FB_OK) return rc;
  const double a[2] = {0.0, 0.0}, dd[2] = {lk->length[FB_GROUND], 0.0};
  const double at[4][2] = {{a[0], a[1]}, {st.b[0], st.b[1]}, {st.c[0], st.c[1]},
                           {dd[0], dd[1]}};
  /* crank A -> B, coupler B -> C, follower D -> C */
  const link_at la[3] = {{a, st.b, link[FB_CRANK].com_fraction, st.crank_angle},
                         {st.b, st.c, link[FB_COUPLER].com_fraction, st.coupler_angle},
                         {dd, st.c, link[FB_FOLLOWER].com_fraction, st.follower_angle}};
  return instance(out, &fb_mech_fourbar, link, la, at, diag);
}

fb_status fb_planar_slider_crank(fb_planar **out, const fb_linkage *lk,
                                 const fb_link_mass link[3], double theta0, fb_diag *diag) {
  *out = NULL;
  const fb_slider_crank sc = fb_slider_crank_of(lk);
  fb_slider_crank_state st;
  fb_status rc = fb_slider_crank_solve(&st, &sc, theta0, 0.0, 0.0, diag);
  if (rc != FB_OK) return rc;
  const double a[2] = {0.0, 0.0};
  const double at[4][2] = {{0.0, 0.0}, {st.b[0], st.b[1]}, {st.c[0], st.c[1]},
                           {st.c[0], st.c[1]}};
  /* crank A -> B, rod B -> C, the slider at the pin C, unturned */
  const link_at la[3] = {{a, st.b, link[0].com_fraction, st.crank_angle},
                         {st.b, st.c, link[1].com_fraction, st.coupler_angle},
                         {st.c, st.c, 0.0, 0.0}};
  return instance(out, &fb_mech_slider_crank, link, la, at, diag);
}

fb_status fb_planar_instance_mass(double w[4][2][2], const fb_planar *m, const double *q,
                                  const double (*cs)[2], unsigned clearance_mask, fb_diag *diag) {
  if (m->nbodies != 4 || m->njoints != 4)
    return fb_diag_set(diag, FB_ERR_ARG, "the closed-form effective mass takes a four-bar or a "
                       "slider-crank (3 moving bodies, 4 joints), not %d and %d",
                       m->nbodies - 1, m->njoints);
  fb_mechanism mc;
  memset(&mc, 0, sizeof mc);
  for (int i = 0; i < 3; i++) {
    mc.mass[i] = m->body[i + 1].mass;
    mc.inertia[i] = m->body[i + 1].inertia;
    mc.com[i][0] = q[3 * i];
    mc.com[i][1] = q[3 * i + 1];
  }
  for (int j = 0; j < 4; j++) {
    const fb_planar_joint *pj = &m->joint[j];
    const int k = pj->body[0] == FB_PLANAR_GROUND; /* its first moving body's side */
    if (cs) fb_planar_point_at(mc.joint[j], q, pj->body[k], pj->point[k], cs[pj->body[k]]);
    else fb_planar_point(mc.joint[j], m, q, pj->body[k], pj->point[k]);
    if (pj->kind == FB_KIND_PRISMATIC) mc.prismatic_mask |= 1 << j;
  }
  mc.clearance_mask = (int)(clearance_mask & 0xfu);
  mc.crank_driven = m->drive >= 0;
  return fb_effective_mass_tensor(w, &mc, diag);
}
