/* A fixed contact row's single impact in ODE (see impact_ode.h); it owns
 * its own world. */
#include <math.h>
#include <ode/ode.h>
#include <string.h>

#include "clock.h"
#include "impact_ode.h"
#include "ode_contact.h"
#include "ode_env.h"

/* one step under the ODE error guard (ode_env.h): 1 stepped, 0 ODE could
 * not allocate, -1 ODE's own fatal check fired (the world is then left
 * mid-step and must not be touched again) */
static int guarded_step(dWorldID world, double h) {
  jmp_buf escape;
  if (setjmp(escape) != 0) return -1;
  fb_ode_escape = &escape;
  const int ok = dWorldStep(world, h);
  fb_ode_escape = NULL;
  return ok ? 1 : 0;
}

/* the impact's world: no gravity, one body of mass [kg] (a sphere's
 * inertia, which a normal contact never uses), a joint group for contacts */
static void impact_world(double mass, dWorldID *world, dJointGroupID *group, dBodyID *body) {
  *world = dWorldCreate();
  dWorldSetGravity(*world, 0, 0, 0);
  dRandSetSeed(1);
  *group = dJointGroupCreate(0);
  *body = dBodyCreate(*world);
  dMass m;
  dMassSetSphereTotal(&m, mass, 0.01);
  dBodySetMass(*body, &m);
}

fb_status fb_impact_ode_row(fb_impact_result *out, double mass, double speed, double h, double erp,
                            double cfm, double max_vel, double t_max, double onset_phase,
                            fb_diag *diag) {
  memset(out, 0, sizeof *out);
  if (!(mass > 0.0) || !(speed > 0.0) || !(h > 0.0) || !(cfm > 0.0) || !(erp >= 0.0) ||
      !(max_vel > 0.0) || !(t_max > h) || !isfinite(mass) || !isfinite(speed) || !isfinite(erp))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "ODE row impact: mass %g kg, speed %g m/s, h %g s, ERP %g, CFM %g, "
                       "max_vel %g m/s, t_max %g s: need positive, finite values, ERP >= 0",
                       mass, speed, h, erp, cfm, max_vel, t_max);
  if (!(onset_phase >= 0.0 && onset_phase < 1.0))
    return fb_diag_set(diag, FB_ERR_RANGE, "ODE row impact: onset phase %g: must lie in [0, 1)",
                       onset_phase);
  /* touching (phase 0), or a free step short of the crossing: the first
   * step that sees the contact then sees the depth phase h v */
  const double t_free = onset_phase > 0.0 ? (1.0 - onset_phase) * h : 0.0;
  const double steps_max = ceil((t_max + t_free) / h);
  if (steps_max > FB_IMPACT_MAX_STEPS)
    return fb_diag_set(diag, FB_ERR_RANGE, "ODE row impact: %g steps of %g s: more than %g",
                       steps_max, h, FB_IMPACT_MAX_STEPS);
  const double t_wall = fb_clock_s();
  fb_ode_acquire();
  dWorldID world;
  dJointGroupID group;
  dBodyID body;
  impact_world(mass, &world, &group, &body);
  dWorldSetContactMaxCorrectingVel(world, isfinite(max_vel) ? max_vel : dInfinity);
  dWorldSetContactSurfaceLayer(world, 0.0);
  dBodySetPosition(body, 0, 0, t_free * speed);
  dBodySetLinearVel(body, 0, 0, -speed);
  fb_status st = FB_OK;
  int broken = 0;
  fb_impact_tally tally = {0, 0, 0.0, 0.0};
  size_t k;
  dJointFeedback fb;
  for (k = 0; (double)k < steps_max && !tally.done; k++) {
    const dReal *p = dBodyGetPosition(body);
    const double delta = -p[2];
    dJointID cj = 0;
    if (delta >= 0.0) {
      dContact c;
      memset(&c, 0, sizeof c);
      c.surface.mode = dContactSoftERP | dContactSoftCFM;
      c.surface.soft_erp = erp;
      c.surface.soft_cfm = cfm;
      c.geom.pos[0] = p[0];
      c.geom.pos[1] = p[1];
      c.geom.normal[2] = 1.0;
      c.geom.depth = delta;
      cj = dJointCreateContact(world, group, &c);
      dJointAttach(cj, body, 0);
      dJointSetFeedback(cj, &fb);
    }
    const int ok = guarded_step(world, h);
    if (ok < 0) {
      st = fb_diag_set(diag, FB_ERR_NUMERIC, "ODE row impact: ode-error: %s at step %zu",
                       fb_ode_last_error(), k + 1);
      broken = 1;
      break;
    }
    if (!ok) {
      st = fb_diag_set(diag, FB_ERR_NOMEM, "ODE step %zu failed to allocate", k + 1);
      break;
    }
    const double force = cj ? fb.f1[2] : 0.0;
    dJointGroupEmpty(group);
    const double t1 = (double)(k + 1) * h - t_free; /* from the crossing */
    const double depth_now = -dBodyGetPosition(body)[2];
    if (!isfinite(depth_now) || !isfinite(force)) {
      st = fb_diag_set(diag, FB_ERR_NUMERIC, "ODE row impact: non-finite state at t = %g s", t1);
      break;
    }
    fb_impact_tally_depth(&tally, out, t1, h, depth_now, force);
  }
  out->steps = k;
  out->contact_duration = tally.t_end;
  if (broken) {
    fb_ode_quarantine(world);
    fb_ode_quarantine(group);
    out->wall_s = fb_clock_s() - t_wall;
    return st;
  }
  out->restitution = dBodyGetLinearVel(body)[2] / speed;
  dJointGroupDestroy(group);
  dWorldDestroy(world);
  fb_ode_release();
  if (st == FB_OK && !tally.done)
    st = fb_diag_set(diag, FB_ERR_NUMERIC,
                     "ODE row impact: the body has not left the contact after %zu steps (%g s)",
                     k, (double)k * h);
  out->wall_s = fb_clock_s() - t_wall;
  return st;
}
