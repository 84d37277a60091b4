/* fourbar impact's output: the study (impact_study.h) as one JSON object or
 * as a text table with the relative errors against the reference. */
#ifndef FB_TABLES_IMPACT_H
#define FB_TABLES_IMPACT_H

#include <stdio.h>

#include "impact_study.h"

/* The JSON object of fourbar impact --json (docs/commands.md) on f. */
void fb_report_impact_json(FILE *f, const fb_impact_study *s);

/* 1 when every engine's impact of s ran (the --json exit status 0). */
int fb_report_impact_ok(const fb_impact_study *s);

/* The text of fourbar impact on f: the heading, one row per result, then
 * each engine's relative errors against the reference. Stops at the first
 * engine whose impact failed and returns its message (the command then
 * fails); NULL when all ran. */
const char *fb_report_impact_text(FILE *f, const fb_impact_study *s);

#endif
