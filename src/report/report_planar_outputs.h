/* A planar run's output points and slides (run/planar_run.h's out,
 * physics/planar/planar_outputs.h) in its CSV, summary.json and printed
 * table, by the names of the case: a point's or a joint's name with '-' as
 * '_' (names.h) before each quantity's suffix. */
#ifndef FB_REPORT_PLANAR_OUTPUTS_H
#define FB_REPORT_PLANAR_OUTPUTS_H

#include <jansson.h>
#include <stddef.h>
#include <stdio.h>

#include "planar_run.h"

/* The CSV column name of output c (0 .. fb_planar_output_count - 1) of
 * description m into buf (size bytes, truncated like snprintf): point P's
 * P_x_m, P_y_m, P_v_x_m_s, P_v_y_m_s, P_a_x_m_s2, P_a_y_m_s2, then
 * prismatic joint J's J_slide_m, J_slide_v_m_s, J_slide_a_m_s2. Returns
 * buf. */
const char *fb_report_planar_output_column(char *buf, size_t size, const fb_planar *m, int c);

/* Sets e's "points" ({"<point>": {"x": {...}, "y": {...}, "speed_max_m_s",
 * "acceleration_max_m_s2"}}, x and y with the slider's extreme keys,
 * report_common.h fb_report_slider_peaks_json: position_max_m ...
 * acceleration_min_m_s2) and "slides" ({"<joint>": the slider's keys})
 * from model p's samples at t >= r->t_window (null where none is
 * finite); nothing when the description has neither. */
void fb_report_planar_outputs_json(json_t *e, const fb_planar_run *r, const fb_planar_model *p);

/* The printed table's lines of model p's points and slides: their
 * extremes (above) in two markdown tables; nothing when it has none. */
void fb_report_planar_outputs_table(FILE *f, const fb_planar_run *r, const fb_planar_model *p);

#endif
