/* Sampled time series of one model on its time grid: the data every model
 * produces and every metric and writer consumes (column-major arrays). */
#ifndef FB_SERIES_H
#define FB_SERIES_H

#include <stddef.h>

#include "mechanism.h"
#include "status.h"

/* Columns of a series, in CSV order (names carry their SI unit), generated
 * from the series' mechanism description (mechanism.h): time_s, the input
 * body's <input>_angle_rad (crank_angle_rad), then per output body in body
 * order its position, velocity and acceleration (fb_mech_body_column: the
 * four-bar's coupler_angle_rad, coupler_omega_rad_s, coupler_alpha_rad_s2,
 * follower_angle_rad, follower_omega_rad_s, follower_alpha_rad_s2), then the
 * contact columns of each enabled clearance joint and the load columns. */
enum { FB_Q_POS = 0, FB_Q_VEL = 1, FB_Q_ACC = 2 }; /* second index of body[][] */

/* Contact columns of each clearance joint, after the joint's name:
 * <joint>_force_n (contact force magnitude on the pin during the last step),
 * <joint>_penetration_m (max(0, eccentricity - radial clearance)),
 * <joint>_ecc_x_m, <joint>_ecc_y_m (eccentricity vector pin centre - hole
 * centre), <joint>_state (0 free flight, 1 impact, 2 continuous contact). */
#define FB_CONTACT_COLS 5
enum { FB_C_FORCE = 0, FB_C_PEN = 1, FB_C_EX = 2, FB_C_EY = 3, FB_C_STATE = 4 };
enum { FB_STATE_FREE = 0, FB_STATE_IMPACT = 1, FB_STATE_CONTINUOUS = 2 };

/* Load columns (models whose engine reports joint reactions): the drive
 * torque on the crank about +z, drive_torque_n_m, then per joint of the
 * description (the four-bar's ground-crank, crank-coupler, coupler-follower,
 * follower-ground) the force on the second-named body from the first,
 * <joint>_reaction_x_n, <joint>_reaction_y_n and its magnitude
 * <joint>_reaction_n (invdyn.h's convention): 1 + 3 x njoints columns. At a
 * clearance joint the reaction is the contact force. */

/* The per-output-body values as an array indexed [output][FB_Q_*] and,
 * over the same storage, the four-bar's names for them (coupler, follower:
 * fb_mech_fourbar's output bodies in order). The names are the four-bar's
 * alone: code that serves any mechanism indexes the array. */
#define FB_SERIES_BODY_UNION(T)                                                        \
  union {                                                                              \
    T body[FB_MECH_MAX_OUTPUTS][3]; /* per output body: position, velocity, acceleration */ \
    __extension__ struct {                                                             \
      T coupler_angle;                                                                 \
      T coupler_omega;                                                                 \
      T coupler_alpha;                                                                 \
      T follower_angle;                                                                \
      T follower_omega;                                                                \
      T follower_alpha;                                                                \
    };                                                                                 \
  }

typedef struct {
  size_t n;                  /* samples held */
  size_t cap;                /* samples allocated */
  const fb_mech_desc *mech;  /* the mechanism whose columns these are (fb_series_init: the four-bar) */
  double *t;                 /* time [s] (n) */
  double *crank_angle;       /* the input body's angle [rad] (n) */
  FB_SERIES_BODY_UNION(double *); /* (n) each, NULL for a body the mechanism lacks */
  int contact_mask;                        /* bit j: joint j's contact columns are held */
  double impact_floor[FB_MECH_MAX_JOINTS]; /* contact force a sample must exceed to belong to an
                                              impact at joint j [N] (the scene's, episode.h
                                              FB_IMPACT_FLOOR_SHARE); 0 (fb_series_init): any
                                              positive force */
  double *contact[FB_MECH_MAX_JOINTS][FB_CONTACT_COLS]; /* (n) each, NULL unless enabled */
  int has_loads;                           /* 1: the load columns are held */
  double *drive_torque;                    /* drive torque on the crank [N m] (n), NULL unless has_loads */
  double *reaction[FB_MECH_MAX_JOINTS][2]; /* joint force x, y [N] (njoints x 2 x n), NULL unless has_loads */
  double *arena;                           /* the columns' storage (series.c), cap per column */
  size_t arena_bytes;                      /* its size [bytes] */
} fb_series;

