/* The engine interface: what the harness (model_run.c, and through it run,
 * bench, check and sweep) knows of an engine. An engine is a table of
 * function pointers; an instance is an opaque pointer the engine owns.
 *
 *   create   builds the world of one model (fb_model_scene: the scene
 *            definition with the model's row applied) at t = 0; it calls
 *            fb_scene_check first
 *   step     advances one step of def->solver.h; FB_ERR_NUMERIC (or
 *            FB_ERR_NOMEM) ends this model's run, and stopped() says why
 *   sample   the state now as an fb_sample (contact columns of the model's
 *            clearance joints included)
 *   contact  penetration now and impacts so far (fb_engine_contact)
 *   provenance  optional: per clearance joint, the range of the effective
 *            mass, ERP, CFM and h omega_c the engine used (NULL: not kept)
 *   reactions   optional: joint reactions and drive torque of the last step
 *   drift    loop-closure drift of the ideal joints now [m]
 *   steps    steps taken (for the reference: the integrator's accepted steps)
 *   destroy  frees the instance (NULL is ignored)
 *   impact   optional: one body's single impact in the engine, for fourbar
 *            impact and contact-params (fb_engine_impact below)
 *   bench    optional: its configurations in fourbar bench's grids
 *            (engine_bench.h)
 *
 * Engines today: analytic and reference (engines.c, the exact kinematics and
 * the GSL reference behind the same interface, which compute their series
 * in create and replay it), ODE (src/engines/ode/engine_ode.c), MuJoCo
 * (src/engines/mujoco/engine_mujoco.c), Bullet (src/engines/bullet/engine_bullet.c, C++
 * behind C linkage; docs/engines.md) and Simbody (src/engines/simbody/engine_simbody.c,
 * likewise). A new engine fills
 * one fb_engine and is returned by fb_engine_get for its fb_engine_id. */
#ifndef FB_ENGINE_H
#define FB_ENGINE_H

#include <stddef.h>
#include <stdio.h>

#include "engine_bench.h"
#include "engine_params.h"
#include "impact.h"
#include "model_table.h"
#include "outcome.h"
#include "scene.h"
#include "series.h"

/* Contact data of an instance now. */
typedef struct {
  double penetration;  /* largest penetration over the clearance joints [m] (>= 0) */
  int joint;           /* joint it is at (fb_joint), -1 without clearance joints */
  int impacts[4];      /* impact episodes counted so far per joint [-] */
} fb_engine_contact;

/* What an engine did at one clearance joint, over the steps so far (for the
 * validity warnings of the penalty model and the mapping). NAN where the
 * engine keeps no such figure. */
typedef struct {
  double mass_eff_min;    /* smallest effective mass at the contact [kg] */
  double mass_eff_max;    /* largest [kg] */
  double erp_max;         /* largest contact ERP handed to the solver [-] */
  double cfm_min;         /* smallest contact CFM [m/(N s)] */
  double h_omega_max;     /* largest h sqrt(kp / m_eff) [-] */
  size_t contact_steps;   /* steps with a contact row at this joint [-] */
} fb_contact_provenance;

/* The steps an instance took ([solver] h_s = adaptive: ODE steps of varying
 * size; fixed: every step h). */
typedef struct {
  size_t steps;    /* engine steps taken [-] */
  double h_min;    /* shortest step taken [s] */
  double h_max;    /* longest step taken [s] */
  size_t n_h_min;  /* steps of the shortest size [-] */
  size_t n_h_max;  /* steps of the longest size [-] */
} fb_step_stats;

/* One key=value argument of a peer program (peer_args below). */
typedef void (*fb_engine_put_arg)(void *a, const char *key, const char *value);

/* put(a, key, v) with v as "%.17g" text (a peer reads it back exactly). */
static inline void fb_engine_put_number(fb_engine_put_arg put, void *a, const char *key, double v) {
  char text[40];
  snprintf(text, sizeof text, "%.17g", v);
  put(a, key, text);
}
/* ---- the single-impact verification (fourbar impact, contact-params) ----
 * One body meets one contact in the engine itself, no gravity: how
 * fourbar impact and contact-params check an engine's contact against the
 * engine-free reference and closed forms (impact.h). An engine offers it as
 * its table's optional impact op (NULL: none); each op inside is optional
 * too. Callers reach it through fb_engine_get, never an engine's own
 * function. */

