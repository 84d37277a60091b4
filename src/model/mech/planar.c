/* The planar description (planar.h): building it, finding by name, the
 * Gruebler-Kutzbach count and the assembly configuration. */
#include "planar.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "names.h"

fb_planar *fb_planar_new(int max_bodies, int max_joints) {
  if (max_bodies < 1 || max_joints < 1) return NULL;
  fb_planar *m = calloc(1, sizeof *m);
  if (!m) return NULL;
  m->body = calloc((size_t)max_bodies + 1, sizeof *m->body);
  m->joint = calloc((size_t)max_joints, sizeof *m->joint);
  if (!m->body || !m->joint) {
    fb_planar_free(m);
    return NULL;
  }
  m->cap_bodies = max_bodies + 1;
  m->cap_joints = max_joints;
  m->nbodies = 1;
  snprintf(m->body[FB_PLANAR_GROUND].name, FB_PLANAR_NAME_SIZE, "ground");
  m->drive = -1;
  m->torque_joint = -1;
  return m;
}

void fb_planar_free(fb_planar *m) {
  if (!m) return;
  free(m->body);
  free(m->joint);
  free(m->point);
  free(m->spring);
  free(m->load);
  free(m);
}

/* a name that is not empty, fits, and is new: no body or joint of m has
 * its column and key word (names.h, one rule for every kind of name), and
 * it is not a fixed word */
static int name_ok(const fb_planar *m, const char *name, const char *what, fb_diag *diag) {
  if (!name || !*name || strlen(name) >= FB_PLANAR_NAME_SIZE) {
    fb_diag_set(diag, FB_ERR_ARG, "a %s name is 1 to %d characters", what,
                FB_PLANAR_NAME_SIZE - 1);
    return 0;
  }
  const char *fixed_what = NULL;
  if (fb_name_fixed(name, &fixed_what)) {
    fb_diag_set(diag, FB_ERR_ARG, "%s '%s': its columns would repeat %s: give it another name",
                what, name, fixed_what);
    return 0;
  }
  for (int k = 0; k < m->nbodies + m->njoints + m->npoints; k++) {
    const int body = k < m->nbodies, joint = !body && k < m->nbodies + m->njoints;
    const char *other = body    ? m->body[k].name
                        : joint ? m->joint[k - m->nbodies].name
                                : m->point[k - m->nbodies - m->njoints].name;
    if (!fb_name_same_word(other, name)) continue;
    const char *kind = body ? "body" : joint ? "joint" : "point";
    if (strcmp(other, name) == 0 && strcmp(kind, what) == 0)
      fb_diag_set(diag, FB_ERR_ARG, "%s '%s' is named twice: give each %s a name of its own",
                  what, name, what);
    else
      fb_diag_set(diag, FB_ERR_ARG, "%s '%s' and %s '%s' both write one word: %s", what, name,
                  kind, other, FB_NAME_RULE);
    return 0;
  }
  return 1;
}

/* -1, for a refusal whose message fb_diag_set has written */
static int refused(fb_status st) {
  (void)st;
  return -1;
}

int fb_planar_add_body(fb_planar *m, const char *name, double mass, double inertia,
                       const double centre[2], double angle0, int derived, fb_diag *diag) {
  if (!name_ok(m, name, "body", diag)) return -1;
  if (m->nbodies == m->cap_bodies)
    return refused(fb_diag_set(diag, FB_ERR_ARG, "body '%s': the description holds %d moving "
                               "bodies", name, m->cap_bodies - 1));
  if (!(mass > 0.0 && isfinite(mass)) || !(inertia > 0.0 && isfinite(inertia)))
    return refused(fb_diag_set(diag, FB_ERR_RANGE, "body '%s': mass %g kg, moment of inertia "
                               "%g kg m^2: both must be positive and finite", name, mass,
                               inertia));
  if (!isfinite(centre[0]) || !isfinite(centre[1]) || !isfinite(angle0))
    return refused(fb_diag_set(diag, FB_ERR_RANGE, "body '%s': its centre and angle must be "
                               "finite", name));
  fb_planar_body *b = &m->body[m->nbodies];
  memset(b, 0, sizeof *b);
  snprintf(b->name, sizeof b->name, "%s", name);
  b->mass = mass;
  b->inertia = inertia;
  b->centre[0] = centre[0];
  b->centre[1] = centre[1];
  b->angle0 = angle0;
  b->derived = derived;
  return m->nbodies++;
}

