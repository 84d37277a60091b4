/* The model table: every model the harness can run, one row each, and the
 * only place in the code where model names are compared.
 *
 * A row says which engine runs the model, which link lengths it uses, which
 * joints have clearance, which contact law and collider the clearance joints
 * use, and what the model is measured against (always the analytic solution
 * of its own lengths; for clearance models also a reference model of the
 * same law and the ideal model whose peak accelerations its spike ratios
 * divide by). Adding a model is one row in model_table.c, plus the engine's
 * support for the row's law and collider.
 *
 * Callers hold a model as `const fb_model *` (a row of the table) and compare
 * rows or their fields, never names. */
#ifndef FB_MODEL_TABLE_H
#define FB_MODEL_TABLE_H

#include "case.h"
#include "fb_config.h"
#include "status.h"

/* Engines a model can run on (engine.h has their interface): the analytic
 * and reference engines, then the engines that step a world in the order of
 * meson.build's engine_names (FB_ENGINE_LIST, fb_config.h):
 * FB_ENGINE_ODE = 2 (src/engines/ode), FB_ENGINE_MUJOCO = 3, FB_ENGINE_BULLET
 * = 4 (double precision), FB_ENGINE_SIMBODY = 5, each in src/engines/<name>
 * and, but for ODE, only in builds with it (FB_HAVE_<ID>). */
typedef enum {
  FB_ENGINE_ANALYTIC = 0,  /* exact kinematics (analytic.h) sampled on the grid */
  FB_ENGINE_REFERENCE = 1, /* minimal-coordinate dynamics, GSL rk8pd (reference.h) */
#define X(ID, name) FB_ENGINE_##ID,
  FB_ENGINE_LIST
#undef X
  FB_ENGINE_COUNT
} fb_engine_id;

/* "analytic", "reference", then each engine's folder name ("ode", "mujoco",
 * "bullet", "simbody"): the "kind" written in summary.json. */
const char *fb_engine_name(fb_engine_id e);

/* 1 when this build has engine e (MuJoCo only when built with it). */
int fb_engine_available(fb_engine_id e);

/* The how-to for engine e when this build lacks it ("" for engines every
 * build has): FB_<ID>_HOWTO of fb_config.h, written in the engine folder's
 * meson.build. */
const char *fb_engine_howto(fb_engine_id e);

/* 1 for engines that step a world of bodies and joints (every engine of
 * FB_ENGINE_LIST): they have a loop-closure drift and a stability guard. */
int fb_engine_steps_world(fb_engine_id e);

/* Which link lengths a model uses. */
typedef enum {
  FB_LENGTHS_NOMINAL = 0, /* the case's basic lengths */
  FB_LENGTHS_STACKUP = 1  /* the case's stack-up corner (worst corner resolved) */
} fb_lengths_kind;

/* Which joints are modelled with clearance. */
typedef enum {
  FB_JOINTS_IDEAL = 0,    /* four ideal revolute joints */
  FB_JOINTS_CLEARANCE = 1 /* the case's [clearance] joints are pin-in-hole contacts */
} fb_joint_set;

/* Contact law of the clearance joints (scene.h holds the resolved laws). */
typedef enum {
  FB_MODEL_LAW_NONE = 0,        /* no clearance joint */
  FB_MODEL_LAW_IMPACT = 1,      /* Adams-style IMPACT, K delta^n + STEP(...) ddot */
  FB_MODEL_LAW_RESTITUTION = 2, /* POISSON-like, p delta + c ddot for restitution cr */
  FB_MODEL_LAW_COUNT
} fb_model_law;

/* How a clearance joint's contact is found. */
typedef enum {
  FB_COLLIDER_NONE = 0,    /* no clearance joint */
  FB_COLLIDER_EXACT = 1,   /* closed-form pin-in-hole eccentricity */
  FB_COLLIDER_FACETED = 2, /* ring of boxes against a cylinder, the engine's own collider */
  FB_COLLIDER_CCD = 3,     /* libccd GJK/MPR on convex pieces */
  FB_COLLIDER_NATIVE = 4,  /* the engine's own contact model */
  FB_COLLIDER_COUNT
} fb_collider;

/* Colour families of the figures: every model of one simulation engine is
 * drawn in shades of its engine's hue, so that two engines are told apart at
 * a glance (the shades are the figures', src/report/figures/figures_style.c). */
typedef enum {
  FB_HUE_NONE = 0, /* the row's own color (the yardsticks: analytic, reference) */
  FB_HUE_BLUES,    /* ODE */
  FB_HUE_ORANGES,  /* MuJoCo */
  FB_HUE_GREENS,   /* Simbody */
  FB_HUE_PURPLES,  /* Bullet */
  FB_HUE_COUNT
} fb_hue;

/* How a model is drawn in every figure. */
typedef struct {
  const char *color; /* '#rrggbb' */
  int dash;          /* gnuplot dash type: 1 solid, 2 dashed, 3 dotted, 4 dash-dot, 5 */
  double width;      /* line width */
  fb_hue hue;        /* the figures' colour family: a shade of it by the row's rank among the
                        rows of that hue replaces color; FB_HUE_NONE: color */
} fb_model_style;

/* "none", "exact", "faceted", "ccd", "native". */
const char *fb_collider_name(fb_collider c);

/* "nominal", "stackup": the names fourbar models prints for fb_lengths_kind. */
const char *fb_lengths_name(fb_lengths_kind k);

/* "ideal", "clearance": the names fourbar models prints for fb_joint_set. */
const char *fb_joint_set_name(fb_joint_set j);

/* "none", "impact", "restitution": the names fourbar models prints for
 * fb_model_law (the [clearance] law values of the same laws). */
const char *fb_model_law_name(fb_model_law l);

