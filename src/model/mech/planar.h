/* A planar mechanism as data (model floor): its bodies and joints as lists
 * sized when the description is built, not by the mechanism's type. The
 * four-bar, the slider-crank and a case's own [joint.NAME] sections all
 * become one of these (physics/planar/planar_case.h builds them); the
 * planar core (physics/planar/) computes on it and never asks which
 * mechanism it holds.
 *
 *   body 0           the ground (fixed; its frame is the world frame)
 *   body 1 .. n-1    the moving bodies; body b's frame has its origin at
 *                    the body's centre of mass and its x axis at angle0
 *                    (counter-clockwise from the world's +x) in the
 *                    assembly configuration
 *   joint j          two bodies, a kind (revolute: a pin; prismatic: a
 *                    slide along an axis), its point on each body in that
 *                    body's frame, its position in the assembly
 *                    configuration
 *   drive            one revolute joint turned at the case's speed
 *
 * Coordinates of the core: q = (x, y, theta) per moving body, the frame's
 * origin and angle in the world, 3 (n - 1) of them; body b's are
 * q[3 (b - 1)] .. q[3 (b - 1) + 2]. In the assembly configuration
 * q = (centre, angle0) of every body and every joint's two points
 * coincide. Lengths in metres, angles in radians, SI throughout.
 * Built by fb_planar_new, fb_planar_add_body, fb_planar_add_joint and
 * fb_planar_set_drive; freed by fb_planar_free. */
#ifndef FB_PLANAR_H
#define FB_PLANAR_H

#include "mechanism.h"
#include "status.h"

/* Longest body or joint name plus its NUL: a [joint.NAME] section's name
 * fits inih's 49 characters (setup/ini_lines.h) with "joint." before it. */
#define FB_PLANAR_NAME_SIZE 44

/* A spring's ends closer than this in the assembly meet [m]: the line
 * its force acts along is not defined (FB_PLANAR_SAME_POINT_M's scale,
 * planar_spec.h: a position typed to microns at best). */
#define FB_PLANAR_SPRING_MIN_M 1e-9

/* Index of the ground in fb_planar.body. */
#define FB_PLANAR_GROUND 0

/* How a body's mass properties came about (fb_planar_body.derived bits). */
enum {
  FB_PLANAR_DERIVED_MASS = 1,    /* mass from its bars and the density */
  FB_PLANAR_DERIVED_INERTIA = 2, /* moment of inertia from its bars */
  FB_PLANAR_DERIVED_CENTRE = 4   /* centre of mass from its bars (or its joint point) */
};

/* One body. */
typedef struct {
  char name[FB_PLANAR_NAME_SIZE]; /* "coupler"; the ground's is "ground" */
  double mass;                    /* [kg] > 0 (0 for the ground) */
  double inertia;                 /* about +z through the centre of mass [kg m^2] > 0 */
  double centre[2];               /* centre of mass in the assembly configuration [m] (2) */
  double angle0;                  /* the body frame's x axis in the assembly configuration,
                                     counter-clockwise from +x [rad] */
  int derived;                    /* FB_PLANAR_DERIVED_* bits: what was derived, not given */
  int on_one_bar;                 /* 1: three or more joint points on one bar of its section
                                     (planar_case.c): one bar end to end for its mass, a line
                                     for its stack-up's lengths; 0 otherwise */
} fb_planar_body;

/* One joint. */
typedef struct {
  char name[FB_PLANAR_NAME_SIZE]; /* "crank-coupler" */
  fb_joint_kind kind;             /* revolute or prismatic (mechanism.h) */
  int body[2];                    /* its bodies (indices into fb_planar.body); a reaction is
                                     the force on body[1] from body[0]; a clearance joint's
                                     pin is on body[0], its hole on body[1] */
  double at[2];                   /* position in the assembly configuration [m] (2) */
  double point[2][2];             /* the joint's point in body[k]'s frame [m] (2 x 2) */
  double axis[2];                 /* prismatic: the slide's unit direction in body[0]'s
                                     frame [-] (2); revolute: (1, 0), unused */
  int clearance_ok;               /* 1: may be a clearance joint (a revolute joint) */
} fb_planar_joint;

/* One output point ([point.NAME]): a point of a body whose motion the
 * run reports (fb_planar_outputs, physics/planar/planar_outputs.h); it
 * adds no mass and no constraint. */
typedef struct {
  char name[FB_PLANAR_NAME_SIZE]; /* "tool" */
  int body;                       /* the moving body it is a point of (index into body) */
  double at[2];                   /* position in the assembly configuration [m] (2) */
  double point[2];                /* the same point in the body's frame [m] (2) */
} fb_planar_mark;

