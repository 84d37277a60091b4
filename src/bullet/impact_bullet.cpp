/* The single impact in Bullet (bullet_scene.h, fb_impact_bullet): the
 * counterpart of impact_ode.c with the same soft row as the clearance
 * joints. */
#include <math.h>
#include <string.h>

#include <new>

#include "bt_rows.h"
#include "bullet_scene.h"
extern "C" {
#include "clock.h"
}

extern "C" fb_status fb_impact_bullet(fb_impact_result *out, const fb_impact_def *d,
                                      const fb_bullet_opts *bt, fb_diag *diag) {
  memset(out, 0, sizeof *out);
  fb_status st = fb_impact_check(d, diag);
  if (st != FB_OK) return st;
  if (bt->iterations < 1 || bt->iterations > 100000)
    return fb_diag_set(diag, FB_ERR_RANGE, "Bullet impact: iterations = %d: must be 1 to 100000",
                       bt->iterations);
  const double t_wall = fb_clock_s();
  fb_contact_law law = d->law;
  law.mass = d->mass;
  fb_contact_law_prepare(&law, NULL);
  const double T = fb_impact_duration_estimate(d);
  const size_t max_steps = (size_t)ceil(100.0 * T / d->h) + 10;
  const double h = d->h;

  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher(&config);
  btDbvtBroadphase broadphase;
  btDantzigSolver dantzig;
  FbMlcp mlcp(&dantzig);
  FbSequentialImpulse si;
  btConstraintSolver *solver =
      bt->solver == FB_BULLET_MLCP_DANTZIG ? static_cast<btConstraintSolver *>(&mlcp) : &si;
  btDiscreteDynamicsWorld world(&dispatcher, &broadphase, solver, &config);
  world.setGravity(btVector3(0, 0, 0));
  world.getSolverInfo().m_numIterations = bt->iterations;
  world.getSolverInfo().m_minimumSolverBatchSize = 1;
  btEmptyShape shape;
  /* a sphere's inertia, which a normal row through the centre never uses */
  const double I = 0.4 * d->mass * 0.01 * 0.01;
  btRigidBody::btRigidBodyConstructionInfo ci(d->mass, nullptr, &shape, btVector3(I, I, I));
  btRigidBody body(ci);
  body.setFlags(0);
  body.setActivationState(DISABLE_DEACTIVATION);
  world.addRigidBody(&body, 0, 0);
  FbRows row(body);
  world.addConstraint(&row, true);
  body.setLinearVelocity(btVector3(0, 0, -d->speed)); /* touching: penetration 0 */

  double v0 = -1.0;
  int in_contact = 0, done = 0;
  double t_end = 0.0, prev_depth = 0.0, phase = 0.0;
  size_t k;
  for (k = 0; k < max_steps && !done; k++) {
    const double delta = -body.getCenterOfMassPosition()[2];
    const double ddot = -body.getLinearVelocity()[2];
    double share = 1.0;
    row.nrows = 0;
    if (delta > 0.0) {
      const int onset = v0 < 0.0;
      if (onset) v0 = ddot;
      fb_contact_row u;
      if (fb_contact_row_step(&u, &law, d->mapping, h, d->mass, 1, delta, ddot, v0, onset,
                              fb_contact_persistence(phase)) == FB_OK) {
        share = u.step_share;
        phase += fb_contact_h_omega(h, u.kp, d->mass);
        FbRow &r = row.row[0];
        r.n = btVector3(0, 0, 1); /* pushes the body out along +z */
        r.p = body.getCenterOfMassPosition();
        r.angular = 0;
        r.rhs = u.erp * u.depth / h;
        r.cfm_h = u.cfm / h;
        r.lo = 0.0;
        r.hi = SIMD_INFINITY;
        row.nrows = 1;
      }
    }
    world.stepSimulation(h, 0, h);
    const double force = row.nrows ? share * row.getAppliedImpulse() / h : 0.0;
    const double t1 = (double)(k + 1) * h;
    const double depth_now = -body.getCenterOfMassPosition()[2];
    if (!isfinite(depth_now) || !isfinite(force)) {
      st = fb_diag_set(diag, FB_ERR_NUMERIC, "Bullet impact: non-finite state at t = %g s", t1);
      break;
    }
    if (depth_now > out->penetration_max) out->penetration_max = depth_now;
    if (force > out->force_max) out->force_max = force;
    if (force > 0.0) {
      in_contact = 1;
      t_end = t1;
      if (depth_now <= 0.0 && prev_depth > 0.0)
        t_end = t1 - h + h * prev_depth / (prev_depth - depth_now);
    } else if (in_contact && body.getLinearVelocity()[2] > 0.0) {
      done = 1;
    }
    prev_depth = depth_now;
    if (in_contact && depth_now <= 0.0 && body.getLinearVelocity()[2] > 0.0) done = 1;
  }
  out->steps = k;
  out->contact_duration = t_end;
  out->restitution = body.getLinearVelocity()[2] / d->speed;
  world.removeConstraint(&row);
  world.removeRigidBody(&body);
  if (st == FB_OK && !done)
    st = fb_diag_set(diag, FB_ERR_NUMERIC,
                     "Bullet impact: the body has not left the contact after %zu steps (%g s)", k,
                     (double)k * h);
  out->wall_s = fb_clock_s() - t_wall;
  return st;
}