/* One model. */
typedef struct fb_model {
  const char *name;        /* name in case files and outputs */
  fb_engine_id engine;     /* engine that runs it */
  fb_lengths_kind lengths; /* nominal or stack-up lengths */
  fb_joint_set joints;     /* ideal, or the case's clearance joints */
  fb_model_law law;        /* contact law of the clearance joints */
  fb_collider collider;    /* how the clearance contact is found; for ODE rows naming the exact
                              collider the case's [clearance] collider replaces it */
  const char *reference;   /* reference model it is compared with (same law), or NULL */
  const char *spikes_vs;   /* ideal model whose peak |alpha| its spike ratios divide by when
                              that model ran in the same case (else the analytic peaks of the
                              same lengths), or NULL for models without clearance */
  const char *partner;     /* the model its engine difference is taken against (omega.svg:
                              this model's omega minus the partner's): a model of another
                              engine with the same lengths, joints and law; in a run, the
                              first model of the partner's engine, lengths, joints and law
                              stands for it (e.g. ode-clearance-ccd for ode-clearance-impact).
                              NULL: no difference row (the yardsticks, and the models the
                              others are compared with) */
  int rigid;               /* 1: its contact is rigid (an impulse within a step, Newton's
                              restitution): it has no stiffness, its force and alpha peaks
                              do not converge to a penalty reference's (they grow as the
                              penalty stiffens), and it is judged on what does converge
                              (verdict.h) */
  const char *mechanisms;  /* the types it builds besides those every model builds
                              (mechanism.h fb_mech_desc.every_model_builds), by their
                              [linkage] type names, space-separated ("slider-crank");
                              NULL: those alone */
  const char *summary;     /* one line for help texts */
  fb_model_style style;    /* its line in every figure; color NULL and hue FB_HUE_NONE: the
                              figures pick one */
  int by_name_only;        /* 1: a pattern in [run] models ("*-ideal-nominal") leaves it out,
                              a case lists it by name (DART's rows: the shipped cases'
                              patterns and their check baselines predate the engine) */
} fb_model;

/* The rows, in the order help texts list them. */
extern const fb_model fb_models[];
/* Number of rows. */
extern const int fb_model_count;

/* 1 when model m builds mechanism t: every model builds a description
 * whose every_model_builds is 1 (the four-bar), a row's mechanisms names
 * the others. */
int fb_model_builds(const fb_model *m, fb_mech_type t);

/* The models a case with clearance joints runs by default, after the
 * [run] models key's default list, when it gives no [run] models: each
 * clearance model with its reference (casefile_internal.h's
 * FB_CLEARANCE_DEFAULT_MODELS says them in the key's row; the loaders,
 * casefile.c and casefile_planar.c, run them). */
#define FB_CLEARANCE_DEFAULT_COUNT 4
extern const char *const fb_clearance_default_models[FB_CLEARANCE_DEFAULT_COUNT];

/* The row named name, or NULL. */
const fb_model *fb_model_find(const char *name);

/* The row named name; for an unknown name returns FB_ERR_ARG with the list
 * of known names in diag ("unknown model 'x' (known: analytic, ...)"). */
fb_status fb_model_lookup(const fb_model **out, const char *name, fb_diag *diag);

/* The known names, comma-separated, into buf (returned; truncated to size). */
const char *fb_model_list(char *buf, size_t size);

/* 1 when the model has clearance joints (and so contact columns and spikes). */
int fb_model_has_clearance(const fb_model *m);

/* 1 when model name is an ideal model at the stack-up lengths
 * (analytic-stackup, *-ideal-stackup: what a planar case runs at its
 * stack-up corner, run/planar_run.h), else 0 (an unknown name too). */
int fb_model_ideal_stackup(const char *name);

/* The model table's collider for [clearance] collider of case c. */
fb_collider fb_case_collider_of(const fb_case *c);

/* The collider model m uses when the case asks for case_collider: the
 * row's, except that an ODE row naming the exact collider takes the case's
 * (so one case runs ode-clearance-impact and -restitution with each). */
fb_collider fb_model_collider(const fb_model *m, fb_collider case_collider);

/* Why model m cannot follow [solver] h_s = adaptive (the step that follows
 * the project's contact law through the exact collider, in ODE and MuJoCo)
 * with the case's collider case_collider, in words for the refusal; NULL
 * when it can (or steps on its own error control: Simbody, the reference). */
const char *fb_model_adaptive_refusal(const fb_model *m, fb_collider case_collider);

/* The first row with these properties, or NULL: how code picks a model
 * ("the ideal stack-up model of engine e") without naming it. */
const fb_model *fb_model_match(fb_engine_id engine, fb_lengths_kind lengths, fb_joint_set joints,
                               fb_model_law law, fb_collider collider);

/* The row of m's reference model, or NULL (m->reference). */
const fb_model *fb_model_reference_of(const fb_model *m);

/* The engine kit drives an ideal joint only (src/engines/kit/kit.c): model
 * m, built by the kit (kit_built: every engine model of a planar case; a
 * four-bar's or slider-crank's with [solver] builder = kit, or of an engine
 * without a world of its own), cannot have a clearance at the driven joint
 * (named joint). FB_OK when it can (an ideal model, analytic, the
 * references, a hand-built engine model); else FB_ERR_ARG, the rule in
 * diag, naming [clearance] joints and [run] models for the caller to say
 * where they were given. */
fb_status fb_model_clearance_at_drive(const fb_model *m, int kit_built, const char *joint,
                                      fb_diag *diag);

/* The row of the ideal model m's spike ratios divide by, or NULL (m->spikes_vs). */
const fb_model *fb_model_ideal_of(const fb_model *m);

/* The row of m's partner, or NULL (m->partner). */
const fb_model *fb_model_partner_of(const fb_model *m);

#endif
