/* A planar case ([linkage] type = planar, docs/planar.md) through
 * `fourbar run`: its description compiled (physics/planar/planar_case.h)
 * and its models run on the planar core, outputs by body name.
 *
 * The models a planar case runs today:
 *   analytic   the core's position, velocity and acceleration analysis
 *              (planar_kinematics.h: Newton on the loop equations,
 *              converged to the rounding level) sampled every h over the
 *              run, and every moving body's omega and alpha extremes over
 *              a revolution (planar_path.h: 3600 drive angles, then
 *              Brent), the drive at constant speed from the assembly
 *              configuration; at every sample the drive torque and every
 *              joint's reaction (planar_invdyn.h: the Lagrange multipliers,
 *              gravity [environment] gravity_m_s2 along -y).
  *   reference, reference-restitution
 *              the clearance joint's dynamics (planar_dynamics.h: the
 *              case's one [clearance] joint a pin in a hole, the impact or
 *              the restitution law of the case's [clearance] keys at the
 *              joint's largest ideal reaction, joint_law.h) integrated by
 *              rk8pd at FB_REFERENCE_TOL (planar_reference.h) from the
 *              steady start, sampled
 *              every h, each spike sample holding the extreme between its
 *              neighbours (peak_refine.h, the closed-form reference's
 *              rule); its window peaks (t from fb_case_peak_window_from:
 *              after the first revolution, or all with [run] peaks = all) and,
 *              as the reference's own error estimate, the same run at
 *              tol / FB_REFERENCE_CHECK_FACTOR (down to FB_REFERENCE_TOL_MIN):
 *              verdict "ok" when every window peak (omega, alpha of every
 *              body, the contact force) moves by at most FB_UNCONVERGED_REL,
 *              else "unconverged" (run.h's rule for a reference).
  *   ode-ideal-nominal, ode-clearance-impact, ode-clearance-restitution,
 *              ode-clearance-faceted, ode-clearance-ccd
 *              (fb_planar_kit_models lists them; fb_planar_kit_of says which models
 *              an engine with a binding of the engine kit builds)
 *              the description built in the engine through the kit
 *              (src/engines/kit/kit.h: every body at its assembly pose
 *              with the drive's velocities there, the engine's own joints,
 *              loop closure, stepper and [solver] settings; a clearance
 *              model's clearance joints each a pin in its hole (or a
 *              slider in its guide) with the reference's law of that
 *              joint, the kit's contact pipeline), one engine
 *              step of h per sample; its window peaks as a reference's;
 *              its verdict against the analytic model (ideal) or the
 *              reference of its law (planar_verdict.h).
 *   analytic-stackup, ode-ideal-stackup, ... (every engine's ideal
 *              stack-up model with a binding)
 *              the analytic model and the engines' ideal models at the
 *              stack-up corner: the description's dimensions
 *              (planar_dims.h, ISO 2768-1 [tolerance] class) at [tolerance]
 *              stackup's signs, one per dimension (max: every one '+'), its
 *              assembly closed by Newton at the drive's start; an engine's
 *              verdict against analytic-stackup.
 * Every model also samples the description's output points and every
 * prismatic joint's slide (planar_outputs.h) into out, when it has any.
 * An undriven case ([drive] joint = none, or a torque drive) runs the
 * references and the engines' models, from its bodies' initial angular
 * velocities (planar_free.h), its window the whole run; with no clearance
 * joint, `reference` is its ideal mechanism's forward dynamics and the
 * engines' ideal models' yardstick. A prismatic clearance joint is a
 * slider in its guide.
 * Every other model (an engine's without a binding, a clearance model
 * its engine's binding cannot build) is refused by name, with the reason
 * (fb_planar_run_refusal). A planar case that lists no [run] models runs
 * the four-bar's default rule on its description (casefile_planar.c:
 * analytic and ode-ideal-nominal, or an undriven case's reference; their
 * stack-up models with [tolerance] class; each clearance model with its
 * reference when it has clearance joints). */
#ifndef FB_PLANAR_RUN_H
#define FB_PLANAR_RUN_H

#include <stddef.h>

#include "case.h"
#include "contact.h"
#include "engine.h"
#include "metrics.h"
#include "planar.h"
#include "planar_resolution.h"
#include "planar_verdict.h"

/* The engines' models a planar case runs through the engine kit
 * (fb_planar_kit_of over the model table, in its order), comma-separated
 * into buf (size bytes, truncated to fit), for the refusals and report.md.
 * Returns buf. */