/* One linear spring-damper ([spring.NAME]) between a point of body[0]
 * and a point of body[1] (either may be the ground): along the line from
 * its end on body[0] to its end on body[1], of length l, it pulls the ends
 * together with the tension f = stiffness (l - free_length) + damping l'
 * (negative: it pushes them apart); potential energy
 * 1/2 stiffness (l - free_length)^2. */
typedef struct {
  char name[FB_PLANAR_NAME_SIZE]; /* "return-spring" */
  int body[2];                    /* its bodies (indices into fb_planar.body) */
  double point[2][2];             /* its end on body[k] in that body's frame [m] (2 x 2) */
  double stiffness;               /* [N/m] >= 0 */
  double free_length;             /* [m] >= 0 */
  double damping;                 /* [N s/m] >= 0 */
} fb_planar_spring;

/* When a load acts (fb_planar_load.active). */
enum {
  FB_PLANAR_LOAD_ALWAYS = 0,
  FB_PLANAR_LOAD_OUTSTROKE = 1, /* while its stroke joint's slide rate is positive */
  FB_PLANAR_LOAD_RETURN = 2     /* while it is negative */
};

/* One constant load ([load.NAME]) on a moving body: a force in the world
 * frame at a point of the body and a torque about +z, acting always or on
 * one stroke of a prismatic joint (the slide of planar_outputs.h, its
 * rate's sign). */
typedef struct {
  char name[FB_PLANAR_NAME_SIZE]; /* "cutting" */
  int body;                       /* the moving body it acts on */
  double point[2];                /* its point of application in the body's frame [m] (2) */
  double force[2];                /* world frame [N] (2) */
  double torque;                  /* about +z [N m] */
  int active;                     /* FB_PLANAR_LOAD_* */
  int stroke;                     /* the prismatic joint whose stroke it follows; -1: always */
} fb_planar_load;

/* A planar mechanism. */
typedef struct {
  int nbodies;            /* bodies held, the ground (index 0) included */
  int njoints;            /* joints held */
  int cap_bodies;         /* room in body */
  int cap_joints;         /* room in joint */
  fb_planar_body *body;   /* (nbodies) */
  fb_planar_joint *joint; /* (njoints) */
  int drive;              /* the driven joint (revolute), -1 before fb_planar_set_drive */
  int npoints;            /* output points held (fb_planar_add_point) */
  fb_planar_mark *point;  /* (npoints), NULL when none */
  int nsprings;           /* springs held (fb_planar_add_spring) */
  fb_planar_spring *spring; /* (nsprings), NULL when none */
  int nloads;             /* loads held (fb_planar_add_load) */
  fb_planar_load *load;   /* (nloads), NULL when none */
  int torque_joint;       /* a torque drive: the revolute joint it turns (drive -1), -1: none
                             (fb_planar_set_drive_torque) */
  double drive_torque;    /* its torque: +T on the joint's body[1], -T on its body[0], about
                             +z [N m] */
} fb_planar;

/* A description with the ground alone (named "ground"), room for
 * max_bodies moving bodies and max_joints joints; NULL when out of memory
 * or a size is not positive. Free with fb_planar_free. */
fb_planar *fb_planar_new(int max_bodies, int max_joints);

/* Frees m (NULL is fine). */
void fb_planar_free(fb_planar *m);

/* Adds a moving body named name with mass [kg], inertia about its centre
 * [kg m^2], centre of mass centre (2) [m] and frame angle angle0 [rad],
 * all in the assembly configuration; derived: FB_PLANAR_DERIVED_* bits.
 * Returns its index (1, 2, ...), or -1 with diag filled: FB_ERR_ARG when
 * the name is empty, too long, "ground", "drive" or taken (a body's or
 * joint's name equal to it after '-' becomes '_': the rule of names.h),
 * or the description is full; FB_ERR_RANGE when mass or inertia is not positive and finite. */
int fb_planar_add_body(fb_planar *m, const char *name, double mass, double inertia,
                       const double centre[2], double angle0, int derived, fb_diag *diag);

/* Adds a joint named name of kind between bodies b0 and b1 at position at
 * (2) [m] in the assembly configuration; for a prismatic joint, the slide's
 * direction axis_angle [rad] counter-clockwise from +x in that
 * configuration (ignored for a revolute joint). Its points in each body's
 * frame are computed from the bodies' centres and angles, which must be
 * added first. A revolute joint may carry clearance, a prismatic one not.
 * Returns its index, or -1 with diag filled: FB_ERR_ARG when the name is
 * empty, too long, "drive" or taken (as for a body), a body index is out of range, b0 == b1 or the
 * description is full; FB_ERR_RANGE when at or the axis is not finite. */
int fb_planar_add_joint(fb_planar *m, const char *name, fb_joint_kind kind, int b0, int b1,
                        const double at[2], double axis_angle, fb_diag *diag);