/* The engines' own settings of a single impact (each engine reads its own). */
typedef struct {
  fb_bullet_opts bullet; /* Bullet: solver and iterations (fb_bullet_opts_default) */
} fb_impact_opts;

/* One FIXED contact as a user pastes it into an engine, and the impact it
 * meets: each engine reads the common fields and its own parameters. */
typedef struct {
  double mass;             /* body mass [kg] */
  double speed;            /* impact speed [m/s] */
  double h;                /* step [s] */
  double t_max;            /* the body still in contact at t_max [s] fails the impact */
  double onset_phase;      /* in [0, 1): where inside a step the contact begins; 0: the
                              body touches at t = 0; p > 0: (1 - p) h of free flight short
                              of the crossing (times and depths from the crossing) */
  fb_ode_row ode;          /* ODE: soft ERP [-], CFM [m/(N s)] */
  double max_vel;          /* ODE: contact_max_correcting_vel [m/s] (INFINITY: ODE's) */
  fb_mujoco_params mujoco; /* MuJoCo: solref, solimp */
  fb_spring_damper bullet; /* Bullet: contact stiffness kp [N/m] and damping kd [N s/m] */
} fb_impact_row;

typedef struct {
  /* the law of d mapped every step into the engine's contact row, as its
   * clearance joints map it (d->mapping; ODE also d->stepper); o: the
   * engine's own settings. Errors: those of fb_impact_check, FB_ERR_NUMERIC
   * on a non-finite state or a body still in contact after 100 estimated
   * contact durations (ODE, Bullet: the world their kit binding builds,
   * kit_impact.h fb_kit_impact). */
  fb_status (*law)(fb_impact_result *out, const fb_impact_def *d, const fb_impact_opts *o,
                   fb_diag *diag);
  /* one fixed row r (ODE: its kit binding, kit_impact.h fb_kit_impact_row; MuJoCo:
   * impact_mujoco.h; Bullet: impact_bullet.h, fb_impact_bullet_contact).
   * Errors: FB_ERR_RANGE (bad parameter or onset phase), FB_ERR_NUMERIC (a
   * non-finite state, still in contact at t_max), FB_ERR_NOMEM. */
  fb_status (*row)(fb_impact_result *out, const fb_impact_row *r, fb_diag *diag);
  /* the engine library's version as it reports it at run time ("2.2.2":
   * MuJoCo's mj_versionString), which contact-params names beside the
   * rows it verified; NULL: none reported */
  const char *(*version)(void);
} fb_engine_impact;

/* One of an engine's own settings as a model used it (summary.json's
 * "<engine name>" object, in the order given; the writers format it). */
typedef enum { FB_SETTING_TEXT, FB_SETTING_NUMBER, FB_SETTING_INTEGER } fb_setting_kind;
typedef struct {
  const char *key;       /* its JSON key, with its unit ("loop_damping_1_s") */
  fb_setting_kind kind;
  const char *text;      /* FB_SETTING_TEXT */
  double number;         /* FB_SETTING_NUMBER (not finite: null) */
  long integer;          /* FB_SETTING_INTEGER */
} fb_engine_setting;
#define FB_ENGINE_SETTINGS_MAX 16

/* Which of an engine's models a run has (for its settings lines). */
typedef struct {
  int ideal;     /* a model without clearance joints */
  int clearance; /* a model with clearance joints */
  int native;    /* a model whose clearance contact is the engine's own (FB_COLLIDER_NATIVE) */
} fb_engine_models_used;

/* One line of text of an engine's settings (settings_lines below). */
typedef void (*fb_engine_put_line)(void *a, const char *line);

