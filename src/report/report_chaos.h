/* The writers of what tells a chaotic impact sequence from a wrong model:
 * the impact statistics of `[run] ensemble` (ensemble.h) and their
 * comparison with the reference, the step h_s = auto ran at and its
 * h omega_c, and what each verdict rests on. Each model's status word (an
 * error when its matched impacts miss the bound while it stays with its
 * reference) and the mark on figures that are not converged numbers are
 * report_common.h's, included here. summary.json, the printed table and
 * report.md take them from here (report_summary.c, report_table.c,
 * report_markdown.c). */
#ifndef FB_REPORT_CHAOS_H
#define FB_REPORT_CHAOS_H

/* jansson's object type, declared here so that includers do not get jansson
 * (C11 allows the same typedef again where <jansson.h> is included too) */
typedef struct json_t json_t;
#include <stdio.h>

#include "report_common.h"
#include "run.h"

/* summary.json: the model's "impact_statistics" (null without), its
 * "peaks_converged" reason, and the run's "step" object. */
json_t *fb_report_ensemble_json(const fb_model_result *m, const fb_run *r);
json_t *fb_report_converged_json(const fb_model_result *m);
json_t *fb_report_step_json(const fb_run *r);

/* The step's single-impact verification (run.h, fb_step_check) in words:
 * the restitution law's worst restitution and penetration error in ODE's
 * matched row at the run's step against the faithful bounds, and that the
 * run accepts it when it is not faithful. NULL (buf "") when not checked. */
const char *fb_report_step_check_text(char *buf, size_t size, const fb_run *r);

/* The printed lines: the step and its h omega_c, then the impact
 * statistics table (nothing without clearance models). */
void fb_report_print_chaos(FILE *f, const fb_run *r);

/* The verdict's reason (verdict.h): what it rests on and what settles it,
 * printed beside the verdict and written to summary.json as
 * verdict_reason. Returns buf ("" when there is nothing to add). */
const char *fb_report_verdict_why(char *buf, size_t size, const fb_model_result *m,
                                  const fb_run *r);

/* The model's verdict word (verdict.h, fb_verdict_name), its reason in why
 * (fb_report_verdict_why): the printed table and summary.json's
 * "verdict" and "verdict_reason". */
const char *fb_report_verdict(char *why, size_t why_size, const fb_model_result *m,
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
void fb_report_check_json(json_t *estimate, const fb_model_result *m, const fb_run *r);

/* The printed line on an ensemble the run added by itself, or would have
 * (nothing when it neither did nor would). */
void fb_report_print_ensemble_auto(FILE *f, const fb_run *r);

/* summary.json's "ensemble": {"members", "source": "case"|"run"|"none",
 * "reason"} (docs/outputs.md). */
json_t *fb_report_ensemble_run_json(const fb_run *r);

/* report.md's section of the same. */
void fb_report_markdown_chaos(FILE *f, const fb_run *r);

#endif
