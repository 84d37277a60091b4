/* fourbar stackup's output: a stack-up (tolerance.h, fb_stackup_result) as
 * one JSON object (keys: docs/commands.md, stackup) or as text tables:
 * the methods' ranges, the exact sensitivities with their units, the Monte
 * Carlo quantiles with their confidence intervals. */
#ifndef FB_TABLES_STACKUP_H
#define FB_TABLES_STACKUP_H

#include <stdio.h>

#include "case.h"
#include "tolerance.h"

/* The JSON object on f: r of case c by the methods of mask (FB_TOL_*),
 * with the Monte Carlo seed and jobs as asked. */
void fb_report_stackup_json(FILE *f, const fb_stackup_result *r, const fb_case *c, int mask,
                            unsigned long seed, int jobs);

/* The text tables on f (r, c, mask as above). */
void fb_report_stackup_text(FILE *f, const fb_stackup_result *r, const fb_case *c, int mask);

/* The Monte Carlo parts both stack-ups write (the four-bar's above, a
 * planar case's, tables_planar.h); JSON objects the caller owns (jansson's
 * json_t, not included here):
 * {"level", "method", "ranks": {"q00135": [lo, hi], "q50", "q99865"}}
 * from the ranks (0: null) and confidence level of the intervals; */
struct json_t *fb_report_mc_ci_json(const size_t q_rank[3][2], double level);
/* one output's {"q00135", "q50", "q99865", "mean", "std", "q00135_ci_lo",
 * "q00135_ci_hi", ... "q99865_ci_hi"} (a bound null when open). */
struct json_t *fb_report_mc_output_json(const double q[3], const double q_ci[3][2], double mean,
                                        double std);
/* A quantile bound as text into buf: "%.6g", or "-" when open (returns 1). */
int fb_report_mc_bound(char *buf, size_t size, double x);
/* "Monte Carlo: N samples (normal, 3 sigma at the limit), J jobs, T s (U us
 * per sample)" after a blank line. */
void fb_report_mc_footer(FILE *f, size_t samples, int uniform, int jobs, double wall_s);

#endif
