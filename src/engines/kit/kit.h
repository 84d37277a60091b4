/* The engine kit (issue 58): one walk of a planar description
 * (model/mech/planar.h) that builds it in any engine through the engine's
 * binding, a table of builder functions, then steps the engine and samples
 * every moving body. An engine's folder supplies the binding (C; a C++
 * engine behind its extern "C" table) and keeps its own choices: its own
 * joints and loop closure, its own stepper, its own constraint settings.
 *
 * The walk (kit.c), in this order:
 *   world_new     the engine's world: gravity g [m/s^2] along -y, the
 *                 case's [solver] settings, step h [s]
 *   add_body      every moving body of the description at its assembly
 *                 pose (centre of mass, frame angle), mass [kg], moment of
 *                 inertia about +z through the centre [kg m^2], and the
 *                 velocity the drive gives it there (the core's velocity
 *                 analysis, planar_kinematics.h): the start is on the
 *                 ideal mechanism's path
 *   add_revolute  every revolute joint (a pin about +z at its assembly
 *                 position)
 *   add_prismatic every prismatic joint (a slide along its unit axis in
 *                 the world at the assembly configuration)
 *   add_clearance optional: each clearance joint in its place, once: an
 *                 engine whose clearance is a relation of its own (no
 *                 add_contact), one that evaluates the contact inside
 *                 its integrator (with add_contact), or one whose own
 *                 collider finds a pin's contacts (collide)
 *   close_loop    optional: an engine whose joints form a tree closes the
 *                 loops here (NULL: the engine's joints close them)
 *   hold_in_plane optional: a body that only clearance joints hold
 *   add_drive     the drive: the rate of body b1 relative to body b0 of
 *                 the driven joint [rad/s], constant; the walk's last
 *                 call (a binding may build its world there). An undriven
 *                 description (m->drive < 0, [drive] joint = none: a free
 *                 start, its velocities fb_kit_world's qd0) gets joint -1
 *                 and rate 0: no drive, the walk's end all the same
 *   add_contact   before every step, each clearance joint in contact: the
 *                 contact the kit's pipeline computed (fb_kit_contact),
 *                 after collide, for a binding's own collider, found
 *                 contacts there; a binding with contact_always gets every
 *                 revolute one off its hole's centre, in free flight too
 *                 (depth <= 0)
 *   step, body_state  advance h; read a body's pose and velocity
 *   contact_force optional: what the contact applied in the step
 * Bodies are named by the kit's handles: the ground is FB_KIT_GROUND, the
 * description's body b (1 ..) is handle b - 1; add_drive's joint is the
 * driven joint's place among the joints added (the description's order,
 * clearance joints left out); add_contact's and contact_force's k a
 * contact slot: a revolute clearance joint's slot is its description
 * index j, a prismatic one's (a slider in its guide, four corners) are
 * fb_kit_slot(j, 0 .. 3), every slot below FB_KIT_SLOTS, so that a
 * binding keeps one contact per slot whatever the joint's kind. SI
 * throughout. */
#ifndef FB_KIT_H
#define FB_KIT_H

#include <stddef.h>

#include "case.h"
#include "contact.h"
#include "model_table.h"
#include "engine.h"
#include "load_scale.h"
#include "planar.h"
#include "planar_guide.h"
#include "status.h"

/* The ground's handle. */
#define FB_KIT_GROUND (-1)

/* Contact slots of a kit run (add_contact's k): one per revolute
 * clearance joint, one per corner of a prismatic one. */
#define FB_KIT_SLOTS (FB_PLANAR_GUIDE_CORNERS * FB_PLANAR_SPEC_MAX_JOINTS)

/* The contact slot of corner `corner` (0 .. FB_PLANAR_GUIDE_CORNERS - 1,
 * planar_guide.h's order) of clearance joint `joint` (0 ..
 * FB_PLANAR_SPEC_MAX_JOINTS - 1): the joint's own index for corner 0 (a
 * revolute joint's one slot), the slots past FB_PLANAR_SPEC_MAX_JOINTS for
 * the others. */
int fb_kit_slot(int joint, int corner);

