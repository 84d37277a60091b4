/* How a model's run ended and what it warns about, as data: the stop reason
 * (an enum with the time, step and joint) and a typed list of warnings.
 * Callers compare kinds; only the writers turn them into text
 * (outcome_text.h). */
#ifndef FB_OUTCOME_H
#define FB_OUTCOME_H

#include <stddef.h>

/* Why a run stopped before its end. */
typedef enum {
  FB_STOP_NONE = 0,        /* ran to its end */
  FB_STOP_PENETRATION = 1, /* a clearance joint's penetration passed the limit (unstable) */
  FB_STOP_NONFINITE = 2,   /* NaN or infinity in the state */
  FB_STOP_STEP_BUDGET = 3, /* the integrator spent its step budget */
  FB_STOP_ALLOCATION = 4,  /* the engine could not allocate memory */
  FB_STOP_SOLVER = 5,      /* the engine's solver failed (ODE's internal check, GSL) */
  FB_STOP_ALIASED = 6,     /* a matched contact row's omega_d h passed FB_MATCHED_ALIAS_BOUND */
  FB_STOP_WALL_TIME = 7,   /* the run reached its wall-time limit ([run] max_wall_s) */
  FB_STOP_COUNT
} fb_stop_kind;

/* A stop reason with where it happened. */
typedef struct {
  fb_stop_kind kind;  /* FB_STOP_NONE: the run is complete */
  const char *engine; /* name of the engine that stopped ("ode", "reference", ...) */
  double t;           /* time of the stop [s] */
  size_t step;        /* step at which it stopped; 0 for adaptive integrators */
  int joint;          /* clearance joint (fb_joint) for FB_STOP_PENETRATION and
                         FB_STOP_ALIASED, else -1 */
  const char *joint_name; /* that joint's name in the case's mechanism (set where the run
                         knows the mechanism: model_run.c, reference.c); NULL: the
                         four-bar's name of joint */
  double value;       /* penetration [m] (PENETRATION); steps spent (STEP_BUDGET);
                         omega_d h [-] (ALIASED) */
  double limit;       /* penetration limit [m] (PENETRATION); steps per sample (STEP_BUDGET);
                         the bound on omega_d h [-] (ALIASED); max_wall_s [s] (WALL_TIME) */
  double t_end;       /* the run's duration [s] (STEP_BUDGET, WALL_TIME) */
  double h_max;       /* ALIASED: the largest usable step, h limit / value [s] */
  char detail[160];   /* the solver's own words (ODE's error message, GSL's error string) */
} fb_stop;

/* What a completed or stopped run warns about. */
typedef enum {
  FB_WARN_PENALTY_VALIDITY = 0, /* penetration beyond FB_PENALTY_VALIDITY_FACTOR x clearance */
  FB_WARN_DRIVE_SATURATED = 1,  /* the crank left its prescribed angle */
  FB_WARN_ERROR_BOUND = 2,      /* the error against a yardstick passed a stated bound */
  FB_WARN_UNDER_RESOLVED = 3,   /* h omega_c of a contact above the bound (resolution.h) */
  FB_WARN_DIVERGENT = 4,        /* the trajectory left its reference's (metrics.h, fb_divergence) */
  FB_WARN_COUNT
} fb_warning_kind;

/* One warning with its figures. */
typedef struct {
  fb_warning_kind kind;
  double value;  /* penetration [m]; crank angle lag [rad]; error [-]; h omega_c [-];
                    DIVERGENT: crank angle where it left [rad] */
  double limit;  /* radial clearance [m]; -; the bound [-]; the bound [-] */
  double ratio;  /* penetration / clearance [-]; -; -; steps per contact (pi / h omega_c) */
  double factor; /* the validity factor [-]; -; - */
  double t;      /* time [s] where it applies (DIVERGENT: where it left), or NaN */
  char what[64]; /* the case key that lifts the limit (DRIVE_SATURATED); what the error is of
                    (ERROR_BOUND); the joint (UNDER_RESOLVED); the reference (DIVERGENT);
                    else "" */
  double h;      /* UNDER_RESOLVED: the step the run used [s]; else 0 */
  int h_auto;    /* UNDER_RESOLVED: fb_warning_step, how that step was chosen; else 0 */
} fb_warning;

/* How the step of an UNDER_RESOLVED run was chosen (fb_warning.h_auto). */
typedef enum {
  FB_WARN_STEP_FIXED = 0,       /* [solver] h_s = a number */
  FB_WARN_STEP_AUTO_CONTACT = 1, /* h_s = auto, set by the contact estimate (resolution.h) */
  FB_WARN_STEP_AUTO_CAP = 2      /* h_s = auto, set by its steps-per-revolution cap */
} fb_warning_step;

#endif
