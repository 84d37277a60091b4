/* The writers of what tells a chaotic impact sequence from a wrong model:
 * each model's status word (an error when its matched impacts miss the
 * bound while it stays with its reference), the impact statistics of
 * `[run] ensemble` (ensemble.h) and their comparison with the reference,
 * the step h_s = auto ran at and its h omega_c, and the marks on figures
 * that are not converged numbers. summary.json, the printed table and
 * report.md take them from here (report.c). */
#ifndef FB_REPORT_CHAOS_H
#define FB_REPORT_CHAOS_H

#include <jansson.h>
#include <stdio.h>

#include "run.h"

/* The model's status: "ok"; the stop reason (outcome_text.h, fb_stop_text);
 * "error: ..." when its matched-impact peaks miss
 * FB_MATCHED_IMPACT_ERROR_BOUND while its trajectory stays with the
 * reference's; or "divergent: ..." when they miss it before the trajectory
 * leaves the reference's (fb_model_result.matched_error). A model that
 * leaves its reference with its matched impacts within the bound stays
 * "ok" with the warning divergent. Returns buf. */
const char *fb_report_model_status(char *buf, size_t size, const fb_model_result *m);

/* A figure cell: x printed with fmt when the quantity is converged, else
 * "~" and 3 significant figures (the mark of a divergent or unconverged
 * quantity, docs/chaos.md). Returns buf. */
const char *fb_report_figure(char *buf, size_t size, const char *fmt, double x, int unconverged);

/* summary.json: the model's "impact_statistics" (null without), its
 * "peaks_converged" reason, and the run's "step" object. */
json_t *fb_report_ensemble_json(const fb_model_result *m, const fb_run *r);
json_t *fb_report_converged_json(const fb_model_result *m);
json_t *fb_report_step_json(const fb_run *r);

/* The printed lines: the step and its h omega_c, then the impact
 * statistics table (nothing without clearance models). */
void fb_report_print_chaos(FILE *f, const fb_run *r);

/* The verdict's reason (verdict.h): what it rests on and what settles it,
 * printed beside the verdict and written to summary.json as
 * verdict_reason. Returns buf ("" when there is nothing to add). */
const char *fb_report_verdict_why(char *buf, size_t size, const fb_model_result *m,
                                  const fb_run *r);

/* The verdict table's error cell and what it is against, for a clearance
 * model or a reference: on statistics, the largest |relative difference|
 * of the pooled impact statistics; else the
 * largest relative peak error (omega, alpha, force) against the reference
 * or the check integration. 0 when the model has neither. */
int fb_report_verdict_error(char *err, size_t err_size, char *against, size_t against_size,
                            const fb_model_result *m);

/* Adds to a reference's summary.json error_estimate what else its check
 * integration measured: "divergence" (where the reference leaves its check,
 * impacts matched before; null: not measured), "impact_statistics" (the
 * check's, over the window; null without impacts) and "vs_ensemble" (those
 * against the reference's ensemble members; null without an ensemble). */
void fb_report_check_json(json_t *estimate, const fb_model_result *m);

/* The printed line on an ensemble the run added by itself, or would have
 * (nothing when it neither did nor would). */
void fb_report_print_ensemble_auto(FILE *f, const fb_run *r);

/* summary.json's "ensemble": {"members", "source": "case"|"run"|"none",
 * "reason"} (docs/outputs.md). */
json_t *fb_report_ensemble_run_json(const fb_run *r);

/* Prose for the printed table: printf-formatted text wrapped at spaces to
 * 120 columns, continuation lines indented by two (report.c). */
void fb_report_say(FILE *f, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* report.md's section of the same. */
void fb_report_markdown_chaos(FILE *f, const fb_run *r);

#endif
