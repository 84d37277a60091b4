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

/* ---- a model file for a user (fourbar export --format mjcf) ---------------
 * A user's first edit of an exported file is its <option timestep>: the
 * drive and the loop are written so that any step from the exported one to
 * FB_MUJOCO_EXPORT_H_USER_MAX_S holds (measured: docs/contact-params.md, "A
 * MuJoCo user at 2 ms"). One rule for the four-bar's export
 * (mujoco_mjcf.c) and a planar case's (mujoco_kit.c). */

/* the largest step [s] an export is written for (MuJoCo's default step) */
#define FB_MUJOCO_EXPORT_H_USER_MAX_S 2e-3

/* the drive's time constant [s]: armature / kv of the export's velocity
 * servo (a general actuator, torque kv (omega + ctrl - qvel)). A speed
 * error decays as exp(-t / tau) at any step; h / tau = 0.2 at
 * FB_MUJOCO_EXPORT_H_USER_MAX_S, inside explicit Euler's and RK4's
 * stability (2 and 2.78). A plain load starts at rest and the drive spins
 * the crank up to the case's speed within 1 % in 4.6 tau */
#define FB_MUJOCO_EXPORT_DRIVE_TAU_S 1e-2

/* the loop's damping ratio in MuJoCo's time-constant form (solref = (tc,
 * dampratio)): MuJoCo raises tc to 2 h at a step h above tc / 2 (refsafe,
 * on by default in 2.2 and 3.x), which makes the loop's stiffness and
 * damping per step B h = 1, K h^2 = 1 / (4 dampratio^2) at any step.
 * Semi-implicit Euler (and implicit, the same for constraints): 0.5,
 * K h^2 = 1, its deadbeat update (the scene's own direct form (-1/h^2, -1/h));
 * RK4: 0.2, K h^2 = 6.25, the ratio at which RK4's update of the loop error
 * decays fastest (amplification 0.345 per step; unstable below 0.17). The
 * stiffer loop leaves 6.25 times less of the drift MuJoCo 2.2 to 3.6 leave
 * from the J-dot-v term their reference acceleration lacks (measured, paper
 * case at 2 ms: Euler 0.5 +9.1 %, RK4 0.2 +0.7 % on the follower's omega
 * peak) */
#define FB_MUJOCO_EXPORT_LOOP_DAMPRATIO_EULER 0.5
#define FB_MUJOCO_EXPORT_LOOP_DAMPRATIO_RK4 0.2

/* The export's integrator (fb_mujoco_integrator): the case's [mujoco]
 * integrator, auto resolved to RK4 (its loop holds a 2 ms step within 1 %,
 * measured above). */
int fb_mujoco_export_integrator(const fb_mujoco_opts *o);

/* The export's loop solref at the written step h [s]: the case's own
 * direct form (fb_mujoco_loop_solref) when it gives [mujoco]
 * loop_stiffness_1_s2 or loop_damping_1_s; else the time-constant form
 * (2 h, the damping ratio of integrator above), which MuJoCo raises to
 * 2 x timestep at a user's longer step. */
void fb_mujoco_export_loop_solref(const fb_mujoco_opts *o, int integrator, double h,
                                  double sr[2]);

#endif
