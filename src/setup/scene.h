/* The scene stage: a case resolved once per run into the engine-free
 * definition every engine builds its world from.
 *
 * fb_scene_from_case settles everything a case leaves open, in one place:
 * the worst stack-up corner (tolerance.h), the nominal and stack-up lengths,
 * the contact law of every clearance joint for each law a listed model uses,
 * with the penalty stiffness the run really uses (joint_law.h: inverse-
 * dynamics reactions solved once, stiffness_scale applied), the penetration
 * limit of the stability guard, and the initial state ([run] start and
 * pin_start, start.h) of both linkages, ideal and with clearance. fb_scene_check validates the result field by field (Box2D's
 * b2CreateBody pattern); every engine calls it first.
 *
 * A model (model_table.h) then selects from the definition: its lengths, its
 * clearance joints and its law (fb_scene_select). No engine header is
 * included here. */
#ifndef FB_SCENE_H
#define FB_SCENE_H

#include "case.h"
#include "contact.h"
#include "model_table.h"
#include "start.h"

/* Everything an engine needs to build the mechanism, in SI units. */
typedef struct {
  fb_linkage lengths[2];          /* nominal, stack-up link lengths [m] (FB_LENGTHS_*) */
  fb_start_state start[2][2];     /* state at t = 0 ([run] start, pin_start; start.h) per
                                     lengths (FB_LENGTHS_*) and joint set (FB_JOINTS_*) */
  int start_given;                /* 1: start[][] holds the case's start; 0: the start was moved
                                     (fb_scene_set_start): engines start steady from the
                                     analytic solver at crank_angle0, omega2, pins centred */
  fb_stackup stackup;             /* stack-up corner as resolved (worst flag cleared) */
  fb_branch branch;               /* assembly branch of the initial configuration */
  double crank_angle0;            /* crank angle at t = 0 [rad] */
  double omega2;                  /* signed crank speed [rad/s] */
  double gravity;                 /* along -y [m/s^2] */
  fb_link_mass link[3];           /* crank, coupler, follower */
  fb_solver solver;               /* step size, stepper, ERP/CFM, drive torque, seed */
  double duration;                /* simulated time [s] */
  size_t steps;                   /* steps of size solver.h over duration [-] */
  int clearance_mask;             /* bit j: joint j is a clearance joint (fb_joint) */
  double radial_clearance;        /* c = R_hole - R_pin [m] */
  double pin_radius;              /* R_pin [m] */
  double pin_length;              /* pin length in contact [m] (faceted geometry) */
  int has_law[FB_MODEL_LAW_COUNT]; /* 1: law[k] was resolved (a listed model uses it) */
  fb_contact_law law[FB_MODEL_LAW_COUNT][4]; /* law of each clearance joint, per model law */
  fb_mapping mapping;             /* per-step linearisation of the law */
  double friction;                /* Coulomb coefficient [-]; 0 for frictionless */
  double impact_velocity_min;     /* onset rates below this count as continuous contact [m/s] */
  double penetration_limit;       /* a model stops beyond this penetration [m] (> 0) */
  double impact_floor[4];         /* contact force above which a sample belongs to an impact, per
                                     clearance joint: FB_IMPACT_FLOOR_SHARE x the joint's largest
                                     ideal reaction over a revolution (stack-up lengths) [N]
                                     (episode.h); every model's series counts with it */
  int faceted_n;                  /* boxes in the ring of the faceted collider [-] */
  fb_collider case_collider;      /* [clearance] collider: replaces FB_COLLIDER_EXACT in ODE rows */
  int ccd_segments;               /* convex segments of the libccd bore ring [-] (collide_ccd.h) */
  double bore_ovality;            /* libccd bore: diameter excess along the hole body's x [m];
                                     0: circle */
  int ccd_split;                  /* libccd: 0 depth-weighted split of the law, 1 by contact count */
  double settle_damping;          /* body velocity damping per step [-] for static settling
                                     tests; 0 in every model */
#define X(name) fb_##name##_opts name; /* the case's [name] options (model/opts_name.h) */
  FB_ENGINE_OPTS_LIST             /* each engine's own choices: mujoco, bullet, simbody, ... */
#undef X
  fb_case source;                 /* the case as resolved (worst corner set), for engines
                                     that take a case (reference.h) */
} fb_scene;

/* What one model sees of a scene definition: the fields an engine builds
 * its world from, with the model's row applied (its lengths and start, its
 * clearance joints and their law, its collider's parameters). */
