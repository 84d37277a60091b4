/* The summary table printed to the terminal (and embedded in report.md):
 * text, every line at most 120 columns wide. */
#ifndef FB_REPORT_TABLE_H
#define FB_REPORT_TABLE_H

#include <stdio.h>

#include "contact.h"
#include "run.h"

/* Prints the summary table in the spirit of the paper's: per model, peaks of
 * coupler and follower angular velocity and acceleration, error against the
 * analytic solution of the same lengths, step size, steps, wall time. */
void fb_report_print_table(FILE *f, const fb_run *r);

/* Prints one clearance joint's contact law (the keys of
 * fb_report_contact_law_json, report_summary.h) as text, one line per joint
 * and law (joint: the joint's name), with %.6g digits. */
void fb_report_print_contact_law(FILE *f, const char *joint, const fb_contact_law *law,
                                 fb_mapping mapping);

#endif
