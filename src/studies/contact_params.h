/* fourbar contact-params: a physical contact in the parameters of ODE,
 * Gazebo, MuJoCo 2.2 and Bullet at a step h, each recommended row held to
 * the resolution rule of a run and verified by single impacts in the engine
 * itself (docs/contact-params.md).
 *
 *   translation  the law as a linear spring k [N/m] and damper c [N s/m]:
 *                restitution and linear laws as they are; hertz linearised
 *                at an operating point (the impact's peak penetration, or
 *                the tangent at a static load); the damped Hertz laws
 *                (lankarani-nikravesh, hunt-crossley, flores, gonthier) as
 *                the spring-damper with the law's own restitution and peak
 *                penetration at the speed and design mass
 *                (fb_params_linear_equivalent). An undamped contact gets the
 *                damper of restitution FB_CP_RESTITUTION_MAX: an ODE row
 *                needs a finite CFM, and one without a damper has ERP ~ 1e10
 *   rows         the translations of engine_params.h at the design mass m0
 *                (geometric mean of the range) and step h
 *   faithful     a row is faithful when every single impact of it, at every
 *                mass of the range (min, design, max) and every onset phase
 *                of FB_CP_ONSET_PHASES (a contact starts anywhere inside a
 *                step, and the engine sees it only at the step's end), leaves
 *                with the continuous contact's restitution within
 *                FB_CP_RESTITUTION_TOL and reaches its peak penetration
 *                within FB_CP_PENETRATION_TOL
 *   recommended  rows are recommended at h when h omega_c <= FB_H_OMEGA_C_BOUND
 *                (the run's rule, omega_c = sqrt(k / m_min), resolution.h)
 *                and h <= the largest faithful step; then verified, and a
 *                recommended row that fails is the command's exit status 1
 *   largest_step the largest h at which the recommended rows of the given
 *                contact are faithful: the rule's h if faithful there, else
 *                halving to a faithful step and bisecting (geometric) to
 *                FB_CP_STEP_REL
 *   at_step      at the given h, the stiffest contact with the same
 *                restitution that is faithful: the outcome of a linear
 *                contact's impact depends only on h omega and zeta at each
 *                mass, so k' = k (h* / h)^2 and c' = c (h* / h) keep zeta and
 *                move h omega to that of the largest step h*
 *   per-step     nonlinear laws: the law mapped every step (tangent spring and
 *                the law's damper, matched on the mass: fb_contact_row_step),
 *                for users who set ERP/CFM per contact; verified in ODE */
#ifndef FB_CONTACT_PARAMS_H
#define FB_CONTACT_PARAMS_H

#include "case.h"
#include "planar.h"
#include "contact.h"
#include "engine_params.h"
#include "impact.h"
#include "run.h"
#include "status.h"

/* The acceptance bounds on one impact: restitution within 1 %, peak
 * penetration within 2 % of the continuous contact's (impact.h, one rule
 * for the verification and the verdict's first impact). */
#define FB_CP_RESTITUTION_TOL FB_FAITHFUL_RESTITUTION_TOL
#define FB_CP_PENETRATION_TOL FB_FAITHFUL_PENETRATION_TOL

/* Onset phases verified: the fraction of a step by which the contact began
 * before the first step that sees it (engine.h, fb_impact_row). The
 * restitution error is linear in the phase (measured: -zeta h omega at 0,
 * +zeta h omega just short of 1), so both ends are in the set. */
#define FB_CP_ONSET_PHASES 5
extern const double fb_cp_onset_phases[FB_CP_ONSET_PHASES];

/* Restitution of the damper an undamped contact gets (see above): 0.1 % of
 * restitution, a tenth of FB_CP_RESTITUTION_TOL. */
#define FB_CP_RESTITUTION_MAX 0.999

/* The largest step is bisected to this relative width [-]. */
#define FB_CP_STEP_REL 0.01

/* No faithful step below h omega_c = this [-] counts as none (a contact of
 * 3000 steps that still fails is failing for another reason). */
#define FB_CP_H_OMEGA_MIN 1e-3

/* Single impacts run until the body leaves, or for this many contact
 * durations of the continuous contact (then the row fails). */
#define FB_CP_VERIFY_DURATIONS 100.0

