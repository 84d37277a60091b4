/* Writers: per-model CSV, summary.json (jansson) and the printed summary
 * table. Keys and column names carry their SI unit; NaN and infinity are
 * never written (JSON null stands for "not measured"). */
#ifndef FB_REPORT_H
#define FB_REPORT_H

/* jansson's object type, declared here so that includers do not get jansson
 * (C11 allows the same typedef again where <jansson.h> is included too) */
typedef struct json_t json_t;
#include <stdio.h>

#include "contact.h"
#include "run.h"

/* JSON object {"omega_max_rad_s", "omega_min_rad_s", "alpha_max_rad_s2",
 * "alpha_min_rad_s2"} of one body's peaks (new reference). */
json_t *fb_report_body_peaks_json(const fb_body_peaks *p);

/* The summary of a run as documented in docs/outputs.md (new reference):
 * {"case", "models": [{"name", "kind", "status", "h_s", "steps",
 *  "coupler", "follower", "error_vs_analytic", ...}], ...}. It holds no
 * wall time, so two runs of the same case give byte-identical summaries. */
json_t *fb_report_summary_json(const fb_run *r, const char *case_path);

/* The wall times of a run (new reference): {"case", "models": [{"name",
 * "steps", "wall_s", "time_per_step_us"}]}, in the order of the summary. */
json_t *fb_report_timing_json(const fb_run *r);

/* Writes DIR/<model>.csv for every model, DIR/summary.json and
 * DIR/timing.json, each atomically. Errors: FB_ERR_IO naming the file. */
fb_status fb_report_write_run(const char *dir, const fb_run *r, const char *case_path,
                              fb_diag *diag);

/* Writes a JSON value to path atomically (indented, keys in insertion order). */
fb_status fb_report_write_json(const char *path, const json_t *j, fb_diag *diag);

/* Writes DIR/report.md atomically: the command line, the summary table (as
 * printed), the stack-up and contact parameters used, and each figure in
 * figures (n names, may be 0) embedded. Errors: FB_ERR_IO. */
fb_status fb_report_write_markdown(const char *dir, const fb_run *r, const char *case_path,
                                   const char *command, char figures[][128], int n,
                                   const char *figure_note, fb_diag *diag);

/* The law-and-mapping part of one clearance joint's `contact` object (the
 * keys fourbar run's summary.json and fourbar penalty --json share):
 * {"joint", "law", "mapping", "stiffness" (N/m^n), "exponent", then for the
 * impact law "damping_n_s_m" (c_max) and "damping_depth_m" (d_max), for the
 * restitution law "restitution" and "damping_ratio" (zeta: the damper is
 * 2 zeta sqrt(p m_eff) at each step's effective mass), for other laws
 * "damping_n_s_m" (linear) or "restitution"}. */
json_t *fb_report_contact_law_json(int joint, const fb_contact_law *law, fb_mapping mapping);

/* Prints the same as text, one line per joint and law, with %.6g digits. */
void fb_report_print_contact_law(FILE *f, int joint, const fb_contact_law *law,
                                 fb_mapping mapping);

/* Prints the summary table in the spirit of the paper's: per model, peaks of
 * coupler and follower angular velocity and acceleration, error against the
 * analytic solution of the same lengths, step size, steps, wall time. */
void fb_report_print_table(FILE *f, const fb_run *r);

#endif
