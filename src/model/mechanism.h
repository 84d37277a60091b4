/* A mechanism's topology as data (model floor): its type name, its bodies as
 * a list (name, how each moves, which the outputs report), its joints as a
 * list (name, kind, the two bodies, whether it may carry clearance) and its
 * link-length parameters by name. Every list the harness writes per body or
 * per joint (series columns, joint names, joint masks) is read from here, so
 * a second member of the four-bar family adds a description, not branches.
 * The closed-form kinematics stay in physics/ (linkage.h for the four-bar).
 * Two descriptions: fb_mech_fourbar and fb_mech_slider_crank, chosen by a
 * case's [linkage] type (fb_mech_type, fb_mech_find). */
#ifndef FB_MECHANISM_H
#define FB_MECHANISM_H

#include <stddef.h>

/* Room for the largest description (the four-bar's 4 bodies with the
 * ground, 4 joints, 4 lengths, 2 output bodies). */
#define FB_MECH_MAX_BODIES 4
#define FB_MECH_MAX_JOINTS 4
#define FB_MECH_MAX_LENGTHS 4
#define FB_MECH_MAX_OUTPUTS 2

/* How a body moves. */
typedef enum {
  FB_MOTION_FIXED = 0,      /* the ground (frame) */
  FB_MOTION_ROTATING = 1,   /* about a ground pivot: one angle */
  FB_MOTION_PLANAR = 2,     /* general planar motion: x, y and an angle */
  FB_MOTION_TRANSLATING = 3 /* along a straight guide fixed to the ground: one position */
} fb_body_motion;

/* How a joint connects its two bodies. */
typedef enum {
  FB_KIND_REVOLUTE = 0, /* a pin: relative rotation about +z */
  FB_KIND_PRISMATIC = 1 /* a slide along the guide: relative translation */
} fb_joint_kind;

/* One body. Its index in the list is its index in the case's per-link
 * arrays (links.h fb_link: mass properties, lengths where it has one). */
typedef struct {
  const char *name;      /* "coupler": column and JSON key prefix */
  fb_body_motion motion; /* how it moves */
  int output;            /* 1: the series and summary report its motion (q, q', q'') */
} fb_mech_body;

/* One joint, in loop order. */
typedef struct {
  const char *name;  /* "crank-coupler": body[0]'s name, '-', body[1]'s name */
  fb_joint_kind kind;
  int body[2];       /* indices into the bodies; a load column is the force on body[1] from body[0]
                        (but see load_on_first) */
  int clearance_ok;  /* 1: may be a clearance joint (pin in hole); a prismatic joint stays ideal */
  int load_on_first; /* 1: its load columns are the force on body[0] from body[1] (the
                        four-bar's follower-ground, invdyn.h's D: an output contract) */
} fb_mech_joint;

/* A mechanism description. */
typedef struct {
  const char *type;                        /* "four-bar": the case's [linkage] type */
  int nbodies;                             /* bodies held, the ground included */
  fb_mech_body body[FB_MECH_MAX_BODIES];   /* (nbodies) */
  int input;                               /* the driven body (the crank): time_s, <input>_angle_rad */
  int njoints;                             /* joints held */
  fb_mech_joint joint[FB_MECH_MAX_JOINTS]; /* (njoints), loop order; joint masks are over these */
  int reference_joint;                     /* the clearance joint the engine-free reference
                                              integrates (its minimal-coordinate dynamics) and
                                              every clearance model is compared at */
  int nlengths;                            /* link-length parameters held */
  const char *length[FB_MECH_MAX_LENGTHS]; /* their names, in the order of fb_linkage.length [m] */
  /* what the rest of the harness does with the mechanism, as data (a zero
   * member is the cautious answer: a new description builds on no model
   * until a model table row names it, exports no SDF, ...) */
  int every_model_builds;                  /* 1: every row of the model table builds it (the
                                              four-bar); 0: the rows naming its type
                                              (fb_model.mechanisms) build it */
  int sdf_export;                          /* 1: fourbar export --format sdf writes it (the SDF
                                              world has links and revolute joints only) */
  int peers_build;                         /* 1: the bare peer programs (tests/peers) build it */
  int title_names_type;                    /* 1: a stack-up table's title names the type (the
                                              four-bar, the default type, goes unnamed) */
  const char *assembly_note;               /* the run table's case line on its assembly when it
                                              has no branch key ("the slider at +x of the crank
                                              pivot"); NULL: the case's branch (open, crossed) */
  const char *position_length;             /* the length that is a signed position, not a size
                                              ("offset": the guide line's y [m]): absent from the
                                              case it is 0 with tolerance 0, below ISO 2768-1's
                                              smallest size (0.5 mm) it has no class tolerance;
                                              NULL: every length is a size */
  const char *position_zero_note;          /* the stack-up's note when that length is 0 (its
                                              symmetry), NULL: none */
  const char *const *keys;                 /* the case keys it alone owns, NULL-terminated pairs
                                              {section, key, ..., NULL}: a case of another type
                                              that gives one is refused */
  const char *foreign_key_hint;            /* appended to that refusal in a case of this type
                                              (the keys it has); NULL: " or set [linkage] type =
                                              <the owner's type>" */
  const char *contact_models[2];           /* fourbar penalty's models of its clearance joint,
                                              impact law then restitution law (model table
                                              names) */
} fb_mech_desc;

