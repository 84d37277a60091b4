/* What the MuJoCo four-bar scene (mujoco_scene.h) and the engine kit's
 * MuJoCo binding (mujoco_kit.h) share, private to src/engines/mujoco (it
 * includes MuJoCo's header): the passive-force hook (mjcb_passive is one
 * global in MuJoCo; here it runs the hook of the model being stepped on
 * this thread), one step of MuJoCo's integrator, the loop closure's
 * softness from the case's [mujoco] keys, and MuJoCo's native contact on
 * a clearance joint (mujoco-clearance-native: its MJCF, its solref, its
 * force), written once for both. */
#ifndef FB_MUJOCO_COMMON_H
#define FB_MUJOCO_COMMON_H

#include <stddef.h>

#include <mujoco/mujoco.h>

#include "contact.h"
#include "opts_mujoco.h"
#include "textbuf.h"

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

/* ---- MuJoCo's native contact on a clearance joint (mujoco-clearance-native)
 * [mujoco] native_bore: tendon, a spatial tendon from a site at the hole's
 * centre to one at the pin's, limited to [0, c] (c the radial clearance):
 * MuJoCo adds one limit row along the eccentricity e when |e| > c
 * (mj_instantiateLimit, engine_core_constraint.c of 2.2.2: distance
 * c - |e|, force >= 0), the law's own geometry; or facets, the pin a
 * sphere and the hole a ring of boxes collided by MuJoCo. The restitution
 * law reaches either as a solref set before every step from the effective
 * mass along e (fb_mujoco_native_solref). */

/* native bore = tendon: the limit row's impedance, dmin = dmax = d. With
 * the solref of the force form (fb_mujoco_bore_solref) the row's force is
 * the law's k delta + c ddot plus an inerter d / ((1 - d) A) times the
 * penetration's acceleration, A MuJoCo's diagonal approximation of the
 * row's inverse mass: MuJoCo's smallest impedance (mjMINIMP, 1e-4) makes
 * the inerter 8e-6 kg here, 1e-4 of the smallest effective mass 0.09 kg.
 * Measured at the automatic step on cases/engines_restitution.ini, peak
 * force against the reference: +3.0 % at 1e-4, -1.6 % at 1e-3, -0.3 % at
 * 1e-2, +0.9 % at 0.1 (the sequence after revolution 1 is chaotic; the
 * first three impacts are within 0.5 % at each) */
#define FB_MUJOCO_BORE_IMPEDANCE mjMINIMP

/* native bore = facets: the radial thickness of a ring's boxes [m] (as
 * the ODE faceted collider's) */
#define FB_MUJOCO_RING_THICKNESS_M 2e-3

/* The bore tendon's solreflimit in the force form, sr (2): the limit
 * row's force is f = (aref - a1) / R at MuJoCo's optimum (a1 the row's
 * acceleration, R = (1 - d)/d A, A = tendon_invweight0; aref = -(s1 v +
 * s0 r)/d from the direct solref (-s0, -s1) and solimp d: mj_makeImpedance,
 * engine_core_constraint.c of 2.2.2), so sr = (-k keep, -c keep) with
 * keep = (1 - d) A gives f = k delta + c ddot + d/((1 - d) A) d2delta/dt2:
 * the law's spring k [N/m] and its damper c = 2 zeta sqrt(k mass) [N s/m]
 * on mass [kg] whatever else pushes along e. Before the model compiles
 * (no A yet) keep = (1 - d) / mass. */
void fb_mujoco_bore_solref(double sr[2], const fb_contact_law *law, double mass, double keep);

/* The facets' solref at impedance d, sr (2): the direct form per unit of
 * the effective mass m_eff [kg] (MuJoCo's K is s0 / dmax^2 and the contact
 * applies d K): (-d k / m_eff, -2 zeta sqrt(k / m_eff)). */
void fb_mujoco_facet_solref(double sr[2], const fb_contact_law *law, double m_eff, double d);

/* One clearance joint's native contact in a compiled model (ids, -1:
 * none): the bore tendon (tendon), or the pin's sphere and the first of
 * the hole's ring_n consecutive boxes (facets) on body hole_body (0: the
 * world). */
typedef struct {
  int tendon;     /* bore = tendon: the tendon hole centre -> pin centre, else -1 */
  int site_pin, site_hole; /* bore = tendon: its sites at the pin's and the hole's centres */
  int pin_geom;   /* bore = facets: the pin's sphere, else -1 */
  int ring_first; /* bore = facets: the first of the ring's boxes, else -1 */
  int ring_n;     /* boxes in the ring */
  int hole_body;  /* the body carrying the hole (0: the world) */
} fb_mujoco_native;

/* Sets bore b's solref in model m for the coming step: the law's spring
 * and damper on the effective mass m_eff [kg] along e (> 0, finite), the
 * tendon's in the force form (keep = (1 - its solimp d) A), the facets'
 * at impedance d (their sphere's and every box's). */
void fb_mujoco_native_solref(mjModel *m, const fb_mujoco_native *b, const fb_contact_law *law,
                             double m_eff, double d);

/* The force on bore b's pin from MuJoCo's constraints of the last forward
 * pass of d [N]: the tendon's limit force (efc_force of its
 * mjCNSTR_LIMIT_TENDON row, >= 0, along e), or |sum of f_n n| over the
 * contacts between the pin's sphere and the hole's body; and, f_pin (2)
 * not NULL, its vector on the pin (x, y) [N]: the tendon's -F e / |e| at
 * its sites, the facets' contact forces summed (each f_n along its
 * normal, the sphere MuJoCo's geom1 of a sphere-box pair). */
double fb_mujoco_native_force(const mjModel *m, const mjData *d, const fb_mujoco_native *b,
                              double f_pin[2]);

/* MJCF: the bore tendon name [0, c] between sites hole and pin, its
 * solreflimit sr (2) and solimplimit FB_MUJOCO_BORE_IMPEDANCE, each line
 * after indent ind (inside <tendon>). */
void fb_mujoco_put_bore(fb_text *t, const char *ind, const char *name, double c,
                        const double sr[2], const char *hole, const char *pin);

/* MJCF: the facets of a clearance joint at point (x, y) of a body's frame
 * [m], each line after indent ind: the pin (pin = 1) a sphere name of
 * radius r_pin, or the hole a ring of ring_n boxes (length the pin's [m])
 * whose inner faces touch the circle of radius r_pin + c, the box of
 * angle 0 along the frame's x and named name (NULL: unnamed), the ring's
 * boxes consecutive in the compiled model. Pins collide with rings only (a sphere's
 * contype 1 and conaffinity 0, a box's contype 0 and conaffinity 1). Their
 * solref the law's on its own mass at impedance d
 * (fb_mujoco_native_solref replaces it before the first step). */
void fb_mujoco_put_facets(fb_text *t, const char *ind, const char *name, int pin,
                          const fb_contact_law *law, double d, double r_pin, double c, int ring_n,
                          double length, double x, double y);

#endif
