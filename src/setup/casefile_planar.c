/* A planar case's sections in the case-file reader (casefile_planar.h):
 * [joint.NAME], [body.NAME], [point.NAME], [spring.NAME], [load.NAME], [drive] joint
 * and [clearance] joints read
 * into fb_case.planar (model/mech/planar_spec.h), units converted to SI
 * here, then checked as a whole, compiled and checked by the planar core. */
#include "casefile_planar.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "casefile.h"
#include "casefile_planar_free.h"
#include "casefile_planar_loads.h"
#include "casefile_planar_values.h"
#include "model_table.h"
#include "names.h"
#include "planar_case.h"
#include "planar_check.h"
#include "planar_dims.h"
#include "planar_resolution.h"
#include "units.h"

#define JOINT_PREFIX "joint."
#define BODY_PREFIX "body."
#define POINT_PREFIX "point."
#define SPRING_PREFIX "spring."
#define LOAD_PREFIX "load."
#define AXIS_RULE "an angle from -360 to 360 deg, counter-clockwise from +x"
#define HALF_RULE "a slider's half-size must be positive, from 0.001 mm to 1e5 mm"

static int prefixed(const char *s, const char *prefix) {
  return strncmp(s, prefix, strlen(prefix)) == 0;
}

int fb_casefile_planar_type(const entry *e) {
  return strcmp(e->section, "linkage") == 0 && strcmp(e->key, "type") == 0 &&
         strcmp(e->value, "planar") == 0;
}

/* a four-bar key a planar case does not take */
static int fourbar_key(const entry *e) {
  if (strcmp(e->section, "linkage") == 0) return strcmp(e->key, "type") != 0;
  if (strcmp(e->section, "mass") == 0) return 1;
  const size_t n = strlen(e->key), s = strlen("_plus_minus_mm");
  return strcmp(e->section, "tolerance") == 0 && n > s &&
         strcmp(e->key + n - s, "_plus_minus_mm") == 0;
}

/* a section only a planar description has */
static int description_section(const entry *e) {
  return prefixed(e->section, JOINT_PREFIX) || prefixed(e->section, BODY_PREFIX) ||
         prefixed(e->section, POINT_PREFIX) || fb_casefile_planar_loads_section(e);
}

/* a [drive] key of a planar case's own: the joint, a torque drive's */
static int torque_drive_key(const char *key) {
  return strcmp(key, "joint") == 0 || strcmp(key, "torque_n_m") == 0 ||
         strcmp(key, "speed0_rpm") == 0;
}

/* [tolerance] stackup, which a planar case reads as one sign per dimension */
static int stackup_key(const entry *e) {
  return strcmp(e->section, "tolerance") == 0 && strcmp(e->key, "stackup") == 0;
}

int fb_casefile_planar_claims(const fb_case *c, const entry *e) {
  if (description_section(e)) return 1;
  if (strcmp(e->section, "drive") == 0 && torque_drive_key(e->key)) return 1;
  if (!c->planar.on) return 0;
  if (strcmp(e->section, "clearance") == 0 && strcmp(e->key, "joints") == 0) return 1;
  if (stackup_key(e)) return 1;
  return fb_casefile_planar_type(e) || fourbar_key(e);
}

/* ---- values -------------------------------------------------------------- */





/* the body named name in s (created at its first mention), or -1 when full */
static int body_index(fb_planar_spec *s, const char *name) {
  if (s->nbodies == 0) { /* the ground first */
    memset(&s->body[0], 0, sizeof s->body[0]);
    snprintf(s->body[0].name, sizeof s->body[0].name, "ground");
    s->nbodies = 1;
  }
  for (int b = 0; b < s->nbodies; b++)
    if (strcmp(s->body[b].name, name) == 0) return b;
  if (s->nbodies == FB_PLANAR_SPEC_MAX_BODIES + 1) return -1;
  fb_planar_spec_body *b = &s->body[s->nbodies];
  memset(b, 0, sizeof *b);
  snprintf(b->name, sizeof b->name, "%s", name);
  return s->nbodies++;
}

/* the joint named name in s (created at its first mention), or -1 when full */
static int joint_index(fb_planar_spec *s, const char *name) {
  for (int j = 0; j < s->njoints; j++)
    if (strcmp(s->joint[j].name, name) == 0) return j;
  if (s->njoints == FB_PLANAR_SPEC_MAX_JOINTS) return -1;
  fb_planar_spec_joint *j = &s->joint[s->njoints];
  memset(j, 0, sizeof *j);
  snprintf(j->name, sizeof j->name, "%s", name);
  j->kind = FB_KIND_REVOLUTE;
  return s->njoints++;
}

/* bodies = A, B */
static fb_status joint_bodies(fb_planar_spec *s, fb_planar_spec_joint *j, const entry *e,
                              fb_diag *diag) {
  char name[2][FB_PLANAR_NAME_SIZE];
  fb_status st = fb_planar_key_two_bodies(e, "a joint", name, diag);
  if (st != FB_OK) return st;
  for (int k = 0; k < 2; k++)
    if ((j->body[k] = body_index(s, name[k])) < 0)
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] bodies: more than %d moving bodies",
                         e->origin, e->section, FB_PLANAR_SPEC_MAX_BODIES);
  j->given |= FB_SPEC_JOINT_BODIES;
  return FB_OK;
}

