/* The writers of a planar case's run (run/planar_run.h), by body name:
 * summary.json, timing.json, one CSV per model, report.md and the printed
 * table (docs/planar.md, docs/outputs.md). */
#ifndef FB_REPORT_PLANAR_H
#define FB_REPORT_PLANAR_H

#include <stdio.h>

#include "planar_run.h"
#include "report_common.h"

/* summary.json of a planar run: {"case", "case_file", "mechanism":
 * "planar", "description": {"bodies": [{"name", "mass_kg",
 * "inertia_kg_m2", "centre_m", "derived": [...]}], "joints": [{"name",
 * "kind", "bodies", "at_m"}], "drive"}, "drive_omega_rad_s",
 * "revolutions", "models": [{"name", "kind" ("analytic", "reference",
 * "engine"), "status", "h_s", "steps",
 * "bodies": {"<body>": {"omega_max_rad_s", "omega_min_rad_s",
 * "alpha_max_rad_s2", "alpha_min_rad_s2"}}, and the analytic model's
 * "loads": {"drive_torque_max_n_m", "drive_torque_min_n_m",
 * "drive_torque_abs_max_n_m" [N m], "reaction_max_n": {"<joint>": [N]}}
 * (the four-bar's keys, report_internal.h: the samples' extremes over
 * t >= the window's start, <joint> the joint's name with '-' as '_', in
 * the description's order), and with output points or prismatic joints
 * "points" and "slides" (report_planar_outputs.h)}]} (every moving body, in
 * the description's order). No wall time: two runs give the same bytes. */
json_t *fb_report_planar_summary_json(const fb_planar_run *r, const char *case_path);

/* Writes DIR/summary.json, DIR/timing.json ({"case", "models": [{"name",
 * "steps", "wall_s", "time_per_step_us"}]}), DIR/<model>.csv (time_s,
 * drive_angle_rad, then per moving body <body>_angle_rad,
 * <body>_omega_rad_s, <body>_alpha_rad_s2; a clearance model's
 * <joint>_force_n, <joint>_penetration_m; the analytic model's loads
 * (planar_run.h, planar_invdyn.h): drive_torque_n_m, the drive's torque on
 * the driven body about +z [N m], then per joint in the description's
 * order, <joint> its name with '-' as '_', <joint>_reaction_x_n,
 * <joint>_reaction_y_n, <joint>_reaction_n, the force on the joint's
 * second body from its first and its magnitude [N], and for a prismatic
 * joint <joint>_reaction_moment_n_m, its couple about +z on the second body
 * from the first, about the joint's point on the second body (on the first
 * when the second is the ground) [N m]; a joint's force is on its second body even when
 * that is the ground (the four-bar's follower_ground columns, invdyn.h's D,
 * are the other way: on the follower from the ground); then the output
 * points' and slides' columns (report_planar_outputs.h); every [run] series_every-th
 * sample; with [run] series = hdf5 the same columns and samples as
 * DIR/series.h5, one group per model (series_write.h); none with [run]
 * series = none) and DIR/report.md (the table below, the command, and the
 * nfig figures named in figures, each as an image; none: "No figures were
 * drawn."). Errors: FB_ERR_IO naming the file; FB_ERR_ARG for series =
 * hdf5 in a build without HDF5; FB_ERR_NOMEM. */
fb_status fb_report_planar_write(const char *dir, const fb_planar_run *r, const char *case_path,
                                 const char *command, char figures[][128], int nfig,
                                 fb_diag *diag);

/* The printed table: per model, one row per moving body with its omega
 * and alpha extremes [rad/s, rad/s^2]; its points' and slides' extremes
 * (report_planar_outputs.h); the analytic model's load peaks
 * (summary.json's loads): the drive torque's extremes [N m] and one row per
 * joint with its largest reaction [N]. */
void fb_report_planar_table(FILE *f, const fb_planar_run *r);

#endif
