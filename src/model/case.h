/* A case: one mechanism, its tolerances, its drive and the models to run,
 * everything in SI units. Filled by casefile.c from an INI file (the only
 * place where mm, rpm, degrees and GPa are converted), checked as a whole by
 * fb_case_check before any simulation starts. */
#ifndef FB_CASE_H
#define FB_CASE_H

#include <stddef.h>

#include "fb_engine_opts.h"
#include "links.h"
#include "mechanism.h"
#include "planar_spec.h"
#include "status.h"

#define FB_NAME_SIZE 64
#define FB_MAX_MODELS 16

/* Mass properties of one moving link; its centre of mass lies on the line
 * between its two joint centres at com_fraction of the way from the first
 * (crank: A->B, coupler: B->C, follower: D->C). */
typedef struct {
  double mass;                 /* [kg] */
  double inertia;              /* about the hinge (out-of-plane) axis through the centre of mass [kg m^2] */
  double inertia_long;         /* about the link's long axis [kg m^2] */
  double inertia_transverse;   /* about the in-plane axis across the link [kg m^2] */
  double com_fraction;         /* position of the centre of mass along the link [-] in [0, 1] */
} fb_link_mass;

/* Where a value the run uses came from: the case file (or a base file, or
 * --set), derived from other values (a link's mass and inertias from its bar
 * and the material density: bar_mass.h), or the key table's default. */
typedef enum {
  FB_SOURCE_CASE = 0,
  FB_SOURCE_DERIVED = 1,
  FB_SOURCE_DEFAULT = 2
} fb_value_source;

/* "case", "derived", "default". */
const char *fb_value_source_name(int s);

/* Source of each field of one link's fb_link_mass (fb_value_source). */
typedef struct {
  int mass;
  int inertia;
  int inertia_long;
  int inertia_transverse;
  int com_fraction;
} fb_link_mass_source;

/* Slots of fb_case.given: at least the key table's size (casefile.c asserts it). */
#define FB_CASE_MAX_KEYS 192

/* Most dimensions a planar case's stack-up corner names (one sign each):
 * more than a description of FB_PLANAR_SPEC_MAX_BODIES bodies and
 * FB_PLANAR_SPEC_MAX_JOINTS joints has (3 distances a body, an offset and
 * an angle a prismatic joint: 31 x 3 + 31 x 2 = 155). */
#define FB_STACKUP_PLANAR_MAX 192

/* How the stack-up lengths are chosen from the nominal ones: each link at
 * nominal + corner * plus_minus, corner in {-1, 0, +1}. */
typedef struct {
  int corner[FB_LINK_COUNT]; /* -1 minimum, 0 nominal, +1 maximum (4) */
  int worst;                 /* 1: corner still to be chosen as the worst for worst_output */
  int worst_output;          /* output index (tolerance.h) whose |value| the worst corner maximises */
  char planar[FB_STACKUP_PLANAR_MAX + 1]; /* a planar case: one of + - 0 per dimension of its
                                description (planar_dims.h, fourbar stackup's rows in order),
                                set when the case is read (casefile_planar.c); "" otherwise */
} fb_stackup;

typedef enum { FB_STEPPER_WORLD = 0, FB_STEPPER_QUICK = 1 } fb_stepper;

/* How [solver] h_s was given. */
typedef enum {
  FB_STEP_DEFAULT = 0, /* not given: auto with clearance joints, else 1e-5 s */
  FB_STEP_FIXED = 1,   /* a number */
  FB_STEP_AUTO = 2,    /* "auto": from the contact (resolution.h, fb_step_auto) */
  FB_STEP_ADAPTIVE = 3 /* "adaptive": ODE steps from h_min to h_max that follow the contact,
                          landing on the output grid of step h = h_min (ode/adaptive.h) */
} fb_step_mode;

/* The four revolute joints, in loop order: indices into the four-bar's
 * joint list (mechanism.h fb_mech_fourbar). */
typedef enum {
  FB_JOINT_A = 0, /* ground-crank (driven) */
  FB_JOINT_B = 1, /* crank-coupler */
  FB_JOINT_C = 2, /* coupler-follower */
  FB_JOINT_D = 3  /* follower-ground */
} fb_joint;

/* Name of the four-bar's joint j, from its description (mechanism.h):
 * "ground-crank", "crank-coupler", "coupler-follower", "follower-ground";
 * "?" for any other j. */
const char *fb_joint_name(int j);