static fb_status joint_key(fb_planar_spec *s, const entry *e, fb_diag *diag) {
  const char *name = e->section + strlen(JOINT_PREFIX);
  fb_status st = fb_planar_key_name(e, name, "joint", diag);
  if (st != FB_OK) return st;
  const int ji = joint_index(s, name);
  if (ji < 0)
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s]: more than %d joints", e->origin,
                       e->section, FB_PLANAR_SPEC_MAX_JOINTS);
  fb_planar_spec_joint *j = &s->joint[ji];
  if (strcmp(e->key, "bodies") == 0) return joint_bodies(s, j, e, diag);
  if (strcmp(e->key, "at_mm") == 0) {
    j->given |= FB_SPEC_JOINT_AT;
    return fb_planar_key_point(e, j->at, diag);
  }
  if (strcmp(e->key, "kind") == 0) {
    j->given |= FB_SPEC_JOINT_KIND;
    if (strcmp(e->value, "revolute") == 0) j->kind = FB_KIND_REVOLUTE;
    else if (strcmp(e->value, "prismatic") == 0) j->kind = FB_KIND_PRISMATIC;
    else
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] kind = '%s': revolute or prismatic",
                         e->origin, e->section, e->value);
    return FB_OK;
  }
  if (strcmp(e->key, "axis_deg") == 0) {
    j->given |= FB_SPEC_JOINT_AXIS;
    return fb_planar_key_number(e, e->value, -360.0, 360.0, FB_RAD_PER_DEG, AXIS_RULE, &j->axis,
                                diag);
  }
  if (strcmp(e->key, "slider_half_length_mm") == 0 || strcmp(e->key, "slider_half_height_mm") == 0) {
    const int len = strcmp(e->key, "slider_half_length_mm") == 0;
    j->given |= len ? FB_SPEC_JOINT_HALF_LENGTH : FB_SPEC_JOINT_HALF_HEIGHT;
    return fb_planar_key_number(e, e->value, 1e-3, FB_PLANAR_COORD_MAX_MM, FB_M_PER_MM,
                                HALF_RULE, len ? &j->half_length : &j->half_height, diag);
  }
  return fb_diag_set(diag, FB_ERR_PARSE, "%s: unknown key '%s' in [%s] (a joint has bodies, "
                     "at_mm, kind, axis_deg, slider_half_length_mm and slider_half_height_mm)",
                     e->origin, e->key, e->section);
}

/* a [body.NAME] section's numbers: key, bit, field, range, scale to SI,
 * rule, and for fourbar keys their unit, default and meaning */
static const struct {
  const char *key;
  int bit;
  size_t offset;
  double lo, hi, scale;
  const char *rule, *unit, *def, *doc;
} body_numbers[] = {
    {"mass_kg", FB_SPEC_BODY_MASS, offsetof(fb_planar_spec_body, mass), FB_MASS_MIN_KG,
     FB_MASS_MAX_KG, 1.0, MASS_RULE, "kg", "(derived)",
     "the body's mass; without it (and inertia_kg_mm2, centre_mm) they are derived as bars of "
     "[material] density_kg_m3 between its joint points (docs/planar.md, Masses derived as "
     "bars)"},
    {"inertia_kg_mm2", FB_SPEC_BODY_INERTIA, offsetof(fb_planar_spec_body, inertia), 1e-6, 1e12,
     FB_KG_M2_PER_KG_MM2, "a moment of inertia must be positive, from 1e-6 to 1e12 kg mm^2",
     "kg mm^2", "(derived)", "moment of inertia about +z through the body's centre of mass"},
    {"width_mm", FB_SPEC_BODY_WIDTH, offsetof(fb_planar_spec_body, width), 1e-3, 1e5,
     FB_M_PER_MM, "a bar width must be positive, from 0.001 mm to 1e5 mm", "mm", "20",
     "the width of the bars a derived mass is made of"},
    {"thickness_mm", FB_SPEC_BODY_THICK, offsetof(fb_planar_spec_body, thickness), 1e-3, 1e5,
     FB_M_PER_MM, "a bar thickness must be positive, from 0.001 mm to 1e5 mm", "mm", "6.5",
     "the thickness of the bars a derived mass is made of"},
    {"initial_omega_rad_s", FB_SPEC_BODY_OMEGA0, offsetof(fb_planar_spec_body, omega0), -1e6,
     1e6, 1.0, "an angular velocity from -1e6 to 1e6 rad/s, counter-clockwise positive", "rad/s",
     "0", "an undriven case ([drive] joint = none): the body's angular velocity at the start"}};

static fb_status body_key(fb_planar_spec *s, const entry *e, fb_diag *diag) {
  const char *name = e->section + strlen(BODY_PREFIX);
  fb_status st = fb_planar_key_name(e, name, "body", diag);
  if (st != FB_OK) return st;
  if (strcmp(name, "ground") == 0)
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s]: the ground is fixed and has no mass "
                       "properties; name a moving body", e->origin, e->section);
  const int bi = body_index(s, name);
  if (bi < 0)
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s]: more than %d moving bodies", e->origin,
                       e->section, FB_PLANAR_SPEC_MAX_BODIES);
  fb_planar_spec_body *b = &s->body[bi];
  b->given |= FB_SPEC_BODY_SECTION;
  if (strcmp(e->key, "centre_mm") == 0) {
    b->given |= FB_SPEC_BODY_CENTRE;
    return fb_planar_key_point(e, b->centre, diag);
  }
  for (size_t i = 0; i < sizeof body_numbers / sizeof body_numbers[0]; i++)
    if (strcmp(e->key, body_numbers[i].key) == 0) {
      b->given |= body_numbers[i].bit;
      return fb_planar_key_number(e, e->value, body_numbers[i].lo, body_numbers[i].hi,
                                  body_numbers[i].scale, body_numbers[i].rule,
                                  (double *)((char *)b + body_numbers[i].offset), diag);
    }
  return fb_diag_set(diag, FB_ERR_PARSE, "%s: unknown key '%s' in [%s] (a body has mass_kg, "
                     "inertia_kg_mm2, centre_mm, width_mm, thickness_mm and initial_omega_rad_s)",
                     e->origin, e->key, e->section);
}

