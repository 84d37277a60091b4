/* An undriven planar case's start and a slider's guide (planar_free.h). */
#include "planar_free.h"

#include <stdlib.h>
#include <string.h>

#include "planar_kinematics.h"

/* [clearance] penalty's words, by fb_penalty_source */
static const char *const SOURCE[] = {"physical", "paper", "explicit", "goldsmith"};

fb_status fb_planar_free_parts(fb_planar_guide **guide, double **omega0, int *needs_explicit,
                               const fb_case *c, const fb_planar *m, const unsigned char *clear,
                               fb_diag *diag) {
  *guide = NULL;
  *omega0 = NULL;
  int prismatic = 0;
  const int undriven = m->drive < 0;
  for (int j = 0; j < m->njoints; j++) prismatic |= clear[j] && m->joint[j].kind == FB_KIND_PRISMATIC;
  *needs_explicit = prismatic || undriven;
  if (*needs_explicit && c->clearance.penalty != FB_PENALTY_SOURCE_EXPLICIT)
    return fb_diag_set(diag, FB_ERR_ARG, "[clearance] penalty = %s: %s has no %s to take the "
                       "stiffness from; give penalty = explicit with stiffness_impact_n_m1_5 "
                       "(reference) or penalty_n_m (reference-restitution)",
                       SOURCE[c->clearance.penalty],
                       prismatic ? "a slider's corner against its guide's flat wall"
                                 : "an undriven case",
                       prismatic ? "pin radius" : "revolution of ideal reactions");
  if (prismatic) {
    *guide = calloc((size_t)m->njoints, sizeof **guide);
    if (!*guide) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
    for (int j = 0; j < m->njoints; j++) {
      if (!clear[j] || m->joint[j].kind != FB_KIND_PRISMATIC) continue;
      const int s = fb_planar_find_joint(m, m->joint[j].name); /* the spec's joints are m's */
      const fb_planar_spec_joint *sj = &c->planar.joint[s];
      (*guide)[j] = (fb_planar_guide){sj->half_length, sj->half_height,
                                      c->clearance.guide_clearance};
    }
  }
  return undriven ? fb_planar_free_omega0(omega0, c, m, diag) : FB_OK;
}

/* a torque drive's start: every body's angular rate in the motion that
 * turns its joint at speed0 (the joint's body[1] relative to its body[0])
 * from the assembly, by the kinematics of m driven there */
static fb_status torque_start(double *omega0, const fb_case *c, const fb_planar *m,
                              fb_diag *diag) {
  fb_planar driven = *m; /* the same description, the joint driven at the start's speed */
  driven.drive = m->torque_joint;
  driven.torque_joint = -1;
  const fb_planar_joint *jt = &m->joint[m->torque_joint];
  /* the kinematics turn the joint's other body than the ground, its
   * body[1] when neither is (planar.h fb_planar_drive_bodies) */
  const double w = jt->body[1] == FB_PLANAR_GROUND ? -c->planar.speed0 : c->planar.speed0;
  const int nq = fb_planar_nq(m);
  double *q = malloc(2 * (size_t)nq * sizeof *q);
  fb_planar_kin *k = NULL;
  fb_status st = q ? fb_planar_kin_new(&k, &driven, diag)
                   : fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  if (st == FB_OK) {
    fb_planar_assembly(m, q);
    st = fb_planar_position(k, q, 0.0, NULL, diag);
  }
  const fb_planar_drive dr = {0.0, w, 0.0};
  if (st == FB_OK) st = fb_planar_motion(k, q + nq, NULL, q, &dr, NULL, diag);
  for (int b = 1; b < m->nbodies && st == FB_OK; b++) omega0[b] = q[nq + 3 * (b - 1) + 2];
  fb_planar_kin_free(k);
  free(q);
  return st;
}

fb_status fb_planar_free_omega0(double **omega0, const fb_case *c, const fb_planar *m,
                                fb_diag *diag) {
  *omega0 = calloc((size_t)m->nbodies, sizeof **omega0);
  if (!*omega0) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  if (m->torque_joint >= 0) {
    const fb_status st = torque_start(*omega0, c, m, diag);
    if (st != FB_OK) free(*omega0), *omega0 = NULL;
    return st;
  }
  for (int b = 1; b < c->planar.nbodies; b++) {
    const int k = fb_planar_find_body(m, c->planar.body[b].name);
    if (k > 0) (*omega0)[k] = c->planar.body[b].omega0;
  }
  return FB_OK;
}
