/* fourbar mapping's output: the ERP/CFM grid (mapping_grid.h) as one JSON
 * object or a text table of ERP with marks, and as files: mapping.csv and
 * the ERP map figure. */
#ifndef FB_TABLES_MAPPING_H
#define FB_TABLES_MAPPING_H

#include <stddef.h>
#include <stdio.h>

#include "figures.h"
#include "mapping_grid.h"

/* The JSON object of fourbar mapping --json on f. */
void fb_report_mapping_json(FILE *f, const fb_mapping_grid *g);

/* The text table on f: ERP per stiffness (rows) and step (columns), marked
 * '<' below 0.1, '>' above 0.99, '*' where h omega > 1. */
void fb_report_mapping_text(FILE *f, const fb_mapping_grid *g);

/* Prepares folder out and writes out/mapping.csv (stiffness_n_m, h_s, erp,
 * cfm_m_n_s, h_omega) and the figure out/mapping.<fmt>. Errors: those of
 * the folder and the CSV. A figure that fails is no error: figure (size
 * bytes) gets its path, or "" with why in fig_diag. */
fb_status fb_report_mapping_files(const char *out, fb_figure_format fmt, const fb_mapping_grid *g,
                                  char *figure, size_t size, fb_diag *fig_diag, fb_diag *diag);

#endif
