/* MuJoCo's own options: the [mujoco] section of a case file. The options
 * struct (fb_case.mujoco), the names of its enums and its key rows (name,
 * kind, field, range, unit, default, rule, meaning), the one place the
 * defaults are written. Engine-free: no MuJoCo header is needed to hold or
 * check them. Listed for fb_case, the key table and the scene by the
 * generated fb_engine_opts.h (meson.build, engine_names). */
#ifndef FB_OPTS_MUJOCO_H
#define FB_OPTS_MUJOCO_H

#include "status.h"

/* Integrator of the mujoco-* models (MuJoCo's mjtIntegrator). */
typedef enum {
  FB_MUJOCO_EULER = 0,    /* semi-implicit Euler (mjINT_EULER) */
  FB_MUJOCO_IMPLICIT = 1, /* implicit in velocity (mjINT_IMPLICIT) */
  FB_MUJOCO_RK4 = 2,      /* 4th-order Runge-Kutta (mjINT_RK4) */
  FB_MUJOCO_AUTO = 3      /* euler for ideal models, rk4 for clearance models (measured) */
} fb_mujoco_integrator;

/* "euler", "implicit", "rk4", "auto" (NULL-terminated; index = fb_mujoco_integrator). */
extern const char *const fb_mujoco_integrator_words[];

/* "euler", "implicit", "rk4", "auto" ("?" outside). */
const char *fb_mujoco_integrator_name(int k);

/* The hole of mujoco-clearance-native (MuJoCo's own constraint solver on the
 * clearance; docs/engines.md, "MuJoCo"). */
typedef enum {
  FB_MUJOCO_BORE_TENDON = 0, /* a spatial tendon from the hole's centre to the pin's, length
                              * |e|, limited to [0, c]: one limit row along e, no facets */
  FB_MUJOCO_BORE_FACETS = 1  /* the pin a sphere, the hole a ring of [clearance] faceted_n
                              * boxes, collided by MuJoCo (one contact per touching box) */
} fb_mujoco_bore;

/* "tendon", "facets" (NULL-terminated; index = fb_mujoco_bore). */
extern const char *const fb_mujoco_bore_words[];

/* "tendon", "facets" ("?" outside). */
const char *fb_mujoco_bore_name(int k);

/* MuJoCo's own choices for the mujoco-* models. The loop closure is
 * MuJoCo's soft equality constraint in its direct form: solref =
 * (-stiffness, -damping), solimp = (impedance, impedance, 0.001, 0.5, 2). */
typedef struct {
  int integrator;        /* fb_mujoco_integrator */
  double loop_stiffness; /* direct-form solref stiffness of the loop closure [1/s^2]; 0: 1/h^2 */
  double loop_damping;   /* direct-form solref damping of the loop closure [1/s]; 0: 1/h */
  double loop_impedance; /* solimp dmin = dmax of the loop closure [-] in (0, 1) */
  double drive_armature; /* armature of the crank hinge (flywheel drive) [kg m^2] */
  int native_bore;       /* fb_mujoco_bore of mujoco-clearance-native */
} fb_mujoco_opts;

/* The [mujoco] key rows (docs/keys.md; docs/engines.md, "MuJoCo"), each
 * ROW(section, kind, key, field, words, scale, lo, hi, lo_open, hi_open,
 * unit, default, rule, meaning) as setup/casefile_keys.c reads it: kind
 * DOUBLE, INT, ULONG or WORDS (one of the NULL-terminated words, stored as
 * its index); field a member of fb_mujoco_opts; range in the file's unit. */
#define FB_OPTS_KEYS_mujoco(ROW)                                                               \
  ROW(mujoco, WORDS, "integrator", integrator, fb_mujoco_integrator_words, 0, 0, 0, 0, 0, "-", \
      "auto", "euler, implicit, rk4 or auto",                                                  \
      "integrator of the mujoco-* models (MuJoCo's option integrator); auto: euler for the "   \
      "ideal models, rk4 for the clearance models (the most accurate of the three for each, "  \
      "measured at h = 1e-5 s; see docs/engines.md)")                                          \
  ROW(mujoco, DOUBLE, "loop_stiffness_1_s2", loop_stiffness, NULL, 1.0, 0, HUGE_VAL, 0, 1,    \
      "1/s^2", "0", "the stiffness must be >= 0",                                              \
      "loop closure (the connect equality at the coupler-follower joint): MuJoCo's "           \
      "direct-form solref stiffness (mass-normalised); 0: 1/h^2, which with euler removes a "  \
      "violation in one step")                                                                 \
  ROW(mujoco, DOUBLE, "loop_damping_1_s", loop_damping, NULL, 1.0, 0, HUGE_VAL, 0, 1, "1/s",  \
      "0", "the damping must be >= 0", "loop closure: MuJoCo's direct-form solref damping; 0: 1/h") \
  ROW(mujoco, DOUBLE, "loop_impedance", loop_impedance, NULL, 1.0, 0, 1, 1, 1, "-", "0.9999",  \
      "the impedance must lie in (0, 1)",                                                      \
      "loop closure: MuJoCo's solimp dmin = dmax (how much of the reference acceleration the " \
      "constraint enforces; 1 would be rigid)")                                                \
  ROW(mujoco, DOUBLE, "drive_armature_kg_m2", drive_armature, NULL, 1.0, 0, HUGE_VAL, 1, 1,   \
      "kg m^2", "1e6", "the armature must be positive",                                        \
      "armature of the crank hinge: the crank is a flywheel set to the crank speed at t = 0, " \
      "so the reaction torques barely change its speed (the crank-angle error is reported)")   \
  ROW(mujoco, WORDS, "native_bore", native_bore, fb_mujoco_bore_words, 0, 0, 0, 0, 0, "-",     \
      "tendon", "tendon or facets",                                                            \
      "the hole of mujoco-clearance-native, solved by MuJoCo's constraint solver: tendon, a "  \
      "spatial tendon from the hole's centre to the pin's limited to the radial clearance "    \
      "(one limit row along the eccentricity); facets, a sphere pin in a ring of [clearance] " \
      "faceted_n boxes (one contact per touching box; see docs/engines.md)")

/* The integrator a MuJoCo model with these options runs: o->integrator, with
 * auto resolved to euler for an ideal mechanism (clearance_mask 0) and rk4
 * with clearance joints (measured: docs/engines.md, "MuJoCo"). */
int fb_mujoco_integrator_resolve(const fb_mujoco_opts *o, int clearance_mask);

/* Checks o field by field (a scene built in code, not from a case file):
 * integrator known, loop stiffness and damping finite and >= 0, loop
 * impedance in (0, 1), drive armature positive and finite. Errors:
 * FB_ERR_RANGE naming the field (prefix "scene: mujoco"), its value and the
 * rule. */
fb_status fb_mujoco_opts_check(const fb_mujoco_opts *o, fb_diag *diag);

#endif
