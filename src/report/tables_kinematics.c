/* fourbar kinematics' output as JSON or text (tables_kinematics.h). */
#include "tables_kinematics.h"

#include <jansson.h>

#include "report.h"
#include "units.h"

static const char *branch_name(fb_branch b) { return b == FB_BRANCH_OPEN ? "open" : "crossed"; }

/* {"x_m", "crank_angle_rad"} of a dead centre */
static json_t *dead_centre_json(double x, double theta) {
  return json_pack("{s:f,s:f}", "x_m", x, "crank_angle_rad", theta);
}

/* {"crank_angle_rad", "time_s"} of a stroke */
static json_t *stroke_json(double angle, double time) {
  return json_pack("{s:f,s:f}", "crank_angle_rad", angle, "time_s", time);
}

static void slider_crank_json(FILE *f, const fb_kinematics *k) {
  const double deg = 1.0 / FB_RAD_PER_DEG;
  const fb_mech_desc *m = fb_mech_of(k->mech);
  json_t *o = json_object();
  json_object_set_new(o, "mechanism", json_string(m->type));
  json_t *l = json_object();
  for (int i = 0; i < m->nlengths; i++) json_object_set_new(l, m->length[i], json_real(k->lk.length[i]));
  json_object_set_new(o, "lengths_m", l);
  json_object_set_new(o, "case_file", k->case_path[0] ? json_string(k->case_path) : json_null());
  json_object_set_new(o, "speed_rpm", json_real(k->rpm));
  json_object_set_new(o, "crank_omega_rad_s", json_real(k->omega2));
  json_object_set_new(o, "direction", json_string(k->dir > 0 ? "ccw" : "cw"));
  json_object_set_new(o, "class", json_string(fb_sc_class_name(k->sc_class)));
  json_object_set_new(o, "class_margin_m", json_real(k->sc_margin));
  json_object_set_new(o, "class_rule", json_string("full-turn: coupler > crank + |offset|; "
                                                   "class_margin_m = coupler - (crank + |offset|)"));
  json_object_set_new(o, "stroke_m", json_real(k->lim.stroke));
  json_object_set_new(o, "dead_centre_outer", dead_centre_json(k->lim.x_max, k->lim.theta_outer));
  json_object_set_new(o, "dead_centre_inner", dead_centre_json(k->lim.x_min, k->lim.theta_inner));
  json_object_set_new(o, "quick_return_ratio", json_real(k->quick_return));
  json_object_set_new(o, "quick_return_ratio_is",
                      json_string("the slower stroke's time over the faster's at constant crank "
                                  "speed (>= 1)"));
  json_object_set_new(o, "outstroke", stroke_json(k->outstroke_angle, k->outstroke_time));
  json_object_set_new(o, "return", stroke_json(k->return_angle, k->return_time));
  json_object_set_new(o, "coupler", fb_report_body_peaks_json(&k->p.body[0]));
  json_object_set_new(o, "slider", fb_report_slider_peaks_json(&k->p.body[1]));
  json_object_set_new(o, "transmission_angle_min_deg", json_real(k->mu_min * deg));
  json_object_set_new(o, "transmission_angle_max_deg", json_real(k->mu_max * deg));
  json_dumpf(o, f, JSON_INDENT(2) | JSON_REAL_PRECISION(12));
  fputc('\n', f);
  json_decref(o);
}

void fb_report_kinematics_json(FILE *f, const fb_kinematics *k) {
  if (k->mech == FB_MECH_SLIDER_CRANK) {
    slider_crank_json(f, k);
    return;
  }
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

static void slider_crank_text(FILE *f, const fb_kinematics *k) {
  const double deg = 1.0 / FB_RAD_PER_DEG;
  const fb_mech_desc *m = fb_mech_of(k->mech);
  const fb_slider_crank_limits *lim = &k->lim;
  if (k->case_path[0]) fprintf(f, "case: %s\n", k->case_path);
  fprintf(f, "slider-crank: crank %g, coupler %g, offset %g mm (%s), %g rpm %s\n", k->mm[0],
          k->mm[1], k->mm[FB_LENGTH_OFFSET], fb_sc_class_name(k->sc_class), k->rpm,
          k->dir > 0 ? "ccw" : "cw");
  fprintf(f, "%s\n", k->grashof);
  fprintf(f, "stroke %.6f mm between the dead centres:\n", lim->stroke * 1e3);
  fprintf(f, "  outer x = %.6f mm at crank angle %.4f deg\n", lim->x_max * 1e3,
          lim->theta_outer * deg);
  fprintf(f, "  inner x = %.6f mm at crank angle %.4f deg\n", lim->x_min * 1e3,
          lim->theta_inner * deg);
  fprintf(f, "quick-return ratio %.6f (slower stroke's time over the faster's): outstroke "
          "(inner to outer) %.4f deg of crank, %.6g s; return %.4f deg, %.6g s\n",
          k->quick_return, k->outstroke_angle * deg, k->outstroke_time, k->return_angle * deg,
          k->return_time);
  fprintf(f, "%-9s %-6s %14s %14s  %s\n", "body", "", "max", "min", "unit");
  for (int b = 0; b < 2; b++)
    for (int q = 1; q <= 2; q++) {
      const fb_body_peaks *p = &k->p.body[b];
      fprintf(f, "%-9s %-6s %14.6f %14.6f  %s\n", fb_mech_output_name(m, b),
              fb_mech_output_symbol(m, b, q), q == 1 ? p->omega_max : p->alpha_max,
              q == 1 ? p->omega_min : p->alpha_min, fb_mech_output_unit(m, b, q));
    }
  fprintf(f, "transmission angle: %.4f to %.4f deg (smallest with the crank perpendicular to the "
          "guide, on the side away from it)\n", k->mu_min * deg, k->mu_max * deg);
}

void fb_report_kinematics_text(FILE *f, const fb_kinematics *k) {
  if (k->mech == FB_MECH_SLIDER_CRANK) {
    slider_crank_text(f, k);
    return;
  }
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
