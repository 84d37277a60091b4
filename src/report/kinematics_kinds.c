/* The kinds of fourbar kinematics (kinematics_kinds.h): the four-bar's and
 * the slider-crank's text and JSON entries and the table by type. */
#include "kinematics_kinds.h"

#include <jansson.h>

#include "units.h"

static const char *branch_name(fb_branch b) { return b == FB_BRANCH_OPEN ? "open" : "crossed"; }

/* the four-bar: branch, Grashof class and sums */
static void fourbar_json(json_t *o, const fb_kinematics *k) {
  json_object_set_new(o, "branch", json_string(branch_name(k->branch)));
  json_object_set_new(o, "grashof", json_string(fb_grashof_name(k->g)));
  json_object_set_new(o, "grashof_s_plus_l_m", json_real(k->sl));
  json_object_set_new(o, "grashof_p_plus_q_m", json_real(k->pq));
}

static void fourbar_text(FILE *f, const fb_kinematics *k) {
  const double deg = 1.0 / FB_RAD_PER_DEG;
  const fb_mech_desc *m = fb_mech_of(k->mech);
  fprintf(f, "linkage: crank %g, coupler %g, follower %g, ground %g mm (%s), %g rpm %s, %s "
          "branch\n", k->mm[0], k->mm[1], k->mm[2], k->mm[3], fb_grashof_name(k->g), k->rpm,
          k->dir > 0 ? "ccw" : "cw", branch_name(k->branch));
  fprintf(f, "%s\n", k->grashof);
  fprintf(f, "%-9s %12s %12s %14s %14s\n", "body", "omega_max", "omega_min", "alpha_max",
          "alpha_min");
  fprintf(f, "%-9s %12s %12s %14s %14s\n", "", "rad/s", "rad/s", "rad/s^2", "rad/s^2");
  int out[FB_MECH_MAX_OUTPUTS];
  const int n = fb_mech_outputs(m, out);
  for (int b = 0; b < n; b++) {
    const fb_body_peaks *p = &k->p.body[b];
    fprintf(f, "%-9s %12.6f %12.6f %14.4f %14.4f\n", fb_mech_output_name(m, b), p->omega_max,
            p->omega_min, p->alpha_max, p->alpha_min);
  }
  fprintf(f, "transmission angle: %.4f to %.4f deg\n", k->mu_min * deg, k->mu_max * deg);
}

/* {"x_m", "crank_angle_rad"} of a dead centre */
static json_t *dead_centre_json(double x, double theta) {
  return json_pack("{s:f,s:f}", "x_m", x, "crank_angle_rad", theta);
}

/* {"crank_angle_rad", "time_s"} of a stroke */
static json_t *stroke_json(double angle, double time) {
  return json_pack("{s:f,s:f}", "crank_angle_rad", angle, "time_s", time);
}

/* the slider-crank: class, stroke, dead centres, quick return, strokes */
static void slider_crank_json(json_t *o, const fb_kinematics *k) {
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
}

static void slider_crank_text(FILE *f, const fb_kinematics *k) {
  const double deg = 1.0 / FB_RAD_PER_DEG;
  const fb_mech_desc *m = fb_mech_of(k->mech);
  const fb_slider_crank_limits *lim = &k->lim;
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
  int out[FB_MECH_MAX_OUTPUTS];
  const int n = fb_mech_outputs(m, out);
  for (int b = 0; b < n; b++)
    for (int q = 1; q <= 2; q++) {
      const fb_body_peaks *p = &k->p.body[b];
      fprintf(f, "%-9s %-6s %14.6f %14.6f  %s\n", fb_mech_output_name(m, b),
              fb_mech_output_symbol(m, b, q), q == 1 ? p->omega_max : p->alpha_max,
              q == 1 ? p->omega_min : p->alpha_min, fb_mech_output_unit(m, b, q));
    }
  fprintf(f, "transmission angle: %.4f to %.4f deg (smallest with the crank perpendicular to the "
          "guide, on the side away from it)\n", k->mu_min * deg, k->mu_max * deg);
}

/* one row per mechanism type */
static const fb_kinematics_kind kinds[FB_MECH_COUNT] = {
    [FB_MECH_FOURBAR] = {.branch = 1, .offset_length = -1, .json_names_mechanism = 0,
                         .run = fb_kinematics_fourbar_run, .text = fourbar_text,
                         .json = fourbar_json},
    [FB_MECH_SLIDER_CRANK] = {.branch = 0, .offset_length = FB_LENGTH_OFFSET,
                              .json_names_mechanism = 1, .run = fb_kinematics_slider_crank_run,
                              .text = slider_crank_text, .json = slider_crank_json},
};

const fb_kinematics_kind *fb_report_kinematics_kind(fb_mech_type t) {
  return &kinds[(t >= 0 && t < FB_MECH_COUNT) ? t : FB_MECH_FOURBAR];
}