typedef struct fb_engine {
  const char *name;                 /* fb_engine_name of its id */
  int guarded;                      /* 1: the harness stops a run whose penetration exceeds
                                       def->penetration_limit; 0: the engine controls its own
                                       accuracy (reference) */
  int step_values_lag;              /* 1: sample() after the step from t_n reports that step's
                                       acceleration (omega_{n+1} - omega_n) / h and contact
                                       force, which belong to t_n: the harness moves them one
                                       sample earlier (fb_series_attribute_to_step_start) */
  int refine_peaks;                 /* 1: the samples lie on a discrete motion whose spikes the
                                       harness refines by parabola (fb_series_refine_peaks); 0:
                                       exact (analytic) or refined by the engine (reference) */
  int computes_in_create;           /* 1: create computes the whole series (the analytic
                                       solution, the reference's integration) and step replays
                                       it: the run books create as the engine's stepping */
  fb_status (*create)(void **self, const fb_model_scene *sm, fb_diag *diag);
  fb_status (*step)(void *self, fb_diag *diag);
  void (*stopped)(const void *self, fb_stop *out); /* optional: why step returned
                                       FB_ERR_NUMERIC or FB_ERR_NOMEM (NULL: a solver stop with
                                       the step's message as detail) */
  void (*sample)(const void *self, fb_sample *x);
  void (*contact)(const void *self, fb_engine_contact *out);
  void (*provenance)(const void *self, int joint, fb_contact_provenance *out);
  void (*reactions)(const void *self, double force[4][2], double *drive_torque);
  double (*drift)(const void *self);
  size_t (*steps)(const void *self);
  void (*destroy)(void *self);
  void (*step_stats)(const void *self, fb_step_stats *out); /* optional: the steps taken
                                       (engines that follow [solver] h_s = adaptive) */
  double (*stepping_s)(const void *self); /* optional: of the time spent in step(), the
                                       engine's own stepping [s], for an engine whose step()
                                       also fills the output grid (Simbody: its integrator's
                                       steps, the interpolation and exact samples being the
                                       sampling); NULL: all of step() is stepping */
  double (*cost_per_sample)(const fb_model *m, const fb_case *c); /* optional: the time
                                       of one sample of model m in case c [s]: its CPU time
                                       (an idle machine's wall time) measured as timing.json's
                                       models[].cpu_s over its samples on the shipped cases
                                       and rounded up to their largest, for fb_run_estimate
                                       (run.h); NULL: FB_COST_DEFAULT_S */
  const char *drive_key;            /* the case key that sizes the crank's drive, named by the
                                       drive-saturation warning when the crank lags its
                                       prescribed angle (NULL: no such warning) */
  void (*peer_args)(const fb_model_scene *sm, double h, fb_engine_put_arg put, void *a);
                                    /* optional: the engine's own settings of model view sm at
                                       step h [s] for its bare peer program
                                       tests/peers/peer_<name> (fourbar bench --grid peers,
                                       peers.h), each as put(a, key, value text); NULL: the
                                       engine has no peer */
  const char *model_format;         /* optional: the model file format the engine reads and
                                       export_model writes ("mjcf": MuJoCo), or NULL */
  fb_status (*export_model)(char *buf, size_t size, const fb_model_scene *sm, fb_diag *diag);
                                    /* optional: model view sm as a model file of model_format
                                       that a user loads into the engine (fourbar export,
                                       docs/commands.md), into buf; errors: the engine's, and
                                       FB_ERR_RANGE when buf is too small */
  const fb_engine_impact *impact;   /* optional: the engine's single impact (NULL: none) */
  int (*settings)(fb_engine_setting *out, const fb_case *c, int clearance_mask,
                  fb_collider collider, double h);
                                    /* optional: the engine's own choices as a model with
                                       clearance joints clearance_mask and collider collider
                                       used them in case c at step h [s], into out (at most
                                       FB_ENGINE_SETTINGS_MAX); returns their count (0: none) */
  void (*settings_lines)(const fb_case *c, const fb_engine_models_used *used,
                         fb_engine_put_line put, void *a);
                                    /* optional: the lines the run's table prints for the
                                       engine's models (used: which kinds ran) */
  const char *(*mapping_text)(fb_collider collider);
                                    /* optional: how the clearance contact of a model with
                                       collider reaches the engine when it is not the case's
                                       ERP/CFM mapping ("none (applied force)"); NULL, or a
                                       NULL result: the mapping's name */
  const fb_engine_bench *bench;     /* optional: the engine's rows of fourbar bench's grids
                                       (engine_bench.h; NULL: none) */
  const struct fb_kit_binding *kit; /* optional: the engine's binding of the engine kit
                                       (src/engines/kit/kit.h), with which it builds any
                                       planar case's ideal models; NULL: none */
  void (*refine)(const void *self, fb_series *s, double fraction, double t_split);
                                    /* optional, with refine_peaks 1: the run's series refined
                                       by the engine's own figures between samples
                                       (fb_series_refine_peaks_max: the kit adapter's
                                       sub-stepped force maxima); NULL: fb_series_refine_peaks */
  const struct fb_kit_binding *kit_native; /* optional: the binding that builds a model whose
                                       collider is the engine's native contact
                                       (FB_COLLIDER_NATIVE: MuJoCo's own constraint solver on
                                       the clearance, Siconos's unilateral relation), on a
                                       planar case and through the kit adapter; it reports joint
                                       reactions when kit does (the adapter's table follows
                                       kit's); NULL: none */
  int kit_default;                  /* optional, with create and kit: the models [solver]
                                       builder = auto builds through the kit, FB_KIT_DEFAULT_*
                                       bits (below): those of a kind whose every feature of the
                                       engine's own world the binding builds, at its cost and
                                       within the committed baselines (docs/architecture.md);
                                       never a case with clearance at the driven joint, which
                                       the kit does not drive; 0: every model through the
                                       engine's own world */
  int own_one_pin;                  /* optional, with create and kit: 1 when the engine's own
                                       world takes clearance at the description's
                                       reference_joint alone (Simbody's tree is cut there,
                                       Siconos's relation written there): [solver] builder =
                                       auto builds a clearance model of a case with clearance
                                       at other joints through the kit, which takes any pins */
} fb_engine;