/* a [point.NAME] section's keys: body = NAME, at_mm = x, y */
static fb_status point_key(fb_planar_spec *s, const entry *e, fb_diag *diag) {
  const char *name = e->section + strlen(POINT_PREFIX);
  fb_status st = fb_planar_key_name(e, name, "point", diag);
  if (st != FB_OK) return st;
  const int k = fb_planar_named(s->point, sizeof s->point[0], &s->npoints,
                                FB_PLANAR_SPEC_MAX_POINTS, name);
  if (k < 0)
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s]: more than %d points", e->origin,
                       e->section, FB_PLANAR_SPEC_MAX_POINTS);
  fb_planar_spec_point *p = &s->point[k];
  if (strcmp(e->key, "body") == 0) {
    char word[sizeof e->value];
    snprintf(word, sizeof word, "%s", e->value);
    const char *body = trim(word);
    if ((st = fb_planar_key_name(e, body, "body", diag)) != FB_OK) return st;
    snprintf(p->body, sizeof p->body, "%s", body);
    p->given |= FB_SPEC_POINT_BODY;
    return FB_OK;
  }
  if (strcmp(e->key, "at_mm") == 0) {
    p->given |= FB_SPEC_POINT_AT;
    return fb_planar_key_point(e, p->at, diag);
  }
  return fb_diag_set(diag, FB_ERR_PARSE, "%s: unknown key '%s' in [%s] (a point has body and "
                     "at_mm)", e->origin, e->key, e->section);
}






_Static_assert(FB_STACKUP_PLANAR_MAX >= 3 * FB_PLANAR_SPEC_MAX_BODIES + 2 * FB_PLANAR_SPEC_MAX_JOINTS,
               "a planar stack-up corner holds every dimension of the largest description");

/* what a planar case's [tolerance] stackup may be */
#define STACKUP_RULE "nominal, max, min, or one of + - 0 per dimension in fourbar stackup's " \
                     "order (a planar case)"

/* [tolerance] stackup on a planar case: a word or the signs, kept as
 * written until the description counts its dimensions (stackup_whole) */
static fb_status stackup_take(fb_case *c, const entry *e, fb_diag *diag) {
  if (strcmp(e->value, "worst") == 0)
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [tolerance] stackup = worst: a planar case has no "
                       "one worst output; give the corner as one sign per dimension: fourbar "
                       "stackup's table names each output's worst corner in its 'at' columns",
                       e->origin);
  const size_t n = strlen(e->value);
  const int word = strcmp(e->value, "nominal") == 0 || strcmp(e->value, "max") == 0 ||
                   strcmp(e->value, "min") == 0;
  if (!word && (n == 0 || n > FB_STACKUP_PLANAR_MAX || strspn(e->value, "+-0") != n))
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [tolerance] stackup = '%s': must be "
                       STACKUP_RULE, e->origin, e->value);
  snprintf(c->stackup.planar, sizeof c->stackup.planar, "%.*s",
           (int)sizeof c->stackup.planar - 1, e->value);
  return FB_OK;
}

fb_status fb_casefile_planar_take(fb_case *c, const entry *e, fb_diag *diag) {
  const int planar_section = description_section(e) || strcmp(e->section, "drive") == 0;
  if (!c->planar.on && planar_section)
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s describes a planar mechanism, but the "
                       "case is a %s: set [linkage] type = planar (docs/planar.md)", e->origin,
                       e->section, e->key, fb_case_mech(c)->type);
  if (prefixed(e->section, JOINT_PREFIX)) return joint_key(&c->planar, e, diag);
  if (prefixed(e->section, BODY_PREFIX)) return body_key(&c->planar, e, diag);
  if (prefixed(e->section, POINT_PREFIX)) return point_key(&c->planar, e, diag);
  if (fb_casefile_planar_loads_section(e))
    return fb_casefile_planar_loads_take(&c->planar, e, diag);
  if (strcmp(e->section, "drive") == 0 && strcmp(e->key, "torque_n_m") == 0) {
    c->planar.torque_drive = 1; /* the joint: [drive] joint, when the case is finished */
    return fb_planar_key_number(e, e->value, -1e9, 1e9, 1.0, "a torque from -1e9 to 1e9 N m, "
                                "counter-clockwise positive", &c->planar.drive_torque, diag);
  }
  if (strcmp(e->section, "drive") == 0 && strcmp(e->key, "speed0_rpm") == 0)
    return fb_planar_key_number(e, e->value, -1e6, 1e6, FB_RAD_S_PER_RPM, "a speed from -1e6 to "
                                "1e6 rpm, counter-clockwise positive", &c->planar.speed0, diag);
  if (stackup_key(e)) return stackup_take(c, e, diag);
  if (fourbar_key(e))
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s is a four-bar or slider-crank key; a "
                       "planar case gives its geometry by [joint.NAME] at_mm and its masses by "
                       "[body.NAME] (docs/planar.md): remove it", e->origin, e->section, e->key);
  return FB_OK; /* [linkage] type, [drive] joint, [clearance] joints: read when finishing */
}

/* ---- the sections as a whole -------------------------------------------- */



/* where body b is described: its [body.NAME] section, else the first joint
 * naming it */
static const entry *body_origin(const fb_planar_spec *s, int b, const entry *e, int n) {
  const entry *at = fb_planar_entry_first(e, n, BODY_PREFIX, s->body[b].name);
  for (int j = 0; j < s->njoints && !at; j++)
    if (s->joint[j].body[0] == b || s->joint[j].body[1] == b)
      at = fb_planar_entry_first(e, n, JOINT_PREFIX, s->joint[j].name);
  return at;
}

/* "file:line: [section]" of a joint or body (where), else the file */
static const char *origin_of(char *buf, size_t size, const fb_planar_spec *s,
                             const fb_planar_where *w, const entry *e, int n, const char *path) {
  const entry *at = NULL;
  if (w->joint >= 0 && w->joint < s->njoints)
    at = fb_planar_entry_first(e, n, JOINT_PREFIX, s->joint[w->joint].name);
  else if (w->body > 0 && w->body < s->nbodies) at = body_origin(s, w->body, e, n);
  if (at) snprintf(buf, size, "%s: [%s]", at->origin, at->section);
  else snprintf(buf, size, "%s", path ? path : "case");
  return buf;
}

