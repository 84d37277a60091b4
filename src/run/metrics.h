/* Metrics of a sampled series: peaks over a time window, and the error of a
 * dynamic series against the exact analytic solution at the same instants. */
#ifndef FB_METRICS_H
#define FB_METRICS_H

#include "analytic.h"
#include "series.h"

/* Error of one body against the analytic solution. */
typedef struct {
  double omega_max_rel;      /* (peak - exact peak) / |exact peak| of max omega [-] */
  double omega_min_rel;      /* same for min omega [-] */
  double alpha_max_rel;      /* same for max alpha [-] */
  double alpha_min_rel;      /* same for min alpha [-] */
  double omega_err_max;      /* max |omega - omega_exact(t)| [rad/s] */
  double omega_err_rms;      /* RMS of omega - omega_exact(t) [rad/s] */
  double alpha_err_max;      /* max |alpha - alpha_exact(t)| [rad/s^2] */
  double alpha_err_rms;      /* RMS of alpha - alpha_exact(t) [rad/s^2] */
  double pos_max_rel;        /* same for the largest position (a slider's x) [-] */
  double pos_min_rel;        /* same for the smallest position [-] */
} fb_body_error;

typedef struct {
  FB_MECH_OUTPUT_MEMBERS(fb_body_error); /* per output body (mechanism.h) */
  double crank_angle_err_max; /* max |theta2 - (theta0 + omega2 t)| [rad] */
} fb_error;

/* Spike metrics of a clearance model over the samples with t >= t_from. */
typedef struct {
  double alpha_peak_ratio_coupler;  /* peak |alpha| / the reference's peak |alpha| [-] */
  double alpha_peak_ratio_follower; /* [-] (the second output body's: a slider's |a|) */
  double omega_dev_max;             /* largest |omega - omega_exact(t)| of the rotating output bodies
                                       (the four-bar's coupler and follower, a slider-crank's rod) [rad/s] */
  double force_max;                 /* largest contact force over the clearance joints [N] */
  double penetration_max;           /* largest penetration [m] */
  int impacts;                      /* impact episodes begun in the window, all joints */
  double free_flight_fraction;      /* share of (sample, joint) pairs in free flight [-] */
  double alpha_peak_crank_angle_coupler;  /* crank angle of the coupler's largest |alpha| [rad] in [0, 2 pi) */
  double alpha_peak_crank_angle_follower; /* [rad] in [0, 2 pi) */
} fb_spikes;

/* The output keys of one body's peaks (fb_body_peaks) and of the spike
 * metrics (fb_spikes), in output order, X(field, key): summary.json
 * (report.c) and the checked metrics (check.c) both spell them from here. */
#define FB_BODY_PEAK_KEYS(X)          \
  X(omega_max, "omega_max_rad_s")     \
  X(omega_min, "omega_min_rad_s")     \
  X(alpha_max, "alpha_max_rad_s2")    \
  X(alpha_min, "alpha_min_rad_s2")
#define FB_SPIKE_KEYS(X)                                                   \
  X(alpha_peak_ratio_coupler, "alpha_peak_ratio_coupler")                  \
  X(alpha_peak_ratio_follower, "alpha_peak_ratio_follower")                \
  X(omega_dev_max, "omega_dev_max_rad_s")                                  \
  X(force_max, "force_max_n")                                              \
  X(penetration_max, "penetration_max_m")                                  \
  X(impacts, "impacts")                                                    \
  X(free_flight_fraction, "free_flight_fraction")                          \
  X(alpha_peak_crank_angle_coupler, "alpha_peak_crank_angle_coupler_rad")  \
  X(alpha_peak_crank_angle_follower, "alpha_peak_crank_angle_follower_rad")