/* v in the frame of body b in the assembly configuration (the ground's
 * frame is the world's) */
static void to_body(double out[2], const fb_planar *m, int b, const double v[2], int is_point) {
  const fb_planar_body *bb = &m->body[b];
  const double d[2] = {v[0] - (is_point ? bb->centre[0] : 0.0),
                       v[1] - (is_point ? bb->centre[1] : 0.0)};
  const double c = cos(bb->angle0), s = sin(bb->angle0);
  out[0] = c * d[0] + s * d[1];
  out[1] = -s * d[0] + c * d[1];
}

void fb_planar_at_assembly(double out[2], const fb_planar *m, int b, const double p[2]) {
  const fb_planar_body *bb = &m->body[b];
  const double c = cos(bb->angle0), s = sin(bb->angle0);
  const double o[2] = {b == FB_PLANAR_GROUND ? 0.0 : bb->centre[0],
                       b == FB_PLANAR_GROUND ? 0.0 : bb->centre[1]};
  out[0] = o[0] + c * p[0] - s * p[1];
  out[1] = o[1] + s * p[0] + c * p[1];
}

int fb_planar_add_joint(fb_planar *m, const char *name, fb_joint_kind kind, int b0, int b1,
                        const double at[2], double axis_angle, fb_diag *diag) {
  if (!name_ok(m, name, "joint", diag)) return -1;
  if (m->njoints == m->cap_joints)
    return refused(fb_diag_set(diag, FB_ERR_ARG, "joint '%s': the description holds %d joints",
                               name, m->cap_joints));
  if (b0 < 0 || b0 >= m->nbodies || b1 < 0 || b1 >= m->nbodies || b0 == b1)
    return refused(fb_diag_set(diag, FB_ERR_ARG, "joint '%s': bodies %d and %d: a joint "
                               "connects two different bodies of the description (0 .. %d)",
                               name, b0, b1, m->nbodies - 1));
  if (!isfinite(at[0]) || !isfinite(at[1]) || (kind == FB_KIND_PRISMATIC && !isfinite(axis_angle)))
    return refused(fb_diag_set(diag, FB_ERR_RANGE, "joint '%s': its position and axis must be "
                               "finite", name));
  fb_planar_joint *j = &m->joint[m->njoints];
  memset(j, 0, sizeof *j);
  snprintf(j->name, sizeof j->name, "%s", name);
  j->kind = kind;
  j->body[0] = b0;
  j->body[1] = b1;
  j->at[0] = at[0];
  j->at[1] = at[1];
  to_body(j->point[0], m, b0, at, 1);
  to_body(j->point[1], m, b1, at, 1);
  const double dir[2] = {cos(axis_angle), sin(axis_angle)};
  if (kind == FB_KIND_PRISMATIC) to_body(j->axis, m, b0, dir, 0);
  else j->axis[0] = 1.0;
  j->clearance_ok = kind == FB_KIND_REVOLUTE;
  return m->njoints++;
}