/* One sample: the values of every column at one instant (SI units). */
typedef struct {
  double t;                      /* [s] */
  double crank_angle;            /* the input body's angle [rad] */
  FB_SERIES_BODY_UNION(double);  /* per output body, SI */
  double contact[FB_MECH_MAX_JOINTS][FB_CONTACT_COLS]; /* per joint; read only where enabled */
  double drive_torque;                /* [N m]; read only when loads are enabled */
  double reaction[FB_MECH_MAX_JOINTS][2]; /* joint force x, y [N]; read only when loads are enabled */
} fb_sample;

/* Adds contact columns for the joints in mask (call right after init).
 * Errors: FB_ERR_NOMEM. */
fb_status fb_series_enable_contact(fb_series *s, int mask);

/* Adds the load columns (drive torque, joint reactions; call right after
 * init). Errors: FB_ERR_NOMEM. */
fb_status fb_series_enable_loads(fb_series *s);

/* Allocates room for cap samples of the four-bar's columns (fb_mech_fourbar).
 * Errors: FB_ERR_NOMEM. */
fb_status fb_series_init(fb_series *s, size_t cap);

/* As fb_series_init, for the columns of mechanism mech (its output bodies).
 * Errors: FB_ERR_NOMEM. */
fb_status fb_series_init_mech(fb_series *s, size_t cap, const fb_mech_desc *mech);

/* Maps the storage of every enabled column from sample n to cap now (one
 * write of zero per page), so that filling it takes no page faults: a run
 * calls it before its timed steps. The first write to a fresh page costs a
 * fault whose price depends on the machine, not on the model (on the 2-core
 * VM these figures come from: 0.39 GB/s with 4 KiB pages, 0.55 to 1.1 GB/s
 * with huge pages the first time the host backs them, 8 to 12 GB/s after).
 * Samples held are not changed. */
void fb_series_touch(fb_series *s);

/* Number of output bodies of the series' mechanism (the body[] rows held). */
int fb_series_output_count(const fb_series *s);

/* Appends one sample, growing the arrays when full. Errors: FB_ERR_NOMEM. */
fb_status fb_series_push(fb_series *s, const fb_sample *x);

/* Reads sample i (i < n) into *x. */
void fb_series_get(const fb_series *s, size_t i, fb_sample *x);

/* 1 when sample k (0 < k < n - 1) of column v is a spike: a local extreme
 * of sign `sign` (+1 maximum, -1 minimum) whose magnitude is at least
 * fraction times big (> 0, the column's largest magnitude). */
int fb_series_is_spike(const double *v, size_t k, int sign, double fraction, double big);

/* Largest |v[i]| over n values. */
double fb_series_largest_abs(const double *v, size_t n);

/* The scale a sample's spike is measured against (fb_series_is_spike's
 * big) in two parts of a run split at t_split [s]: big[0] the largest |v|
 * over the samples before it, big[1] from it on (the peak window: its
 * spikes are refined even where the start-up's are larger); t_split <= 0:
 * both the whole run's. *split receives the first sample index at or after
 * t_split (n: none). */
void fb_series_largest_abs_split(double big[2], size_t *split, const fb_series *s,
                                 const double *v, double t_split);

/* fb_series_largest_abs_split over n values v at times t [s] (n), for a
 * column held outside a series (the planar reference's). */
void fb_largest_abs_split(double big[2], size_t *split, const double *t, size_t n,
                          const double *v, double t_split);

