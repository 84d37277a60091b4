/* fourbar penalty's output (penalty_study.h): the table of Kc, P and the
 * approach per speed and joint, the contact block of a case with clearance
 * joints, one JSON object, and the files penalty_<mode>.csv and its
 * figure. */
#ifndef FB_TABLES_PENALTY_H
#define FB_TABLES_PENALTY_H

#include <stdio.h>

#include "penalty_study.h"

/* The text table on f: the heading (c: the case), the rows computed, and,
 * when every speed's rows were, the line saying which force the table's
 * is. */
void fb_report_penalty_table(FILE *f, const fb_penalty_study *s, const fb_case *c);

/* Writes out/penalty_<mode>.csv (mode "paper" or "physical"; columns
 * speed_rpm, joint, force_n, stiffness_n_m, penalty_n_mm0_5,
 * penalty_n_m0_5, approach_um: a row per speed and joint) and the figure
 * out/penalty_<mode>.svg (fb_figures_penalty, its axis named speed) from
 * columns of n speeds rpm [rpm] per joint j < njoints named joint[j]:
 * force[j] [N], stiffness[j] [N/m], penalty_n_m0_5[j] [N m^0.5],
 * approach_m[j] [m]. The folder is prepared already. Errors: those of the
 * CSV. A figure that fails is no error: *figure_ok 0 and why in
 * fig_diag. */
fb_status fb_report_penalty_columns(const char *out, const char *mode, const char *speed, int n,
                                    const double *rpm, int njoints, const char *const *joint,
                                    const double *const *force, const double *const *stiffness,
                                    const double *const *penalty_n_m0_5,
                                    const double *const *approach_m, int *figure_ok,
                                    fb_diag *fig_diag, fb_diag *diag);

/* Writes out/penalty_<mode>.csv and the figure out/penalty_<mode>.svg (the
 * folder prepared already) of study s (fb_report_penalty_columns). Errors: those of the CSV. A figure that fails
 * is no error: *figure_ok 0 and why in fig_diag. */
fb_status fb_report_penalty_files(const char *out, const fb_penalty_study *s, int *figure_ok,
                                  fb_diag *fig_diag, fb_diag *diag);

/* The contact block as text on f (nothing for a case without clearance
 * joints). */
void fb_report_penalty_contact_text(FILE *f, const fb_penalty_study *s);

/* The JSON object of fourbar penalty --json on f: mode, case, rows, and
 * the contact keys for a case with clearance joints. */
void fb_report_penalty_json(FILE *f, const fb_penalty_study *s, const fb_case *c);

#endif