/* What a world is made with. */
typedef struct {
  double gravity;            /* along -y [m/s^2] */
  double h;                  /* step [s] */
  const fb_solver *solver;    /* the case's [solver] settings (case.h) */
  int nbodies, njoints;      /* moving bodies and joints the walk will add */
  const fb_case *c;          /* optional: the case, for an engine's own options (its [NAME]
                                section, c->bullet ...); NULL: their defaults */
  const double *q0, *qd0;    /* optional (fb_planar_nq each), NULL: the assembly and the
                                drive's velocities there: the start's coordinates x, y
                                [m], theta [rad] per moving body and their rates, the
                                ideal joints placed where their body[0] puts them (a start
                                with a clearance joint's pin off its hole's centre) */
  double contact_speed_max;  /* optional: the largest speed [m/s] at which the engine's contact
                                rows may push bodies apart to remove a depth (ODE's
                                contact_max_correcting_vel; 0: the engine's default,
                                unlimited): the single impact's fixed row (kit_impact.h) sets
                                it, as a user's world does; a mechanism's run leaves it 0. A
                                binding whose engine has no such limit reads 0 only
                                (fb_kit_impact_row refuses it otherwise) */
  int model_file;            /* 1: the world is built to be written as the engine's own model
                                file for a user (fb_kit_model_text): a binding may choose
                                settings that hold at a user's step rather than the run's */
  /* set by the walk (fb_kit_open) whatever the caller gave, for a binding's
   * names and its tree (fb_kit_joint_name, fb_kit_body_name, fb_kit_tree): */
  const fb_planar *mech;     /* the description built */
  unsigned mask;             /* its clearance joints (bit j: joint j, not added as a joint) */
  int drive;                 /* the driven joint's place among the joints added (add_drive's
                                joint), -1: undriven or clearance at the driven joint */
} fb_kit_world;

/* The description's name of the joint added at place (0 .., the order
 * add_revolute and add_prismatic were called, clearance joints left out),
 * or "?" when o->mech is not set or place is out of range. */
const char *fb_kit_joint_name(const fb_kit_world *o, int place);

/* The description's name of body handle b ("ground" for FB_KIT_GROUND),
 * or "?" when o->mech is not set or b is out of range. */
const char *fb_kit_body_name(const fb_kit_world *o, int b);

/* The spanning forest an engine that builds its joints as a tree keeps
 * (MuJoCo, Simbody, DART: a tree of joints from the ground, each other
 * joint closing a loop as a constraint at a pin): Kruskal's forest over the
 * ground (node 0) and the moving bodies (handle b: node b + 1), taking the
 * joints in turn: the driven joint o->drive (a tree joint carries the
 * drive), the prismatic joints (a loop closes at a pin), then the revolute
 * ones, each group in the engine's preferred order `order` (njoints places,
 * a permutation; NULL: the order added). ends[j] are joint place j's body
 * handles, prismatic[j] 1 for a slide. tree[j] (njoints) is set to 1 for a
 * tree joint, 0 for one that closes a loop. Returns -1, or the place of
 * the first prismatic joint that closes a loop all the same (the
 * description's prismatic joints, with the drive, form a loop among
 * themselves): the engine's refusal names it (fb_kit_joint_name). */
int fb_kit_tree(const fb_kit_world *o, int njoints, const int (*ends)[2],
                const unsigned char *prismatic, const int *order, unsigned char *tree);

/* One moving body at the start. */
typedef struct {
  double mass;        /* [kg] */
  double inertia;     /* about +z through the centre of mass [kg m^2] */
  double pos[3];      /* centre of mass x, y [m] and frame angle [rad] */
  double vel[3];      /* centre of mass velocity [m/s] and angular velocity [rad/s] */
} fb_kit_body;

/* One clearance joint's contact for the coming step, computed by the kit
 * (kit_contact.c) from the bodies' states: the pin on the joint's body[0],
 * the hole on its body[1]. A slider's corner in its guide (a prismatic
 * clearance joint, planar_guide.h) is a contact of its own in the same
 * terms: the slider (the joint's body[1]) the pin, the guide (its body[0])
 * the hole, the point on the guide's wall under the corner (the corner
 * less depth along the normal), the normal from the slide's line towards
 * that wall (the wall pushes the slider along -normal), depth and rate
 * the corner's, m_eff the corner's face's share (planar_guide.h). */
