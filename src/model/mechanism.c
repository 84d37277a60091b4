/* The mechanism descriptions (mechanism.h): the four-bar's bodies, joints
 * and link lengths as data, and the names read from a description. */
#include "mechanism.h"

#include <stdio.h>
#include <string.h>

/* the case keys each mechanism alone owns ({section, key} pairs) */
static const char *const fourbar_keys[] = {
    "linkage", "follower_mm", "linkage", "ground_mm", "linkage", "branch",
    "tolerance", "follower_plus_minus_mm", "tolerance", "ground_plus_minus_mm",
    "mass", "follower_kg", "mass", "follower_inertia_kg_mm2",
    "mass", "follower_inertia_long_kg_mm2", "mass", "follower_inertia_transverse_kg_mm2",
    "mass", "follower_com_fraction", "mass", "follower_width_mm",
    "mass", "follower_thickness_mm", NULL};
static const char *const slider_crank_keys[] = {
    "linkage", "offset_mm", "tolerance", "offset_plus_minus_mm", "mass", "slider_kg", NULL};

const fb_mech_desc fb_mech_fourbar = {
    .type = "four-bar",
    .nbodies = 4,
    .body = {{"crank", FB_MOTION_ROTATING, 0},
             {"coupler", FB_MOTION_PLANAR, 1},
             {"follower", FB_MOTION_ROTATING, 1},
             {"ground", FB_MOTION_FIXED, 0}},
    .input = 0,
    .njoints = 4,
    .joint = {{"ground-crank", FB_KIND_REVOLUTE, {3, 0}, 1, 0},
              {"crank-coupler", FB_KIND_REVOLUTE, {0, 1}, 1, 0},
              {"coupler-follower", FB_KIND_REVOLUTE, {1, 2}, 1, 0},
              {"follower-ground", FB_KIND_REVOLUTE, {2, 3}, 1, 1}},
    .reference_joint = 1,
    .nlengths = 4,
    .length = {"crank", "coupler", "follower", "ground"},
    .every_model_builds = 1,
    .sdf_export = 1,
    .peers_build = 1,
    .title_names_type = 0,
    .assembly_note = NULL,
    .position_length = NULL,
    .position_zero_note = NULL,
    .keys = fourbar_keys,
    .foreign_key_hint = NULL,
    .contact_models = {"ode-clearance-impact", "ode-clearance-restitution"},
};

const fb_mech_desc fb_mech_slider_crank = {
    .type = "slider-crank",
    .nbodies = 4,
    .body = {{"crank", FB_MOTION_ROTATING, 0},
             {"coupler", FB_MOTION_PLANAR, 1},
             {"slider", FB_MOTION_TRANSLATING, 1},
             {"ground", FB_MOTION_FIXED, 0}},
    .input = 0,
    .njoints = 4,
    .joint = {{"ground-crank", FB_KIND_REVOLUTE, {3, 0}, 0, 0},
              {"crank-coupler", FB_KIND_REVOLUTE, {0, 1}, 0, 0},
              {"coupler-slider", FB_KIND_REVOLUTE, {1, 2}, 1, 0},
              {"slider-ground", FB_KIND_PRISMATIC, {2, 3}, 0, 0}},
    .reference_joint = 2,
    .nlengths = 3,
    .length = {"crank", "coupler", "offset"},
    .every_model_builds = 0,
    .sdf_export = 0,
    .peers_build = 0,
    .title_names_type = 1,
    .assembly_note = "the slider at +x of the crank pivot",
    .position_length = "offset",
    .position_zero_note =
        "(at offset 0 the slider-crank is symmetric about its guide: the smallest "
        "transmission angle, and a peak two mirrored crank angles tie for (the slider's "
        "acceleration maximum when crank / coupler > 1/4), have a corner in the offset, "
        "which moves them the same way for either sign; their offset column is one side's "
        "derivative, the corners and Monte Carlo give the range)",
    .keys = slider_crank_keys,
    .foreign_key_hint = " (a slider-crank has crank_mm, coupler_mm, offset_mm and [mass] slider_kg)",
    /* the models that build it with each law */
    .contact_models = {"reference", "reference-restitution"},
};

static const fb_mech_desc *const all[FB_MECH_COUNT] = {&fb_mech_fourbar, &fb_mech_slider_crank};

const fb_mech_desc *fb_mech_of(fb_mech_type t) {
  return (t >= 0 && t < FB_MECH_COUNT) ? all[t] : &fb_mech_fourbar;
}