/* every joint has its bodies and position, a prismatic joint its axis, a
 * revolute joint none; every [body.NAME] names a body some joint joins */
static fb_status sections_whole(const fb_planar_spec *s, const entry *e, int n, const char *path,
                                fb_diag *diag) {
  if (s->njoints == 0)
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [linkage] type = planar needs its joints: one "
                       "[joint.NAME] section per joint with bodies and at_mm (docs/planar.md)",
                       path ? path : "case");
  for (int j = 0; j < s->njoints; j++) {
    const fb_planar_spec_joint *sj = &s->joint[j];
    const entry *at = fb_planar_entry_first(e, n, JOINT_PREFIX, sj->name);
    const char *miss = !(sj->given & FB_SPEC_JOINT_BODIES) ? "bodies = A, B"
                       : !(sj->given & FB_SPEC_JOINT_AT)   ? "at_mm = x, y"
                       : sj->kind == FB_KIND_PRISMATIC && !(sj->given & FB_SPEC_JOINT_AXIS)
                           ? "axis_deg (a prismatic joint's slide direction)"
                           : NULL;
    if (miss)
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] has no %s", at->origin, at->section, miss);
    if (sj->kind == FB_KIND_REVOLUTE && (sj->given & FB_SPEC_JOINT_AXIS))
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] axis_deg: a revolute joint has no axis "
                         "in the plane (axis_deg is a prismatic joint's slide direction)",
                         at->origin, at->section);
  }
  for (int b = 1; b < s->nbodies; b++) {
    int joined = 0;
    for (int j = 0; j < s->njoints; j++) joined |= s->joint[j].body[0] == b || s->joint[j].body[1] == b;
    if (!joined) {
      const entry *at = fb_planar_entry_first(e, n, BODY_PREFIX, s->body[b].name);
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s]: no joint names body '%s' in its bodies "
                         "key", at ? at->origin : "case", at ? at->section : "body",
                         s->body[b].name);
    }
  }
  for (int k = 0; k < s->npoints; k++) {
    const fb_planar_spec_point *p = &s->point[k];
    const entry *at = fb_planar_entry_first(e, n, POINT_PREFIX, p->name);
    const char *miss = !(p->given & FB_SPEC_POINT_BODY) ? "body = NAME (the moving body it is a "
                                                          "point of)"
                       : !(p->given & FB_SPEC_POINT_AT) ? "at_mm = x, y (where it is in the "
                                                          "assembly configuration)"
                                                        : NULL;
    if (miss)
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] has no %s", at->origin, at->section, miss);
    const entry *key = fb_planar_entry_of(e, n, at->section, "body");
    if (strcmp(p->body, "ground") == 0)
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] body = %s: the ground does not move; a "
                         "point is on a moving body", key->origin, key->section, p->body);
    int known = 0;
    char bodies[1024] = "";
    for (int b = 1; b < s->nbodies; b++) {
      known |= strcmp(s->body[b].name, p->body) == 0;
      snprintf(bodies + strlen(bodies), sizeof bodies - strlen(bodies), "%s%s", b > 1 ? ", " : "",
               s->body[b].name);
    }
    if (!known)
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] body = %s: not a moving body of the case "
                         "(bodies: %s)", key->origin, key->section, p->body, bodies);
  }
  return FB_OK;
}




/* Every link of the description is a link length the four-bar takes
 * (LEN_RULE, as [linkage] crank_mm: one rule): a body's revolute joints two
 * by two are the same point (a compound hinge, FB_PLANAR_SAME_POINT_M), or
 * FB_LINK_MM_MIN to FB_LINK_MM_MAX apart; and a body with two or more
 * revolute joints, the ground too, has them at two points at least (all at
 * one point, it is a link of length 0: a crank whose joints meet turns
 * nothing). A prismatic joint's position is a point of its slide line, not
 * of a link: it takes no part. The later joint's at_mm is named. */
static fb_status links_whole(const fb_planar_spec *s, const entry *e, int n, fb_diag *diag) {
  for (int b = 0; b < s->nbodies; b++) {
    int rev[FB_PLANAR_SPEC_MAX_JOINTS], nr = 0;
    for (int j = 0; j < s->njoints; j++)
      if (s->joint[j].kind == FB_KIND_REVOLUTE &&
          (s->joint[j].body[0] == b || s->joint[j].body[1] == b))
        rev[nr++] = j;
    int bad[2] = {-1, -1};
    double len = 0.0, far = 0.0;
    for (int i = 0; i < nr && bad[0] < 0; i++)
      for (int k = i + 1; k < nr && bad[0] < 0; k++) {
        const double *p = s->joint[rev[i]].at, *q = s->joint[rev[k]].at;
        const double d = hypot(q[0] - p[0], q[1] - p[1]);
        far = fmax(far, d);
        const int same = d < FB_PLANAR_SAME_POINT_M;
        if (!same && !(d >= FB_LINK_MM_MIN * FB_M_PER_MM && d <= FB_LINK_MM_MAX * FB_M_PER_MM)) {
          bad[0] = rev[i], bad[1] = rev[k];
          len = d;
        }
      }
    if (bad[0] < 0 && nr >= 2 && far < FB_PLANAR_SAME_POINT_M) {
      bad[0] = rev[0], bad[1] = rev[1]; /* every joint at one point: a link of length 0 */
      len = far;
    }
    if (bad[0] < 0) continue;
    char sec0[sizeof e->section], sec1[sizeof e->section];
    snprintf(sec0, sizeof sec0, "%s%s", JOINT_PREFIX, s->joint[bad[0]].name);
    snprintf(sec1, sizeof sec1, "%s%s", JOINT_PREFIX, s->joint[bad[1]].name);
    const entry *a0 = fb_planar_entry_of(e, n, sec0, "at_mm");
    const entry *a1 = fb_planar_entry_of(e, n, sec1, "at_mm");
    if (a0 > a1) { /* the later of the two named first */
      const entry *t = a0;
      a0 = a1, a1 = t;
    }
    char body[FB_PLANAR_NAME_SIZE + 16];
    snprintf(body, sizeof body, b ? "body '%s'" : "the ground", s->body[b].name);
    const char *one = far < FB_PLANAR_SAME_POINT_M ? " (its revolute joints all at one point)" : "";
    char rule[FB_DIAG_SIZE / 2]; /* [linkage] crank_mm's refusal, word for word */
    fb_casefile_rule_text(fb_casefile_spec_find("linkage", "crank_mm"), rule, sizeof rule);
    return fb_diag_set(diag, FB_ERR_RANGE, "%s: [%s] at_mm = %s: %s has a link of %s mm between "
                       "this joint and [%s] at_mm = %s%s: %s", a1->origin, a1->section,
                       a1->value, body, FB_NUM(len / FB_M_PER_MM), a0->section, a0->value, one,
                       rule);
  }
  return FB_OK;
}

