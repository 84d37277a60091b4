/* What a state of the MuJoCo scene (mujoco_scene.h) gives: the sample
 * (interpolated inside an adaptive step), the joint reactions from MuJoCo's
 * recursive Newton-Euler and the loop's equality force, the penetration,
 * the loop-closure drift, the impact count and the contact provenance. */
#include <math.h>

#include "kit_record.h"
#include "mujoco_scene_internal.h"

/* joint reactions at this state (after a forward pass), with invdyn.h's
 * convention (the force on the second-named body from the first): MuJoCo's
 * recursive Newton-Euler after the constraint stage (mj_rnePostConstraint)
 * gives each body's interaction force with its parent, the connect
 * equality's force on the follower is -efc_force (body2), and the drive
 * torque is what the flywheel gives the crank, -armature * alpha. At a
 * clearance joint the slides transmit nothing, so the parent's force is the
 * contact law's (applied through qfrc_passive). */
void mujoco_reactions_now(fb_mujoco_scene *s) {
  const mjModel *m = s->m;
  mjData *d = s->d;
  mj_rnePostConstraint(m, d);
  const double *fa = d->cfrc_int + 6 * s->body[FB_CRANK] + 3;    /* on the crank from ground */
  const double *fb = d->cfrc_int + 6 * s->body[FB_COUPLER] + 3;  /* on the coupler from the crank */
  const double *fd = d->cfrc_int + 6 * s->body[FB_FOLLOWER] + 3; /* on the follower (slider) from ground */
  /* a slider-crank's guide: the force on the ground from the slider (its
   * analytic engine's convention, (0, -N)), the slide's own reaction negated */
  const double sd = s->def.mech == FB_MECH_SLIDER_CRANK ? -1.0 : 1.0;
  for (int k = 0; k < 2; k++) {
    s->reaction[FB_JOINT_A][k] = fa[k];
    s->reaction[FB_JOINT_B][k] = fb[k];
    s->reaction[FB_JOINT_D][k] = sd * fd[k];
    s->reaction[FB_JOINT_C][k] = 0.0;
  }
  if (s->def.clearance_mask & (1 << FB_JOINT_C)) {
    /* the law's force on the follower's hole: +F n, n = e / |e| */
    const mj_clearance *c = &s->cl[FB_JOINT_C];
    const double ecc = hypot(c->e[0], c->e[1]);
    if (ecc > 0.0)
      for (int k = 0; k < 2; k++) s->reaction[FB_JOINT_C][k] = c->force * c->e[k] / ecc;
  } else {
    for (int i = 0; i < d->ne; i++)
      if (d->efc_type[i] == mjCNSTR_EQUALITY && m->eq_type[d->efc_id[i]] == mjEQ_CONNECT) {
        s->reaction[FB_JOINT_C][0] = -d->efc_force[i];
        s->reaction[FB_JOINT_C][1] = -d->efc_force[i + 1];
        break;
      }
  }
  s->drive_torque = -s->def.opts.drive_armature * d->qacc[s->hinge_dof[FB_CRANK]];
}

void fb_mujoco_scene_sample(const fb_mujoco_scene *s, fb_sample *x) {
  if (s->def.adaptive && s->ad.k < s->ad.mc) {
    /* inside a step: every column linear between its ends (MuJoCo's values
     * are those of each end's state), the contact state the end's */
    const double f = (double)s->ad.k / (double)s->ad.mc;
    const fb_sample *a = &s->ad.x0, *b = &s->ad.x1;
    x->t = a->t + f * (b->t - a->t);
    x->crank_angle = a->crank_angle + f * (b->crank_angle - a->crank_angle);
    for (int o = 0; o < FB_MECH_MAX_OUTPUTS; o++)
      for (int q = 0; q < 3; q++) x->body[o][q] = a->body[o][q] + f * (b->body[o][q] - a->body[o][q]);
    for (int j = 0; j < 4; j++) {
      for (int q = 0; q < FB_CONTACT_COLS; q++)
        x->contact[j][q] = a->contact[j][q] + f * (b->contact[j][q] - a->contact[j][q]);
      x->contact[j][FB_C_STATE] = b->contact[j][FB_C_STATE];
      for (int q = 0; q < 2; q++)
        x->reaction[j][q] = a->reaction[j][q] + f * (b->reaction[j][q] - a->reaction[j][q]);
    }
    x->drive_torque = a->drive_torque + f * (b->drive_torque - a->drive_torque);
    x->t = (double)s->steps * s->def.h;
    return;
  }
  mujoco_sample_now(s, x);
}