const char *fb_planar_kit_models(char *buf, size_t size);

/* The clearance joints a reference takes at most (its [clearance] joints). */
#define FB_PLANAR_REF_MAX_JOINTS 8

/* A reference's contact at one of its clearance joints. */
typedef struct {
  int joint;               /* the clearance joint (index in the description) */
  fb_contact_law law;      /* its law as used (taken at its own working force and mass) */
  double force_work;       /* the working force the law was taken at [N] */
  double force_max;        /* its largest contact force in the window [N] */
  double penetration_max;  /* its largest penetration in the window [m] */
  double *force, *pen;     /* its contact force [N] and penetration [m] (n each), each spike's
                              sample holding its refined extreme; in the model's block */
  double *force_sampled, *pen_sampled; /* the same at the samples, before the refinement (n) */
  double *ecc;             /* a pin's eccentricity, x at ecc[i], y at ecc[n + i] [m] (2 n);
                              NULL for a slider in its guide */
  /* an engine's clearance model: what its contact met (kit.h's record) */
  double h_omega_max;      /* largest h omega_c over its contact steps [-]; NaN: not measured
                              (no contact step, or an engine that controls its own steps) */
  double m_eff_min, m_eff_max; /* its effective mass range [kg]; NaN: no contact step */
  size_t contact_steps;    /* steps with its contact */
} fb_planar_ref_joint;

/* What a reference measured beyond its samples. */
typedef struct {
  int joint;               /* the clearance joint (index in the description); a reference of
                              several: the first of at[] */
  fb_contact_law law;      /* its law as used */
  double force_work;       /* the working force the law was taken at [N] */
  double tol, check_tol;   /* rk8pd tolerances of the run and its check [-] */
  size_t steps, check_steps; /* accepted steps of each */
  double force_max;        /* largest contact force in the window [N] (over every clearance
                              joint of a reference of several) */
  double penetration_max;  /* largest penetration in the window [m] (likewise) */
  int njoints;             /* a reference's or an engine's clearance model's clearance
                              joints (at[], in the description's order; at[0] is joint above,
                              its columns the model's force, pen, ...); 0 for the ideal
                              mechanism's and for other models */
  fb_planar_ref_joint at[FB_PLANAR_REF_MAX_JOINTS];
  double check_rel;        /* largest |relative change| of a window peak in the check, NaN
                              without one (fb_planar_ref_checked) [-] */
  int converged;           /* check_rel <= FB_UNCONVERGED_REL */
  int failed;              /* the integration stopped early (why: stop) */
  char stop[FB_DIAG_SIZE];
} fb_planar_ref_result;

/* 1 when reference result q has a check integration: its check tolerance
 * tighter than its own (a run at FB_REFERENCE_TOL_MIN, the floor, has
 * none; its verdict is then "unchecked"). */
static inline int fb_planar_ref_checked(const fb_planar_ref_result *q) {
  return q->check_tol < q->tol;
}

