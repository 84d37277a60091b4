/* The engine interface: what the harness (models.c, and through it run,
 * bench, check and sweep) knows of an engine. An engine is a table of
 * function pointers; an instance is an opaque pointer the engine owns.
 *
 *   create   builds the world of one model (fb_scene_model: the scene
 *            definition with the model's row applied) at t = 0; it calls
 *            fb_scene_def_check first
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

#include "model_table.h"
#include "outcome.h"
#include "scene_def.h"
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
  fb_status (*create)(void **self, const fb_scene_model *sm, fb_diag *diag);
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
  double (*cost_per_sample)(const fb_model *m, const fb_case *c); /* optional: the wall
                                       time of one sample of model m in case c on an idle
                                       2-core machine [s], measured on the paper's case and
                                       rounded up, for fb_run_estimate (run.h); NULL:
                                       FB_COST_DEFAULT_S */
  const char *drive_key;            /* the case key that sizes the crank's drive, named by the
                                       drive-saturation warning when the crank lags its
                                       prescribed angle (NULL: no such warning) */
  void (*peer_args)(const fb_scene_model *sm, double h, fb_engine_put_arg put, void *a);
                                    /* optional: the engine's own settings of model view sm at
                                       step h [s] for its bare peer program
                                       tests/peers/peer_<name> (fourbar bench --grid peers,
                                       peers.h), each as put(a, key, value text); NULL: the
                                       engine has no peer */
  const char *model_format;         /* optional: the model file format the engine reads and
                                       export_model writes ("mjcf": MuJoCo), or NULL */
  fb_status (*export_model)(char *buf, size_t size, const fb_scene_model *sm, fb_diag *diag);
                                    /* optional: model view sm as a model file of model_format
                                       that a user loads into the engine (fourbar export,
                                       docs/commands.md), into buf; errors: the engine's, and
                                       FB_ERR_RANGE when buf is too small */
} fb_engine;

/* The engine for id, or NULL when this build has none (message in diag:
 * FB_ERR_ARG). */
const fb_engine *fb_engine_get(fb_engine_id id, fb_diag *diag);

/* Steps instance self of engine e (step size h [s]) until its sampled time
 * reaches t - h/2 [s]. Errors: those of e->step. */
fb_status fb_engine_advance(const fb_engine *e, void *self, double t, double h, fb_diag *diag);

/* The engines (defined next to their code): the analytic and reference
 * engines (engines.c) ... */
extern const fb_engine fb_engine_analytic;
extern const fb_engine fb_engine_reference;
/* fb_engine_<name> of every engine of FB_ENGINE_LIST (fb_config.h), each
 * defined in its folder src/engines/<name>/ and linked only in builds with it
 * (FB_HAVE_<ID>). */
#define X(ID, name) extern const fb_engine fb_engine_##name;
FB_ENGINE_LIST
#undef X


#endif