/* Default h omega_c when no step is given: the single-impact accuracy point
 * (h omega_c = 0.1, about 31 steps per contact), or the largest faithful
 * step when that is smaller. */
#define FB_CP_DEFAULT_H_OMEGA 0.1

/* Largest ratio of a mass range's ends: beyond it no single row can be
 * faithful, and a user has mistyped a unit. */
#define FB_CP_MASS_RATIO_MAX 1e4
/* A damped Hertz law whose own restitution misses the cr asked by more than
 * this (relative) gets a line saying so: the rows reproduce the law's
 * restitution, and beyond 10 % that reads as another contact than asked
 * (Hunt-Crossley at cr = 0.3 leaves at 0.58; its damping factor
 * 3 (1 - cr) / 2 never passes 1.5, so no cr takes it below 0.49 at n = 1.5). */
#define FB_CP_LAW_NOTE_REL 0.1

/* The default steps of the engines users most often ask about: MuJoCo's
 * opt.timestep (2 ms) and Gazebo's physics max_step_size (1 ms). With
 * fb_cp_request.engine_steps, fb_cp_run gives the at_step contact at each. */
#define FB_CP_MUJOCO_DEFAULT_H 2e-3
#define FB_CP_GAZEBO_DEFAULT_H 1e-3
#define FB_CP_ENGINE_STEPS 2

/* What the user asks for. Laws: FB_LAW_RESTITUTION, FB_LAW_LINEAR,
 * FB_LAW_HERTZ and the damped Hertz laws. */
typedef struct {
  fb_law_kind law;    /* the contact law */
  double stiffness;   /* k [N/m] (linear, restitution) or K [N/m^n] (Hertz laws) */
  double exponent;    /* n of the Hertz laws [-]; 1 otherwise */
  double restitution; /* cr [-]; NAN when not given (hertz: undamped) */
  double damping;     /* c of the linear law [N s/m] */
  double mass_min;    /* effective mass along the normal, smallest [kg] */
  double mass_max;    /* largest [kg] (= mass_min for one mass) */
  double h;           /* step [s]; 0: automatic (FB_CP_DEFAULT_H_OMEGA) */
  double speed;       /* impact speed [m/s] */
  double load;        /* hertz: linearise at the static penetration of this load [N];
                         NAN: at the impact */
  int verify;         /* 1: search the largest step, build at_step, verify every row */
  int engine_steps;   /* 1 (with verify): also the at_step contact at MuJoCo's and Gazebo's
                         default steps (FB_CP_MUJOCO_DEFAULT_H, FB_CP_GAZEBO_DEFAULT_H);
                         the CLI sets it when no --h-s is given */
  const char *case_path; /* the case the contact was taken from (fb_cp_request_from_case),
                            NULL: from the flags; messages then name the case's keys */
  int h_from_case;    /* 1: h is the case's [solver] h_s (no --h-s), the step fourbar run
                         takes */
  const char *rows_of; /* NULL: the given contact's rows verified for every engine, the
                          comparison forms too, and at_step searched; "ode" (a caller that
                          reads the largest faithful step and ODE's matched row alone:
                          fourbar run's step check, the export's note): ODE's recommended
                          rows alone, no at_step. The largest faithful step is every
                          engine's either way */
} fb_cp_request;

/* Defaults: restitution law, k = 1e7 N/m, cr 0.9, 0.1 kg, automatic step,
 * 1 m/s, verification on, no engine default steps. */
void fb_cp_request_default(fb_cp_request *q);

/* Checks q (each parameter with its range, unit and the flag that sets it:
 * --stiffness, --restitution, ...; for a contact taken from a case, the
 * case's keys and effective masses instead of flags the user never gave).
 * Errors: FB_ERR_RANGE, FB_ERR_ARG. */
fb_status fb_cp_request_check(const fb_cp_request *q, fb_diag *diag);

/* One engine's row verified at one mass: the worst of its impacts over the
 * onset phases. */