/* Where the penalty stiffness of the clearance models comes from. */
typedef enum {
  FB_PENALTY_SOURCE_PHYSICAL = 0, /* Johnson line contact at the inverse-dynamics reaction */
  FB_PENALTY_SOURCE_PAPER = 1,    /* the paper's Kc and P (Tables II, III recipe), read in N-mm units */
  FB_PENALTY_SOURCE_EXPLICIT = 2, /* the case's stiffness keys */
  FB_PENALTY_SOURCE_GOLDSMITH = 3 /* Goldsmith's internal-contact K (paper Eq. 3-5) from the pin
                                     and hole radii and the case's material */
} fb_penalty_source;

/* How the ODE clearance models find the pin-in-hole contact (docs/colliders.md). */
typedef enum {
  FB_CASE_COLLIDER_EXACT = 0,   /* closed-form eccentricity (the models' own) */
  FB_CASE_COLLIDER_FACETED = 1, /* ring of ODE boxes, dCollide */
  FB_CASE_COLLIDER_CCD = 2      /* ring of convex segments, libccd MPR */
} fb_case_collider;

/* Bore shape of the libccd collider. */
typedef enum {
  FB_CASE_BORE_CIRCLE = 0, /* circular hole */
  FB_CASE_BORE_ELLIPSE = 1 /* worn hole: diameter larger by ovality along the hole body's x */
} fb_case_bore;

/* Clearance joints and the contact parameters of the ode-clearance-* models. */
typedef struct {
  int mask;                  /* bit j set: joint j is a clearance joint (pin in hole) */
  fb_penalty_source penalty; /* source of the stiffness */
  double restitution;        /* coefficient of restitution cr of the restitution law [-] */
  double stiffness_impact;   /* explicit K of the impact law [N/m^1.5] */
  double stiffness_linear;   /* explicit penalty p of the restitution law [N/m] */
  double exponent;           /* impact-law exponent n [-] */
  double damping;            /* impact-law maximum damping c_max [N s/m] */
  double damping_depth;      /* impact-law penetration of full damping d_max [m] */
  int mapping;               /* fb_mapping: 0 secant, 1 tangent, 2 matched */
  double friction;           /* Coulomb friction coefficient at the contact [-] */
  double penetration_limit;  /* stop a model beyond this penetration [m]; 0: the radial clearance */
  int penetration_unlimited; /* 1: no limit (penetration_limit_um = none); penetration_limit ignored */
  int faceted_n;             /* boxes in the ring of the ode-clearance-faceted model */
  fb_case_collider collider; /* collider of the ODE models whose row names the exact one */
  int segments;              /* convex segments of the libccd bore ring [-]; with the faceted
                                collider also its boxes (overrides faceted_n) when given */
  int segments_given;        /* 1: [clearance] segments was set in the case */
  fb_case_bore bore;         /* bore shape of the libccd collider */
  double ovality;            /* ellipse bore: major minus minor diameter [m] >= 0 */
  double stiffness_scale;    /* multiplies the stiffness from any source [-] (studies, checks) */
  double engine_stiffness_scale; /* multiplies, after stiffness_scale, the stiffness of every
                                    engine model's law, not the references' [-] (an injected
                                    error: would the verdict notice?) */
  double guide_clearance;    /* a prismatic clearance joint's gap c on each side of the
                                centred slider [m] (0: not given) */
  double engine_damping_scale;   /* multiplies every engine model's damper (the impact law's
                                    c_max; the restitution law's 2 zeta sqrt(p m_eff), then
                                    taken from the case's p, not the scaled one) [-] */
} fb_clearance;

/* Solver parameters of the ODE models. */
typedef struct {
  double h;                /* step size h [s] (resolved when h_mode is not FB_STEP_FIXED) */
  int h_mode;              /* fb_step_mode: how h was chosen */
  double h_min;            /* adaptive: shortest step and the output grid's step [s] */
  double h_max;            /* adaptive: longest step [s] >= h_min */
  double accuracy;         /* adaptive: largest h omega_c in an impact or free flight [-] */
  double rocking_h_omega;  /* adaptive, ODE: largest h omega_t in contact, omega_t the pin's
                              rocking along the wall (step_control.h) [-]; 0: off */
  fb_stepper stepper;      /* dWorldStep (direct) or dWorldQuickStep (SOR) */
  int quick_iterations;    /* dWorldQuickStep iterations [-] */
  double world_erp;        /* ERP of the ideal joints [-] in [0, 1] */
  double world_cfm;        /* CFM of the ideal joints [m/(N s)] >= 0 */
  double drive_torque_max; /* torque limit of the crank drive motor [N m] */
  unsigned long seed;      /* dRandSetSeed value (QuickStep row order) */
  int builder;             /* fb_builder: who builds an engine's four-bar or slider-crank */
} fb_solver;