/* Peak refinement of a series whose samples lie on a smooth motion (an
 * engine's steps): every spike (fb_series_is_spike with fraction) of the
 * output bodies' accelerations and of the contact force and penetration is
 * replaced by the vertex of the parabola through it and its two
 * neighbours, when both neighbours have its sign (a one-sample pulse is
 * left alone). The vertex of a peak sampled at h is exact to O(h^4) where
 * the sample alone misses up to |y''| h^2 / 8. A spike is one against the
 * largest of its own part of the run, before or from t_split [s] (the peak
 * window's start; fb_series_largest_abs_split). */
void fb_series_refine_peaks(fb_series *s, double fraction, double t_split);

/* fb_series_refine_peaks, but every clearance joint's contact force from
 * the engine's own largest force between samples: force_max (njoints x
 * stride, stride >= the samples s->n; joint j's sample i at
 * force_max[j stride + i]) [N], the largest force the engine
 * applied at joint j over its sub-steps of the step from sample i; a
 * maximum spike at sample k takes the largest of the sample,
 * force_max[j stride + k - 1] and force_max[j stride + k] (the force's extreme
 * between its neighbours, as the reference replaces its spikes:
 * peak_refine.h), not the parabola's vertex, which overshoots a pulse
 * lopsided within the three samples. force_max NULL:
 * fb_series_refine_peaks. */
void fb_series_refine_peaks_max(fb_series *s, double fraction, double t_split,
                                const double *force_max, size_t stride);

/* The refined value of a spike of sign `sign` (+1 maximum, -1 minimum) at
 * the middle of three samples y (its neighbours' original values): with
 * ymax (NULL: none; the engine's largest value over the steps from the
 * first and from the middle sample, 2) and sign +1, the largest of y[1],
 * ymax[0] and ymax[1]; else the vertex of the parabola through the three
 * when both neighbours have its sign and it curves that way, else y[1].
 * The one rule fb_series_refine_peaks_max and a planar verdict's matched
 * peaks (planar_verdict.c) refine by; units those of y. */
double fb_series_refined(const double y[3], const double *ymax, int sign);

/* The slope at time at [s] of the quadratic through (t[k], y[k]), k = 0..2
 * (t strictly increasing) [units of y per s]: a rigid contact's approach
 * and rebound rates (metrics.c, planar_verdict.c). */
double fb_series_quad_slope(const double t[3], const double y[3], double at);

/* The refinement of one column v (n) at times t [s] as
 * fb_series_refine_peaks_max does it (vmax NULL: the parabola's vertex at
 * every spike), for a column held outside a series (a planar run's). */
void fb_refine_column(const double *t, size_t n, double *v, const double *vmax, double fraction,
                      double t_split);

/* For an engine that reports at t_{n+1} what its step from t_n applied
 * (ODE: the angular acceleration (omega_{n+1} - omega_n) / h, which is the
 * solver's forces at the configuration of t_n, and the contact force and
 * state of that step): moves the output bodies' accelerations and every contact
 * force and state column one sample earlier, so each sample holds the
 * acceleration and force at its own configuration, as the reference's
 * instantaneous values do. The last sample keeps the value before it. */
void fb_series_attribute_to_step_start(fb_series *s);

/* Frees the arrays; s is left empty and may be re-initialised. */
void fb_series_free(fb_series *s);

/* Number of columns (kinematic, then contact columns of enabled joints) and
 * the CSV name of column k into buf (returned). */
size_t fb_series_column_count(const fb_series *s);
const char *fb_series_column_name(const fb_series *s, size_t k, char *buf, size_t size);
/* Value of column k at sample i. */
double fb_series_value(const fb_series *s, size_t k, size_t i);
/* The array (n) holding column k, or NULL for a column computed from others
 * (a reaction magnitude; read it with fb_series_value). */
const double *fb_series_column(const fb_series *s, size_t k);

#endif
