/* The words and JSON of the test a verdict on statistics rests on
 * (verdict_stats.h): the first impacts compared one to one, each member's
 * statistics, and each statistic's equivalence test against the
 * reference's members (docs/verdicts.md). summary.json, the printed table
 * and report.md take them from here; report_chaos.c says the verdict's
 * reason with fb_report_test_reason. */
#ifndef FB_REPORT_VERDICT_H
#define FB_REPORT_VERDICT_H

#include <stdio.h>

#include "report_common.h"
#include "run.h"

/* jansson's object type, declared here so that includers do not get jansson
 * (C11 allows the same typedef again where <jansson.h> is included too) */
typedef struct json_t json_t;

/* summary.json: an ensemble's "members": [{"member", "impacts", "revolutions",
 * "rate_per_rev", "force_mean_n", "force_p90_n", "omega_dev_rad_s",
 * "parts_s"}] (null where not finite; parts_s null for member 0 and for a
 * member that never parts from it). */
json_t *fb_report_members_json(const fb_ensemble *e);

/* summary.json's model "verdict_test" (null when the model was not tested):
 * {"first_impacts": {"compared", "unpaired", "worst_of_bound" (the largest
 * error over its bound, verdict_stats.h fb_first_check), "worst_impact",
 * "what", "bound", "ok"} or null, "statistics": [{"name", "key", "margin",
 * "members", "members_reference", "skipped", "skipped_reference", "mean",
 * "mean_reference", "sd", "sd_reference", "ratio", "interval": [lo, hi],
 * "df", "p_equivalent", "p_different", "decision", "outside"}], "decision":
 * "equivalent"|"different"|"undecided"|"undefined", "alpha", "look",
 * "looks", "at_cap", "wall_cut"}. */
json_t *fb_report_test_json(const fb_model_result *m);

/* How an ensemble's members spread (the perturbation must part them, docs/
 * verdicts.md "Members"): "16 members: 15 part from the run itself between
 * 6.8 and 73 ms (median 9.3 ms), the window from 75 ms", or that none does.
 * Returns buf. */
const char *fb_report_parting_text(char *buf, size_t size, const fb_ensemble *e, double t_window);

/* report.html's data of the verdicts on statistics (report-data.js
 * "verdicts", docs/report.md): per model judged on them {model, reference,
 * color (its colour in the run's figures, given by the caller), verdict,
 * title (the test's figures in words), model_forces and reference_forces
 * (each member's impact peak forces [N]), model_rates and reference_rates
 * (each member's impacts per revolution), rate {ratio, lo, hi, margin,
 * mean, mean_reference}, first [{force_rel, penetration_rel}] (the first
 * impacts, before it parts), first_bounds (their bounds, relative), rigid,
 * first_ok, first_worst (over its bound)}. color(r, name) gives a model's
 * colour. */
json_t *fb_report_verdicts_json(const fb_run *r, const char *(*color)(const fb_run *, const char *));

/* The title of a verdict on statistics: the model, its verdict and members,
 * each statistic's ratio, interval and margin, the worst p-value and the
 * decision (the verdict figure's and report.html's). */
void fb_report_test_title(char *buf, size_t size, const fb_model_result *m);

/* "equivalent", "different", "undecided", "undefined" */
const char *fb_report_equiv_word(fb_equiv_decision d);

/* The verdict's reason for a model judged on statistics or failing its first
 * impacts, appended to buf at its end (at most size bytes in all). */
void fb_report_test_reason(char *buf, size_t size, const fb_model_result *m);

/* The printed table of the tests (nothing when no model was tested): per
 * statistic the model's and the reference's members (mean, sd, n), the
 * ratio and its interval against the margin, the p-values and the
 * decision; bar non-NULL: a markdown table. */
void fb_report_print_tests(FILE *f, const fb_run *r, int markdown);

#endif
