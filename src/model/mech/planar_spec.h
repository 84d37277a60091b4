/* What a planar case file says ([linkage] type = planar): its [joint.NAME],
 * [body.NAME], [point.NAME], [spring.NAME] and [load.NAME] sections and
 * [drive] joint, as read, in SI, before any
 * derivation (model floor: plain data held by the case, copied with it).
 * The description the core computes on (planar.h) is built from it at run
 * time, sized by its content (physics/planar/planar_case.h,
 * fb_planar_of_case): the spec is the input, the description the compiled
 * model (MuJoCo's mjSpec and mjModel, in miniature). Filled by
 * setup/casefile_planar.c, which says what each key means (docs/planar.md).
 *
 * Sizes: a case file holds at most 512 keys (casefile.c); 31 joints (a
 * [clearance] joints bit mask is an int) and as many moving bodies are
 * more than any planar mechanism with one drive a case describes by hand
 * (a Watt or Stephenson six-bar has 7 joints, an eight-bar 10). */
#ifndef FB_PLANAR_SPEC_H
#define FB_PLANAR_SPEC_H

#include <stdio.h>

#include "planar.h"

#define FB_PLANAR_SPEC_MAX_JOINTS 31
#define FB_PLANAR_SPEC_MAX_BODIES 31
/* Output points ([point.NAME]): a tool tip, a coupler point, a ram's
 * reference point or two per body of a six-bar. */
#define FB_PLANAR_SPEC_MAX_POINTS 16
/* Springs ([spring.NAME]) and loads ([load.NAME]): a return spring or two
 * and a working load per stroke are what a case describes by hand. */
#define FB_PLANAR_SPEC_MAX_SPRINGS 16
#define FB_PLANAR_SPEC_MAX_LOADS 16

/* Two joint positions closer than this are one point [m] (a compound
 * hinge): a position is typed to microns at best, and a bar shorter than
 * 1 nm is no bar (the shortest link a case may give is 1 um,
 * casefile_internal.h FB_LINK_MM_MIN). */
#define FB_PLANAR_SAME_POINT_M 1e-9

/* Which keys of a [joint.NAME] or [body.NAME] section were given (bits). */
enum {
  FB_SPEC_JOINT_BODIES = 1, /* bodies = A, B */
  FB_SPEC_JOINT_AT = 2,     /* at_mm = x, y */
  FB_SPEC_JOINT_KIND = 4,   /* kind = revolute | prismatic */
  FB_SPEC_JOINT_AXIS = 8,   /* axis_deg */
  FB_SPEC_JOINT_HALF_LENGTH = 16, /* slider_half_length_mm */
  FB_SPEC_JOINT_HALF_HEIGHT = 32, /* slider_half_height_mm */
  FB_SPEC_BODY_SECTION = 1, /* a [body.NAME] section exists */
  FB_SPEC_BODY_MASS = 2,    /* mass_kg */
  FB_SPEC_BODY_INERTIA = 4, /* inertia_kg_mm2 */
  FB_SPEC_BODY_CENTRE = 8,  /* centre_mm = x, y */
  FB_SPEC_BODY_WIDTH = 16,  /* width_mm */
  FB_SPEC_BODY_THICK = 32,  /* thickness_mm */
  FB_SPEC_BODY_OMEGA0 = 64, /* initial_omega_rad_s */
  FB_SPEC_POINT_BODY = 1,   /* [point.NAME] body = NAME */
  FB_SPEC_POINT_AT = 2,     /* [point.NAME] at_mm = x, y */
  FB_SPEC_SPRING_BODIES = 1, /* [spring.NAME] bodies = A, B */
  FB_SPEC_SPRING_AT_A = 2,   /* at_a_mm */
  FB_SPEC_SPRING_AT_B = 4,   /* at_b_mm */
  FB_SPEC_SPRING_STIFF = 8,  /* stiffness_n_m */
  FB_SPEC_SPRING_FREE = 16,  /* free_length_mm */
  FB_SPEC_SPRING_DAMP = 32,  /* damping_n_s_m */
  FB_SPEC_LOAD_BODY = 1,     /* [load.NAME] body = NAME */
  FB_SPEC_LOAD_AT = 2,       /* at_mm */
  FB_SPEC_LOAD_FORCE = 4,    /* force_n = fx, fy */
  FB_SPEC_LOAD_TORQUE = 8,   /* torque_n_m */
  FB_SPEC_LOAD_ACTIVE = 16   /* active */
};

/* One [spring.NAME] section: a linear spring-damper (planar.h
 * fb_planar_spring). */
typedef struct {
  char name[FB_PLANAR_NAME_SIZE];    /* NAME */
  char body[2][FB_PLANAR_NAME_SIZE]; /* its bodies' names as given (ground allowed) */
  double at[2][2];                   /* its ends on body[0] and body[1], assembly [m] (2 x 2) */
  double stiffness;                  /* [N/m] */
  double free_length;                /* [m] when given */
  double damping;                    /* [N s/m] (0 unless given) */
  int given;                         /* FB_SPEC_SPRING_* bits */
} fb_planar_spec_spring;