/* The next impact of clearance joint j of series s (with contact columns)
 * at or after sample from, its first and last sample; 0 when none is left.
 * An impact is a contact, an unbroken run of samples with the pin beyond
 * the clearance (penetration > 0) or a force above the series' floor
 * s->impact_floor[j] (a rigid contact's impulse with the pin on the wall),
 * whose force somewhere exceeds that floor (episode.h,
 * FB_IMPACT_FLOOR_SHARE; 0: any positive force). One definition for every
 * model: the reference's and each engine's state columns are not read
 * (they differed: a positive force after a zero one, against a positive
 * penetration at a step approaching faster than 1 mm/s). A contact is not
 * split where its force touches zero while the pin is still in (a damped
 * law's force clamped to zero before the penetration is, then a little
 * above zero again: 0.1 to 1.6 N tails counted as impacts before; ODE's
 * row letting go for a step in a sustained contact), and an impact that
 * turns into continuous contact is one impact, its peaks over the whole
 * contact. Every count of impacts (spikes, the tables, the divergence
 * pairing, impact statistics, report.html's list) walks these. */
int fb_metrics_next_impact(const fb_series *s, int j, size_t from, size_t *first, size_t *last);

/* Impacts of clearance joint j of series s (fb_metrics_next_impact) that
 * begin before t_end [s] (INFINITY: all): the first and last sample index
 * of the first cap, in time order. Returns the count found, which may
 * exceed cap. */
size_t fb_metrics_impact_episodes(const fb_series *s, int j, double t_end, size_t *first,
                                  size_t *last, size_t cap);
/* Most episodes one metric lists per series (more are counted). */
#define FB_METRICS_MAX_EPISODES 4096

/* Spikes of series s (with contact columns) against reference peak |alpha|
 * values alpha_ref_coupler, alpha_ref_follower [rad/s^2] (> 0); omega_dev is
 * taken from err (fb_metrics_error of the same series).
 * Errors: FB_ERR_ARG for an empty window. */
fb_status fb_metrics_spikes(fb_spikes *out, const fb_series *s, double t_from,
                            double alpha_ref_coupler, double alpha_ref_follower,
                            const fb_error *err, fb_diag *diag);

/* Error of a clearance model's series against the reference series of the
 * same law, at equal instants (both sampled at t = k h). */
typedef struct {
  FB_MECH_OUTPUT_MEMBERS(fb_body_error); /* per output body; peaks: relative to the reference's peaks */
  double force_max_rel;         /* (peak force - reference's) / reference's [-] */
  double force_err_rms;         /* RMS of the force difference [N] */
  double penetration_max_rel;   /* (max penetration - reference's) / reference's [-] */
  double persistent_penetration_rel; /* persistent-contact penetration: over the samples where
                                        both are in continuous contact (FB_STATE_CONTINUOUS),
                                        sum of the model's penetration / sum of the reference's
                                        - 1 [-]; NaN without such samples */
  size_t persistent_samples;    /* those samples [-] */
  double ecc_direction_rms;     /* eccentricity-direction error in continuous contact: RMS over
                                   the same samples (both FB_STATE_CONTINUOUS, t >= t_from) of
                                   the angle from the reference's eccentricity vector to the
                                   model's, atan2(ey, ex) differences wrapped to (-pi, pi] [rad];
                                   NaN without such samples */
  int impacts;                  /* impact episodes in the window */
  int impacts_reference;
  double impact_angles[8];      /* crank angles of the first impacts [rad] in [0, 2 pi) */
  double impact_angles_reference[8];
  int first_impacts;            /* impacts of the run (t >= 0) compared below, <= FB_FIRST_IMPACTS */
  double first_impact_force_rel[3];       /* (peak force - reference's) / reference's of the
                                             run's k-th impact [-] (3) */
  double first_impact_penetration_rel[3]; /* same for the peak penetration [-] (3) */
  double first_impact_t[3];               /* onset of the model's k-th impact [s] (3) */
  double first_impact_t_error[3];         /* its onset minus the reference's k-th [s] (3) */
  double first_impact_force_reference[3]; /* the reference's k-th peak force [N] (3) */
} fb_reference_error;