typedef struct {
  int pin, hole;       /* body handles (hole FB_KIT_GROUND for a ground hole) */
  double point[2];     /* on the hole wall, hole centre + (pin radius + c) n [m] */
  double normal[2];    /* n: unit, hole centre towards pin centre [-] */
  double depth;        /* penetration |e| - c > 0 [m] */
  double rate;         /* penetration rate n . (v_pin - v_hole) [m/s] (> 0 approaching) */
  double v0;           /* the episode's onset rate (episode.h) [m/s] */
  int onset;           /* 1 at the first step of a contact episode */
  double m_eff;        /* effective mass along n, the drive held (planar_mass.h) [kg] */
  fb_contact_law law;  /* the joint's law with its damper on m_eff (contact_mass.h) */
  fb_mapping mapping;  /* the case's [clearance] mapping (contact.h) */
  double h;            /* step [s] */
  double m_alone;      /* the contact's own effective mass, 1 / D_cc of the Delassus matrix
                          (a slider's corner alone, lighter than its face's share m_eff: the
                          slider's tilt); a pin's: m_eff [kg] */
  double friction;     /* Coulomb's coefficient mu at the contact ([clearance] friction; 0:
                          frictionless) [-] */
  double persistence;  /* the matched-static mapping's weight of the static row this step
                          (fb_contact_persistence of the slot's contact phase, the sum of its
                          rows' h omega_c since its onset; contact.h); 0 for other mappings */
  int wall;            /* 1: a slider's corner against its guide's flat wall; 0: a pin in its
                          hole */
  double centre[2][2]; /* the pin's and the hole's centres [m] (a corner: the corner and the
                          wall's point under it) */
  double ecc_rate[2];  /* d(pin centre - hole centre)/dt [m/s] (a corner: its normal part,
                          rate n) */
  int has_row;         /* 1: row holds the soft row the law and mapping give this contact
                          (contact.h fb_contact_row_step, persistence included): the kit's,
                          for a binding that takes rows (contact_rows) */
  fb_contact_row row;  /* that row (ERP, CFM, depth, the spring and damper it stands for) */
  double w_inv[2][2];  /* a pin's inverse-mass tensor W at the joint, the drive held: its
                          effective mass along any unit n is 1 / (n^T W n)
                          (effective_mass.h fb_effective_mass_along), for a binding's own
                          collider, whose contacts have normals of their own (collide)
                          [1/kg]; a corner's: 0 */
  int mean_force;      /* 1: the adaptive step's rocking bound is on ([solver] rocking_h_omega
                          > 0, step_control.h): row is the matched one throughout (persistence
                          0) with the mean-force correction already in its depth
                          (contact.h fb_contact_row_mean_force), which takes the place of the
                          matched-static row's drift correction */
} fb_kit_contact;

/* What a run's pins are found in their holes on (fb_kit_clearance.collider):
 * the kit's exact pin in its hole, or a generic collider the binding builds
 * and runs (kit.h's collide): a ring of flat facets, or a bore of convex
 * segments, each tangent to the hole's circle (or to an ellipse around it)
 * on the hole's body, around a cylinder of the pin's radius and length on
 * the pin's. */
typedef struct {
  fb_collider kind;   /* FB_COLLIDER_FACETED: the ring of facets; FB_COLLIDER_CCD: the bore of
                         segments; any other (0): the exact pin in its hole */
  int facets;         /* faceted: the ring's facets [-] (>= 3) */
  int segments;       /* ccd: the bore's segments [-] (>= 8) */
  double ovality;     /* ccd: the bore's diameter along the hole body's x axis less its
                         diameter along y, an ellipse (0: a circle) [m] */
  int split;          /* ccd: the law's rows over its contacts: 0 the deepest contact's row
                         shared in proportion to depth, 1 each contact its own row, the
                         spring divided by their count (the ring's rule) */
  double pin_length;  /* the pin's length in its hole [m] */
} fb_kit_collider;

/* The rows a binding's own collider made of a pin's contact in its last
 * add_contact (collided), for the kit's records of the joint. */
typedef struct {
  size_t rows;                 /* contact rows made [-] (0: none) */
  double m_eff_min, m_eff_max; /* the range of their effective masses [kg] (rows > 0) */
  double erp_max;              /* their largest ERP [-] */
  double cfm_min;              /* their smallest CFM [m/(N s)] */
  double h_omega_max;          /* their largest h omega_c, each row's spring kp times its share
                                  of the law's (rows in parallel) [-] */
  double omega_d_h_max;        /* their largest omega_d h, likewise: the matched mapping's
                                  aliasing stop (contact.h) [-] */
} fb_kit_rows;

/* What a kit run keeps of one clearance joint: its law, and its columns
 * and figures (out). Each column is n long, indexed by sample, or with a
 * window (fb_kit_series.window) window long, sample i at i & (window - 1)
 * (ecc's y then at ecc[window + (i & (window - 1))]). */
