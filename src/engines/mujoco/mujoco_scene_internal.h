/* The MuJoCo scene's insides, shared by the files that make it up (private
 * to src/engines/mujoco: it includes MuJoCo's header). mujoco_scene.h says
 * what the scene is; the files are:
 *   mujoco_scene.c    building the scene (the model compiled from its MJCF,
 *                     the state at t = 0, the ids it reads) and freeing it
 *   mujoco_mjcf.c     the MJCF text: the scene's own and the exported one
 *   mujoco_load.c     loading an MJCF text (mujoco_load.h)
 *   mujoco_contact.c  the clearance contact: the law through the
 *                     passive-force hook, MuJoCo's native contacts and their
 *                     solref, the effective mass and the provenance
 *   mujoco_step.c     one step and the adaptive step
 *   mujoco_sample.c   what a state gives: samples, reactions, penetration,
 *                     drift, counts
 * Calls run one way: scene -> mjcf, load, contact, sample; step -> contact,
 * sample; mjcf -> load. */
#ifndef FB_MUJOCO_SCENE_INTERNAL_H
#define FB_MUJOCO_SCENE_INTERNAL_H

#include <mujoco/mujoco.h>

#include "episode.h"
#include "mujoco_scene.h"

/* one clearance joint's last evaluation (at the last forward pass) */
typedef struct {
  double e[2];   /* eccentricity pin - hole [m] */
  double delta;  /* penetration |e| - c [m], may be negative */
  double ddot;   /* penetration rate [m/s] */
  double force;  /* normal force [N] */
  fb_episode ep; /* episodes, updated once per step */
  fb_contact_provenance prov; /* effective mass and h omega_c over the contact steps */
} mj_clearance;

/* what this scene was built from: the scene definition with the model's row
 * applied */
typedef struct {
  fb_mech_type mech;    /* the case's mechanism: the four-bar, or the slider-crank (its body 2
                           the slider, on a slide joint along x at y = offset) */
  fb_linkage lengths;
  fb_start_state start;
  double omega2;
  double gravity;
  fb_link_mass link[3];
  double h;
  int adaptive;         /* 1: [solver] h_s = adaptive (h is the output grid, h_min) */
  double h_max;         /* adaptive: the longest step [s] */
  double accuracy;      /* adaptive: step_control.h's accuracy [-] */
  int clearance_mask;
  double radial_clearance;
  fb_contact_law law[4];
  double impact_velocity_min;
  fb_mujoco_opts opts;
  int native;           /* 1: MuJoCo's own contacts (FB_COLLIDER_NATIVE) */
  int facets;           /* native: 1 the hole a ring of boxes, 0 a limited tendon (fb_mujoco_bore) */
  int ring_n;           /* boxes in each hole's ring (native, facets) */
  double pin_radius;    /* R_pin [m] (native) */
  double pin_length;    /* [m] (native: the ring's height) */
  int exported;         /* 1: a user's file (fb_mujoco_export): sites named after the joints
                           (crank-coupler_pin), a velocity servo on the crank, a keyframe
                           with the start, the bore's solref fixed (bore_solref) */
  double bore_solref[4][2]; /* exported: each bore tendon's solreflimit; NAN: the scene's */
} mj_def;

struct fb_mujoco_scene {
  mj_def def;
  int integrator; /* fb_mujoco_integrator, resolved */
  mjModel *m;
  mjData *d;
  double *jac;        /* 2 x (3 x nv): pin and hole site Jacobians */
  double *w;          /* 4 x nv: J^T n of each joint at its last evaluation, then 1 x nv scratch */
  int hinge_dof[3];   /* dof of each body's own joint: the hinges z of crank A, coupler B and
                         follower D; a slider-crank's third is the slider's slide x (D) */
  int hinge_qpos[3];  /* its qpos address */
  int site_pin[4];    /* site of each joint's pin centre */
  int site_hole[4];   /* site of each joint's hole centre */
  int pin_geom[4];    /* native: the pin's sphere geom, or -1 */
  int hole_body[4];   /* native: the body carrying the hole's ring (0: world) */
  int ring_first[4];  /* native: the first of the hole's ring_n box geoms (consecutive), or -1 */
  int bore_tendon[4]; /* native: the tendon hole centre -> pin centre limited to [0, c], or -1 */
  double angle0[3];   /* body angles at qpos0 [rad]; a slider-crank's third: the slider's x [m] */
  mj_clearance cl[4];
  int body[3];        /* body id of crank, coupler, follower (a slider-crank's slider) */
  double reaction[4][2]; /* joint forces now, invdyn.h's convention [N] */
  double drive_torque;   /* on the crank from the flywheel about +z [N m] */
  size_t steps;
  /* [solver] h_s = adaptive (step_control.h): each MuJoCo step spans mc grid
   * steps of h; the samples inside it are interpolated between its ends */
  struct {
    int m_max, m_prev, mc, k; /* grid steps: largest, of the last step; sample k of mc */
    double h_prev;            /* the last step [s] */
    double ddot_prev[4];      /* penetration rate at its start [m/s] */
    double m_eff[4];          /* effective mass at the last contact [kg] */
    double m_eff_now[4];      /* effective mass at the state now, where m_eff_fresh [kg] */
    int m_eff_fresh;          /* 1: m_eff_now holds this state's (step_once left it) */
    double phase[4];          /* contact phase so far, sum of h omega_c [rad] (contact.h) */
    fb_sample x0, x1;         /* samples at the last step's start and end */
    fb_step_stats stats;
  } ad;
};

/* ---- mujoco_mjcf.c ---- */

/* d from model sm: the scene definition with the model's row applied, and
 * the start (fb_model_scene_start). Errors: those of fb_model_scene_start;
 * FB_ERR_ARG for an adaptive step with MuJoCo's native contacts */
fb_status mujoco_def_from_model(mj_def *d, const fb_model_scene *sm, fb_diag *diag);

/* the MJCF text of def into buf (size bytes). Errors: FB_ERR_RANGE when buf
 * is too small */
fb_status mujoco_write_mjcf(char *buf, size_t size, const mj_def *def, fb_diag *diag);

/* ---- mujoco_contact.c ---- */

/* the project's passive-force hook on for s's model (mjcb_passive: one
 * global hook) around MuJoCo calls that evaluate forces, and off after */
void mujoco_hook_on(fb_mujoco_scene *s);
void mujoco_hook_off(void);

/* forward pass at the current state with this scene's hook */
void mujoco_forward(fb_mujoco_scene *s);

/* native contacts: the force on joint j's pin from MuJoCo's constraints of
 * this forward pass [N] into cl[j].force */
void mujoco_native_force(fb_mujoco_scene *s, int j);

/* native contacts: joint j's solref from the effective mass at this state */
void mujoco_native_solref_update(fb_mujoco_scene *s, int j);

/* the effective mass of clearance joint j along its normal at this state
 * [kg] (NAN when it cannot be formed) */
double mujoco_joint_effective_mass(fb_mujoco_scene *s, const mjModel *m, mjData *d, int j);

/* joint j's contact provenance at this state, effective mass mass [kg] */
void mujoco_note_contact(fb_mujoco_scene *s, int j, double mass);

/* ---- mujoco_sample.c ---- */

/* joint reactions and the drive torque at this state (after a forward pass) */
void mujoco_reactions_now(fb_mujoco_scene *s);

/* the sample of the state now */
void mujoco_sample_now(const fb_mujoco_scene *s, fb_sample *x);

#endif
