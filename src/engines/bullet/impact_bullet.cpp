/* The single impact through Bullet's own contact (impact_bullet.h,
 * fb_impact_bullet_contact): the counterpart of ODE's fixed row through its
 * kit binding (kit_impact.h fb_kit_impact_row). */
#include <math.h>
#include <string.h>

#include <new>

#include "bt_world.h"
#include "impact_bullet.h"
extern "C" {
#include "clock.h"
}

/* The single impact through Bullet's own contact pipeline: collision
 * detection (sphere against a static plane), a manifold point flagged
 * BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING, and
 * btSequentialImpulseConstraintSolver::setupContactConstraint turning the
 * combined stiffness and damping into erp = h k / (h k + c),
 * cfm = 1 / (h k + c). What a user's setContactStiffnessAndDamping gets. */
extern "C" fb_status fb_impact_bullet_contact(fb_impact_result *out, double mass, double speed,
                                              double h, double stiffness, double damping,
                                              double t_max, double onset_phase, fb_diag *diag) {
  memset(out, 0, sizeof *out);
  if (!(mass > 0.0) || !(speed > 0.0) || !(h > 0.0) || !(stiffness > 0.0) ||
      !isfinite(damping) || !(h * stiffness + damping > 0.0) || !(t_max > 0.0))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "Bullet contact impact: need mass, speed, h, stiffness > 0 and "
                       "h stiffness + damping > 0 (mass %g kg, speed %g m/s, h %g s, stiffness "
                       "%g N/m, damping %g N s/m)", mass, speed, h, stiffness, damping);
  if (!(onset_phase >= 0.0 && onset_phase < 1.0))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "Bullet contact impact: onset phase %g: must lie in [0, 1)", onset_phase);
  /* the sphere touches the plane (phase 0), or is a free step short of the
   * crossing: the first step that sees the contact sees the depth phase h v */
  const double t_free = onset_phase > 0.0 ? (1.0 - onset_phase) * h : 0.0;
  /* the step bound every engine's single impact keeps (impact.h), as the
   * ODE and MuJoCo rows do: no call runs away at a tiny h */
  const double steps_max = ceil((t_max + t_free) / h);
  if (steps_max > FB_IMPACT_MAX_STEPS)
    return fb_diag_set(diag, FB_ERR_RANGE, "Bullet contact impact: %g steps of %g s: more than %g",
                       steps_max, h, FB_IMPACT_MAX_STEPS);
  const double t_wall = fb_clock_s();
  const double R = 0.01; /* sphere radius [m]; a normal contact through the centre */
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher(&config);
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
  world.setGravity(btVector3(0, 0, 0));
  btContactSolverInfo &info = world.getSolverInfo();
  info.m_splitImpulse = 0;   /* split impulse would turn the spring into a position fix */
  info.m_linearSlop = 0.0;   /* the contact starts at distance 0 */
  info.m_sor = 1.0;          /* no over-relaxation */
  info.m_numIterations = 50; /* one contact: converged in the first */
  info.m_restitutionVelocityThreshold = 0.0;
  btStaticPlaneShape ground_shape(btVector3(0, 0, 1), 0.0);
  btRigidBody::btRigidBodyConstructionInfo gi(0.0, nullptr, &ground_shape);
  btRigidBody ground(gi);
  btSphereShape ball_shape(R);
  btVector3 inertia(0, 0, 0);
  ball_shape.calculateLocalInertia(mass, inertia);
  btDefaultMotionState *no_state = nullptr;
  btRigidBody::btRigidBodyConstructionInfo bi(mass, no_state, &ball_shape, inertia);
  btRigidBody ball(bi);
  for (btRigidBody *b : {&ground, &ball}) {
    b->setFriction(0.0);
    b->setRestitution(0.0);
    b->setRollingFriction(0.0);
    b->setSpinningFriction(0.0);
  }
  /* the combined stiffness is the two bodies' in series, the damping their
   * sum (btManifoldResult): the ground gets an infinite spring and no damper
   * (its defaults would add 0.1 N s/m) */
  ball.setContactStiffnessAndDamping(stiffness, damping);
  ground.setContactStiffnessAndDamping(BT_LARGE_FLOAT, 0.0);
  ball.setActivationState(DISABLE_DEACTIVATION);
  /* only touching or penetrating points are solved: Bullet otherwise solves
   * the manifold's points at positive distance too (speculative contact),
   * which starts the spring before the contact (measured: peak penetration
   * -2.9 % at h omega 0.3 for a contact that begins mid-step) */
  ball.setContactProcessingThreshold(0.0);
  btTransform tr;
  tr.setIdentity();
  tr.setOrigin(btVector3(0, 0, R + t_free * speed));
  ball.setWorldTransform(tr);
  world.addRigidBody(&ground);
  world.addRigidBody(&ball);
  ball.setLinearVelocity(btVector3(0, 0, -speed));

  fb_status st = FB_OK;
  const size_t max_steps = (size_t)steps_max + 1;
  fb_impact_tally tally = {0, 0, 0.0, 0.0};
  size_t k;
  for (k = 0; k < max_steps && !tally.done; k++) {
    world.stepSimulation(h, 0, h);
    double impulse = 0.0;
    for (int i = 0; i < dispatcher.getNumManifolds(); i++) {
      const btPersistentManifold *pm = dispatcher.getManifoldByIndexInternal(i);
      for (int c = 0; c < pm->getNumContacts(); c++) impulse += pm->getContactPoint(c).getAppliedImpulse();
    }
    const double force = impulse / h;
    const double t1 = (double)(k + 1) * h - t_free; /* from the crossing */
    const double depth_now = R - ball.getCenterOfMassPosition()[2];
    if (!isfinite(depth_now) || !isfinite(force)) {
      st = fb_diag_set(diag, FB_ERR_NUMERIC, "Bullet contact impact: non-finite state at t = %g s",
                       t1);
      break;
    }
    fb_impact_tally_force(&tally, out, t1, h, depth_now, force, ball.getLinearVelocity()[2]);
  }
  out->steps = k;
  out->contact_duration = tally.t_end;
  out->restitution = ball.getLinearVelocity()[2] / speed;
  world.removeRigidBody(&ball);
  world.removeRigidBody(&ground);
  if (st == FB_OK && !tally.done)
    st = fb_diag_set(diag, FB_ERR_NUMERIC,
                     "Bullet contact impact: the body has not left the contact after %zu steps "
                     "(%g s)", k, (double)k * h);
  out->wall_s = fb_clock_s() - t_wall;
  return st;
}