typedef struct {
  fb_contact_law law;       /* its law (joint_law.h), its damper put on m_eff each step */
  double *force;            /* optional (n), NULL: not kept: its contact force over the step
                               from sample i [N] */
  double *pen;              /* optional (n), NULL: not kept: its penetration at sample i [m] */
  double *ecc;              /* optional (2 x n), NULL: not kept: its eccentricity, pin centre -
                               hole centre, x at ecc[i], y at ecc[n + i] [m] (a slider: its
                               centre across the slide [m], its tilt [rad]) */
  double *state;            /* optional (n), NULL: not kept: its contact state in the step from
                               sample i (series.h FB_STATE_*: free when it applied no force, else
                               its episode's impact or continuous) [-] */
  double *force_max;        /* optional (n), NULL: not kept: its largest contact force over the
                               step from sample i, the binding's sub-steps (contact_force_max)
                               or, without them, force[i] [N] */
  size_t contact_steps;     /* out: contact rows handed (a slider's corners one each) */
  int impacts;              /* out: impact episodes (a slider's per corner) */
  double m_eff_min, m_eff_max; /* out: its effective mass range over its contact steps [kg]
                               (valid when contact_steps > 0) */
  double h_omega_max;       /* out: the largest h omega_c = h sqrt(kp / m_eff) of the rows its
                               law and the mapping gave (contact.h's row, as ODE's), or of
                               the law's secant stiffness for a binding with explicit_law [-] */
  double erp_max, cfm_min;  /* out: the largest ERP [-] and smallest CFM [m/(N s)] of those rows
                               (valid when contact_steps > 0 and the binding takes rows:
                               contact_rows 1) */
} fb_kit_joint_record;

/* The clearance joints of a kit run (NULL: every joint ideal). */
typedef struct {
  unsigned mask;            /* bit j: joint j is a pin in a hole (a revolute joint) or a slider
                               in its guide (a prismatic one) */
  fb_kit_joint_record joint[FB_PLANAR_SPEC_MAX_JOINTS]; /* joint j's law and record (bit j of
                               mask set) */
  fb_mapping mapping;       /* [clearance] mapping */
  double radial_clearance;  /* c [m] */
  double pin_radius;        /* [m] */
  double impact_velocity_min; /* an episode faster than this at onset is an impact [m/s] */
  size_t contact_steps;     /* out: contact rows handed, over the steps and all joints (a
                               slider's corners one each) */
  int impacts;              /* out: impact episodes, all joints (a slider's per corner) */
  double m_eff_min, m_eff_max; /* out: the effective mass range over the contact steps of
                               every clearance joint [kg] (valid when contact_steps > 0) */
  double aliased_omega_d_h; /* out: omega_d h of the row whose aliasing stopped the run
                               (FB_ERR_NUMERIC, "aliased"), else 0 [-] */
  int aliased_joint;        /* out: the joint of that row, else -1 */
  double h_omega_max;       /* out: the largest h omega_c = h sqrt(kp / m_eff) of the rows the
                               laws and mapping gave (contact.h's row, as ODE's) [-] */
  const fb_planar_guide *guide; /* optional (njoints), NULL: no prismatic clearance joint: a
                               prismatic clearance joint j's slider in its guide at guide[j]
                               (planar_guide.h: a, b, c [m]) */
  double friction;          /* [clearance] friction: Coulomb's coefficient mu at the contact
                               (0: frictionless) [-] */
  fb_status (*mass_tensors)(double w[4][2][2], const fb_planar *m, const double *q,
                            const double (*cs)[2], unsigned mask, fb_diag *diag);
                            /* optional: the inverse-mass tensor [1/kg] at each of a four-joint
                               mechanism's joints at the pose q (every body's cos, sin there:
                               cs, fb_planar_rotation; the drive held, the joints of
                               mask left out) by its closed form (planar_case.h
                               fb_planar_instance_mass: the four-bar's and slider-crank's);
                               NULL: the planar core's factorisation (planar_mass.h), at most
                               once a step */
  fb_kit_collider collider; /* what the pins' contacts are found on (0: the exact pin in its
                               hole) */
  const fb_load_scale *load; /* optional: the ideal joint loads' time scale ahead, by the
                               drive's angle theta_to - theta_from (load_scale.h), which the
                               adaptive step follows in persistent contact with a binding whose
                               persistent_rule is FB_PERSIST_LOAD_SCHEDULE; NULL: no schedule
                               (that binding's adaptive step is refused) */
} fb_kit_clearance;

/* One clearance joint for an engine that builds it as its own relation
 * (add_clearance): the pin on body handle pin, the hole on body handle hole,
 * their centres where the start puts them (together at the assembly). */
