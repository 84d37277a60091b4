/* The ODE world (ode_world.h), built and freed: the world with its gravity,
 * ERP, CFM and damping; the case's mechanism (mechanism.h) from its
 * description: crank, coupler and follower (or slider) placed at the start;
 * per joint a hinge (revolute without clearance), the pin and hole points
 * (revolute with clearance, and its faceted or libccd collider) or a slider
 * joint (prismatic); the crank's drive; planar joints for bodies left
 * without a hinge or slider joint; the adaptive step's set-up. Stepping is
 * in ode_step.c, the contact in ode_clearance.c and ode_colliders.c, the
 * outputs in ode_sample.c. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ode_env.h"
#include "ode_world_internal.h"
#include "step_control.h"

/* sets a link body between joint points p and q, COM at fraction f */
static void place_body(dBodyID b, const fb_link_mass *lm, const double p[2], const double q[2],
                       double omega, const double vp[2]) {
  double dx = q[0] - p[0], dy = q[1] - p[1];
  double phi = atan2(dy, dx);
  double rx = lm->com_fraction * dx, ry = lm->com_fraction * dy;
  dMass m;
  /* body frame: x along the link, z the hinge axis */
  dMassSetParameters(&m, lm->mass, 0, 0, 0, lm->inertia_long, lm->inertia_transverse,
                     lm->inertia, 0, 0, 0);
  dBodySetMass(b, &m);
  dBodySetPosition(b, p[0] + rx, p[1] + ry, 0.0);
  dMatrix3 R;
  dRFromAxisAndAngle(R, 0, 0, 1, phi);
  dBodySetRotation(b, R);
  dBodySetLinearVel(b, vp[0] - omega * ry, vp[1] + omega * rx, 0.0);
  dBodySetAngularVel(b, 0, 0, omega);
}

/* sets the slider at its hole centre h [m] (its centre of mass, slider_crank_invdyn.h),
 * unrotated, moving at v [m/s] along +x; its inertias are the link's (the
 * slider joint holds its rotation, so they do not enter) */
static void place_slider(dBodyID b, const fb_link_mass *lm, const double h[2], double v) {
  dMass m;
  dMassSetParameters(&m, lm->mass, 0, 0, 0, lm->inertia_long, lm->inertia_transverse,
                     lm->inertia, 0, 0, 0);
  dBodySetMass(b, &m);
  dBodySetPosition(b, h[0], h[1], 0.0);
  dMatrix3 R;
  dRSetIdentity(R);
  dBodySetRotation(b, R);
  dBodySetLinearVel(b, v, 0.0, 0.0);
  dBodySetAngularVel(b, 0, 0, 0);
}

double ode_body_angle(dBodyID b) {
  const dReal *R = dBodyGetRotation(b);
  return atan2(R[4], R[0]);
}

double ode_body_coord(const fb_ode_world *s, int i) {
  return i == s->translating ? dBodyGetPosition(s->body[i])[0] : ode_body_angle(s->body[i]);
}

double ode_body_rate(const fb_ode_world *s, int i) {
  return i == s->translating ? dBodyGetLinearVel(s->body[i])[0]
                             : dBodyGetAngularVel(s->body[i])[2];
}

/* the generic collider of clearance joint j (ode_colliders.h), the
 * scene's: a ring of faceted_n boxes or a libccd bore of ccd_segments, on
 * the joint's pin and hole */
static fb_status generic_create(fb_ode_world *s, int j, fb_diag *diag) {
  const fb_model_scene *d = &s->def;
  ode_clearance *c = &s->cl[j];
  ode_collider *g = &c->gen;
  g->pin = c->pin;
  g->hole = c->hole;
  memcpy(g->pin_local, c->pin_local, sizeof g->pin_local);
  memcpy(g->hole_local, c->hole_local, sizeof g->hole_local);
  const double r_hole = d->pin_radius + d->radial_clearance;
  if (d->faceted_n > 0)
    return ode_collider_faceted(g, d->faceted_n, d->pin_radius, r_hole, d->pin_length, diag);
  return ode_collider_ccd(g, d->ccd_segments, d->bore_ovality, d->pin_radius, r_hole,
                          d->pin_length, diag);
}