/* Adds output point name on moving body b at position at (2) [m] in the
 * assembly configuration (its point in the body's frame computed from the
 * body's centre and angle, which must be added first). Its name follows
 * the bodies' and joints' rule (names.h). Returns its index (0, 1, ...),
 * or -1 with diag filled: FB_ERR_ARG for a name refused as a body's, b
 * not a moving body, FB_ERR_RANGE when at is not finite, FB_ERR_NOMEM. */
int fb_planar_add_point(fb_planar *m, const char *name, int b, const double at[2], fb_diag *diag);

/* Adds spring name between bodies b0 and b1 (either may be the ground,
 * not both the same) with ends at[0] on b0 and at[1] on b1 (2 x 2) [m] in
 * the assembly configuration, stiffness [N/m], free_length [m] (negative:
 * the assembly distance) and damping [N s/m]. Returns its index, or -1
 * with diag filled: FB_ERR_ARG for a body out of range, b0 == b1, ends
 * that meet in the assembly (no line to pull along), FB_ERR_RANGE for a
 * number not finite or negative, FB_ERR_NOMEM. */
int fb_planar_add_spring(fb_planar *m, const char *name, int b0, int b1, const double at[2][2],
                         double stiffness, double free_length, double damping, fb_diag *diag);

/* Adds load name on moving body b at point at (2) [m] in the assembly
 * configuration: force (2) [N] in the world frame, torque [N m] about +z,
 * active FB_PLANAR_LOAD_* following prismatic joint stroke (-1 with
 * FB_PLANAR_LOAD_ALWAYS). Returns its index, or -1 with diag filled:
 * FB_ERR_ARG for b not a moving body or stroke not a prismatic joint,
 * FB_ERR_RANGE for a number not finite, FB_ERR_NOMEM. */
int fb_planar_add_load(fb_planar *m, const char *name, int b, const double at[2],
                       const double force[2], double torque, int active, int stroke,
                       fb_diag *diag);

/* Makes joint j the driven joint. Errors: FB_ERR_ARG when j is out of range
 * or not revolute. */
fb_status fb_planar_set_drive(fb_planar *m, int j, fb_diag *diag);

/* Makes revolute joint j a torque drive of torque [N m] (+torque on its
 * body[1], -torque on its body[0], about +z) in an undriven description
 * (no speed drive). Errors: FB_ERR_ARG when j is out of range or not
 * revolute, or m has a speed drive; FB_ERR_RANGE when torque is not
 * finite. */
fb_status fb_planar_set_drive_torque(fb_planar *m, int j, double torque, fb_diag *diag);

/* The bodies the drive turns: *from (the ground when the driven joint
 * touches it) and *to, the body whose angle relative to *from the drive
 * prescribes (the joint's other body; the joint's body[1] when neither is
 * the ground). Positive drive angles turn *to counter-clockwise relative
 * to *from. Requires a drive. */
void fb_planar_drive_bodies(const fb_planar *m, int *from, int *to);

/* Which of a prismatic joint's bodies b0, b1 (its body[0], body[1]) is
 * its guide, the body that carries the slot: 1 when b1 is the ground, 0
 * otherwise (the ground when either is, else the first). The one rule of
 * the slide's datum (planar_outputs.h) and of a slot's material
 * (planar_case.h). */
static inline int fb_planar_guide_side(int b0, int b1) {
  (void)b0;
  return b1 == FB_PLANAR_GROUND ? 1 : 0;
}

/* Index of the body or joint named name, or -1. */
int fb_planar_find_body(const fb_planar *m, const char *name);
int fb_planar_find_joint(const fb_planar *m, const char *name);

/* Number of coordinates, 3 (nbodies - 1). */
int fb_planar_nq(const fb_planar *m);

/* Degrees of freedom by the Gruebler-Kutzbach count for planar
 * mechanisms, 3 (n - 1) - 2 j, n bodies with the ground, j joints
 * (revolute and prismatic joints each remove two); the drive removes one
 * more. (Norton, Design of Machinery, sec. 2.7; Uicker, Pennock and
 * Shigley, Theory of Machines and Mechanisms, sec. 1.9.) */
int fb_planar_gruebler(const fb_planar *m);

/* The description's size [m]: the largest distance of a joint's assembly
 * position from the mean of them all, at least 1 mm (the scale of the
 * core's length tolerances). */
double fb_planar_size(const fb_planar *m);

/* Point p (2) [m] of body b's frame where the assembly puts it, in the
 * world [m] (out, 2): the ground's points are world points. */
void fb_planar_at_assembly(double out[2], const fb_planar *m, int b, const double p[2]);

/* The coordinates of the assembly configuration into q (fb_planar_nq):
 * every moving body at (centre, angle0). */
void fb_planar_assembly(const fb_planar *m, double *q);

#endif