/* One planar model's result (fb_planar_model_has_contact below). */
typedef struct {
  char name[FB_NAME_SIZE]; /* "analytic", "reference", "reference-restitution" */
  int reference;           /* 1: a reference (ref holds its results; force, pen its columns) */
  int engine;              /* 1: an engine's model, built through the engine kit (kit.h) */
  const fb_planar *m;      /* the description it ran: the run's, or at a stack-up model
                              (analytic-stackup, *-ideal-stackup) the run's stackup (not
                              owned) */
  fb_planar_ref_result ref;
  double *force, *pen;     /* a reference's contact force [N] and penetration [m] (n), each
                              spike's sample holding its refined extreme (peak_refine.h);
                              an engine's model's at its samples */
  double *ecc;              /* a revolute clearance joint's pin (a reference's, an engine's
                              model's): its eccentricity, pin centre - hole centre, x at ecc[i],
                              y at ecc[n + i] [m] (2 n; in force's block); NULL for the others
                              (a slider in its guide) */
  int rigid;                /* an engine's rigid (impulsive) clearance model (fb_model.rigid):
                              its force column is the impulse over the step [N] */
  double *force_sampled, *pen_sampled; /* a reference's force and penetration at its samples,
                              before the refinement: what a model sampling at the same
                              instants sees of it (planar_verdict.c) (n); NULL for the others */
  fb_body_peaks *peaks;    /* per body of the description (nbodies; the ground's zero): omega
                              and alpha extremes over a revolution (analytic) or over the
                              window's samples (a reference) [rad/s, rad/s^2] */
  size_t n;                /* samples held */
  double h;                /* sample spacing [s] */
  double *t;               /* time [s] (n) */
  double *drive;           /* the drive's angle from the assembly configuration [rad] (n) */
  double *q;               /* body b (1 .. nbodies-1), quantity k (FB_Q_POS, _VEL, _ACC):
                              q[((b - 1) * 3 + k) * n + i]: angle [rad], omega [rad/s],
                              alpha [rad/s^2] (3 (nbodies - 1) n) */
  double wall_s;           /* wall time of the model [s] */
  fb_planar_verdict verdict; /* an engine's model's verdict (planar_verdict.h) */
  double setup_s;          /* an engine's model: of wall_s, the set-up before its first step
                              (its clearance law, the columns, the engine's world built through
                              the kit: kit.h fb_kit_series.setup_s) [s]; 0 for the others */
  double h_omega_max;      /* an engine's clearance model whose engine steps at h (its binding
                              takes the law's rows or applies the law explicitly, kit.h's
                              contact_rows, explicit_law): its clearance joint's largest
                              h omega_c over its contact steps (fb_kit_joint_record) [-]; NaN:
                              not measured (no contact step; an engine that controls its own
                              steps: Simbody's error control, DART's sub-steps, Siconos's
                              impulses; any other model) */
  double m_eff_min, m_eff_max; /* an engine's clearance model: its clearance joint's effective
                              mass range over its contact steps [kg]; NaN: none */
  int has_step_stats;      /* 1: an engine's model under [solver] h_s = adaptive */
  fb_step_stats step_stats; /* its engine steps (engine.h; the kit's fb_kit_series.stats) */
  double *force_max;       /* an engine's model whose binding sub-steps: its largest contact
                              force over the step from sample i [N] (n; kit.h's
                              fb_kit_joint_record.force_max), else NULL */
  double *torque;          /* the analytic model: the drive's torque on the driven body about +z
                              (planar_invdyn.h) [N m] (n), else NULL */
  double *reaction;        /* the analytic model: joint j's reaction on its second body from its
                              first (planar_invdyn.h, the four-bar's convention), force x
                              (k = 0) and y (k = 1) [N], moment about +z (k = 2) [N m]:
                              reaction[(3 j + k) n + i] (3 njoints n; alongside torque) */
  double *out;             /* the description's output points and slides (planar_outputs.h),
                              quantity c of fb_planar_outputs' row at out[c n + i], then
                              each spring's fb_planar_spring_state (planar_loads.h)
                              (nout n); NULL when it has none of them */
  int nout;                /* fb_planar_output_count of the description plus
                              FB_PLANAR_SPRING_QUANTITIES per spring */
} fb_planar_model;

/* One model of a planar case's variant ([variant.NAME], case.h): what its
 * summary and report keep of it, its series freed. */
typedef struct {
  char name[FB_NAME_SIZE];
  int reference, engine;   /* as fb_planar_model's */
  int contact;             /* 1: a clearance joint's contact (a reference of its law, an
                              engine's clearance model): ref.force_max and ref.penetration_max
                              are its peaks */
  fb_planar_ref_result ref; /* as fb_planar_model's (a reference's check, an engine's stop) */
  fb_planar_verdict verdict; /* an engine's model's */
  fb_body_peaks *peaks;    /* per body of the description (nbodies; the ground's zero), as
                              fb_planar_model's (owned) */
} fb_planar_variant_model;

/* One variant's run. */
typedef struct {
  fb_case_variant def;     /* name, set, models, description as the case gave them */
  double h;                /* the step its models ran at [s] */
  int n;                   /* models run */
  fb_planar_variant_model model[FB_MAX_MODELS];
} fb_planar_variant;

/* 1 when model p ran a clearance joint's contact: a reference of its law
 * (the ideal mechanism's has none), an engine's clearance model; its
 * ref.force_max and ref.penetration_max are then the contact's window
 * peaks [N, m]. */
static inline int fb_planar_model_has_contact(const fb_planar_model *p) {
  return (p->reference && p->ref.joint >= 0) || (p->engine && p->force);
}

/* Model p's clearance contacts: a reference's or an engine's clearance
 * model's clearance joints (ref.njoints), else 0. */