typedef struct {
  const char *engine;       /* "ode", "gazebo", "mujoco", "bullet" */
  const char *engine_version; /* the verifying library's version at run time ("2.2.2" for
                                 MuJoCo), NULL when its engine reports none (engine.h) */
  const char *form;         /* "matched", "direct", ... */
  double mass;              /* [kg] */
  int recommended;          /* 1: a row printed as the recommendation */
  int ran;                  /* 0: an impact could not run (why) */
  char why[FB_DIAG_SIZE + 64];
  double restitution;        /* at the worst phase [-] */
  double restitution_target; /* the continuous contact's [-] */
  double restitution_rel;    /* worst relative error over the phases [-] */
  double restitution_phase;  /* its onset phase [-] */
  double penetration;        /* peak penetration at the worst phase [m] */
  double penetration_target; /* [m] */
  double penetration_rel;    /* worst relative error [-] */
  double penetration_phase;  /* its onset phase [-] */
  double force;              /* peak force at phase 0 [N] */
  double force_target;       /* [N] */
  int faithful;              /* every phase within the tolerances */
} fb_cp_check;

#define FB_CP_CHECKS_MAX 48

/* One linear contact's rows at one step. */
typedef struct {
  fb_linear_contact lc;        /* k, c at the design mass, step h */
  double h_omega_c;            /* h sqrt(k / m_min) [-] */
  double omega_d_h;            /* damped h omega at m_min [-] */
  fb_ode_row ode;              /* ODE, matched */
  fb_ode_row ode_standard;     /* ODE manual's formula from k, c (comparison) */
  fb_spring_damper gazebo;     /* Gazebo kp, kd (= Bullet's stiffness, damping) */
  fb_ode_row gazebo_row;       /* what Gazebo makes of them at h */
  fb_spring_damper gazebo_naive; /* kp = k, kd = c (comparison) */
  fb_ode_row gazebo_naive_row;
  double max_vel;              /* Gazebo <max_vel>, ODE contact_max_correcting_vel [m/s] */
  fb_mujoco_params mj_direct;  /* at the design mass */
  fb_mujoco_params mj_continuous; /* k/m, c/m (comparison) */
  fb_mujoco_params mj_naive;   /* (-k/m, -c/m), default solimp (comparison) */
  fb_mujoco_params mj_standard;
  int has_standard;
  char standard_note[FB_DIAG_SIZE]; /* why there is no standard form */
  double masses[3];            /* masses verified: min, design, max [kg] */
  int n_masses;                /* 1 (one mass) or 3 */
  fb_mujoco_params mj_at[3];   /* direct at each of masses[] */
  double penetration[3];       /* the continuous contact's peak penetration at each mass [m] */
  double duration[3];          /* its contact duration [s] */
  double restitution[3];       /* its restitution [-] */
} fb_cp_rows;

/* A contact at a step: its rows, whether they are recommended, and their
 * verification. */
typedef struct {
  fb_cp_rows rows;
  int recommended;        /* 1: the rows are printed as the recommendation */
  char why_not[512];      /* else why */
  fb_cp_check checks[FB_CP_CHECKS_MAX];
  int n_checks;
} fb_cp_step;

/* The per-step mapping of a nonlinear law (ODE, the law's own row every
 * step) verified at the design mass. */
typedef struct {
  int present;            /* 1 for the Hertz laws */
  int recommended;        /* h sqrt(k_t / m_min) within the largest faithful h omega_c */
  double h_omega_t;       /* h sqrt(k_t / m_min), k_t the law's tangent at its peak [-] */
  fb_cp_check check;      /* ode, per-step */
} fb_cp_per_step;

