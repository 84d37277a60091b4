/* What the report floor's files share and nothing outside the floor uses
 * (defined in report_common.c): the width of a printed line, a clearance
 * model's contact law and mapping as its run used them, and its load peaks,
 * which summary.json writes and the printed table shows. */
#ifndef FB_REPORT_INTERNAL_H
#define FB_REPORT_INTERNAL_H

#include "report_common.h"

/* Every printed line is at most this wide (a terminal of 120 columns shows
 * the table without wrapping; issue 30). Prose is wrapped to it; tables
 * size their model column to the longest model name of the run. */
#define FB_TABLE_COLUMNS 120

/* The law of a clearance model's joint j as its run used it (its own view of
 * the scene, fb_scene_select: an engine model's law with the injected error
 * of [clearance] engine_stiffness_scale and engine_damping_scale), copied
 * into buf; NULL if none. */
const fb_contact_law *fb_report_model_law(fb_contact_law *buf, const fb_run *r,
                                          const fb_model_result *m, int j);

/* How model m's contact reaches its engine: ODE's mapping of the law into
 * ERP/CFM (fb_mapping_name); MuJoCo's law is a generalised force through
 * the passive-force hook and its native model MuJoCo's own solref contact,
 * neither mapped; NULL where the engine keeps no provenance (reference). */
const char *fb_report_model_mapping(const fb_run *r, const fb_model_result *m);

/* Peaks of the load columns over t >= t_from: {"drive_torque_max_n_m"
 * [N m], "drive_torque_min_n_m", "drive_torque_abs_max_n_m",
 * "reaction_max_n": {joint: largest |force| [N]}}, or null when the model
 * reports no loads. */
json_t *fb_report_loads_json(const fb_series *s, double t_from);

/* The same peaks of any mechanism's loads: n samples at times t [s] of the
 * drive torque [N m] and, per joint j of njoints (named joint[j]), its
 * reaction force fx[j], fy[j] [N] (n each); the key of a joint is its name
 * with '-' as '_' (fb_report_joint_key). null when no sample has
 * t >= t_from. */
json_t *fb_report_loads_of(const double *t, size_t n, double t_from, const double *torque,
                           int njoints, const char *const joint[], const double *const fx[],
                           const double *const fy[]);

/* Bytes of a joint's key or column stem: a joint name (at most 43
 * characters, planar_spec.h) and its terminator. */
#define FB_REPORT_JOINT_KEY_SIZE 64

/* Joint name joint as a key or column stem: '-' as '_' ("ground-crank":
 * "ground_crank"), into buf (size bytes, truncated to fit). Returns buf. */
const char *fb_report_joint_key(char *buf, size_t size, const char *joint);

/* [run] series as summary.json's "series" names it: "csv", "hdf5" or
 * "none" (docs/series.md). */
const char *fb_report_series_format_name(fb_series_format f);

#endif