/* fb_engine.kit_default's bits: the ideal models (no clearance joint), the
 * clearance models (any collider, the engine's native contact included). */
enum { FB_KIT_DEFAULT_IDEAL = 1, FB_KIT_DEFAULT_CLEARANCE = 2, FB_KIT_DEFAULT_ALL = 3 };

/* The engine for id, or NULL when this build has none (message in diag:
 * FB_ERR_ARG). */
const fb_engine *fb_engine_get(fb_engine_id id, fb_diag *diag);

/* The binding of engine e that builds a model with collider collider:
 * e->kit_native for the engine's native contact, else e->kit (NULL: none). */
const struct fb_kit_binding *fb_engine_kit_of(const fb_engine *e, fb_collider collider);

/* The table that runs model m of engine e on a four-bar or slider-crank
 * case c (model_run.c): e itself, or the kit adapter (fb_engine_kit_adapter,
 * kit_engine.c) over e's engine-kit binding when e has no create of its
 * own, or e has a binding and the case asks [solver] builder = kit, or
 * auto (the default) where e->kit_default names m's kind (ideal or
 * clearance) and the case has no clearance at the driven joint
 * (fb_mech_driven_joint), or m is a clearance model whose engine's own
 * world takes one pin (own_one_pin) and the case has others; an engine
 * without a binding keeps its own. NULL
 * with diag (FB_ERR_ARG) for an engine with neither. */
const fb_engine *fb_engine_runner(const fb_engine *e, const fb_model *m, const fb_case *c,
                                  fb_diag *diag);

/* Steps instance self of engine e (step size h [s]) until its sampled time
 * reaches t - h/2 [s]. Errors: those of e->step. */
fb_status fb_engine_advance(const fb_engine *e, void *self, double t, double h, fb_diag *diag);

/* The engines (defined next to their code): the analytic and reference
 * engines (engines.c) ... */
extern const fb_engine fb_engine_analytic;
extern const fb_engine fb_engine_reference;
/* ... and the kit adapter (kit_engine.c: any engine's kit binding on the
 * four-bar and slider-crank run path; fb_engine_runner picks it) */
extern const fb_engine fb_engine_kit_adapter;
/* 1 when e is the kit adapter (with or without the load columns of a
 * binding that reports joint reactions). */
int fb_engine_is_kit_adapter(const fb_engine *e);
/* fb_engine_<name> of every engine of FB_ENGINE_LIST (fb_config.h), each
 * defined in its folder src/engines/<name>/ and linked only in builds with it
 * (FB_HAVE_<ID>). */
#define X(ID, name) extern const fb_engine fb_engine_##name;
FB_ENGINE_LIST
#undef X


#endif