static inline int fb_planar_model_contacts(const fb_planar_model *p) {
  return p->reference || (p->engine && p->force) ? p->ref.njoints : 0;
}

/* Model p's k-th clearance contact (k < fb_planar_model_contacts(p)): its
 * joint, law, window peaks and columns (an engine's force_sampled,
 * pen_sampled NULL). */
static inline fb_planar_ref_joint fb_planar_model_contact(const fb_planar_model *p, int k) {
  return p->ref.at[k];
}

/* A planar case run. */
typedef struct {
  fb_case c;               /* the case as run */
  fb_planar *m;            /* its description (owned) */
  fb_planar *stackup;      /* m at the stack-up corner [tolerance] stackup (fb_case's
                              stackup.planar, planar_dims.h fb_planar_dims_corner) when a
                              stack-up model runs, else NULL (owned) */
  double omega;            /* the drive's signed speed [rad/s] */
  double duration;         /* simulated time [s] */
  double t_window;         /* a reference's peaks are over t >= t_window [s] */
  double *reaction_max;    /* (njoints) every joint's largest ideal reaction over a revolution
                              [N] (fb_planar_reaction_max), computed once for the models whose
                              contact law takes it (a driven case's references and engines'
                              clearance models); NULL when none does */
  double *stackup_reaction_max; /* (njoints) the same of stackup, when both are computed; else
                              NULL (fb_planar_run_reaction_max) */
  fb_planar_contact_estimate *est; /* (nest) every revolute clearance joint's contact under
                              both laws before the run (planar_resolution.h): what the
                              automatic step keeps, and what a given step resolves; NULL on
                              an undriven case or one without clearance joints */
  int nest;
  double h_auto_estimate;  /* h_s = auto: the step the estimates chose [s] (0 otherwise) */
  int h_rechosen;          /* h_s = auto: times the run was redone at a smaller step because an
                              engine's clearance model met h omega_c above the bound
                              (FB_H_AUTO_RETRIES at most, run.h) */
  int n;                   /* models run */
  fb_planar_model model[FB_MAX_MODELS];
  fb_planar_variant *variant; /* the case's variants run beside it (fb_planar_run_variants;
                              variant_count of them, owned), NULL when none */
  int variant_count;
} fb_planar_run;

/* Engine clearance model p of run r against the step's bound on h omega_c
 * (FB_H_OMEGA_C_BOUND) at its k-th clearance joint (p->ref.at[k]): 1
 * resolved, 0 not (then *w, when not NULL, the four-bar's under-resolved
 * warning, outcome.h, naming the joint, with the largest fixed step that
 * keeps it), -1 not measured (its h_omega_max NaN: no contact step, or an
 * engine that controls its own steps). */
int fb_planar_model_joint_resolution(const fb_planar_run *r, const fb_planar_model *p, int k,
                                     fb_warning *w);

/* fb_planar_model_resolution at the joint of p's largest h omega_c
 * (p->h_omega_max, the model's over its joints). */
int fb_planar_model_resolution(const fb_planar_run *r, const fb_planar_model *p, fb_warning *w);

/* The largest ideal reactions (njoints) [N] of description m of run r: the
 * nominal description's (r->reaction_max) or the stack-up corner's
 * (r->stackup_reaction_max); NULL when not computed. */
static inline const double *fb_planar_run_reaction_max(const fb_planar_run *r,
                                                       const fb_planar *m) {
  return m == r->stackup && r->stackup ? r->stackup_reaction_max : r->reaction_max;
}

/* Runs the n variant cases of run r (each from fb_casefile_load_variant of
 * r->c's file, in r->c.variant order) with fb_planar_run_case, one at a
 * time, and keeps each model's peaks, contact peaks, verdict and stop in
 * r->variant (planar_variants.c). Errors: those of fb_planar_run_case,
 * the message naming the variant (r keeps the variants run before);
 * FB_ERR_NOMEM. */
fb_status fb_planar_run_variants(fb_planar_run *r, const fb_case *cases, int n, fb_diag *diag);

/* The step's resolution of contact estimate e [-]: h times the rate the
 * step keeps (planar_resolution.h), within FB_H_OMEGA_C_BOUND when h
 * resolves it. */
double fb_planar_run_h_rate(const fb_planar_run *r, const fb_planar_contact_estimate *e);