typedef struct {
  const fb_scene *def;        /* the definition it was selected from (not owned) */
  const fb_model *model;          /* the model's row */
  fb_linkage lengths;             /* the model's link lengths [m] */
  fb_start_state start;           /* its state at t = 0 when start_given */
  int start_given;                /* 0: start steady from the analytic solver at crank_angle0 */
  fb_branch branch;               /* assembly branch */
  double crank_angle0;            /* crank angle at t = 0 [rad] */
  double omega2;                  /* signed crank speed [rad/s] */
  double gravity;                 /* along -y [m/s^2] */
  fb_link_mass link[3];           /* crank, coupler, follower */
  fb_solver solver;               /* step size, stepper, ERP/CFM, drive torque, seed */
  int clearance_mask;             /* def->clearance_mask for clearance models, else 0 */
  double radial_clearance;        /* c = R_hole - R_pin [m] */
  double pin_radius;              /* R_pin [m] */
  fb_contact_law law[4];          /* law of each clearance joint (the row's law) */
  fb_mapping mapping;             /* per-step linearisation */
  double friction;                /* Coulomb coefficient [-] */
  double impact_velocity_min;     /* onset rates below this count as continuous contact [m/s] */
  fb_collider collider;           /* the collider used: the row's, or for an ODE row naming the
                                     exact one the case's [clearance] collider */
  int faceted_n;                  /* > 0: the faceted collider with this many boxes; else 0 */
  double pin_length;              /* [m], for the faceted and libccd geometry */
  int ccd_segments;               /* > 0: the libccd collider with a ring of this many convex
                                     segments (collide_ccd.h); else 0 */
  double bore_ovality;            /* libccd only: > 0 makes the bore an ellipse whose diameter
                                     along the hole body's x axis is larger by this [m] */
  int ccd_split;                  /* libccd only: 0 depth-weighted split of the law (default),
                                     1 the faceted model's split by contact count */
  double settle_damping;          /* body velocity damping per step [-]; 0 in every model */
#define X(name) fb_##name##_opts name; /* def's [name] options (name-* models) */
  FB_ENGINE_OPTS_LIST             /* each engine's own choices: mujoco, bullet, simbody, ... */
#undef X
  const fb_clearance *clearance;  /* the case's [clearance] section as resolved
                                     (&def->source.clearance): a new [clearance] key is read
                                     here, not copied; any other section is def->source's */
} fb_model_scene;

/* The state at t = 0 of model sm: sm->start when the case's start holds
 * (start_given), else the steady start from the analytic solver at
 * crank_angle0 and omega2 with every pin centred in its hole.
 * Errors: FB_ERR_ASSEMBLY when that start does not exist. */
fb_status fb_model_scene_start(fb_start_state *out, const fb_model_scene *sm, fb_diag *diag);

/* Zeroes *def and sets the fields no case carries: impact_velocity_min. */
void fb_scene_default(fb_scene *def);

/* The ERP/CFM mapping case c's clearance contacts use ([clearance]
 * mapping, contact.h): the adaptive step's long steps in continuous contact
 * need a row whose static stiffness does not depend on h, so matched turns
 * matched-static under [solver] h_s = adaptive. */
fb_mapping fb_case_contact_mapping(const fb_case *c);

/* Resolves case c once (see above) into *def. Laws are resolved only for
 * the laws the case's models use (a case of ideal models solves no inverse
 * dynamics). Errors: those of fb_case_check, fb_tol_resolve_worst and
 * fb_joint_laws (FB_ERR_RANGE, FB_ERR_ASSEMBLY, FB_ERR_ARG). */
fb_status fb_scene_from_case(fb_scene *def, const fb_case *c, fb_diag *diag);

/* Moves the initial state to crank angle theta0 [rad] and crank speed
 * omega2 [rad/s] (tests that hold the crank still): the steady start with
 * every pin centred (start_given = 0), checked to assemble for both
 * linkages. Errors: FB_ERR_ASSEMBLY. */
fb_status fb_scene_set_start(fb_scene *def, double theta0, double omega2, fb_diag *diag);

/* Checks every field: lengths valid (and assembled at crank_angle0 when the
 * start was moved), masses
 * and inertias positive, step size positive and below the duration, solver
 * ERP in [0, 1], CFM >= 0, clearance smaller than the pin radius, each
 * resolved law valid (contact.h), penetration limit positive, faceted_n >= 3
 * when the faceted collider is used, each engine's options
 * (fb_<name>_opts_check: MuJoCo's integrator known, loop stiffness and
 * damping >= 0, loop impedance in (0, 1), drive armature > 0; Bullet's and
 * Simbody's likewise). Errors: FB_ERR_RANGE, FB_ERR_ASSEMBLY
 * naming the field, its value and the rule. */
fb_status fb_scene_check(const fb_scene *def, fb_diag *diag);



/* The view of model m on def: lengths, start, clearance joints and laws.
 * Errors: FB_ERR_ARG when m needs a law def did not resolve or clearance
 * joints the case does not have. */
fb_status fb_scene_select(fb_model_scene *out, const fb_scene *def, const fb_model *m,
                              fb_diag *diag);

#endif