/* Who builds a four-bar or slider-crank model of an engine that has both
 * ([solver] builder): its own hand-built world, its engine-kit binding
 * through the kit adapter, or (auto, the default) the one its engine table
 * names (engine.h fb_engine.kit_default, fb_engine_runner). */
typedef enum { FB_BUILDER_HAND = 0, FB_BUILDER_KIT = 1, FB_BUILDER_AUTO = 2 } fb_builder;

/* Initial state of the moving bodies ([run] start; physics/start.h resolves it). */
typedef enum {
  FB_START_STEADY = 0, /* every body on the ideal mechanism's motion at t = 0 */
  FB_START_REST = 1    /* crank at full speed, bodies not rigidly tied to it at rest */
} fb_start;

/* Pin position in its hole at t = 0 ([run] pin_start), every clearance joint. */
typedef enum {
  FB_PIN_CENTRED = 0, /* pin centre on the hole centre */
  FB_PIN_RESTING = 1, /* on the wall, along the static gravity load the joint carries */
  FB_PIN_ANGLE = 2    /* on the wall at eccentricity angle pin_start_angle */
} fb_pin_start;

/* Time window the peaks are taken over ([run] peaks). */
typedef enum {
  FB_PEAKS_STEADY = 0, /* from the second revolution on (the first is a run-in) */
  FB_PEAKS_ALL = 1     /* from t = 0, the start-up included */
} fb_peak_window;

/* Format of the per-model time series a run writes ([run] series). */
typedef enum {
  FB_SERIES_CSV = 0,  /* DIR/<model>.csv, one per model */
  FB_SERIES_HDF5 = 1, /* DIR/series.h5, one group per model (builds with libhdf5) */
  FB_SERIES_NONE = 2  /* no time series (summary.json, figures and report.md only) */
} fb_series_format;

/* Penetration beyond this multiple of the radial clearance is outside the
 * penalty model's validity (a run gets a named warning, limit or not): the
 * laws are fitted to contact approaches of microns, a fraction of the
 * clearance; at twice the clearance the pin has passed through the wall by
 * more than the whole gap, which no penalty law describes. */
#define FB_PENALTY_VALIDITY_FACTOR 2.0

/* Each engine's options default: its section's key rows' defaults
 * (docs/keys.md; docs/engines.md), read from the case-file key table, where
 * alone they are written (the rows: model/opts_<name>.h; defined in
 * setup/casefile.c): fb_mujoco_opts fb_mujoco_opts_default(void), ... */
#define X(name) fb_##name##_opts fb_##name##_opts_default(void);
FB_ENGINE_OPTS_LIST
#undef X

/* Most variants a case may define ([variant.NAME] sections). */
#define FB_MAX_VARIANTS 8

/* A variant of the case, run beside it by fourbar run ([variant.NAME]): the
 * same case file with more overrides, as --set takes them, applied after the
 * command line's. Its models are the case's unless it names its own. */
typedef struct {
  char name[FB_NAME_SIZE]; /* NAME of the [variant.NAME] section */
  char set[256];           /* "section.key=value; ..." (at least one) */
  char models[256];        /* [run] models of the variant ("" : the case's) */
  char description[160];   /* one line for the reader ("" : none) */
  char origin[160];        /* file:line of its set key, for messages */
} fb_case_variant;

/* One body's extremes as a publication reports them, NaN where it gives
 * none (the fields of fb_body_peaks, analytic.h) [rad/s, rad/s^2]. */
typedef struct {
  double omega_max, omega_min, alpha_max, alpha_min;
} fb_case_body_values;

/* What a publication reports for the clearance model of one contact law
 * ([published.impact], [published.restitution]): the run prints every
 * model of that law, and every variant's, beside it with the difference. */
typedef struct {
  FB_MECH_OUTPUT_MEMBERS(fb_case_body_values); /* per output body (mechanism.h) */
} fb_case_published;

/* Index of fb_case.published: the contact law a published row belongs to. */
enum { FB_PUBLISHED_IMPACT = 0, FB_PUBLISHED_RESTITUTION = 1, FB_PUBLISHED_LAWS = 2 };

