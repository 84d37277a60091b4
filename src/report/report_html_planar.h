/* report.html of a planar case's run ([linkage] type = planar,
 * docs/planar.md): the same page as a four-bar's (report_html.h), its data
 * by the description's names. Outputs: every moving body (its omega and
 * alpha panels, series keys <body>_omega and <body>_alpha, the headline
 * rows summary.json's models[].bodies.<NAME> peaks); a reference's
 * clearance joint's contact force and penetration panels. Each model's
 * samples are kept as a four-bar's (each plotted column's minimum and
 * maximum in each of FB_REPORT_BUCKETS buckets over the run). Not yet: the
 * pin's orbit and the impact list (a planar reference keeps no
 * eccentricity vector and counts no impacts), verdict panels. */
#ifndef FB_REPORT_HTML_PLANAR_H
#define FB_REPORT_HTML_PLANAR_H

#include "planar_run.h"
#include "report.h" /* json_t */

/* Writes report.html, report-data.js and the charting library (when
 * found: *charts 1) of planar run r into dir; summary is summary.json's
 * value. Errors: FB_ERR_IO naming the file; FB_ERR_NOMEM. */
fb_status fb_report_html_write_planar(const char *dir, const fb_planar_run *r,
                                      const json_t *summary, int *charts, fb_diag *diag);

#endif
