/* The MuJoCo binding's world (mujoco_kit.h), private to src/engines/mujoco
 * (it includes MuJoCo's header): what mujoco_kit.c (the tree, the MJCF, the
 * step, the law through the passive-force hook) and mujoco_kit_native.c
 * (MuJoCo's native contact on the clearance joints: the native binding)
 * share. Calls run one way: mujoco_kit.c -> mujoco_kit_native.c. */
#ifndef FB_MUJOCO_KIT_INTERNAL_H
#define FB_MUJOCO_KIT_INTERNAL_H

#include <stddef.h>

#include "kit.h"
#include "mujoco_common.h"
#include "planar_spec.h"
#include "textbuf.h"

/* an ideal joint as added */
typedef struct {
  int prismatic;       /* 1: a slide along axis; 0: a hinge about +z */
  int b0, b1;          /* kit handles */
  double at[2];        /* [m] */
  double axis[2];      /* unit, world, at assembly */
  int side;            /* the body its reaction's moment is taken on: b1, or b0 when b1 is the
                          ground (kit.h's reactions), as a MuJoCo body id once built */
  double local[2];     /* the joint's point in that body's frame [m] */
  int node;            /* a tree joint: its child node (parent node 0: the ground, b + 1
                          handle b); a loop's: -1 */
  int eq;              /* a loop's connect equality (MuJoCo's id), else -1 */
} mk_joint;

/* a contact slot (kit.h): a pin in its hole (its pin's and hole's
 * centres), or a slider's corner against its guide's wall (the corner on
 * the slider, the wall's point and normal on the guide), its law */
typedef struct {
  int in;              /* 1: a clearance joint's slot */
  int on;              /* 1: the kit handed its contact for this step (law, v0) */
  int pin, hole;       /* kit handles, then MuJoCo body ids (hole 0: the world) */
  double at[2];        /* the pin's centre at the start [m] (kit.h fb_kit_clearance_joint.at) */
  double ah[2];        /* the hole's centre at the start [m] (its at_hole; a slider's guide:
                          unused, aw its wall's point) */
  double lp[2], lh[2]; /* the pin's and the hole's centres in their bodies' frames [m] */
  double c;            /* radial clearance [m] */
  double v_min;        /* an onset slower than this is taken at it [m/s] (episode.h) */
  double v0;           /* the step's onset rate [m/s] */
  fb_contact_law law;  /* the law, its damper on the last effective mass the kit gave (before
                          the first contact: on the law's own mass) */
  int wall;            /* 1: a corner against a flat wall (planar_guide.h), else a pin */
  double aw[2], nw[2]; /* a wall: its point and its unit normal (towards the wall, the way
                          the corner penetrates) at assembly [m], [-] */
  double ln[2];        /* a wall's normal in the hole's (guide's) frame [-]; lh its point */
  double f[2];         /* the force on the pin at the step's first forward pass [N] (0: none) */
  double xp[3], xh[3]; /* where it acts on the pin and, opposite, on the hole [m] */
} mk_contact;

/* a clearance joint's native contact (the native binding) */
typedef struct {
  fb_mujoco_native b;  /* its bore in the compiled model (mujoco_common.h) */
  double r_pin;        /* the pin's radius [m] */
  double m_eff;        /* the effective mass the kit handed for the coming step [kg] (0: none
                          yet) */
  double force;        /* the force on the pin at the step's first forward pass [N] */
  double f[2];         /* its vector on the pin (x, y) [N] */
} mk_native;