typedef struct fb_case_s {
  char name[FB_NAME_SIZE];            /* case name, used for the output folder */
  fb_mech_type mechanism;             /* [linkage] type: the four-bar or the slider-crank */
  fb_planar_spec planar;              /* [linkage] type = planar: its [joint.NAME], [body.NAME]
                                         sections and [drive] joint (planar.on = 1); the
                                         description is built from it (physics/planar/
                                         planar_case.h); no command runs one yet */
  fb_linkage nominal;                 /* basic link lengths [m]; a slider-crank's crank, coupler
                                         and guide offset (mechanism.h FB_LENGTH_OFFSET), ground 0 */
  double plus_minus[FB_LINK_COUNT];   /* symmetric length tolerance per link [m] (4) */
  fb_stackup stackup;                 /* corner used by the *-stackup models */
  char tolerance_source[FB_LINK_COUNT][96]; /* where each tolerance came from */
  char tolerance_class;               /* ISO 2768-1 class f, m, c, v for links without an explicit tolerance; 0 for none */
  int distribution;                   /* Monte Carlo length distribution: 0 normal, 1 uniform */
  char fit[32];                       /* ISO 286 fit of the clearance joints ("" if none) */
  char clearance_source[128];         /* where the radial clearance came from */
  fb_branch branch;                   /* assembly branch */
  double crank_angle0;                /* crank angle at t = 0 [rad] */
  double crank_speed;                 /* crank speed magnitude [rad/s] > 0 */
  int direction;                      /* +1 counter-clockwise, -1 clockwise */
  double gravity;                     /* magnitude of gravity, acting along -y [m/s^2] */
  fb_link_mass link[3];               /* crank, coupler, follower (3) */
  fb_link_mass_source link_source[3]; /* where each field of link[i] came from (3) */
  double link_width[3];               /* bar width in the plane, across the link [m] (3) */
  double link_thickness[3];           /* bar thickness out of the plane [m] (3) */
  double density;                     /* material density of the links [kg/m^3] */
  unsigned char given[FB_CASE_MAX_KEYS]; /* 1: key i of the key table was set by the case
                                         file, a base file or --set (fb_casefile_given) */
  double youngs_modulus;              /* Young's modulus E [Pa] */
  double poisson_ratio;               /* Poisson's ratio nu [-] in (-1, 0.5) */
  double pin_diameter;                /* nominal pin diameter [m] */
  double pin_length;                  /* pin length in contact with the hole [m] */
  double radial_clearance;            /* radial clearance c = R_hole - R_pin [m] */
  fb_solver solver;                   /* ODE settings */
  fb_clearance clearance;             /* clearance joints and contact parameters */
#define X(name) fb_##name##_opts name; /* [name] keys: the name-* models' own settings */
  FB_ENGINE_OPTS_LIST                 /* each engine's options (fb_engine_opts.h): mujoco, ... */
#undef X
  struct {
    char outcome[FB_NAME_SIZE];       /* "stable", "unstable" or "" (no expectation) */
    char model[FB_NAME_SIZE];         /* model the expectation is about */
    double omega_peak_rel_max;        /* bound vs analytic [-]; 0: none */
    double force_peak_rel_max;        /* bound vs reference [-]; 0: none */
    char reason[FB_NAME_SIZE];        /* word the unstable status contains */
  } expect;                           /* hard cases' stated outcome (tests check it) */
  double revolutions;                 /* crank revolutions simulated [-]; the first is a run-in */
  double duration_s;                  /* simulated time when given [s] ([run] duration_s; 0: from
                                         revolutions at the drive's speed) */
  double max_wall_s;                  /* a run whose estimated wall time exceeds this is refused [s] */
  fb_start start;                     /* initial state of the bodies */
  fb_pin_start pin_start;             /* initial pin position of the clearance joints */
  double pin_start_angle;             /* eccentricity angle for FB_PIN_ANGLE [rad], ccw from +x */
  fb_peak_window peaks;               /* window of the reported peaks */
  fb_series_format series;            /* format of the written time series */
  int series_every;                   /* keep every N-th sample (>= 1), and every sample of
                                         an impact episode */
  int ensemble;                       /* [run] ensemble: runs of the clearance models with the
                                         start perturbed (ensemble.h); 1: the run alone [-] */
  double pin_start_offset[2];         /* not a key: added to every clearance joint's initial
                                         eccentricity [m] (an ensemble member's perturbation) */
  int member;                         /* not a key: 1 in an ensemble member's run (no ensemble,
                                         no reference check integration, no step re-choice) */
  int jobs;                           /* not a key: worker processes of the ensemble (--jobs);
                                         0 or 1: one; the results do not depend on it */
  int ensemble_auto;                  /* not a key: members to run when the case leaves
                                         ensemble at 1 and a model's verdict is unsettled
                                         (fourbar run sets it when [run] ensemble is not
                                         given; run.h); 0 or 1: none */
  double wall_deadline;               /* not a key: the fb_clock_s() time [s] at which every model
                                         still running stops (FB_STOP_WALL_TIME); 0: none. Set by
                                         fb_run_case from max_wall_s for each run; an ensemble
                                         member (member = 1) keeps its run's */
  char published_source[160];         /* where the published values come from ("" : none) */
  fb_case_published published[FB_PUBLISHED_LAWS]; /* the publication's values per law */
  int variant_count;                  /* entries used in variant */
  fb_case_variant variant[FB_MAX_VARIANTS]; /* [variant.NAME] sections, in file order */
  int model_count;                    /* entries used in models */
  char models[FB_MAX_MODELS][FB_NAME_SIZE]; /* model names to run, in order */
} fb_case;