/* ---- the names' rule ------------------------------------------------------ */

/* one name the case gives: its kind and the entry that first gives it
 * (NULL for the fixed body, ground) */
typedef struct {
  const char *kind, *name;
  const entry *at;
} case_name;

/* 1 when entry x, a joint's bodies key, names body name */
static int bodies_names(const entry *x, const char *name) {
  if (!prefixed(x->section, JOINT_PREFIX) || strcmp(x->key, "bodies") != 0) return 0;
  char buf[sizeof x->value];
  snprintf(buf, sizeof buf, "%s", x->value);
  char *save = NULL;
  for (char *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save))
    if (strcmp(trim(tok), name) == 0) return 1;
  return 0;
}

/* Every name the case gives, of every kind, each with the entry that first
 * gives it, in the order of the file: the one list the names' rule runs
 * over (fb_name_clash, names.h). A kind of name the description adds
 * (points, springs, loads) is listed here. Returns how many (at most max). */
static int case_names(case_name *out, int max, const fb_planar_spec *s, const entry *e, int n) {
  int k = 0;
  out[k++] = (case_name){"body", "ground", NULL};
  const entry *joint_at[FB_PLANAR_SPEC_MAX_JOINTS];
  for (int j = 0; j < s->njoints; j++)
    joint_at[j] = fb_planar_entry_first(e, n, JOINT_PREFIX, s->joint[j].name);
  for (int i = 0; i < n && k < max; i++) {
    const entry *x = &e[i];
    for (int b = 1; b < s->nbodies && k < max; b++) {
      const char *nm = s->body[b].name;
      char sec[sizeof x->section];
      snprintf(sec, sizeof sec, "%s%s", BODY_PREFIX, nm);
      if (strcmp(x->section, sec) != 0 && !bodies_names(x, nm)) continue;
      int seen = 0;
      for (int q = 0; q < k; q++)
        seen |= strcmp(out[q].kind, "body") == 0 && strcmp(out[q].name, nm) == 0;
      if (!seen) out[k++] = (case_name){"body", nm, x};
    }
    for (int j = 0; j < s->njoints && k < max; j++)
      if (joint_at[j] == x)
        out[k++] = (case_name){"joint", s->joint[j].name, x};
    for (int p = 0; p < s->npoints && k < max; p++)
      if (fb_planar_entry_first(e, n, POINT_PREFIX, s->point[p].name) == x)
        out[k++] = (case_name){"point", s->point[p].name, x};
    for (int p = 0; p < s->nsprings && k < max; p++)
      if (fb_planar_entry_first(e, n, SPRING_PREFIX, s->spring[p].name) == x)
        out[k++] = (case_name){"spring", s->spring[p].name, x};
    for (int p = 0; p < s->nloads && k < max; p++)
      if (fb_planar_entry_first(e, n, LOAD_PREFIX, s->load[p].name) == x)
        out[k++] = (case_name){"load", s->load[p].name, x};
  }
  return k;
}

/* "[section]" where entry x gives name (of kind), "[section] bodies" when
 * a joint's bodies key gives a body */
static const char *given_in(char *buf, size_t size, const entry *x, const char *kind) {
  const int key = strcmp(kind, "body") == 0 && strcmp(x->key, "bodies") == 0;
  snprintf(buf, size, "[%s]%s", x->section, key ? " bodies" : "");
  return buf;
}

/* The names' rule (names.h): no two names of the case, of any kind, with
 * one column and key word, and no fixed word; the later name is refused,
 * with the earlier named beside it. */
static fb_status names_one_word(const fb_planar_spec *s, const entry *e, int n, fb_diag *diag) {
  enum {
    MAX = FB_PLANAR_SPEC_MAX_BODIES + 1 + FB_PLANAR_SPEC_MAX_JOINTS + FB_PLANAR_SPEC_MAX_POINTS +
          FB_PLANAR_SPEC_MAX_SPRINGS + FB_PLANAR_SPEC_MAX_LOADS
  };
  case_name list[MAX];
  const char *names[MAX];
  const int count = case_names(list, MAX, s, e, n);
  char here[sizeof e->section + 16], there[sizeof e->origin + sizeof e->section + 32];
  char word[FB_PLANAR_NAME_SIZE];
  for (int k = 0; k < count; k++) {
    const case_name *c = &list[k];
    const char *what = NULL;
    if (c->at && fb_name_fixed(c->name, &what))
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: %s: %s '%s': its columns would repeat %s; "
                         "give it another name", c->at->origin,
                         given_in(here, sizeof here, c->at, c->kind), c->kind, c->name, what);
    const int q = fb_name_clash(names, k, c->name);
    names[k] = c->name;
    if (q < 0 || !c->at) continue;
    const case_name *p = &list[q];
    if (p->at)
      snprintf(there, sizeof there, " (%s: %s)", p->at->origin,
               given_in(here, sizeof here, p->at, p->kind));
    else
      snprintf(there, sizeof there, " (the fixed body)");
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: %s: %s '%s' and %s '%s'%s both write '%s': %s",
                       c->at->origin, given_in(here, sizeof here, c->at, c->kind), c->kind,
                       c->name, p->kind, p->name, there, fb_name_word(word, sizeof word, c->name),
                       FB_NAME_RULE);
  }
  return FB_OK;
}

