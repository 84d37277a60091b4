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

#endif
