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
 * {"omega_max", "omega_min", "alpha_max", "alpha_min"}}}, "slides":
 * {"<joint>": {"stroke_m", "dead_centre_outer": {"x_m", "drive_angle_rad"},
 * "dead_centre_inner", "quick_return_ratio", "quick_return_ratio_is",
 * "outstroke": {"drive_angle_rad", "time_s"}, "return", and the slider's
 * extreme keys position_max_m ... acceleration_min_m_s2}} (x_m the slide,
 * planar_outputs.h), "transmission": {"<joint>": {"link", "driven",
 * "transmission_angle_min_deg", "transmission_angle_max_deg",
 * "at_drive_angle_rad": {"min", "max"}}} (planar_transmission.h; {} when
 * undefined), "points": {"<point>": {"x", "y" (each with the slider's
 * extreme keys), "speed_max_m_s", "acceleration_max_m_s2"}} (summary.json's
 * keys over a revolution; {} when
 * undefined), "transmission_angle_is"} (d from fb_planar_tool_designer;
 * <joint> its name with '-' as '_'); text: one row per moving body, then
 * each slide's stroke, dead centres and quick-return ratio and the
 * transmission angles' table (or that it is undefined). */
void fb_report_planar_kinematics(FILE *f, const fb_case *c, const fb_planar *m,
                                 const fb_planar_peaks *p, const fb_planar_designer *d,
                                 int json);

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

/* fourbar penalty --out on a planar case: out/penalty_physical.csv and
 * out/penalty_physical.svg (tables_penalty.h fb_report_penalty_columns, a
 * row per speed and revolute joint by its name) from the rows of
 * fb_report_planar_penalty (n[s] joints at every speed s). Errors: those
 * of the CSV; FB_ERR_ARG when the speeds' joints differ; FB_ERR_NOMEM. A
 * figure that fails is no error: *figure_ok 0 and why in fig_diag. */
fb_status fb_report_planar_penalty_files(const char *out, const fb_planar *m,
                                         const fb_planar_penalty_row *rows, const int *n,
                                         const double *rpm, int nspeeds, int *figure_ok,
                                         fb_diag *fig_diag, fb_diag *diag);

/* stackup: {"case", "mechanism": "planar", "lengths": [{"body", "from",
 * "to", "nominal_m", "plus_minus_m", "source"}], "corners": N (0: not
 * run), "corners_unassembled" (corners that cannot assemble or turn,
 * counted and left out of the worst case), "corners_unassembled_first"
 * (the first of them and why, or null), "outputs": [{"name", "nominal", "sensitivity_per_m": [one per
 * length, in their order], "rss": {"low", "high"}, "corners": {"min",
 * "max"} or null, "montecarlo": {"q00135", "q50", "q99865", "mean", "std",
 * "q00135_ci_lo", ... "q99865_ci_hi"} or null}], "distribution",
 * "samples" (0: not run; those that assemble), "samples_unassembled"
 * (samples that cannot assemble or turn, left out of the statistics),
 * "samples_unassembled_first" (the first one's reason, or null), "seed",
 * "jobs", "montecarlo_wall_s",
 * "quantile_ci" (when run; tables_stackup.h)}; text: the lengths, then one
 * row per output (with mc 0.135%, mc 50%, mc 99.865% when run), then the
 * quantiles' intervals. */
void fb_report_planar_stackup(FILE *f, const fb_case *c, const fb_planar *m,
                              const fb_planar_stackup *s, int json);

#endif