/* Fills every field with its documented default (the paper's case where the
 * paper gives a value; see cases/README.md). */
void fb_case_default(fb_case *c);

/* Checks the case as a whole: lengths and masses valid, the nominal and the
 * stack-up linkage assemble and their crank turns fully (it is driven), the
 * step size is smaller than one revolution, every model name is in the
 * model table (model_table.h) and has the clearance joints it needs.
 * Errors: FB_ERR_RANGE, FB_ERR_ASSEMBLY, FB_ERR_ARG with the rule in diag. */
fb_status fb_case_check(const fb_case *c, fb_diag *diag);

/* The rules of the run's keys that every mechanism has, one place for the
 * four-bar, the slider-crank (fb_case_check calls it) and a planar case
 * (casefile.c calls it after its description checks): [solver] h_max_s not
 * below h_min_s for an adaptive step; h_s positive, shorter than the run
 * and at most 1e9 steps of it; [run] revolutions at least 2 when the peaks
 * are the steady window's (peaks = steady, which starts after the first
 * revolution), for a case with a drive. Errors: FB_ERR_RANGE naming the
 * keys, their values and the rule. */
fb_status fb_case_check_run(const fb_case *c, fb_diag *diag);

/* The mechanism the case describes (mechanism.h), chosen by its [linkage]
 * type: fb_mech_fourbar or fb_mech_slider_crank. */
const fb_mech_desc *fb_case_mech(const fb_case *c);

/* Name of joint j of the case's mechanism ("crank-coupler",
 * "coupler-slider"), "?" for any other j. */
const char *fb_case_joint_name(const fb_case *c, int j);

/* Signed crank speed omega2 [rad/s]: negative for a clockwise crank. */
double fb_case_omega2(const fb_case *c);

/* The number of joints [clearance] joints names (the bits of
 * clearance.mask). */
int fb_case_clearance_count(const fb_case *c);

/* The clearance joint a built-in mechanism's clearance model is compared
 * with its reference at (impacts matched, counted and reported): the
 * description's reference_joint when it has clearance, else the first
 * joint [clearance] joints names; -1 without clearance. The divergence
 * watches every clearance joint (run/metrics.h fb_metrics_divergence). */
int fb_case_compared_joint(const fb_case *c);

/* Boxes in the faceted collider's ring [-]: [clearance] segments when
 * given, else faceted_n. */
int fb_case_faceted_n(const fb_case *c);

/* The libccd bore's ovality [m]: [clearance] ovality_um for bore =
 * ellipse, else 0 (a circle). */
double fb_case_bore_ovality(const fb_case *c);

/* Link lengths at the case's stack-up corner [m]. */
void fb_case_stackup_lengths(const fb_case *c, fb_linkage *out);

/* The linkage's Grashof class for a run's header, one sentence into out
 * (size bytes): fb_linkage_grashof_text of the nominal lengths, then the
 * stack-up corner's class when it differs, and a note when the length
 * tolerances can reach the change point (|p + q - (s + l)| at most the sum
 * of the four tolerances, each of which moves the margin by its own size). */
void fb_case_grashof_text(const fb_case *c, char *out, size_t size);

/* Simulated duration [s]: [run] duration_s when given, else revolutions *
 * 2 pi / crank speed. */
double fb_case_duration(const fb_case *c);

/* Penetration limit of the clearance models [m]: the explicit limit, the
 * radial clearance when none is given, or INFINITY for penetration_limit_um
 * = none. */
double fb_case_penetration_limit(const fb_case *c);

/* Start of the peak window [s]: 0 for peaks = all, else one revolution less
 * half a step (so that the sample at exactly one period counts). */
double fb_case_peak_window_from(const fb_case *c);

#endif