/* The planar four-bar (RRRR): bodies crank (rotating, driven), coupler
 * (planar, output), follower (rotating, output), ground; revolute joints
 * ground-crank, crank-coupler, coupler-follower, follower-ground (all may
 * carry clearance); lengths crank, coupler, follower, ground. Body and
 * length indices are links.h's FB_CRANK.. FB_GROUND, joint indices case.h's
 * FB_JOINT_A.. FB_JOINT_D. */
extern const fb_mech_desc fb_mech_fourbar;

/* The offset slider-crank (RRRP): bodies crank (rotating, driven), coupler
 * (the connecting rod: planar, output), slider (translating along the guide
 * y = offset, output), ground; joints ground-crank, crank-coupler,
 * coupler-slider (the piston pin, the one that may carry clearance) and the
 * prismatic slider-ground (ideal); lengths crank, coupler, offset (the
 * guide line's distance from the crank pivot along +y, any sign; index
 * FB_LENGTH_OFFSET). Body indices are those of the case's per-link arrays:
 * the slider's mass is link 2's. Kinematics: physics/slider_crank.h. */
extern const fb_mech_desc fb_mech_slider_crank;

/* Index of the slider-crank's guide offset in fb_linkage.length [m]. */
#define FB_LENGTH_OFFSET 2

/* The mechanisms a case may name ([linkage] type), in the order of this
 * enum. */
typedef enum {
  FB_MECH_FOURBAR = 0,      /* "four-bar" (the default) */
  FB_MECH_SLIDER_CRANK = 1, /* "slider-crank" */
  FB_MECH_COUNT = 2
} fb_mech_type;

/* The description of type t (the four-bar's for a value out of range). */
const fb_mech_desc *fb_mech_of(fb_mech_type t);

/* The type whose description's name is `type` ("slider-crank"), or -1. */
int fb_mech_find(const char *type);

/* Members of type T per output body, as an array body[output] in the
 * description's output order and, over the same storage, the four-bar's
 * names for them (coupler, follower). Code that serves any mechanism reads
 * the array; the names are the four-bar's alone. */
#define FB_MECH_OUTPUT_MEMBERS(T)        \
  union {                                \
    T body[FB_MECH_MAX_OUTPUTS];         \
    __extension__ struct {               \
      T coupler;                         \
      T follower;                        \
    };                                   \
  }

/* The output bodies' indices in body order into out (FB_MECH_MAX_OUTPUTS);
 * returns their number. */
int fb_mech_outputs(const fb_mech_desc *m, int out[FB_MECH_MAX_OUTPUTS]);

/* Index in m's lengths of its signed position (fb_mech_desc.position_length:
 * the slider-crank's offset, FB_LENGTH_OFFSET), or -1 when it has none. */
int fb_mech_position_length(const fb_mech_desc *m);

/* Index of m's driven joint: the joint between the input body (the crank)
 * and a fixed body (the ground), where the drive acts; -1 when m has none. */
int fb_mech_driven_joint(const fb_mech_desc *m);

/* Name of joint j ("crank-coupler"), "?" when j is not one of m's joints. */
const char *fb_mech_joint_name(const fb_mech_desc *m, int j);

/* The series column name of quantity q (0 position, 1 velocity,
 * 2 acceleration) of body b into buf (returned): a rotating or planar body
 * <body>_angle_rad, <body>_omega_rad_s, <body>_alpha_rad_s2; a translating
 * body <body>_x_m, <body>_v_m_s, <body>_a_m_s2. */
const char *fb_mech_body_column(const fb_mech_desc *m, int b, int q, char *buf, size_t size);

/* The k-th output body (k < the outputs' count, fb_mech_outputs): 1 when
 * it translates (a slider), its name, and the symbol and unit of its
 * quantity q (0 position, 1 velocity, 2 acceleration) for labels and
 * tables: a rotating or planar body "angle", "omega", "alpha" in "rad",
 * "rad/s", "rad/s^2"; a translating body "x", "v", "a" in "m", "m/s",
 * "m/s^2". */
int fb_mech_output_translates(const fb_mech_desc *m, int k);
const char *fb_mech_output_name(const fb_mech_desc *m, int k);
const char *fb_mech_output_symbol(const fb_mech_desc *m, int k, int q);
const char *fb_mech_output_unit(const fb_mech_desc *m, int k, int q);

/* The output key of mechanism m for the four-bar's per-body output key
 * `key` (summary.json's, the checked metrics'), into buf (returned): the
 * four-bar's key itself for the four-bar; else "coupler" and "follower" in
 * key become the names of m's first and second output bodies, and for a
 * translating body "omega" -> "velocity", "alpha" -> "acceleration",
 * "rad_s2" -> "m_s2", "rad_s" -> "m_s" (the slider-crank's
 * "alpha_peak_ratio_follower" is "acceleration_peak_ratio_slider",
 * "impact_alpha_follower_rad_s2" is "impact_acceleration_slider_m_s2"). */
const char *fb_mech_output_key(char *buf, size_t size, const fb_mech_desc *m, const char *key);

#endif
