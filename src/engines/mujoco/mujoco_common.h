/* What the MuJoCo four-bar scene (mujoco_scene.h) and the engine kit's
 * MuJoCo binding (mujoco_kit.h) share, private to src/engines/mujoco (it
 * includes MuJoCo's header): the passive-force hook (mjcb_passive is one
 * global in MuJoCo; here it runs the hook of the model being stepped on
 * this thread), one step of MuJoCo's integrator, and the loop closure's
 * softness from the case's [mujoco] keys. */
#ifndef FB_MUJOCO_COMMON_H
#define FB_MUJOCO_COMMON_H

#include <mujoco/mujoco.h>

#include "opts_mujoco.h"

/* solimp width, midpoint and power after dmin = dmax: with dmin = dmax
 * they have no effect (MuJoCo's defaults) */
#define FB_MUJOCO_SOLIMP_TAIL "0.001 0.5 2"

/* A passive-force hook: adds to d->qfrc_passive at the state of d (every
 * forward pass, every integrator stage); ctx the caller's. */
typedef void (*fb_mujoco_passive_fn)(void *ctx, const mjModel *m, mjData *d);

/* fn(ctx, m, d) runs in MuJoCo's passive stage of model m on this thread
 * until fb_mujoco_passive_off (another model's passes run no hook). */
void fb_mujoco_passive_on(const mjModel *m, fb_mujoco_passive_fn fn, void *ctx);
void fb_mujoco_passive_off(void);

/* One step of the model's timestep with integrator (fb_mujoco_integrator,
 * resolved) from the accelerations of the last forward pass: mj_Euler,
 * mj_RungeKutta(m, d, 4), or mj_step2 for implicit (it redoes the
 * acceleration stage; the model's option integrator must be implicit). */
void fb_mujoco_integrate(const mjModel *m, mjData *d, int integrator);

/* MJCF's option integrator of integrator: "Euler", "implicit", "RK4". */
const char *fb_mujoco_integrator_xml(int integrator);

/* The loop closure's direct-form solref (-k, -b) at step h [s]: k the
 * case's loop_stiffness_1_s2, or 1/h^2 when 0; b its loop_damping_1_s, or
 * 1/h (with Euler one step removes a violation; opts_mujoco.h). */
void fb_mujoco_loop_solref(const fb_mujoco_opts *o, double h, double sr[2]);

#endif