/* 1 when the run's step is [solver] h_s = auto on a driven case (chosen
 * from its clearance contacts, planar_resolution.h, when it has any). */
int fb_planar_run_step_auto(const fb_case *c);

/* 1 when model name runs on a planar case (above). */
int fb_planar_run_takes(const char *name);

/* The models of planar case c checked against what a planar case runs,
 * and its keys against what a planar run acts on: FB_ERR_ARG naming the
 * first key given otherwise than a planar run can honour ([run] ensemble
 * above 1, start other than steady, pin_start other than centred,
 * [clearance] penetration_limit_um, [published.*], [solver] builder =
 * hand; every command that runs a planar case refuses them) or the first
 * model it cannot run and why (an engine's: FB_PLANAR_ENGINE_FOLLOWUP). */
fb_status fb_planar_run_check(const fb_case *c, fb_diag *diag);

/* Runs planar case c (c->planar.on) into *r (fb_planar_run_free). With
 * [solver] h_s = auto, a run in which an engine's clearance model met
 * h omega_c above FB_H_OMEGA_C_BOUND is redone at h bound / h omega_c
 * FB_H_AUTO_MARGIN, at most FB_H_AUTO_RETRIES times, as the four-bar's
 * (run.h); r->c.solver.h is then the step it ran at.
 * Errors: those of fb_planar_run_check, fb_planar_of_case (the
 * description), fb_planar_kin_new, fb_planar_peaks_of and
 * fb_planar_follow (the drive cannot turn); FB_ERR_RANGE when the run
 * would hold more than FB_PLANAR_RUN_MAX_SAMPLES samples; FB_ERR_NOMEM.
 * On error *r holds nothing that needs freeing. */
fb_status fb_planar_run_case(fb_planar_run *r, const fb_case *c, fb_diag *diag);

/* Most samples a planar model holds: 2e7 (at 5 moving bodies, 15 columns
 * of 8 bytes, 2.4 GB): beyond it a run is refused with the figure. */
#define FB_PLANAR_RUN_MAX_SAMPLES 20000000

void fb_planar_run_free(fb_planar_run *r);

/* Sets every engine model's verdict of run r (planar_verdict.h) from its
 * yardstick in the run: the analytic model for an ideal one, the reference
 * of its law for a clearance one. fb_planar_run_case calls it. */
void fb_planar_verdicts(fb_planar_run *r);

/* The first impact of clearance model p (of run r) against reference ref's
 * by the verdict's rule 1 (planar_verdict.h: each one's first contact
 * episode whose peak force reaches FB_MATCHED_GRAZING_SHARE of the
 * reference's largest, paired when their onsets lie within
 * FB_IMPACT_MATCH_REV_FRACTION of a revolution), each peak taken over its
 * own episode's samples, so that p and ref may be sampled at different
 * steps (fourbar bench's rows against a reference run once): *force_rel
 * and *pen_rel the relative errors of p's peak force and penetration
 * (NaN when not paired, or when either stopped or has no contact column).
 * Returns 1 when paired, else 0; -1 out of memory. */
int fb_planar_first_impact(double *force_rel, double *pen_rel, const fb_planar_run *r,
                           const fb_planar_model *p, const fb_planar_model *ref);

/* The reference model p (its samples allocated, p->name set) of run r:
 * the impact law (impact = 1, "reference") or the restitution law
 * (planar_ref_model.c) at the case's clearance joints; with none, the
 * ideal mechanism's forward dynamics under its loads, springs and
 * gravity (p->ref.joint = -1, no force or penetration columns), an
 * undriven or torque-driven case's yardstick. Errors: FB_ERR_ARG with
 * more than FB_PLANAR_REF_MAX_JOINTS clearance joints, or where fb_planar_ref_ideal_refusal
 * refuses; those of joint_law.h, planar_invdyn.h and planar_dynamics.h.
 * An integration that fails is a result (p->ref.failed), not an error. */
/* Why reference model `model` cannot run case c when c has no clearance
 * joint (the text after "model 'NAME': "), or NULL when it can or c has
 * one: a speed-driven mechanism's ideal motion is its kinematics (the
 * analytic model, exact), and the restitution law has no contact to act
 * at. */
const char *fb_planar_ref_ideal_refusal(const fb_case *c, const char *model);

fb_status fb_planar_run_reference(fb_planar_model *p, const fb_planar_run *r, int impact,
                                  fb_diag *diag);

