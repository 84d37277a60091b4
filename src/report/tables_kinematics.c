/* fourbar kinematics' output as JSON or text (tables_kinematics.h). */
#include "tables_kinematics.h"

#include <jansson.h>

#include "report.h"
#include "units.h"

static const char *branch_name(fb_branch b) { return b == FB_BRANCH_OPEN ? "open" : "crossed"; }

void fb_report_kinematics_json(FILE *f, const fb_kinematics *k) {
  const double deg = 1.0 / FB_RAD_PER_DEG;
  json_t *o = json_object();
  json_t *l = json_object();
  for (int i = 0; i < FB_LINK_COUNT; i++)
    json_object_set_new(l, fb_link_name(i), json_real(k->lk.length[i]));
  json_object_set_new(o, "lengths_m", l);
  json_object_set_new(o, "case_file", k->case_path[0] ? json_string(k->case_path) : json_null());
  json_object_set_new(o, "speed_rpm", json_real(k->rpm));
  json_object_set_new(o, "crank_omega_rad_s", json_real(k->omega2));
  json_object_set_new(o, "direction", json_string(k->dir > 0 ? "ccw" : "cw"));
  json_object_set_new(o, "branch", json_string(branch_name(k->branch)));
  json_object_set_new(o, "grashof", json_string(fb_grashof_name(k->g)));
  json_object_set_new(o, "grashof_s_plus_l_m", json_real(k->sl));
  json_object_set_new(o, "grashof_p_plus_q_m", json_real(k->pq));
  json_object_set_new(o, "coupler", fb_report_body_peaks_json(&k->p.coupler));
  json_object_set_new(o, "follower", fb_report_body_peaks_json(&k->p.follower));
  json_object_set_new(o, "transmission_angle_min_deg", json_real(k->mu_min * deg));
  json_object_set_new(o, "transmission_angle_max_deg", json_real(k->mu_max * deg));
  json_dumpf(o, f, JSON_INDENT(2) | JSON_REAL_PRECISION(12));
  fputc('\n', f);
  json_decref(o);
}

void fb_report_kinematics_text(FILE *f, const fb_kinematics *k) {
  const double deg = 1.0 / FB_RAD_PER_DEG;
  const fb_peaks *p = &k->p;
  if (k->case_path[0]) fprintf(f, "case: %s\n", k->case_path);
  fprintf(f, "linkage: crank %g, coupler %g, follower %g, ground %g mm (%s), %g rpm %s, %s "
          "branch\n", k->mm[0], k->mm[1], k->mm[2], k->mm[3], fb_grashof_name(k->g), k->rpm,
          k->dir > 0 ? "ccw" : "cw", branch_name(k->branch));
  fprintf(f, "%s\n", k->grashof);
  fprintf(f, "%-9s %12s %12s %14s %14s\n", "body", "omega_max", "omega_min", "alpha_max",
          "alpha_min");
  fprintf(f, "%-9s %12s %12s %14s %14s\n", "", "rad/s", "rad/s", "rad/s^2", "rad/s^2");
  fprintf(f, "%-9s %12.6f %12.6f %14.4f %14.4f\n", "coupler", p->coupler.omega_max,
          p->coupler.omega_min, p->coupler.alpha_max, p->coupler.alpha_min);
  fprintf(f, "%-9s %12.6f %12.6f %14.4f %14.4f\n", "follower", p->follower.omega_max,
          p->follower.omega_min, p->follower.alpha_max, p->follower.alpha_min);
  fprintf(f, "transmission angle: %.4f to %.4f deg\n", k->mu_min * deg, k->mu_max * deg);
}