/* the binding's world */
typedef struct {
  double gravity, h;
  double h_now;        /* the coming step's timestep (step_by; 0: h) [s] */
  fb_mujoco_opts opts;
  fb_kit_body *body;   /* (nb) */
  mk_joint *joint;     /* (nj) the ideal joints, as added */
  int nb, nj, nj_all;  /* bodies, ideal joints added, the description's joints */
  int *parent, *edge;  /* per node (0 the ground, b + 1 handle b): parent node, tree joint (-1:
                          planar freedom from the world) */
  unsigned char *tree; /* (nj) 1: a tree joint; 0: closes a loop */
  int drive;           /* the driven joint */
  double drive_qvel;   /* its qvel at the drive's rate [rad/s] (its hinge's sense) */
  int integrator;      /* fb_mujoco_integrator, resolved */
  mjModel *m;
  mjData *d;
  int *bid;            /* (nb) MuJoCo body id of each handle */
  mk_contact ct[FB_KIT_SLOTS]; /* by the kit's contact slot */
  int used[FB_KIT_SLOTS], nused; /* the slots in use (ct[].in), ascending: the step's loops */
  size_t steps;
  int record;          /* 1: the hook keeps each contact's force (the step's first pass) */
  double pos_ready;    /* the timestep [s] at which the last step's end ran MuJoCo's position
                          stage (after_step); 0: the next step runs the whole forward pass */
  double *acc;         /* (nb x 3) every body's acceleration at the last step's start:
                          centre x, y [m/s^2], about +z [rad/s^2] (kit.h's body_accel) */
  double *react;       /* (nj x 3) every ideal joint's reaction there (kit.h's reactions) */
  double *frc;         /* ((nb + 1) x 6) MuJoCo's interaction forces less the contacts' */
  fb_kit_world o;      /* the walk's settings: names, drive, model_file (kit.h) */
  int native;          /* 1: MuJoCo's native contact on the clearance joints (the native
                          binding, mujoco_kit_native.c); 0: the law through the hook */
  int facets;          /* native: 1 [mujoco] native_bore = facets, 0 tendon */
  int ring_n;          /* native facets: boxes in each hole's ring */
  double pin_length;   /* native facets: the rings' height [m] */
  mk_native nat[FB_PLANAR_SPEC_MAX_JOINTS]; /* native: by clearance joint */
} mk_world;

/* slot *c of a pin in its hole, clearance joint cj (kit.h's add_clearance):
 * its pin's and hole's handles and centre, the clearance and the law */
static inline void mk_pin_slot(mk_contact *c, const fb_kit_clearance_joint *cj) {
  *c = (mk_contact){.in = 1, .pin = cj->pin, .hole = cj->hole, .at = {cj->at[0], cj->at[1]},
                    .ah = {cj->at_hole[0], cj->at_hole[1]},
                    .c = cj->cl->radial_clearance, .v_min = cj->cl->impact_velocity_min,
                    .law = cj->law};
}

/* ---- mujoco_kit_native.c: the native binding's own members (kit.h) ---- */

/* clearance joint j as MuJoCo's native contact ([mujoco] native_bore of
 * the case), a pin in its hole only: FB_ERR_ARG for a slider in its guide */
fb_status mk_native_add_clearance(void *w, int j, const fb_kit_clearance_joint *cj,
                                  fb_diag *diag);

/* contact slot k's effective mass for the coming step (every step: kit.h's
 * contact_always) */
fb_status mk_native_add_contact(void *w, int k, const fb_kit_contact *c, fb_diag *diag);

/* the force on slot k's pin at the last step's first forward pass [N] */
double mk_native_contact_force(const void *w, int k);

/* ... and its vector (x, y) [N] */
void mk_native_contact_force_vec(const void *w, int k, double f[2]);

/* ---- mujoco_kit_native.c: what the world's build and step ask of it ---- */

/* bytes of MJCF text the native contacts add */
size_t mk_native_mjcf_bytes(const mk_world *k);

/* MJCF: the native contacts' sites or geoms on node v (0: the world; the
 * slots' centres in their bodies' frames, lp and lh, set) */
void mk_native_put_body(fb_text *t, const mk_world *k, int v);

/* MJCF, a user's file (model_file): a comment on each native contact,
 * its elements' names, its law and the largest step it holds (h omega_c
 * at h_omega_max, the integrator's stability bound on an undamped spring) */
void mk_native_put_comment(fb_text *t, const mk_world *k, double h_omega_max);

/* MJCF: the bore tendons (bore = tendon), after the world body */
void mk_native_put_tendons(fb_text *t, const mk_world *k);

/* the native contacts' ids in the compiled model k->m */
void mk_native_bind(mk_world *k);

/* after the step's first forward pass at the state it starts from: each
 * native contact's force there (and a tendon's on the pin's and the
 * hole's centres, ct[j].f, for the reactions), then its solref for the
 * integrator's stages from the effective mass the kit handed */
void mk_native_start(mk_world *k);

#endif