/* The engine kit's binding (kit.h) that builds model name on a planar
 * case: an engine's ideal model of the nominal lengths whose engine table
 * has a binding, or its clearance model with the exact pin in the hole
 * and a law when the binding takes a contact (add_contact; on the
 * description's geometry, as the reference), or with a faceted or libccd
 * collider when the binding builds it (kit.h's collide: ODE's); NULL
 * otherwise (planar_kit_model.c). */
const struct fb_kit_binding *fb_planar_kit_of(const char *name);

/* Why model name does not run on a planar case, in words a refusal can
 * quote (its lengths a stack-up corner, its collider the four-bar's
 * world's, ...); NULL when it runs (fb_planar_run_takes). */
const char *fb_planar_run_refusal(const char *name);

/* fb_planar_run_refusal's part for an engine's model: NULL when
 * fb_planar_kit_of builds it (planar_kit_model.c). */
const char *fb_planar_kit_refusal(const char *name);

/* 1 when engine model name's binding applies a description's springs and
 * loads (kit.h apply_wrench); 0 otherwise. */
int fb_planar_kit_applies_loads(const char *name);

/* The engine models whose bindings apply springs and loads, comma-separated,
 * into buf (size); returns buf. */
const char *fb_planar_kit_loaded_models(char *buf, size_t size);

/* Engine model p (its samples allocated, p->name one fb_planar_kit_of
 * takes) of run r through the engine kit: the description built in the
 * engine, one engine step of h per sample, the window peaks; a clearance
 * model's clearance joints each with the reference's law of that joint
 * (p->ref.at[], njoints: each one's law, force_max, penetration_max and
 * columns, the first's also p->ref.joint, law and p's force, pen, ecc;
 * p->ref.force_max, penetration_max the largest over them; steps: the
 * steps with a contact row). Errors: FB_ERR_ARG without a clearance joint
 * or with more than FB_PLANAR_REF_MAX_JOINTS; those of joint_law.h and of
 * fb_kit_run. */
fb_status fb_planar_run_kit(fb_planar_model *p, const fb_planar_run *r, fb_diag *diag);

/* Engine model name's world of planar case c (a model fb_planar_kit_of
 * builds; its clearance joints' laws as fb_planar_run_kit takes them: at
 * each joint's largest ideal reaction over a revolution), built at step h
 * [s] (a run's: fb_planar_run_step) and written as the engine's own model
 * file into buf (size bytes, NUL terminated): kit.h fb_kit_model_text.
 * Errors: FB_ERR_ARG when no binding builds the model (naming why) or
 * it has no model file; those of the case's description, the laws
 * (joint_law.h) and fb_kit_model_text; FB_ERR_NOMEM. */
fb_status fb_planar_kit_model_text(char *buf, size_t size, const fb_case *c, const char *name,
                                   double h, fb_diag *diag);

/* The step h [s] of a planar case's samples and engine models: [solver]
 * h_s, h_min_s for an adaptive step, else (auto) a 6000th of a drive
 * revolution. */
double fb_planar_run_step(const fb_case *c);

/* Sample i of model p's output points and slides (p->out, when held) at
 * the coordinates q, rates qd and accelerations qdd (planar_outputs.h). */
void fb_planar_model_store_outputs(fb_planar_model *p, const fb_planar *m, size_t i,
                                   const double *q, const double *qd, const double *qdd);

/* Model p's rows of the output points and slides from its samples' body
 * angles (p->q) and centres of mass (centre: x at centre[(b 3 + k) n + i],
 * y at centre[(nb 3 + b 3 + k) n + i], body b = 0 .. nb - 1 the moving
 * ones, k = FB_Q_POS, _VEL, _ACC; the engine kit's layout, kit.h) into
 * p->out (held). */
void fb_planar_model_outputs_from(fb_planar_model *p, const fb_planar *m, const double *centre);

/* Model p's sample i of joint j's reaction (fb_planar_model.reaction):
 * force x (k = 0), y (k = 1) [N], its magnitude (k = 2) [N], the moment
 * about +z (k = 3) [N m]; p->reaction must be held. */
double fb_planar_model_reaction(const fb_planar_model *p, int j, int k, size_t i);

/* The analytic model's sample i of body b's quantity k (FB_Q_*). */
double fb_planar_model_value(const fb_planar_run *r, const fb_planar_model *p, int b, int k,
                             size_t i);

#endif