typedef struct {
  int pin, hole;            /* body handles (FB_KIT_GROUND: the ground) */
  double at[2];             /* the joint's position at the start where its body[0] puts it,
                               the pin's centre (the assembly position when the world starts
                               at the assembly) [m] */
  double at_hole[2];        /* ... and where its body[1] puts it, the hole's centre: at but
                               for a start with the pin off its hole's centre, or a stack-up
                               corner whose assembly the start closed [m] */
  double radial_clearance;  /* c [m] */
  double pin_radius;        /* [m] */
  double restitution;       /* the law's coefficient of restitution cr, Newton's e_N [-] */
  fb_contact_law law;       /* the joint's law (cl->joint[k].law) */
  const fb_planar *m;       /* the description (the joint is m->joint[k]) */
  const fb_kit_clearance *cl; /* the run's clearance joints: law, sizes, mask */
  int kind;                 /* the joint's kind (planar.h FB_KIND_REVOLUTE: a pin in a hole;
                               FB_KIND_PRISMATIC: a slider in its guide, pin the guide's body
                               handle, hole the slider's) */
  double axis[2];           /* prismatic: the slide's unit direction u in the world at the
                               start (the guide's body at its start angle) [-]; revolute: 0 */
  fb_planar_guide guide;    /* prismatic: the slider's half-length a, half-height b and the
                               gap c on each side (planar_guide.h: corner (sigma, tau) at
                               at + sigma a u + tau b perp(u) at the start, the walls at
                               +-(b + c) from the slide's line through at) [m]; revolute: 0 */
  double friction;          /* Coulomb's coefficient mu at the contact ([clearance]
                               friction; 0: frictionless) [-] */
} fb_kit_clearance_joint;

