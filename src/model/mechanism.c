/* The mechanism descriptions (mechanism.h): the four-bar's bodies, joints
 * and link lengths as data, and the names read from a description. */
#include "mechanism.h"

#include <stdio.h>
#include <string.h>

const fb_mech_desc fb_mech_fourbar = {
    .type = "four-bar",
    .nbodies = 4,
    .body = {{"crank", FB_MOTION_ROTATING, 0},
             {"coupler", FB_MOTION_PLANAR, 1},
             {"follower", FB_MOTION_ROTATING, 1},
             {"ground", FB_MOTION_FIXED, 0}},
    .input = 0,
    .njoints = 4,
    .joint = {{"ground-crank", FB_KIND_REVOLUTE, {3, 0}, 1},
              {"crank-coupler", FB_KIND_REVOLUTE, {0, 1}, 1},
              {"coupler-follower", FB_KIND_REVOLUTE, {1, 2}, 1},
              {"follower-ground", FB_KIND_REVOLUTE, {2, 3}, 1}},
    .reference_joint = 1,
    .nlengths = 4,
    .length = {"crank", "coupler", "follower", "ground"},
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
    .joint = {{"ground-crank", FB_KIND_REVOLUTE, {3, 0}, 0},
              {"crank-coupler", FB_KIND_REVOLUTE, {0, 1}, 0},
              {"coupler-slider", FB_KIND_REVOLUTE, {1, 2}, 1},
              {"slider-ground", FB_KIND_PRISMATIC, {2, 3}, 0}},
    .reference_joint = 2,
    .nlengths = 3,
    .length = {"crank", "coupler", "offset"},
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