/* Impacts of a run compared one by one (from t = 0, before the clearance
 * motion's chaos separates the model's sequence from the reference's). */
#define FB_FIRST_IMPACTS 3

/* Compares series s (model) with r (reference) over t >= t_from at clearance
 * joint j; the first impacts of the run (an impact: a contact episode, one
 * unbroken run of positive force, with a sample in the impact state; its
 * peaks over the episode) one by one from t = 0. Errors: FB_ERR_ARG when the grids differ or the window is empty. */
fb_status fb_metrics_vs_reference(fb_reference_error *out, const fb_series *s, const fb_series *r,
                                  double t_from, int j, fb_diag *diag);

/* A model parts from its reference when the pin's eccentricity vector differs
 * from the reference's by more than this fraction of the radial clearance:
 * half the gap, so the two pins are on different sides of the clearance
 * circle's centre, not one impact a few steps late (the paper case's
 * models stay within ~1e-2 of it) [-]. */
#define FB_DIVERGE_ECC_FRACTION 0.5
/* ... or when the coupler angles differ by more than this fraction of
 * c / L_coupler, the rotation that moves the coupler's far joint by the
 * same half clearance [-]. */
#define FB_DIVERGE_ANGLE_FRACTION 0.5
/* Two impacts, one of the model and one of the reference, match when their
 * onsets lie within this fraction of a crank revolution: 1e-3 (60 us at
 * 1000 rpm, ~18 automatic steps); the paper case's first onsets agree to
 * 0.01 us, and an impact missed or extra shifts the sequence by a whole
 * free flight (~1 ms) [-]. */
#define FB_IMPACT_MATCH_REV_FRACTION 1e-3
/* Matched impacts whose peak force or penetration differ from the
 * reference's by more than this are an error of the model (warning "error
 * bound"), the bound of the ideal models (run.h, FB_IDEAL_PEAK_ERROR_BOUND):
 * the paper case's matched impacts agree to ~1e-3 [-]. */
#define FB_MATCHED_IMPACT_ERROR_BOUND 0.05
/* A matched impact whose reference peak force is below this share of the
 * largest matched one is a grazing touch: its peak (newtons, nanometres of
 * penetration) moves by tens of percent with its onset's phase inside a
 * step while the trajectory and every real impact agree (measured: MuJoCo
 * on a slider-crank, a 4.2 N touch among impacts of 2.6 to 13 kN at
 * -13.6 %, every other within 0.6 %, its window peaks within 3e-6 of the
 * reference's). It is listed and counted, not held to the bound [-]. */
#define FB_MATCHED_GRAZING_SHARE 0.01
/* matched impacts listed per model (the rest counted) */
#define FB_DIVERGE_MAX_IMPACTS 64

/* One impact of a model matched with the reference's. */
typedef struct {
  double t;               /* onset of the model's impact [s] */
  double t_error;         /* its onset minus the reference's [s] */
  double force;           /* the model's peak force over the impact [N] */
  double force_rel;       /* (force - reference's) / reference's [-] */
  double penetration;     /* the model's peak penetration [m] */
  double penetration_rel; /* (penetration - reference's) / reference's [-] */
} fb_matched_impact;

/* Where a model's trajectory leaves its reference's, and its impacts before. */
typedef struct {
  int diverged;              /* 1: it leaves the reference within the common run */
  double t;                  /* time it leaves [s]; INFINITY when it does not */
  double crank_angle;        /* crank angle then [rad] in [0, 2 pi); NAN when it does not */
  double ecc_tol;            /* the eccentricity tolerance used [m] */
  double angle_tol;          /* the coupler-angle tolerance used [rad] */
  double t_end;              /* end of the common run compared [s] */
  int impacts_model;         /* impacts of the model beginning before t */
  int impacts_reference;     /* impacts of the reference beginning before t */
  int matched;               /* impacts paired by time (one to one, in order) before t */
  int one_to_one;            /* 1: every impact before t matched (matched = both counts) */
  double force_rel_max;      /* largest |force_rel| of the matched impacts that are not
                                grazing touches (FB_MATCHED_GRAZING_SHARE) [-] (0: none) */
  double penetration_rel_max; /* largest |penetration_rel| of the same [-] */
  fb_matched_impact impact[FB_DIVERGE_MAX_IMPACTS]; /* the first matched (matched, at most the cap) */
} fb_divergence;

