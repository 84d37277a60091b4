/* The tables of fourbar kinematics, penalty and stackup on a planar case
 * (studies/planar_tools.h), by body and joint name, as text or one JSON
 * object (docs/planar.md gives the keys). */
#ifndef FB_TABLES_PLANAR_H
#define FB_TABLES_PLANAR_H

#include <stdio.h>

#include "planar_resolution.h"
#include "planar_tools.h"

/* kinematics: {"case", "mechanism": "planar", "drive", "speed_rpm",
 * "bodies": {"<body>": {"omega_max_rad_s", "omega_min_rad_s",
 * "alpha_max_rad_s2", "alpha_min_rad_s2", "at_drive_angle_rad":
 * {"omega_max", "omega_min", "alpha_max", "alpha_min"}}}}; text: one row
 * per moving body. */
void fb_report_planar_kinematics(FILE *f, const fb_case *c, const fb_planar *m,
                                 const fb_planar_peaks *p, int json);

/* penalty (physical mode), rows[s * m->njoints ..] of n[s] joints for the
 * speeds rpm[s], s < nspeeds: {"case", "mode": "physical", "rows":
 * [{"speed_rpm", "joint", "force_n", "stiffness_n_m", "penalty_n_m0_5",
 * "penalty_n_mm0_5", "approach_m"}], "contact": [one per clearance pin and
 * law, est (nest): the law's keys (report_summary.h), "model",
 * "effective_mass_estimate_kg": {"min", "max"}, "force_expected_n",
 * "reaction_n", "omega_c_rad_s", "h_resolving_s"]}; text: the same as a
 * table and a block. */
void fb_report_planar_penalty(FILE *f, const fb_case *c, const fb_planar *m,
                              const fb_planar_penalty_row *rows, const int *n, const double *rpm,
                              int nspeeds, const fb_planar_contact_estimate *est, int nest,
                              int json);

/* stackup: {"case", "mechanism": "planar", "lengths": [{"body", "from",
 * "to", "nominal_m", "plus_minus_m", "source"}], "corners": N (0: not
 * run), "outputs": [{"name", "nominal", "sensitivity_per_m": [one per
 * length, in their order], "rss": {"low", "high"}, "corners": {"min",
 * "max"} or null, "montecarlo": {"q00135", "q50", "q99865", "mean", "std",
 * "q00135_ci_lo", ... "q99865_ci_hi"} or null}], "distribution",
 * "samples" (0: not run), "seed", "jobs", "montecarlo_wall_s",
 * "quantile_ci" (when run; tables_stackup.h)}; text: the lengths, then one
 * row per output (with mc 0.135%, mc 50%, mc 99.865% when run), then the
 * quantiles' intervals. */
void fb_report_planar_stackup(FILE *f, const fb_case *c, const fb_planar *m,
                              const fb_planar_stackup *s, int json);

#endif