void mujoco_sample_now(const fb_mujoco_scene *s, fb_sample *x) {
  const mjData *d = s->d;
  const int *dof = s->hinge_dof;
  /* planar chain: a body turns by its own hinge plus its parent's */
  const double q[3] = {d->qpos[s->hinge_qpos[0]], d->qpos[s->hinge_qpos[1]],
                       d->qpos[s->hinge_qpos[2]]};
  x->t = (double)s->steps * s->def.h;
  x->crank_angle = s->angle0[FB_CRANK] + q[0];
  x->coupler_angle = s->angle0[FB_COUPLER] + q[0] + q[1];
  x->coupler_omega = d->qvel[dof[0]] + d->qvel[dof[1]];
  x->coupler_alpha = d->qacc[dof[0]] + d->qacc[dof[1]];
  /* the follower's angle, or a slider-crank's slider x, v, a from its
   * slide (body[1], the same storage) */
  x->follower_angle = s->angle0[FB_FOLLOWER] + q[2];
  x->follower_omega = d->qvel[dof[2]];
  x->follower_alpha = d->qacc[dof[2]];
  for (int j = 0; j < 4; j++) {
    for (int k = 0; k < FB_CONTACT_COLS; k++) x->contact[j][k] = 0.0;
    if (!(s->def.clearance_mask & (1 << j))) continue;
    const mj_clearance *c = &s->cl[j];
    fb_kit_sample_contact(x->contact[j], c->force, c->delta > 0.0 ? c->delta : 0.0, c->e[0],
                          c->e[1], &c->ep);
  }
}

double fb_mujoco_scene_joint_drift(const fb_mujoco_scene *s) {
  if (s->def.clearance_mask & (1 << FB_JOINT_C)) return 0.0;
  const mjtNum *p = s->d->site_xpos + 3 * s->site_pin[FB_JOINT_C];
  const mjtNum *q = s->d->site_xpos + 3 * s->site_hole[FB_JOINT_C];
  return sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
              (p[2] - q[2]) * (p[2] - q[2]));
}

double fb_mujoco_scene_penetration(const fb_mujoco_scene *s, int *joint) {
  double worst = 0.0;
  *joint = -1;
  for (int j = 0; j < 4; j++) {
    if (!(s->def.clearance_mask & (1 << j))) continue;
    if (*joint < 0 || s->cl[j].delta > worst) {
      worst = s->cl[j].delta;
      *joint = j;
    }
  }
  return worst > 0.0 ? worst : 0.0;
}

void fb_mujoco_scene_provenance(const fb_mujoco_scene *s, int j, fb_contact_provenance *out) {
  *out = s->cl[j].prov;
  out->erp_max = NAN; /* no constraint row: the law is a force */
  out->cfm_min = NAN;
  if (out->contact_steps == 0) out->mass_eff_min = out->mass_eff_max = out->h_omega_max = NAN;
}

void fb_mujoco_scene_reactions(const fb_mujoco_scene *s, double force[4][2],
                               double *drive_torque) {
  for (int j = 0; j < 4; j++)
    for (int k = 0; k < 2; k++) force[j][k] = s->reaction[j][k];
  *drive_torque = s->drive_torque;
}

int fb_mujoco_scene_impacts(const fb_mujoco_scene *s, int j) { return s->cl[j].ep.impacts; }

size_t fb_mujoco_scene_steps(const fb_mujoco_scene *s) { return s->steps; }