int fb_planar_add_point(fb_planar *m, const char *name, int b, const double at[2], fb_diag *diag) {
  if (!name_ok(m, name, "point", diag)) return -1;
  if (b <= FB_PLANAR_GROUND || b >= m->nbodies)
    return refused(fb_diag_set(diag, FB_ERR_ARG, "point '%s': body %d: a point is on a moving "
                               "body of the description (1 .. %d); the ground's do not move",
                               name, b, m->nbodies - 1));
  if (!isfinite(at[0]) || !isfinite(at[1]))
    return refused(fb_diag_set(diag, FB_ERR_RANGE, "point '%s': its position must be finite",
                               name));
  fb_planar_mark *grown = realloc(m->point, ((size_t)m->npoints + 1) * sizeof *grown);
  if (!grown) return refused(fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for point '%s'", name));
  m->point = grown;
  fb_planar_mark *p = &m->point[m->npoints];
  memset(p, 0, sizeof *p);
  snprintf(p->name, sizeof p->name, "%s", name);
  p->body = b;
  p->at[0] = at[0];
  p->at[1] = at[1];
  to_body(p->point, m, b, at, 1);
  return m->npoints++;
}

/* name fits a spring's or load's name (they write no column) */
static int short_name(const char *name, const char *what, fb_diag *diag) {
  if (name && *name && strlen(name) < FB_PLANAR_NAME_SIZE) return 1;
  fb_diag_set(diag, FB_ERR_ARG, "a %s name is 1 to %d characters", what, FB_PLANAR_NAME_SIZE - 1);
  return 0;
}

int fb_planar_add_spring(fb_planar *m, const char *name, int b0, int b1, const double at[2][2],
                         double stiffness, double free_length, double damping, fb_diag *diag) {
  if (!short_name(name, "spring", diag)) return -1;
  if (b0 < 0 || b0 >= m->nbodies || b1 < 0 || b1 >= m->nbodies || b0 == b1)
    return refused(fb_diag_set(diag, FB_ERR_ARG, "spring '%s': bodies %d and %d: a spring "
                               "joins two different bodies of the description (0 .. %d)",
                               name, b0, b1, m->nbodies - 1));
  const double nums[6] = {at[0][0], at[0][1], at[1][0], at[1][1], stiffness, damping};
  for (int k = 0; k < 6; k++)
    if (!isfinite(nums[k]) || (k >= 4 && nums[k] < 0.0) || !isfinite(free_length))
      return refused(fb_diag_set(diag, FB_ERR_RANGE, "spring '%s': its ends must be finite and "
                                 "its stiffness, free length and damping finite and not "
                                 "negative", name));
  const double l0 = hypot(at[1][0] - at[0][0], at[1][1] - at[0][1]);
  if (l0 < FB_PLANAR_SPRING_MIN_M)
    return refused(fb_diag_set(diag, FB_ERR_ARG, "spring '%s': its ends meet in the assembly "
                               "(%g m apart): it has no line to pull along", name, l0));
  fb_planar_spring *grown = realloc(m->spring, ((size_t)m->nsprings + 1) * sizeof *grown);
  if (!grown) return refused(fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for spring '%s'", name));
  m->spring = grown;
  fb_planar_spring *p = &m->spring[m->nsprings];
  memset(p, 0, sizeof *p);
  snprintf(p->name, sizeof p->name, "%s", name);
  p->body[0] = b0;
  p->body[1] = b1;
  to_body(p->point[0], m, b0, at[0], 1);
  to_body(p->point[1], m, b1, at[1], 1);
  p->stiffness = stiffness;
  p->free_length = free_length < 0.0 ? l0 : free_length;
  p->damping = damping;
  return m->nsprings++;
}

int fb_planar_add_load(fb_planar *m, const char *name, int b, const double at[2],
                       const double force[2], double torque, int active, int stroke,
                       fb_diag *diag) {
  if (!short_name(name, "load", diag)) return -1;
  if (b <= FB_PLANAR_GROUND || b >= m->nbodies)
    return refused(fb_diag_set(diag, FB_ERR_ARG, "load '%s': body %d: a load acts on a moving "
                               "body of the description (1 .. %d)", name, b, m->nbodies - 1));
  if (!isfinite(at[0]) || !isfinite(at[1]) || !isfinite(force[0]) || !isfinite(force[1]) ||
      !isfinite(torque))
    return refused(fb_diag_set(diag, FB_ERR_RANGE, "load '%s': its point, force and torque must "
                               "be finite", name));
  const int follows = active != FB_PLANAR_LOAD_ALWAYS;
  if (follows && (stroke < 0 || stroke >= m->njoints || m->joint[stroke].kind != FB_KIND_PRISMATIC))
    return refused(fb_diag_set(diag, FB_ERR_ARG, "load '%s': a load on one stroke follows a "
                               "prismatic joint's slide (joint %d is none)", name, stroke));
  fb_planar_load *grown = realloc(m->load, ((size_t)m->nloads + 1) * sizeof *grown);
  if (!grown) return refused(fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for load '%s'", name));
  m->load = grown;
  fb_planar_load *p = &m->load[m->nloads];
  memset(p, 0, sizeof *p);
  snprintf(p->name, sizeof p->name, "%s", name);
  p->body = b;
  to_body(p->point, m, b, at, 1);
  p->force[0] = force[0];
  p->force[1] = force[1];
  p->torque = torque;
  p->active = active;
  p->stroke = follows ? stroke : -1;
  return m->nloads++;
}

fb_status fb_planar_set_drive_torque(fb_planar *m, int j, double torque, fb_diag *diag) {
  if (j < 0 || j >= m->njoints || m->joint[j].kind != FB_KIND_REVOLUTE || m->drive >= 0)
    return fb_diag_set(diag, FB_ERR_ARG, "a torque drive turns a revolute joint of an "
                       "undriven description (joint %d)", j);
  if (!isfinite(torque))
    return fb_diag_set(diag, FB_ERR_RANGE, "drive torque %g N m: not finite", torque);
  m->torque_joint = j;
  m->drive_torque = torque;
  return FB_OK;
}

fb_status fb_planar_set_drive(fb_planar *m, int j, fb_diag *diag) {
  if (j < 0 || j >= m->njoints)
    return fb_diag_set(diag, FB_ERR_ARG, "drive: joint %d is not one of the %d joints", j,
                       m->njoints);
  if (m->joint[j].kind != FB_KIND_REVOLUTE)
    return fb_diag_set(diag, FB_ERR_ARG, "drive: joint '%s' is prismatic; the drive turns a "
                       "revolute joint at speed_rpm", m->joint[j].name);
  m->drive = j;
  return FB_OK;
}

void fb_planar_drive_bodies(const fb_planar *m, int *from, int *to) {
  const fb_planar_joint *j = &m->joint[m->drive];
  const int swap = j->body[1] == FB_PLANAR_GROUND;
  *from = j->body[swap ? 1 : 0];
  *to = j->body[swap ? 0 : 1];
}

int fb_planar_find_body(const fb_planar *m, const char *name) {
  for (int b = 0; b < m->nbodies; b++)
    if (strcmp(m->body[b].name, name) == 0) return b;
  return -1;
}

int fb_planar_find_joint(const fb_planar *m, const char *name) {
  for (int j = 0; j < m->njoints; j++)
    if (strcmp(m->joint[j].name, name) == 0) return j;
  return -1;
}

int fb_planar_nq(const fb_planar *m) { return 3 * (m->nbodies - 1); }

int fb_planar_gruebler(const fb_planar *m) { return 3 * (m->nbodies - 1) - 2 * m->njoints; }

void fb_planar_assembly(const fb_planar *m, double *q) {
  for (int b = 1; b < m->nbodies; b++) {
    q[3 * (b - 1)] = m->body[b].centre[0];
    q[3 * (b - 1) + 1] = m->body[b].centre[1];
    q[3 * (b - 1) + 2] = m->body[b].angle0;
  }
}

double fb_planar_size(const fb_planar *m) {
  double c[2] = {0.0, 0.0}, size = 1e-3;
  for (int j = 0; j < m->njoints; j++) {
    c[0] += m->joint[j].at[0] / m->njoints;
    c[1] += m->joint[j].at[1] / m->njoints;
  }
  for (int j = 0; j < m->njoints; j++)
    size = fmax(size, hypot(m->joint[j].at[0] - c[0], m->joint[j].at[1] - c[1]));
  return size;
}
