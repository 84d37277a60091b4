/* The cells every writer of the report floor formats the same way: prose
 * wrapped to the printed table's width, a figure cell marked when it is not
 * a converged number, a model's status word, one body's peaks as JSON, and
 * a JSON file written atomically. The bottom of the report floor: it calls
 * no other file of the floor; report_chaos.c, report_variants.c, the
 * summary (report_summary.h), the printed table (report_table.h) and the
 * markdown report (report_markdown.h) call it. */
#ifndef FB_REPORT_COMMON_H
#define FB_REPORT_COMMON_H

/* jansson's object type, declared here so that includers do not get jansson
 * (C11 allows the same typedef again where <jansson.h> is included too) */
typedef struct json_t json_t;
#include <stdio.h>

#include "run.h"

/* Prose for the printed table: printf-formatted text wrapped at spaces to
 * 120 columns, continuation lines indented by two. */
void fb_report_say(FILE *f, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* A figure cell: x printed with fmt when the quantity is converged, else
 * "~" and 3 significant figures (the mark of a divergent or unconverged
 * quantity, docs/chaos.md). Returns buf. */
const char *fb_report_figure(char *buf, size_t size, const char *fmt, double x, int unconverged);

/* The model's status: "ok"; the stop reason (outcome_text.h, fb_stop_text);
 * "error: ..." when its matched-impact peaks miss
 * FB_MATCHED_IMPACT_ERROR_BOUND while its trajectory stays with the
 * reference's; or "divergent: ..." when they miss it before the trajectory
 * leaves the reference's (fb_model_result.matched_error). A model that
 * leaves its reference with its matched impacts within the bound stays
 * "ok" with the warning divergent. Returns buf. */
const char *fb_report_model_status(char *buf, size_t size, const fb_model_result *m);

/* The injected error of the run ([clearance] engine_stiffness_scale and
 * engine_damping_scale, scene.h), in words for the run's header: which
 * factor multiplies every engine model's contact law, that the references
 * keep the case's, and which models of the run are rigid and have nothing
 * to scale. Returns NULL (buf "") when both are 1 and the damping scale was
 * not given. */
const char *fb_report_injected_text(char *buf, size_t size, const fb_run *r);
/* The same for case c alone (a planar run: no rigid model), or NULL. */
const char *fb_report_injected_case_text(char *buf, size_t size, const fb_case *c);

/* A body's name in three letters for narrow table columns: "cpl" (coupler),
 * "flw" (follower), "sld" (slider); the name's first three letters
 * otherwise. */
const char *fb_report_body_abbrev(const char *body);

/* JSON object {"omega_max_rad_s", "omega_min_rad_s", "alpha_max_rad_s2",
 * "alpha_min_rad_s2"} of one body's peaks (new reference). */
json_t *fb_report_body_peaks_json(const fb_body_peaks *p);

/* summary.json's models[].bodies: {"<name[b]>": fb_report_body_peaks_json
 * of p[b]} for the n moving bodies of any mechanism, by their names. */
json_t *fb_report_bodies_json(const char *const *name, const fb_body_peaks *p, int n);

/* JSON object {"position_max_m", "position_min_m", "velocity_max_m_s",
 * "velocity_min_m_s", "acceleration_max_m_s2", "acceleration_min_m_s2"} of a
 * translating body's peaks (a slider: docs/outputs.md, models[].slider;
 * fb_body_peaks' omega/alpha fields hold its v/a), non-finite values as null
 * (new reference). */
json_t *fb_report_slider_peaks_json(const fb_body_peaks *p);

/* summary.json's models[].adaptive_steps: with [solver] h_s = adaptive,
 * the engine's own steps (its "steps" counts the output grid's samples):
 * {steps_taken, h_min_s, h_min_count, h_max_s, h_max_count} of *s
 * (engine.h); null when s is NULL (a fixed step, or a model that does not
 * step an engine). */
json_t *fb_report_adaptive_steps_json(const fb_step_stats *s);

/* Writes a JSON value to path atomically (indented, keys in insertion order).
 * Errors: FB_ERR_IO naming the file. */
fb_status fb_report_write_json(const char *path, const json_t *j, fb_diag *diag);

#endif