/* the joints named in list ("none" or NAME, NAME, ...) as a mask, by the
 * rule every mechanism's list follows (fb_casefile_joint_list); single: one
 * revolute joint (the drive) */
static fb_status joint_names(int *mask, const fb_planar_spec *s, const entry *e, int single,
                             fb_diag *diag) {
  char known[1024] = "", tok[sizeof e->value];
  const char *names[FB_PLANAR_SPEC_MAX_JOINTS];
  for (int j = 0; j < s->njoints; j++) {
    names[j] = s->joint[j].name;
    snprintf(known + strlen(known), sizeof known - strlen(known), "%s%s", j ? ", " : "",
             s->joint[j].name);
  }
  int count = 0;
  fb_status st = fb_casefile_joint_list(e, names, s->njoints, mask, &count, tok, sizeof tok, diag);
  if (st == FB_ERR_ARG)
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s: '%s' is not a joint of the case "
                       "(joints: %s)", e->origin, e->section, e->key, tok, known);
  if (st != FB_OK) return st;
  if (single && count != 1)
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s = '%s': name one joint (joints: %s)",
                       e->origin, e->section, e->key, e->value, known);
  for (int j = 0; single && j < s->njoints; j++)
    if ((*mask & (1 << j)) && s->joint[j].kind != FB_KIND_REVOLUTE)
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s: joint '%s' is prismatic; the drive "
                         "turns a revolute joint at speed_rpm", e->origin, e->section, e->key,
                         s->joint[j].name);
  return FB_OK;
}

/* [drive] torque_n_m: the joint [drive] joint names turned by a torque,
 * the description undriven (its speed from the dynamics, its start at
 * speed0_rpm); speed_rpm, direction and bodies' initial_omega_rad_s are
 * refused beside it, speed0_rpm without it */
static fb_status torque_drive(fb_planar_spec *s, const entry *e, int n, const entry *dr,
                              fb_diag *diag) {
  s->torque_joint = -1;
  const entry *tq = fb_planar_entry_last(e, n, "drive", "torque_n_m");
  const entry *w0 = fb_planar_entry_last(e, n, "drive", "speed0_rpm");
  if (!tq && w0)
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [drive] speed0_rpm = %s: the start speed of a "
                       "torque drive; give [drive] torque_n_m (a speed drive starts at its "
                       "speed_rpm)", w0->origin, w0->value);
  if (!tq) return FB_OK;
  if (s->undriven)
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [drive] torque_n_m = %s: the torque turns the "
                       "joint [drive] joint names, and %s: [drive] joint = none names none",
                       tq->origin, tq->value, dr->origin);
  static const char *const speed_keys[] = {"speed_rpm", "direction"};
  for (int k = 0; k < 2; k++) {
    const entry *x = fb_planar_entry_last(e, n, "drive", speed_keys[k]);
    if (x)
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [drive] %s = %s: a torque drive (%s: [drive] "
                         "torque_n_m = %s) sets no speed, the dynamics do; remove it (speed0_rpm "
                         "gives the start speed)", x->origin, speed_keys[k], x->value, tq->origin,
                         tq->value);
  }
  for (int b = 1; b < s->nbodies; b++)
    if (s->body[b].given & FB_SPEC_BODY_OMEGA0) {
      char sec[sizeof e->section];
      snprintf(sec, sizeof sec, "body.%s", s->body[b].name);
      const entry *x = fb_planar_entry_last(e, n, sec, "initial_omega_rad_s");
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] initial_omega_rad_s: a torque drive's "
                         "start is [drive] speed0_rpm, every body's rate following from it; "
                         "remove it", x ? x->origin : "case", sec);
    }
  s->torque_joint = s->drive;
  s->drive = -1;
  s->undriven = 1;
  return FB_OK;
}

/* the drive and the clearance joints, by name */
static fb_status drive_and_clearance(fb_case *c, const entry *e, int n, const char *path,
                                     fb_diag *diag) {
  fb_planar_spec *s = &c->planar;
  const entry *dr = fb_planar_entry_of(e, n, "drive", "joint");
  if (!dr)
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [linkage] type = planar needs [drive] joint = "
                       "NAME, the revolute joint the drive turns", path ? path : "case");
  int mask;
  char word[sizeof dr->value];
  snprintf(word, sizeof word, "%s", dr->value);
  s->undriven = strcmp(trim(word), "none") == 0;
  s->drive = -1;
  fb_status st = s->undriven ? FB_OK : joint_names(&mask, s, dr, 1, diag);
  if (st != FB_OK) return st;
  for (s->drive = 0; !s->undriven && !(mask & (1 << s->drive)); s->drive++) continue;
  if (s->undriven) s->drive = -1;
  if ((st = torque_drive(s, e, n, dr, diag)) != FB_OK) return st;
  const entry *cl = fb_planar_entry_of(e, n, "clearance", "joints");
  c->clearance.mask = 0; /* a planar case's default: no clearance joint */
  st = cl ? joint_names(&c->clearance.mask, s, cl, 0, diag) : FB_OK;
  if (st == FB_OK) st = fb_casefile_planar_free(c, e, n, path, diag);
  return st == FB_OK ? fb_casefile_planar_guides(c, e, n, path, diag) : st;
}


/* An engine's clearance model of a planar case is built by the engine kit
 * (fb_model_clearance_at_drive's rule): a clearance at the driven joint
 * with such a model in [run] models is refused here, where both keys were
 * given, never at run time after the other models. */