fb_status fb_ode_world_create(fb_ode_world **out, const fb_model_scene *sm, fb_diag *diag) {
  fb_status rc0 = fb_scene_check(sm->def, diag);
  if (rc0 != FB_OK) return rc0;
  if (sm->clearance_mask && sm->collider != FB_COLLIDER_EXACT &&
      sm->collider != FB_COLLIDER_FACETED && sm->collider != FB_COLLIDER_CCD)
    return fb_diag_set(diag, FB_ERR_ARG, "model '%s': the ODE engine has no such collider",
                       sm->model->name);
  if (sm->solver.h_mode == FB_STEP_ADAPTIVE && sm->clearance_mask &&
      sm->collider != FB_COLLIDER_EXACT)
    return fb_diag_set(diag, FB_ERR_ARG,
                       "model '%s': [solver] h_s = adaptive follows the exact collider's contact "
                       "only; run the %s collider at a fixed or auto step",
                       sm->model->name, fb_collider_name(sm->collider));
  const fb_model_scene *def = sm;
  fb_start_state st;
  fb_status rc = fb_model_scene_start(&st, def, diag);
  if (rc != FB_OK) return rc;
  fb_ode_world *s = calloc(1, sizeof *s);
  if (!s) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the scene");
  fb_ode_acquire();
  s->def = *sm;
  s->world = dWorldCreate();
  dWorldSetGravity(s->world, 0, -def->gravity, 0);
  dWorldSetERP(s->world, def->solver.world_erp);
  dWorldSetCFM(s->world, def->solver.world_cfm);
  dWorldSetQuickStepNumIterations(s->world, def->solver.quick_iterations);
  dRandSetSeed(def->solver.seed);
  if (def->settle_damping > 0.0) {
    dWorldSetLinearDamping(s->world, def->settle_damping);
    dWorldSetAngularDamping(s->world, def->settle_damping);
    /* ODE damps only above these speeds (default 0.01): damp everything */
    dWorldSetLinearDampingThreshold(s->world, 0.0);
    dWorldSetAngularDampingThreshold(s->world, 0.0);
  }

  /* the description's bodies (mechanism.h): the moving ones are this
   * world's body[] by index, the ground ODE's static environment (0); the
   * translating one (a slider-crank's slider) reports x, v, a */
  const fb_mech_desc *mech = fb_case_mech(&def->def->source);
  s->translating = -1;
  s->slider_joint = -1;
  for (int i = 0; i < 3 && i < mech->nbodies; i++)
    if (mech->body[i].motion == FB_MOTION_TRANSLATING) s->translating = i;

  /* each body between its joints' pin or hole centres (start.h): crank A_pin
   * to B_pin, coupler B_hole to C_pin, follower D_pin to C_hole; a slider at
   * its hole centre C_hole on the guide */
  const double zero[2] = {0, 0};
  for (int i = 0; i < 3; i++) s->body[i] = dBodyCreate(s->world);
  place_body(s->body[FB_CRANK], &def->link[FB_CRANK], st.pin[FB_JOINT_A], st.pin[FB_JOINT_B],
             st.crank_omega, zero);
  place_body(s->body[FB_COUPLER], &def->link[FB_COUPLER], st.hole[FB_JOINT_B], st.pin[FB_JOINT_C],
             st.coupler_omega, st.coupler_b_vel);
  if (s->translating == FB_FOLLOWER)
    place_slider(s->body[FB_FOLLOWER], &def->link[FB_FOLLOWER], st.hole[FB_JOINT_C],
                 st.body[1][FB_Q_VEL]);
  else
    place_body(s->body[FB_FOLLOWER], &def->link[FB_FOLLOWER], st.pin[FB_JOINT_D],
               st.hole[FB_JOINT_C], st.follower_omega, zero);
  s->guide_y = st.hole[FB_JOINT_C][1];

  /* each joint of the description, in its order: the pin on b1 (its moving
   * first body; the crank at ground-crank), the hole on b2 (0: the ground) */
  dBodyID b1[4] = {0}, b2[4] = {0};
  for (int j = 0; j < 4 && j < mech->njoints; j++) {
    const int *jb = mech->joint[j].body;
    const int ground_first = mech->body[jb[0]].motion == FB_MOTION_FIXED;
    const int first = ground_first ? jb[1] : jb[0], second = ground_first ? jb[0] : jb[1];
    b1[j] = s->body[first];
    b2[j] = mech->body[second].motion == FB_MOTION_FIXED ? 0 : s->body[second];
  }
  const double *anchor[4] = {st.pin[0], st.pin[1], st.pin[2], st.pin[3]};
  s->contacts = dJointGroupCreate(0);
  for (int j = 0; j < 4 && j < mech->njoints; j++) {
    if (mech->joint[j].kind == FB_KIND_PRISMATIC) {
      /* the guide: ODE's slider joint along +x holds the slider's y (the
       * guide line through its start) and its rotation (5 rows) */
      s->slider = dJointCreateSlider(s->world, 0);
      dJointAttach(s->slider, b1[j], b2[j]);
      dJointSetSliderAxis(s->slider, 1, 0, 0);
      dJointSetFeedback(s->slider, &s->feedback[j]);
      s->slider_joint = j;
      continue;
    }
    if (def->clearance_mask & (1 << j)) {
      /* pin and hole centres at t = 0 (the start's eccentricity) */
      ode_clearance *c = &s->cl[j];
      c->pin = b1[j];
      c->hole = b2[j];
      dVector3 lp;
      dBodyGetPosRelPoint(c->pin, st.pin[j][0], st.pin[j][1], 0.0, lp);
      for (int q = 0; q < 3; q++) c->pin_local[q] = lp[q];
      if (c->hole) {
        dBodyGetPosRelPoint(c->hole, st.hole[j][0], st.hole[j][1], 0.0, lp);
        for (int q = 0; q < 3; q++) c->hole_local[q] = lp[q];
      } else {
        c->hole_local[0] = st.hole[j][0];
        c->hole_local[1] = st.hole[j][1];
        c->hole_local[2] = 0.0;
      }
      continue;
    }
    s->hinge[j] = dJointCreateHinge(s->world, 0);
    dJointAttach(s->hinge[j], b1[j], b2[j]);
    dJointSetHingeAnchor(s->hinge[j], anchor[j][0], anchor[j][1], 0.0);
    dJointSetHingeAxis(s->hinge[j], 0, 0, 1);
    dJointSetFeedback(s->hinge[j], &s->feedback[j]);
  }
  for (int j = 0; j < 4 && (def->faceted_n > 0 || def->ccd_segments > 0); j++) {
    if (!(def->clearance_mask & (1 << j))) continue;
    fb_status bst = generic_create(s, j, diag);
    if (bst != FB_OK) {
      fb_ode_world_destroy(s);
      return bst;
    }
  }
  /* the drive: velocity motor on the ground-crank hinge, or an angular motor
   * on the crank when that joint has ode_clearance */
  if (s->hinge[0]) {
    dJointSetHingeParam(s->hinge[0], dParamVel, def->omega2);
    dJointSetHingeParam(s->hinge[0], dParamFMax, def->solver.drive_torque_max);
  } else {
    s->amotor = dJointCreateAMotor(s->world, 0);
    dJointAttach(s->amotor, s->body[FB_CRANK], 0);
    dJointSetAMotorNumAxes(s->amotor, 1);
    dJointSetAMotorAxis(s->amotor, 0, 0, 0, 0, 1);
    dJointSetAMotorParam(s->amotor, dParamVel, def->omega2);
    dJointSetAMotorParam(s->amotor, dParamFMax, def->solver.drive_torque_max);
  }
  /* a body with no hinge or slider joint left is held in the plane (the
   * four-bar's crank: A, B; coupler: B, C; follower: C, D) */
  for (int i = 0; i < 3; i++) {
    int held = 0;
    for (int j = 0; j < 4 && j < mech->njoints; j++)
      if ((mech->joint[j].body[0] == i || mech->joint[j].body[1] == i) &&
          (s->hinge[j] || j == s->slider_joint))
        held = 1;
    if (held) continue;
    dJointID p2 = dJointCreatePlane2D(s->world, 0);
    dJointAttach(p2, s->body[i], 0);
  }

  for (int i = 0; i < 3; i++) {
    s->angle[i] = ode_body_coord(s, i);
    s->omega_prev[i] = ode_body_rate(s, i);
    s->alpha[i] = 0.0;
  }
  s->h_now = def->solver.h;
  if (def->solver.h_mode == FB_STEP_ADAPTIVE) {
    s->ad.on = 1;
    s->ad.m_max = (int)floor(def->solver.h_max / def->solver.h * (1.0 + 1e-9));
    if (s->ad.m_max < 1) s->ad.m_max = 1;
    s->ad.m_prev = 1;
    s->ad.rocking = def->solver.rocking_h_omega > 0.0 && def->clearance_mask != 0;
    /* persistent contact steps on the ideal load's schedule (step_control.h) */
    fb_status lst = fb_load_scale_build_mech(
        &s->ad.load, def->def->source.mechanism, &def->lengths, def->branch, def->link,
        def->gravity, def->omega2, def->clearance_mask,
        FB_STEP_LOAD_LOOKAHEAD * def->solver.h_max, diag);
    if (lst != FB_OK) {
      fb_ode_world_destroy(s);
      return lst;
    }
  }
  *out = s;
  return FB_OK;
}

void fb_ode_world_destroy(fb_ode_world *s) {
  if (!s) return;
  if (s->broken) {
    /* ODE's world was left mid-step (its job list still holds the step):
     * destroying it would fail ODE's own checks, so it is leaked, and ODE is
     * never closed in this process; the project's own allocations are freed */
    fb_ode_quarantine(s->world);
    fb_ode_quarantine(s->contacts);
    for (int j = 0; j < 4; j++) fb_ccd_bore_destroy(s->cl[j].gen.bore);
    fb_load_scale_free(&s->ad.load);
    free(s);
    return;
  }
  for (int j = 0; j < 4; j++) ode_collider_free(&s->cl[j].gen);
  dJointGroupDestroy(s->contacts);
  dWorldDestroy(s->world);
  fb_load_scale_free(&s->ad.load);
  free(s);
  fb_ode_release();
}