typedef struct {
  fb_cp_request q;          /* as asked, with h resolved */
  double m0;                /* design mass: sqrt(m_min m_max) [kg] */
  double k, c;              /* the linear contact [N/m], [N s/m] */
  double op_penetration;    /* hertz: the operating point's penetration [m]; else NAN */
  int damper_floored;       /* the undamped contact got FB_CP_RESTITUTION_MAX */
  double law_restitution;   /* the law's own impact at m0 and v: restitution [-] */
  double law_floor;         /* Lankarani-Nikravesh, Hunt-Crossley whose restitution misses cr
                               by more than FB_CP_LAW_NOTE_REL: the least restitution the law
                               reaches (its impact as cr -> 0) [-]; else NAN */
  double law_penetration;   /* peak penetration [m] */
  double law_force;         /* peak force [N] */
  double lin_force;         /* the linear contact's peak force at m0 [N] */
  fb_cp_step given;         /* the given contact at h */
  double largest_step;      /* [s]; NAN: none found, or not verified */
  double largest_h_omega;   /* h omega_c there [-] */
  const char *largest_limited_by; /* "rule" or "verification" */
  int has_at_step;
  double at_k, at_c;        /* the at_step contact [N/m], [N s/m] */
  fb_cp_step at_step;
  int n_engine_steps;       /* at_step at the engines' default steps (engine_steps) */
  struct {
    const char *engine;     /* "mujoco" (2 ms), "gazebo" (1 ms) */
    double h;               /* [s] */
    double k, c;            /* the stiffest faithful contact of the same restitution there
                               [N/m], [N s/m] */
    fb_cp_step step;        /* its rows, recommended, verified */
  } engine_step[FB_CP_ENGINE_STEPS];
  fb_cp_per_step per_step;
  int failed;               /* a recommended row failed its verification (or could not run) */
  int n_unverified;         /* engines whose rows this build cannot verify */
  struct {
    const char *engine;     /* "mujoco", "bullet" */
    const char *howto;      /* how to get it into a build (fb_engine_howto) */
  } unverified[2];
} fb_cp_result;

/* The contact of clearance joint j (FB_JOINT_*) of case c into q, as
 * `fourbar contact-params --case` reads it: with q->law FB_LAW_RESTITUTION
 * the law of the case's clearance-restitution models (k, cr), with
 * FB_LAW_HERTZ that of its clearance-impact models (K, n, linearised at the
 * joint's expected force); the joint's effective-mass range over a
 * revolution and every direction (resolution.h, fb_case_contact_of); the
 * case's step when q->h is NAN. The other fields of q stay as given.
 * Errors: those of fb_case_contact_of. */
fb_status fb_cp_request_from_case(fb_cp_request *q, const fb_case *c, int j, fb_diag *diag);

/* As fb_cp_request_from_case for a planar case c (description m, a
 * driven one) at its revolute clearance joint j (index in the
 * description): the law a run's clearance-restitution or clearance-impact
 * models take there, the pin's effective-mass range over a revolution and
 * every direction and its expected force (planar_resolution.h
 * fb_planar_contact_estimates, the estimate fourbar penalty prints); the
 * case's step (h_s = auto: the one its run takes) when q->h is NAN.
 * Errors: FB_ERR_ARG when j is not a revolute clearance joint of the case;
 * those of fb_planar_contact_estimates; FB_ERR_NOMEM. */
fb_status fb_cp_request_from_planar(fb_cp_request *q, const fb_case *c, const fb_planar *m, int j,
                                    fb_diag *diag);

/* The step h of case c as this verification sees it, for `fourbar run`'s
 * step line (run.h, fb_step_check): for every clearance joint, the
 * restitution law's contact (fb_cp_request_from_case) verified at h; the
 * worst relative restitution and penetration of ODE's matched row over the
 * joint's masses and onset phases, and the smallest largest faithful step.
 * Errors: those of fb_cp_request_from_case and fb_cp_run. */
fb_status fb_cp_case_step_check(fb_step_check *out, const fb_case *c, double h, fb_diag *diag);

/* Runs q (checked with fb_cp_request_check first): translation, rows, and
 * with q->verify the largest faithful step, at_step and every row's
 * verification. FB_OK also when a row fails its verification (out->failed).
 * Errors: those of the check (FB_ERR_RANGE, FB_ERR_ARG); FB_ERR_NUMERIC when
 * the law's own impact cannot be integrated. */
fb_status fb_cp_run(fb_cp_result *out, const fb_cp_request *q, fb_diag *diag);

/* Verifies one linear contact's rows at a step (what fb_cp_run does for
 * the given contact and for at_step): fills st->checks. recommended marks
 * the rows printed as recommendations. Returns the number of recommended
 * checks that failed. */
int fb_cp_verify(fb_cp_step *st, double speed, int recommended);

/* Fills rows for the linear contact (k, c) at step h over masses
 * [m_min, m_max] at speed v (design mass their geometric mean). Errors:
 * FB_ERR_RANGE (fb_linear_contact_check, Gazebo's h kp + kd <= 0). */
fb_status fb_cp_rows_make(fb_cp_rows *rows, double k, double c, double m_min, double m_max,
                          double h, double v, fb_diag *diag);

#endif