static fb_status clearance_at_drive(const fb_case *c, const entry *e, int n, const char *path,
                                    fb_diag *diag) {
  const fb_planar_spec *s = &c->planar;
  if (s->undriven || s->drive < 0 || !((c->clearance.mask >> s->drive) & 1)) return FB_OK;
  for (int i = 0; i < c->model_count; i++) {
    const fb_model *m = fb_model_find(c->models[i]);
    fb_diag inner;
    if (!m || fb_model_clearance_at_drive(m, 1, s->joint[s->drive].name, &inner) == FB_OK) continue;
    const entry *cl = fb_planar_entry_last(e, n, "clearance", "joints");
    const entry *md = fb_planar_entry_last(e, n, "run", "models");
    const entry *dr = fb_planar_entry_last(e, n, "drive", "joint");
    return fb_diag_set(diag, FB_ERR_ARG, "%s: %s (given: [drive] joint at %s; [run] models at %s)",
                       cl ? cl->origin : path ? path : "case", inner.msg, dr ? dr->origin : "?",
                       md ? md->origin : "its default");
  }
  return FB_OK;
}


/* one line on a checked description, for the refusal */
static void summary(char *buf, size_t size, const fb_planar *m) {
  char derived[256] = "";
  for (int b = 1; b < m->nbodies; b++)
    if (m->body[b].derived & FB_PLANAR_DERIVED_MASS)
      snprintf(derived + strlen(derived), sizeof derived - strlen(derived), "%s%s",
               derived[0] ? ", " : "", m->body[b].name);
  snprintf(buf, size, "%d moving bodies, %d joints, one degree of freedom %s%s%s%s%s%s",
           m->nbodies - 1, m->njoints, m->drive >= 0 ? "driven at '" : "undriven",
           m->drive >= 0 ? m->joint[m->drive].name : "", m->drive >= 0 ? "', a full turn" : "",
           derived[0] ? "; masses derived as bars: " : "", derived, derived[0] ? "" : "");
}

/* c->stackup.planar: the corner as one sign per dimension of m, a word
 * (max when not given, as the four-bar's) spelled out */
static fb_status stackup_whole(fb_case *c, const fb_planar *m, const entry *e, int n,
                               fb_diag *diag) {
  char *s = c->stackup.planar;
  const int dims = fb_planar_dims_count(m);
  if (dims > FB_STACKUP_PLANAR_MAX) /* case.h's bound holds every description */
    return fb_diag_set(diag, FB_ERR_RANGE, "the description has %d stack-up dimensions, more "
                       "than %d", dims, FB_STACKUP_PLANAR_MAX);
  const char sign = !s[0] || strcmp(s, "max") == 0 ? '+' : strcmp(s, "min") == 0 ? '-'
                    : strcmp(s, "nominal") == 0    ? '0' : 0;
  if (sign) {
    memset(s, sign, (size_t)dims);
    s[dims] = '\0';
    return FB_OK;
  }
  if ((int)strlen(s) == dims) return FB_OK;
  const entry *at = NULL;
  for (int i = 0; i < n; i++)
    if (stackup_key(&e[i])) at = &e[i]; /* the last given wins, as every key's */
  return fb_diag_set(diag, FB_ERR_PARSE, "%s: [tolerance] stackup = '%s': %d signs, and the "
                     "description has %d dimensions: give one of + - 0 for each, in the order "
                     "fourbar stackup lists them (or nominal, max, min)",
                     at ? at->origin : "case", s, (int)strlen(s), dims);
}

/* [solver] h_s = auto on a driven case with clearance joints, or h_s not
 * given there (the four-bar's rule, scene.c): the step that resolves its
 * clearance contacts (planar_resolution.h), into c->solver.h, h_mode auto.
 * Without clearance joints a case without h_s keeps the key's default. */
static fb_status step_auto(fb_case *c, const fb_planar *m, const char *path, fb_diag *diag) {
  if (c->planar.undriven || !c->clearance.mask) return FB_OK;
  if (c->solver.h_mode == FB_STEP_DEFAULT) c->solver.h_mode = FB_STEP_AUTO;
  if (c->solver.h_mode != FB_STEP_AUTO) return FB_OK;
  fb_diag inner;
  const fb_status st = fb_planar_step_auto(&c->solver.h, c, m, &inner);
  if (st != FB_OK)
    return fb_diag_set(diag, st, "%s: [solver] h_s = auto (the step from the clearance "
                       "contacts): %s", path ? path : "case", inner.msg);
  return FB_OK;
}

/* The models a planar case runs when it lists no [run] models: the
 * four-bar's rule ([run] models' row, casefile_keys.c) on the description.
 * A driven case: analytic and ode-ideal-nominal, their stack-up models
 * with [tolerance] class (refused without one); an undriven one, which has
 * no ideal motion to follow: its reference (the ideal mechanism's forward
 * dynamics without clearance joints, ode-ideal-nominal's yardstick then).
 * With clearance joints also each clearance model with its reference
 * (FB_CLEARANCE_DEFAULT_MODELS: ode-clearance-impact,
 * ode-clearance-restitution, reference, reference-restitution). */
static void default_models(fb_case *c) {
  const int clearance = c->clearance.mask != 0;
  const char *list[8];
  int n = 0;
  if (c->planar.undriven) {
    list[n++] = "reference";
    if (!clearance) list[n++] = "ode-ideal-nominal";
  } else {
    list[n++] = "analytic";
    if (fb_casefile_given(c, "tolerance", "class")) list[n++] = "analytic-stackup";
    list[n++] = "ode-ideal-nominal";
    if (fb_casefile_given(c, "tolerance", "class")) list[n++] = "ode-ideal-stackup";
  }
  for (size_t k = 0; clearance && k < FB_CLEARANCE_DEFAULT_COUNT; k++) {
    int dup = 0;
    for (int q = 0; q < n; q++) dup |= strcmp(list[q], fb_clearance_default_models[k]) == 0;
    if (!dup) list[n++] = fb_clearance_default_models[k];
  }
  c->model_count = n;
  for (int k = 0; k < n; k++) snprintf(c->models[k], sizeof c->models[k], "%s", list[k]);
}