/* Compares model series s with reference series r (same grid, from t = 0) at
 * clearance joint j: the first sample where the eccentricity vectors differ
 * by more than FB_DIVERGE_ECC_FRACTION x clearance [m] at any clearance joint
 * both series hold (j, and the others of a case with several) or the coupler angles
 * by more than FB_DIVERGE_ANGLE_FRACTION x clearance / coupler_length [m],
 * and the impacts (a contact episode, one unbroken run of positive force,
 * with a sample in the impact state; peaks over the episode) before it, paired by time: both onset lists in
 * order, two onsets within FB_IMPACT_MATCH_REV_FRACTION x period [s] match,
 * an onset with none is left unmatched (so an extra impact of a rattling
 * pin does not shift every later pair); a pair's peaks (and errors) are
 * both series' largest force and penetration over the span of the two
 * episodes together, so a contact one integration splits into two (its
 * force touching zero) and the other does not is compared whole.
 * Errors: FB_ERR_ARG without contact columns at j or on different grids. */
fb_status fb_metrics_divergence(fb_divergence *out, const fb_series *s, const fb_series *r, int j,
                                double clearance, double coupler_length, double period,
                                fb_diag *diag);

/* Where one extreme of a window happened. */
typedef struct {
  double t;           /* time of the extreme [s] */
  double crank_angle; /* crank angle then [rad] in [0, 2 pi) */
} fb_peak_at;

/* Where each of a body's four extremes happened. */
typedef struct {
  fb_peak_at omega_max, omega_min, alpha_max, alpha_min;
} fb_body_peak_at;

typedef struct {
  FB_MECH_OUTPUT_MEMBERS(fb_body_peak_at); /* per output body (mechanism.h) */
} fb_peaks_at;

/* Peaks of coupler and follower over the samples with t_from <= t < t_to
 * [s] (t_to = INFINITY: to the end), and, when at is not NULL, the time and
 * crank angle of each (the first sample reaching it).
 * Errors: FB_ERR_ARG when no sample lies in the window. */
fb_status fb_metrics_peaks_between(fb_peaks *out, fb_peaks_at *at, const fb_series *s,
                                   double t_from, double t_to, fb_diag *diag);

