/* fourbar kinematics' output as JSON or text (tables_kinematics.h): what
 * every mechanism writes, by its description's names, around its kind's
 * entries (kinematics.h fb_kinematics_kind). */
#include "tables_kinematics.h"

#include <jansson.h>

#include "report.h"
#include "units.h"

void fb_report_kinematics_json(FILE *f, const fb_kinematics *k) {
  const double deg = 1.0 / FB_RAD_PER_DEG;
  const fb_mech_desc *m = fb_mech_of(k->mech);
  json_t *o = json_object();
  if (k->kind->json_names_mechanism) json_object_set_new(o, "mechanism", json_string(m->type));
  json_t *l = json_object();
  for (int i = 0; i < m->nlengths; i++) json_object_set_new(l, m->length[i], json_real(k->lk.length[i]));
  json_object_set_new(o, "lengths_m", l);
  json_object_set_new(o, "case_file", k->case_path[0] ? json_string(k->case_path) : json_null());
  json_object_set_new(o, "speed_rpm", json_real(k->rpm));
  json_object_set_new(o, "crank_omega_rad_s", json_real(k->omega2));
  json_object_set_new(o, "direction", json_string(k->dir > 0 ? "ccw" : "cw"));
  k->kind->json(o, k);
  /* each output body's peaks by its name: a slider's as positions, velocities, accelerations */
  int out[FB_MECH_MAX_OUTPUTS];
  const int n = fb_mech_outputs(m, out);
  for (int b = 0; b < n; b++)
    json_object_set_new(o, fb_mech_output_name(m, b),
                        fb_mech_output_translates(m, b) ? fb_report_slider_peaks_json(&k->p.body[b])
                                                        : fb_report_body_peaks_json(&k->p.body[b]));
  json_object_set_new(o, "transmission_angle_min_deg", json_real(k->mu_min * deg));
  json_object_set_new(o, "transmission_angle_max_deg", json_real(k->mu_max * deg));
  json_dumpf(o, f, JSON_INDENT(2) | JSON_REAL_PRECISION(12));
  fputc('\n', f);
  json_decref(o);
}

void fb_report_kinematics_text(FILE *f, const fb_kinematics *k) {
  if (k->case_path[0]) fprintf(f, "case: %s\n", k->case_path);
  k->kind->text(f, k);
}