fb_status fb_casefile_planar_finish(fb_case *c, const entry *e, int n, const char *path, int run,
                                    fb_diag *diag) {
  fb_status st = names_one_word(&c->planar, e, n, diag);
  if (st == FB_OK) st = sections_whole(&c->planar, e, n, path, diag);
  if (st == FB_OK) st = links_whole(&c->planar, e, n, diag);
  if (st == FB_OK) st = fb_casefile_planar_loads_whole(&c->planar, e, n, diag);
  if (st == FB_OK) st = drive_and_clearance(c, e, n, path, diag);
  if (st != FB_OK) return st;
  fb_planar *m;
  fb_planar_where w;
  fb_diag inner;
  char where[FB_DIAG_SIZE];
  st = fb_planar_compile(&m, &c->planar, c->density, &w, &inner);
  if (st == FB_OK && (st = fb_planar_check(m, &w, &inner)) != FB_OK) fb_planar_free(m);
  if (st != FB_OK)
    return fb_diag_set(diag, st, "%s: %s",
                       origin_of(where, sizeof where, &c->planar, &w, e, n, path), inner.msg);
  char line[512];
  summary(line, sizeof line, m);
  st = stackup_whole(c, m, e, n, diag);
  if (st != FB_OK) {
    fb_planar_free(m);
    return st;
  }
  if (run) st = step_auto(c, m, path, diag);
  fb_planar_free(m);
  if (st != FB_OK) return st;
  if (!fb_casefile_given(c, "run", "models")) default_models(c);
  st = clearance_at_drive(c, e, n, path, diag);
  if (st != FB_OK) return st;
  if (run) return FB_OK;
  return fb_diag_set(diag, FB_ERR_ARG,
                     "%s: [linkage] type = planar: the description checks (%s), but this command "
                     "does not run a planar case yet: fourbar run, kinematics, stackup, penalty, "
                     "bench, check, contact-params --case and export (mjcf) do (docs/planar.md)",
                     path ? path : "case", line);
}

void fb_casefile_planar_write_keys(FILE *f) {
  static const char *const joint_rows[][5] = {
      {"bodies", "-", "(required)", "two different body names, ground or a body of the case",
       "the two bodies the joint joins; a revolute clearance joint's pin is on the first, its "
       "hole on the second; a joint's reaction is the force on the second from the first"},
      {"at_mm", "mm", "(required)", FB_PLANAR_POINT_RULE,
       "where the joint is in the assembly configuration (both bodies' point)"},
      {"kind", "-", "revolute", "revolute or prismatic",
       "revolute: a pin, both bodies' points together; prismatic: a slide, the bodies keep "
       "their relative angle and the second's point stays on the first's line along axis_deg"},
      {"axis_deg", "deg", "(none)", AXIS_RULE,
       "prismatic: the slide's direction in the assembly configuration; required there"},
      {"slider_half_length_mm", "mm", "(none)", HALF_RULE,
       "a prismatic joint named in [clearance] joints: the slider's half-length along the "
       "slide (its corners meet the guide's walls); required there"},
      {"slider_half_height_mm", "mm", "(none)", HALF_RULE,
       "a prismatic joint named in [clearance] joints: the slider's half-height across the "
       "slide; required there"}};
  for (size_t i = 0; i < sizeof joint_rows / sizeof joint_rows[0]; i++)
    fprintf(f, "| [joint.NAME] %s | %s | %s | %s | planar case: %s |\n", joint_rows[i][0],
            joint_rows[i][1], joint_rows[i][2], joint_rows[i][3], joint_rows[i][4]);
  fprintf(f, "| [body.NAME] centre_mm | mm | (derived) | %s | planar case: the body's centre of "
          "mass in the assembly configuration |\n", FB_PLANAR_POINT_RULE);
  for (size_t i = 0; i < sizeof body_numbers / sizeof body_numbers[0]; i++)
    fprintf(f, "| [body.NAME] %s | %s | %s | %s | planar case: %s |\n", body_numbers[i].key,
            body_numbers[i].unit, body_numbers[i].def, body_numbers[i].rule, body_numbers[i].doc);
  fprintf(f, "| [point.NAME] body | - | (required) | a moving body of the case | planar case: "
          "the body an output point is a point of; the run writes its position, velocity and "
          "acceleration (columns NAME_x_m ... NAME_a_y_m_s2) and their extremes |\n");
  fprintf(f, "| [point.NAME] at_mm | mm | (required) | %s | planar case: where the output point "
          "is in the assembly configuration |\n", FB_PLANAR_POINT_RULE);
  fb_casefile_planar_loads_write_keys(f);
  fprintf(f, "| [drive] joint | - | (required) | a revolute joint of the case, or none | planar "
          "case: the joint the drive turns at speed_rpm in direction (its second body relative "
          "to its first); none: an undriven case, moving from its bodies' initial_omega_rad_s "
          "under gravity ([run] duration_s required) |\n");
  fprintf(f, "| [drive] torque_n_m | N m | (none: a speed drive) | a torque from -1e9 to 1e9 N m, "
          "counter-clockwise positive | planar case: the joint [drive] joint names turned by a "
          "constant torque instead of a speed: +T on its second body, -T on its first; "
          "speed_rpm, direction and bodies' initial_omega_rad_s are refused beside it, [run] "
          "duration_s is required and the analytic model does not run (the speed follows from "
          "the dynamics) |\n");
  fprintf(f, "| [drive] speed0_rpm | rpm | 0 | a speed from -1e6 to 1e6 rpm | planar case with "
          "[drive] torque_n_m: the joint's second body's speed relative to its first at the "
          "start, every body's rate following from it |\n");
}