int fb_mech_find(const char *type) {
  for (int t = 0; t < FB_MECH_COUNT; t++)
    if (strcmp(all[t]->type, type) == 0) return t;
  return -1;
}

int fb_mech_outputs(const fb_mech_desc *m, int out[FB_MECH_MAX_OUTPUTS]) {
  int n = 0;
  for (int b = 0; b < m->nbodies && n < FB_MECH_MAX_OUTPUTS; b++)
    if (m->body[b].output) out[n++] = b;
  return n;
}

int fb_mech_position_length(const fb_mech_desc *m) {
  for (int k = 0; m->position_length && k < m->nlengths; k++)
    if (strcmp(m->length[k], m->position_length) == 0) return k;
  return -1;
}

int fb_mech_driven_joint(const fb_mech_desc *m) {
  for (int j = 0; j < m->njoints; j++) {
    const int *b = m->joint[j].body;
    if ((b[0] == m->input || b[1] == m->input) &&
        (m->body[b[0]].motion == FB_MOTION_FIXED || m->body[b[1]].motion == FB_MOTION_FIXED))
      return j;
  }
  return -1;
}

const char *fb_mech_joint_name(const fb_mech_desc *m, int j) {
  return (j >= 0 && j < m->njoints) ? m->joint[j].name : "?";
}

const char *fb_mech_body_column(const fb_mech_desc *m, int b, int q, char *buf, size_t size) {
  static const char *const turn[3] = {"angle_rad", "omega_rad_s", "alpha_rad_s2"};
  static const char *const slide[3] = {"x_m", "v_m_s", "a_m_s2"};
  const char *const *part = m->body[b].motion == FB_MOTION_TRANSLATING ? slide : turn;
  snprintf(buf, size, "%s_%s", m->body[b].name, part[q]);
  return buf;
}

static int output_body(const fb_mech_desc *m, int k) {
  int out[FB_MECH_MAX_OUTPUTS];
  const int n = fb_mech_outputs(m, out);
  return k >= 0 && k < n ? out[k] : -1;
}

int fb_mech_output_translates(const fb_mech_desc *m, int k) {
  const int b = output_body(m, k);
  return b >= 0 && m->body[b].motion == FB_MOTION_TRANSLATING;
}

const char *fb_mech_output_name(const fb_mech_desc *m, int k) {
  const int b = output_body(m, k);
  return b >= 0 ? m->body[b].name : "?";
}

const char *fb_mech_output_symbol(const fb_mech_desc *m, int k, int q) {
  static const char *const turn[3] = {"angle", "omega", "alpha"}, *const slide[3] = {"x", "v", "a"};
  return q < 0 || q > 2 ? "?" : fb_mech_output_translates(m, k) ? slide[q] : turn[q];
}

const char *fb_mech_output_unit(const fb_mech_desc *m, int k, int q) {
  static const char *const turn[3] = {"rad", "rad/s", "rad/s^2"}, *const slide[3] = {"m", "m/s", "m/s^2"};
  return q < 0 || q > 2 ? "?" : fb_mech_output_translates(m, k) ? slide[q] : turn[q];
}

/* replaces every `from` in buf (holding at most size bytes) by `to` */
static void replace_all(char *buf, size_t size, const char *from, const char *to) {
  char out[256];
  size_t n = 0;
  const size_t lf = strlen(from), lt = strlen(to);
  for (const char *p = buf; *p && n + 1 < sizeof out;) {
    if (strncmp(p, from, lf) == 0 && n + lt < sizeof out) {
      memcpy(out + n, to, lt);
      n += lt;
      p += lf;
    } else {
      out[n++] = *p++;
    }
  }
  out[n] = '\0';
  snprintf(buf, size, "%s", out);
}

const char *fb_mech_output_key(char *buf, size_t size, const fb_mech_desc *m, const char *key) {
  snprintf(buf, size, "%s", key);
  if (m == &fb_mech_fourbar) return buf;
  static const char *const fourbar_name[2] = {"coupler", "follower"};
  for (int k = 0; k < 2; k++) {
    if (!strstr(buf, fourbar_name[k])) continue;
    if (fb_mech_output_translates(m, k)) {
      replace_all(buf, size, "omega", "velocity");
      replace_all(buf, size, "alpha", "acceleration");
      replace_all(buf, size, "rad_s2", "m_s2");
      replace_all(buf, size, "rad_s", "m_s");
    }
    replace_all(buf, size, fourbar_name[k], fb_mech_output_name(m, k));
  }
  return buf;
}