/* An engine's builder functions. */
typedef struct fb_kit_binding {
  const char *engine; /* "ode" */
  fb_status (*world_new)(void **w, const fb_kit_world *o, fb_diag *diag);
  fb_status (*add_body)(void *w, const fb_kit_body *b, fb_diag *diag);
  fb_status (*add_revolute)(void *w, int b0, int b1, const double at[2], fb_diag *diag);
  fb_status (*add_prismatic)(void *w, int b0, int b1, const double at[2], const double axis[2],
                             fb_diag *diag);
  fb_status (*close_loop)(void *w, fb_diag *diag); /* optional (NULL) */
  fb_status (*add_drive)(void *w, int joint, double rate, fb_diag *diag);
  fb_status (*hold_in_plane)(void *w, int b, fb_diag *diag);
                             /* optional: keep body b in the plane (a body that only a
                                clearance joint holds); NULL: the engine is planar */
  fb_status (*add_contact)(void *w, int k, const fb_kit_contact *c, fb_diag *diag);
                             /* contact slot k's contact for the coming step (the
                                engine's native row or its force; k < FB_KIT_SLOTS: a
                                revolute clearance joint's index, or a slider's corner,
                                fb_kit_slot); NULL: no clearance */
  double (*contact_force)(const void *w, int k);
                             /* optional: the normal force contact slot k's contact
                                applied in the last step [N] (0 when none); NULL: the
                                law's */
  fb_status (*step)(void *w, fb_diag *diag);
  void (*body_state)(const void *w, int b, double pos[3], double vel[3]);
  void (*world_free)(void *w);
  fb_status (*add_clearance)(void *w, int k, const fb_kit_clearance_joint *c, fb_diag *diag);
                             /* optional: clearance joint k (the description's index), called
                                once by the walk in the joint's place, before close_loop.
                                With add_contact NULL, the engine's own rigid relation
                                (Siconos: a unilateral constraint with Newton's impact law):
                                the kit then hands it no contact, counts its episodes from
                                contact_force (required with it) and reads its penetration
                                from the bodies. With add_contact, an engine that evaluates
                                the contact inside its own integrator (Simbody's force
                                element, MuJoCo's passive hook at every stage): each step's
                                add_contact still hands the law on the effective mass and
                                the episode; c->m and c->cl outlive the world. NULL: the
                                kit's contact every step only */
  int applied_force;         /* optional: 1 when add_contact applies the law itself, not the
                                kit's soft row (its force: MuJoCo's hook, Simbody; or the
                                engine's own constraint set from it: MuJoCo's native contact;
                                no [clearance] mapping): the matched row's aliasing stop is not
                                the engine's, which names its own */
  fb_status (*model_text)(const void *w, char *buf, size_t size, fb_diag *diag);
                             /* optional: the built world (after add_drive) as the engine's
                                own model file, its start in it, into buf (size bytes, NUL
                                terminated; FB_ERR_RANGE when it does not fit): MuJoCo's
                                MJCF (fb_kit_model_text); NULL: the engine reads no model
                                file */
  double (*contact_force_max)(const void *w, int k);
                             /* optional: the largest normal force clearance joint k's contact
                                applied over the sub-steps of the last step [N] (DART, which
                                splits a step in contact); NULL: one force per step */
  int contact_rows;          /* optional: 1 when add_contact hands the engine the law as a soft
                                constraint row (ERP and CFM: ODE, Bullet), whose largest ERP
                                and smallest CFM the kit reports (fb_kit_joint_record) */
  void (*reactions)(const void *w, int k, double out[3]);
                             /* optional: what ideal joint k (its place among the joints
                                added) applied over the last step: the force on its body[1]
                                from its body[0] (x, y) [N] and the moment on body[1] from
                                body[0] about +z at the joint's point on body[1] (body[0]'s
                                when body[1] is the ground) [N m] (a revolute joint's: the
                                drive's torque, or 0); NULL: the engine reports no reactions
                                (no load columns) */
  void (*contact_force_vec)(const void *w, int k, double f[2]);
                             /* optional: the force contact slot k applied on the pin's body
                                in the last step (x, y) [N], its friction included; NULL: the
                                normal force (contact_force, else the law's) along -normal */
  int friction;              /* optional: 1 when add_contact applies Coulomb friction at the
                                contact (fb_kit_contact.friction: ODE's friction pyramid);
                                0: a normal law only, and the kit refuses [clearance]
                                friction > 0 naming the engine */
  void (*body_accel)(const void *w, int b, double acc[3]);
                             /* optional: body handle b's acceleration at the state the last
                                step started from, as the engine solved it there with that
                                step's contacts (instantaneous, not a difference): its centre
                                of mass's along x and y [m/s^2] and its angular acceleration
                                about +z [rad/s^2] (MuJoCo: the step's first forward pass);
                                NULL: the kit takes the step's difference (v_{i+1} - v_i) / h
                                (fb_kit_series) */
  int explicit_law;          /* optional, with applied_force: 1 when the engine integrates the
                                law's force explicitly at step h (MuJoCo's integrators): the
                                kit reports each joint's h omega_c with the law's secant
                                stiffness on the effective mass (fb_kit_joint_record
                                h_omega_max, the hand-built MuJoCo world's figure); 0: none
                                (an error-controlled integrator, Simbody) */
  void (*apply_wrench)(void *w, int b, const double f[3]);
                             /* optional: the force (x, y) [N] at body handle b's centre of
                                mass and the torque about +z [N m] that act on it over the
                                coming step, replacing the last step's: the kit hands every
                                moving body its springs' and loads' (planar_loads.h, gravity
                                left to the engine) from the state each step starts from;
                                NULL: the kit refuses a description with springs or loads,
                                naming the engine (unless loads_from_state) */
  int loads_from_state;      /* optional: 1 when the binding's own force element evaluates the
                                springs' and loads' forces at every evaluation of its
                                integrator, from the state it is given (planar_loads.h
                                fb_planar_applied on its bodies' states, o->mech's
                                description): the forces then follow the motion inside a
                                step, and an error-controlled integrator keeps its order,
                                where a wrench held over the step makes it first order in
                                h; the kit calls no apply_wrench. 0: apply_wrench */
  int (*reactions_in)(const fb_kit_world *o);
                             /* optional, with reactions: 0 when the world settings o build a
                                world that holds its joints by no multipliers it can report
                                (Siconos's angle coordinates: the tree's joints are its
                                coordinates), whose model then has no load columns; NULL:
                                every world reports them */
  void (*clearance_reaction)(const void *w, int j, double out[3]);
                             /* with reactions, add_clearance and no add_contact (required
                                then): clearance joint j's (the description's index) reaction
                                over the last step, as reactions gives an ideal joint's: the
                                force on body[1] from body[0] (x, y) [N] and its moment about
                                +z at the joint's point on body[1] (body[0]'s when body[1] is
                                the ground) [N m], from the engine's own relation, whose
                                contacts the kit does not hold (Siconos: a guide's corners'
                                sum); NULL: the kit's contacts' (fb_kit_pipe_reaction) */
  int (*collide)(void *w, int k, double *rate);
                             /* optional, with add_clearance and add_contact: the binding's own
                                collider of a pin in its hole (fb_kit_clearance.collider),
                                revolute clearance joint k, built by add_clearance: its
                                contacts at the bodies' state now, kept for the add_contact
                                that follows; returns how many (0: none), *rate the
                                penetration rate its episode follows [m/s] (> 0
                                approaching). The kit calls it for a joint whose exact
                                penetration |e| - c is positive only: a ring or bore whose
                                facets are tangent to the hole's circle (or to an ellipse
                                around it) lies outside that circle, so the pin reaches it
                                only once it leaves the circle. The contact's episode
                                follows the collider's contacts; add_contact hands the
                                engine a row per contact on the effective mass along the
                                contact's own normal (fb_kit_contact.w_inv), the episode's
                                onset rate v0 and the matched-static row's persistence the
                                kit's. NULL: the kit refuses a collider but the exact one,
                                naming the engine */
  void (*collided)(const void *w, int k, fb_kit_rows *out);
                             /* with collide (required then): the rows the last add_contact of
                                clearance joint k made, for the joint's record (its contact
                                steps count rows, as its provenance does) */
  double (*penetration)(const void *w, int k);
                             /* optional, with collide: the pin's depth into the hole its own
                                collider builds at clearance joint k, at the bodies' state now
                                [m] (0 when free), the joint's penetration column (a bore that
                                is no circle lets the pin past the radial clearance untouched);
                                NULL: the exact |e| - c */
  int contact_always;        /* optional, with add_contact: 1 when the engine's own contact needs
                                a revolute clearance joint's effective mass before every step,
                                in free flight too (MuJoCo's native contact, whose stiffness
                                and damper are set from it and whose row may open within a
                                step): add_contact is then called for every such joint whose
                                pin is off its hole's centre, in free flight with c->depth <= 0
                                (its geometry, m_eff and law on it, onset 0; no episode, no
                                contact step, no law's force noted); the force the kit reports
                                is contact_force's, the engine's. 0: in contact only */
  fb_status (*step_by)(void *w, double h, fb_diag *diag);
                             /* optional: one step of h [s], a whole multiple of the world's
                                o->h, the engine's own step at that size, for [solver] h_s =
                                adaptive (the kit chooses each step's multiple, step_control.h,
                                and samples inside it on the grid of o->h); NULL: the engine
                                steps at o->h only, and the kit refuses an adaptive step naming
                                the engine */
  int persistent_rule;       /* with step_by: how the adaptive step is chosen in persistent
                                contact (step_control.h fb_persistent_rule): from the ideal
                                joint load ahead (FB_PERSIST_LOAD_SCHEDULE, an engine whose
                                contact row's update depends on h: ODE's; needs
                                fb_kit_clearance.load) or from the penetration's rate
                                (FB_PERSIST_DEPTH_CHANGE, a law integrated explicitly:
                                MuJoCo's) */
  int contact_speed_limit;   /* optional: 1 when world_new honours fb_kit_world's
                                contact_speed_max (ODE's); 0: the kit refuses a finite one */
  void (*body_rotation)(const void *w, int b, double cs[2]);
                             /* optional: body b's (a handle) cos and sin of its angle
                                about +z as the engine holds its orientation (ODE's rotation
                                matrix, Bullet's basis, MuJoCo's xmat), at the state
                                body_state reads: the clearance pipeline's and the drift's
                                points take them in place of the cosine and sine of
                                body_state's angle, which that angle came from; NULL: those */
} fb_kit_binding;