/* One [load.NAME] section: a constant load (planar.h fb_planar_load). */
typedef struct {
  char name[FB_PLANAR_NAME_SIZE]; /* NAME */
  char body[FB_PLANAR_NAME_SIZE]; /* the moving body's name as given */
  double at[2];                   /* point of application, assembly [m] (2) */
  double force[2];                /* world frame [N] (2) (0 unless given) */
  double torque;                  /* about +z [N m] (0 unless given) */
  int active;                     /* FB_PLANAR_LOAD_* (always unless given) */
  int stroke;                     /* the prismatic joint it follows (index into joint), -1 */
  int given;                      /* FB_SPEC_LOAD_* bits */
} fb_planar_spec_load;

/* One [point.NAME] section: an output point (planar.h fb_planar_mark). */
typedef struct {
  char name[FB_PLANAR_NAME_SIZE]; /* NAME */
  char body[FB_PLANAR_NAME_SIZE]; /* the body's name as given (resolved when the case is
                                     finished: a body some joint joins) */
  double at[2];                   /* assembly position [m] (2) */
  int given;                      /* FB_SPEC_POINT_* bits */
} fb_planar_spec_point;

/* One [joint.NAME] section. */
typedef struct {
  char name[FB_PLANAR_NAME_SIZE]; /* NAME */
  int body[2];                    /* indices into fb_planar_spec.body (0: the ground) */
  double at[2];                   /* assembly position [m] (2) */
  int kind;                       /* fb_joint_kind (mechanism.h); revolute by default */
  double axis;                    /* prismatic: slide direction, ccw from +x [rad] */
  double half_length;             /* prismatic with clearance: the slider's half-length a
                                     along the slide [m] when given */
  double half_height;             /* and its half-height b across it [m] when given */
  int given;                      /* FB_SPEC_JOINT_* bits */
} fb_planar_spec_joint;

/* One body: named by a joint's bodies key or a [body.NAME] section. */
typedef struct {
  char name[FB_PLANAR_NAME_SIZE]; /* NAME; body 0 is "ground" */
  double mass;                    /* [kg] when given */
  double inertia;                 /* about +z through the centre of mass [kg m^2] when given */
  double centre[2];               /* centre of mass in the assembly configuration [m] when given */
  double width;                   /* bar width for derived masses [m] when given */
  double thickness;               /* bar thickness for derived masses [m] when given */
  double omega0;                  /* initial angular velocity of an undriven case, ccw
                                     [rad/s] (0 unless given) */
  int given;                      /* FB_SPEC_BODY_* bits */
} fb_planar_spec_body;

/* A planar case's mechanism as its file gives it. */
typedef struct {
  int on;                      /* 1: [linkage] type = planar */
  int njoints;                 /* joints held, in file order */
  fb_planar_spec_joint joint[FB_PLANAR_SPEC_MAX_JOINTS];
  int nbodies;                 /* bodies held, the ground (index 0) included, in order of
                                  first mention */
  fb_planar_spec_body body[FB_PLANAR_SPEC_MAX_BODIES + 1];
  int drive;                   /* [drive] joint: index into joint, -1 when not given */
  int undriven;                /* 1: [drive] joint = none, or a torque drive (a free start,
                                  drive -1) */
  int torque_drive;            /* 1: [drive] torque_n_m given: the joint [drive] joint names
                                  is driven by a torque, not a speed */
  int torque_joint;            /* that joint (index into joint), set when the case is
                                  finished; -1: no torque drive */
  double drive_torque;         /* [drive] torque_n_m [N m]: +T on the joint's second body, -T
                                  on its first, about +z */
  double speed0;               /* [drive] speed0_rpm [rad/s]: the joint's second body's
                                  angular rate relative to its first at the start (0 unless
                                  given) */
  int npoints;                 /* output points held, in file order */
  fb_planar_spec_point point[FB_PLANAR_SPEC_MAX_POINTS];
  int nsprings;                /* springs held, in file order */
  fb_planar_spec_spring spring[FB_PLANAR_SPEC_MAX_SPRINGS];
  int nloads;                  /* loads held, in file order */
  fb_planar_spec_load load[FB_PLANAR_SPEC_MAX_LOADS];
} fb_planar_spec;

/* The first of s's springs and loads as its section, "[spring.NAME]" or
 * "[load.NAME]", into buf (size); NULL when it has neither: what a
 * command that does not apply them names when it refuses the case. */
static inline const char *fb_planar_spec_loaded(const fb_planar_spec *s, char *buf, size_t size) {
  if (s->nsprings) snprintf(buf, size, "[spring.%s]", s->spring[0].name);
  else if (s->nloads) snprintf(buf, size, "[load.%s]", s->load[0].name);
  else return NULL;
  return buf;
}

#endif