/* The first impact at clearance joint j of a series with contact columns:
 * the first sample whose eccentricity |e| exceeds the radial clearance c, or
 * that carries a contact force (a rigid contact's impulse, which may stop
 * the pin before any sample passes c), with the crossing time interpolated
 * linearly in the free flight before it (at most that sample's time) and
 * the approach speed d|e|/dt over the last free-flight interval (the two
 * samples before the crossing; exact for a free flight at constant relative
 * velocity, which gravity and the crank's centripetal acceleration bend by
 * ~1e-4 relative over a microsecond step in the paper's case). A pin that
 * starts on the wall and enters at once (crossing at the first step) has its
 * speed from that first step, contact force included: an estimate.
 *
 * The rebound of that first contact episode (the samples from the first
 * one on, until the pin is free again: no force, |e| <= c): its separation
 * speed over its approach speed, each the slope of d|e|/dt of a quadratic
 * through the three free-flight samples on its side, taken where that
 * quadratic crosses c next to the episode (the approach at the entry
 * crossing, at most the first contact sample's time; the separation at the
 * exit crossing, at most the first free sample's time). For a penalty
 * contact this is the coefficient of restitution the mechanism shows, the
 * law's cr bent by every other force over the contact's duration; for a
 * rigid contact (an impulse within one step) it is Newton's e_N up to the
 * free flight's curvature between the two speeds, taken up to two steps
 * apart: d^2|e|/dt^2 holds the pin's sliding speed squared over |e| ~ c,
 * ~7e3 m/s^2 after the paper case's first impact, so at h = 3.3e-6 s the
 * ratio can be off by 5 % either way, and 0.1 % at h = 2e-7 s. NAN (and
 * duration NAN) when the episode has fewer than three free samples on a
 * side or never ends in the series.
 *
 * With rigid set (a rigid model, model_table.h: an impulse within one step,
 * Moreau-Jean's velocity jump), the two speeds are taken at the two ends of
 * the impulse's step, the velocities Newton's law relates: the impulse
 * stamped on sample i acts over the step from it to sample i + 1 (the
 * Siconos engine's samples: sample i still holds the approach's position,
 * i + 1 the first after the jump), so the approach is the slope at t_i of
 * the quadratic through samples i - 2 .. i and the separation the slope at
 * t_{i+1} of the quadratic through i + 1 .. i + 3 (each exact for a
 * trapezoidal flight at constant acceleration, theta = 0.5). The ratio then
 * reads e_N: on the paper case's first impact 0.904 for e_N 0.9 (0.843 by
 * the crossings, which sit up to two steps apart on a curved free flight),
 * and 0.895 to 0.903 over its next 24 impacts; the duration is that step.
 * NAN when the impulse is followed by another within three samples (the
 * pin held on the wall). */
typedef struct {
  int found;          /* 0: the pin never touched the wall */
  double t;           /* crossing time [s] */
  double speed;       /* approach speed along the normal [m/s] */
  double crank_angle; /* crank angle at the crossing [rad] in [0, 2 pi) */
  double rebound;     /* separation speed / approach speed of the first episode [-], or NAN */
  double duration;    /* exit crossing minus entry crossing of that episode [s], or NAN */
} fb_first_impact;

void fb_metrics_first_impact(fb_first_impact *out, const fb_series *s, int j, double clearance,
                             int rigid);

/* The output keys of the first impact (fb_first_impact) as study metrics
 * (check.c: <model>.first_impact.<key>), X(field, key); summary.json
 * spells the same names (report_summary.c). */
#define FB_FIRST_IMPACT_KEYS(X)      \
  X(t, "time_s")                     \
  X(speed, "speed_m_s")              \
  X(rebound, "rebound_ratio")        \
  X(duration, "contact_duration_s")

/* Largest penetration over every clearance joint and sample [m] (0 without
 * contact columns). */
double fb_metrics_penetration_max(const fb_series *s);

/* Peaks of coupler and follower over the samples with t >= t_from [s].
 * Errors: FB_ERR_ARG when no sample lies in the window. */
fb_status fb_metrics_peaks(fb_peaks *out, const fb_series *s, double t_from, fb_diag *diag);

/* Error of series s against the analytic solution of linkage lk (branch,
 * theta2(t) = theta0 + omega2 t), over samples with t >= t_from; exact peaks
 * are those of fb_analytic_peaks, passed in as exact.
 * Errors: FB_ERR_ARG for an empty window; those of fb_linkage_solve. */
fb_status fb_metrics_error(fb_error *out, const fb_series *s, double t_from,
                           const fb_linkage *lk, fb_branch branch, double theta0, double omega2,
                           const fb_peaks *exact, fb_diag *diag);

/* Signed relative difference (x - ref) / |ref|; 0 when both are 0, and
 * (x - ref) when ref is 0 (absolute, no division by zero). */
double fb_metrics_rel(double x, double ref);

/* The largest |relative error| of the eight omega and alpha peak errors of
 * coupler and follower (NaN entries skipped; 0 when all are) [-]. */
double fb_metrics_peak_rel_worst(const fb_body_error *coupler, const fb_body_error *follower);

#endif