/* Where a kit run writes: n samples every h from t = 0; body handle b's
 * quantity k (FB_Q_POS, _VEL, _ACC: angle unwrapped [rad], omega [rad/s],
 * alpha [rad/s^2]) at q[(b * 3 + k) * n + i]; t (n) [s]; optionally the
 * centres of mass (centre, a translating body's motion) likewise. Sample i's alpha
 * is the step from t_i, (omega_{i+1} - omega_i) / h, the acceleration the
 * engine solved at sample i's configuration (series.h's
 * fb_series_attribute_to_step_start, as the engines' four-bar runs report
 * it), or the engine's own there where the binding gives it (body_accel);
 * the last sample keeps the one before. With a window (below), every
 * column here and in the clearance joints' records (fb_kit_joint_record)
 * is window long instead of n and sample i sits at index i & (window - 1)
 * in it: q[(b * 3 + k) * window + (i & (window - 1))]. */
typedef struct {
  size_t n;
  double h;
  size_t window;  /* optional, 0: every sample kept, each column n long; else a power of two
                     of at least fb_kit_window(o): the columns keep the last window samples,
                     for a caller that reads each sample once, just behind the kit (the kit
                     adapter: a run's columns then stay in the cache the engine's own step
                     works in, instead of growing by megabytes); after fb_kit_advance(k, j)
                     samples j - 3 (or 0) up to the last filled are there. FB_ERR_ARG from
                     fb_kit_open for another window */
  double *t;
  double *q;
  double *centre; /* optional ((bodies x 3) x n), NULL: not kept: body handle b's centre of
                     mass along x at centre[(b * 3 + k) * n + i] (k as q's: x [m], its rate
                     [m/s], the step's acceleration [m/s^2]) and along y at
                     centre[(nb * 3 + b * 3 + k) * n + i], nb the moving bodies */
  double *torque;   /* optional (n), NULL: not kept (the binding must have reactions): the
                       drive's torque on the driven body about +z over the step from sample i
                       [N m] (0 for an undriven description) */
  double *reaction; /* optional (3 njoints x n), with torque: joint j's reaction over the step
                       from sample i, the force on its body[1] from its body[0] along x (k =
                       0) and y (k = 1) [N] and the moment about +z at the joint's point on
                       body[1] (on body[0] when body[1] is the ground) (k = 2) [N m], at
                       reaction[(3 j + k) n + i] (planar_invdyn.h's convention); a clearance
                       joint's: its contact's force on the hole's body from the pin's, no
                       moment */
  double *drift;    /* optional (n), NULL: not kept: the largest separation of an ideal
                       revolute joint's two points (its body[0]'s and body[1]'s) at sample
                       i [m], the loop-closure drift, at the state the engine reports at
                       each step's end (the samples inside an adaptive step on the straight
                       line between its ends) */
  double setup_s; /* set by fb_kit_run: wall time of the set-up (the start's velocities, the
                     engine's world and the walk that builds it) [s]; the rest of the run is
                     the stepping and sampling (fourbar bench's cost splits there) */
  fb_step_stats stats; /* set by the run: the engine's steps so far (engine.h: count,
                     shortest and longest h and how many of each; every step h at a fixed
                     step) */
} fb_kit_series;

/* Builds description m driven at omega [rad/s] in the engine of binding b
 * (world settings o; o->h the series' h), the joints of cl->mask (cl may
 * be NULL) as pins in holes, steps it s->n - 1 times and fills s (and
 * cl's columns and counts). Each step, before the engine's, the kit
 * computes every clearance joint's contact (fb_kit_contact) and hands it
 * to the binding's add_contact. Errors: FB_ERR_ARG when the binding has
 * no add_contact for a clearance joint; those of the binding, of the
 * core's velocity analysis (planar_kinematics.h: no drive, not one degree
 * of freedom, a singular start) and of its effective mass; FB_ERR_NOMEM.
 * An undriven m (m->drive < 0) takes its start velocities from o->qd0
 * (required: FB_ERR_ARG without) and omega is ignored. */
fb_status fb_kit_run(const fb_kit_binding *b, const fb_planar *m, double omega,
                     const fb_kit_world *o, fb_kit_clearance *cl, fb_kit_series *s,
                     fb_diag *diag);

/* fb_kit_run a sample at a time, for a caller that may stop early (the
 * kit adapter, kit_engine.c): fb_kit_open builds the world (fb_kit_run's
 * arguments, kept by reference until fb_kit_close; its errors but the
 * steps'), fb_kit_advance fills s's samples up to (not including) n,
 * taking the steps to them (sample i's alpha and contact force are its
 * step's, so they are final once sample i + 1 is filled), fb_kit_close
 * frees the world (NULL is ignored). Opened, advanced to s->n and closed,
 * it is fb_kit_run, the same numbers. After an error, fb_kit_advance
 * fills nothing more (FB_ERR_NUMERIC etc. again); the samples reached are
 * those with a finite s->t when s->t was filled with NaN first, as many as
 * fb_kit_written gives (samples 0 to fb_kit_written(k) - 1 have their time
 * and motion; with a window, the only way to tell). */
typedef struct fb_kit_runner fb_kit_runner;

/* The smallest window (fb_kit_series.window) a run with world settings o
 * can keep: a power of two of at least 2 m + 4 samples, m its longest
 * step in grid steps (kit_adaptive.h fb_kit_adapt_m_max: 1 at a fixed
 * step) [-]. */
size_t fb_kit_window(const fb_kit_world *o);

fb_status fb_kit_open(fb_kit_runner **k, const fb_kit_binding *b, const fb_planar *m,
                      double omega, const fb_kit_world *o, fb_kit_clearance *cl,
                      fb_kit_series *s, fb_diag *diag);
fb_status fb_kit_advance(fb_kit_runner *k, size_t n, fb_diag *diag);
/* the samples of k's run whose time and motion are written [-]: those
 * filled, and after a stop the ones its last step wrote before it */
size_t fb_kit_written(const fb_kit_runner *k);
void fb_kit_close(fb_kit_runner *k);

/* Builds description m driven at omega [rad/s] in the engine of binding b
 * (world settings o), its clearance joints cl's (NULL: every joint ideal;
 * else as fb_kit_run takes them, their laws set), as fb_kit_run does
 * before its first step, and writes the built world as the engine's own
 * model file into buf (size bytes, NUL terminated) through b->model_text:
 * the file the engine itself runs, so that it and a kit run start alike.
 * Errors: FB_ERR_ARG when the binding has no model_text; those of the walk
 * (as fb_kit_run's: a clearance joint the binding cannot build is refused
 * by its add_clearance) and of model_text; FB_ERR_NOMEM. */
fb_status fb_kit_model_text(const fb_kit_binding *b, const fb_planar *m, double omega,
                            const fb_kit_world *o, fb_kit_clearance *cl, char *buf, size_t size,
                            fb_diag *diag);

#endif
