/* The description of a case's mechanism (planar_case.h): a planar case's
 * spec compiled with its masses derived as bars; a closed-form member's
 * instance (planar_instances.c) through its table (closed_form.h). */
#include "planar_case.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bar_mass.h"
#include "closed_form.h"
#include "planar_check.h"
#include "planar_outputs.h"
#include "planar_path.h"
#include "units.h"

/* ---- a planar case's spec ---------------------------------------------- */

/* body b's distinct joint points in order (its joints with the ground
 * first, then the file's); returns how many */
static int body_points(double pts[][2], int max, const fb_planar_spec *s, int b) {
  int n = 0;
  for (int pass = 0; pass < 2; pass++)
    for (int j = 0; j < s->njoints; j++) {
      const fb_planar_spec_joint *jt = &s->joint[j];
      const int touches = jt->body[0] == b || jt->body[1] == b;
      const int grounded = jt->body[0] == FB_PLANAR_GROUND || jt->body[1] == FB_PLANAR_GROUND;
      if (!touches || grounded != (pass == 0)) continue;
      int seen = 0;
      for (int i = 0; i < n; i++)
        seen |= hypot(pts[i][0] - jt->at[0], pts[i][1] - jt->at[1]) < FB_PLANAR_SAME_POINT_M;
      if (!seen && n < max) {
        pts[n][0] = jt->at[0];
        pts[n][1] = jt->at[1];
        n++;
      }
    }
  return n;
}

/* The guide of prismatic joint jt, the body that carries the slot
 * (planar.h fb_planar_guide_side) */
static int guide_of(const fb_planar_spec_joint *jt) {
  return jt->body[fb_planar_guide_side(jt->body[0], jt->body[1])];
}

/* A slot's travel: the ends of the slider's point's path along each
 * prismatic joint's axis over a drive revolution, in the assembly
 * configuration's world frame [m] (travel[j][k], k = 0, 1; NaN: not known,
 * the joint's position counts where the assembly puts it). */
typedef double travel_t[2][2];

/* body b's material points: its distinct joint points (body_points), a
 * slot it carries (a prismatic joint it guides) taken as its travel's two
 * ends instead of where the assembly puts the slider, when travel knows
 * them (NULL: none); returns how many */
static int material_points(double pts[][2], int max, const fb_planar_spec *s, int b,
                           const travel_t *travel) {
  int n = body_points(pts, max, s, b);
  for (int j = 0; travel && j < s->njoints; j++) {
    const fb_planar_spec_joint *jt = &s->joint[j];
    if (jt->kind != FB_KIND_PRISMATIC || guide_of(jt) != b || !isfinite(travel[j][0][0])) continue;
    int shared = 0; /* another joint of b at the slot's point keeps it */
    for (int k = 0; k < s->njoints; k++)
      shared |= k != j && (s->joint[k].body[0] == b || s->joint[k].body[1] == b) &&
                hypot(s->joint[k].at[0] - jt->at[0], s->joint[k].at[1] - jt->at[1]) <
                    FB_PLANAR_SAME_POINT_M;
    for (int i = 0; i < n && !shared; i++)
      if (hypot(pts[i][0] - jt->at[0], pts[i][1] - jt->at[1]) < FB_PLANAR_SAME_POINT_M) {
        memmove(pts[i], pts[i + 1], (size_t)(n - i - 1) * sizeof pts[0]);
        n--;
        break;
      }
    for (int e = 0; e < 2; e++) {
      int seen = 0;
      for (int i = 0; i < n; i++)
        seen |= hypot(pts[i][0] - travel[j][e][0], pts[i][1] - travel[j][e][1]) <
                FB_PLANAR_SAME_POINT_M;
      if (!seen && n < max) {
        pts[n][0] = travel[j][e][0];
        pts[n][1] = travel[j][e][1];
        n++;
      }
    }
  }
  return n;
}

/* mass properties of the bars between every pair of the points, or of the
 * one bar between the two farthest apart when every point lies on it
 * (within half the bar's width of its line: a lever with a pin in its
 * middle is one bar, not a triangle of three) */
typedef struct {
  double mass, centre[2], inertia; /* [kg], [m], about centre [kg m^2] */
} bars_t;

double fb_planar_farthest_pair(const double (*pts)[2], int n, int *a, int *b) {
  double far = -1.0;
  *a = 0;
  *b = n > 1 ? 1 : 0;
  for (int i = 0; i < n; i++)
    for (int k = i + 1; k < n; k++) {
      const double l = hypot(pts[k][0] - pts[i][0], pts[k][1] - pts[i][1]);
      if (l > far) far = l, *a = i, *b = k;
    }
  return far > 0.0 ? far : 0.0;
}

/* 1 when the n >= 3 points lie on one bar of width w: each within w / 2
 * of the line through the two farthest apart (*a, *b), which then span
 * them all */
static int on_one_bar(double pts[][2], int n, double w, int *a, int *b) {
  const double far = fb_planar_farthest_pair((const double (*)[2])pts, n, a, b);
  if (n < 3 || !(far > 0.0)) return 0;
  const double u[2] = {(pts[*b][0] - pts[*a][0]) / far, (pts[*b][1] - pts[*a][1]) / far};
  for (int i = 0; i < n; i++) {
    const double d = fabs((pts[i][0] - pts[*a][0]) * u[1] - (pts[i][1] - pts[*a][1]) * u[0]);
    if (d > 0.5 * w) return 0;
  }
  return 1;
}

static bars_t bars_of(double pts[][2], int n, double w, double t, double rho) {
  bars_t r = {0.0, {0.0, 0.0}, 0.0};
  int a = 0, b = 1;
  if (on_one_bar(pts, n, w, &a, &b)) { /* collinear points: one bar end to end */
    double ends[2][2] = {{pts[a][0], pts[a][1]}, {pts[b][0], pts[b][1]}};
    return bars_of(ends, 2, w, t, rho);
  }
  for (int i = 0; i < n; i++)
    for (int k = i + 1; k < n; k++) {
      const double l = hypot(pts[k][0] - pts[i][0], pts[k][1] - pts[i][1]);
      const double m = rho * w * t * l;
      r.mass += m;
      r.centre[0] += m * 0.5 * (pts[i][0] + pts[k][0]);
      r.centre[1] += m * 0.5 * (pts[i][1] + pts[k][1]);
    }
  if (!(r.mass > 0.0)) return r;
  r.centre[0] /= r.mass;
  r.centre[1] /= r.mass;
  for (int i = 0; i < n; i++)
    for (int k = i + 1; k < n; k++) {
      const double l = hypot(pts[k][0] - pts[i][0], pts[k][1] - pts[i][1]);
      const double m = rho * w * t * l;
      const double dx = 0.5 * (pts[i][0] + pts[k][0]) - r.centre[0];
      const double dy = 0.5 * (pts[i][1] + pts[k][1]) - r.centre[1];
      r.inertia += m * (l * l + w * w) / 12.0 + m * (dx * dx + dy * dy);
    }
  return r;
}

/* the joints of spec s at body b, and the first of them */
static int body_joints(const fb_planar_spec *s, int b, int *first) {
  int n = 0;
  *first = -1;
  for (int j = 0; j < s->njoints; j++)
    if (s->joint[j].body[0] == b || s->joint[j].body[1] == b) {
      if (!n) *first = j;
      n++;
    }
  return n;
}

/* A body whose mass no bar gives: the unit body that stands in for it
 * while the joints are counted (fb_planar_compile), never run. */
#define STAND_IN_KG 1.0
#define STAND_IN_KG_M2 1.0

/* body b of spec s into p: its mass properties given or derived. A body
 * with fewer than two joint points and no mass (or moment) given gets the
 * stand-in, *pending = 1 and the refusal in diag, for the caller to give
 * after the joints are counted. */
static int compile_body(fb_planar *p, const fb_planar_spec *s, int b, double density,
                        const travel_t *travel, int *pending, fb_diag *diag) {
  const fb_planar_spec_body *sb = &s->body[b];
  double pts[FB_PLANAR_SPEC_MAX_JOINTS][2], mat[FB_PLANAR_SPEC_MAX_JOINTS + 2][2];
  const int n = body_points(pts, FB_PLANAR_SPEC_MAX_JOINTS, s, b);
  const int nm = material_points(mat, FB_PLANAR_SPEC_MAX_JOINTS + 2, s, b, travel);
  const fb_bar def = fb_bar_default();
  const double w = sb->given & FB_SPEC_BODY_WIDTH ? sb->width : def.width;
  const double t = sb->given & FB_SPEC_BODY_THICK ? sb->thickness : def.thickness;
  const bars_t bars = bars_of(mat, nm, w, t, density);
  const int has_bar = n >= 2;
  const int given_m = sb->given & FB_SPEC_BODY_MASS, given_i = sb->given & FB_SPEC_BODY_INERTIA;
  const int given_c = sb->given & FB_SPEC_BODY_CENTRE;
  if (!has_bar && (!given_m || !given_i)) {
    int first;
    const int nj = body_joints(s, b, &first);
    char has[FB_PLANAR_NAME_SIZE + 64];
    if (nj == 0) snprintf(has, sizeof has, "no joint");
    else if (nj == 1) snprintf(has, sizeof has, "one joint ('%s')", s->joint[first].name);
    else snprintf(has, sizeof has, "%d joints at one point", nj);
    fb_diag_set(diag, FB_ERR_ARG,
                "body '%s' has %s, so no bar to derive its %s from: give [body.%s] %s%s%s",
                sb->name, has, given_m ? "moment of inertia" : "mass", sb->name,
                given_m ? "" : "mass_kg", !given_m && !given_i ? " and " : "",
                given_i ? "" : "inertia_kg_mm2");
    *pending = 1;
    const double at[2] = {n ? pts[0][0] : 0.0, n ? pts[0][1] : 0.0};
    fb_diag inner;
    const int id = fb_planar_add_body(p, sb->name, STAND_IN_KG, STAND_IN_KG_M2, at, 0.0, 0, &inner);
    if (id < 0) *diag = inner; /* (its name's refusal comes first) */
    return id;
  }
  const double mass = given_m ? sb->mass : bars.mass;
  if (!given_m && !(mass >= FB_MASS_MIN_KG && mass <= FB_MASS_MAX_KG)) {
    fb_diag_set(diag, FB_ERR_RANGE,
                "body '%s': its bars weigh %g kg (density %g kg/m^3, %g x %g mm section, %g mm "
                "of bars): a mass must lie in [%g, %g] kg; give [body.%s] mass_kg or change the "
                "section", sb->name, mass, density, w * 1e3, t * 1e3, bars.mass / (density * w * t) * 1e3,
                FB_MASS_MIN_KG, FB_MASS_MAX_KG, sb->name);
    return -1;
  }
  double c[2] = {bars.centre[0], bars.centre[1]};
  if (given_c) {
    c[0] = sb->centre[0];
    c[1] = sb->centre[1];
  } else if (!has_bar) {
    c[0] = pts[0][0];
    c[1] = pts[0][1];
  }
  double inertia = sb->inertia;
  if (!given_i) {
    const double dx = c[0] - bars.centre[0], dy = c[1] - bars.centre[1];
    inertia = bars.inertia * (mass / bars.mass) + mass * (dx * dx + dy * dy);
  }
  const double angle0 = has_bar ? atan2(pts[1][1] - pts[0][1], pts[1][0] - pts[0][0]) : 0.0;
  const int derived = (given_m ? 0 : FB_PLANAR_DERIVED_MASS) |
                      (given_i ? 0 : FB_PLANAR_DERIVED_INERTIA) |
                      (given_c ? 0 : FB_PLANAR_DERIVED_CENTRE);
  int ends[2];
  const int id = fb_planar_add_body(p, sb->name, mass, inertia, c, angle0, derived, diag);
  if (id >= 0) p->body[id].on_one_bar = on_one_bar(pts, n, w, &ends[0], &ends[1]);
  return id;
}

/* fb_planar_compile with the slots' travel (NULL: where the assembly puts
 * the sliders) */
static fb_status compile(fb_planar **out, const fb_planar_spec *s, double density,
                         const travel_t *travel, fb_planar_where *where, fb_diag *diag) {
  *out = NULL;
  fb_planar_where none = {-1, -1};
  if (!where) where = &none;
  *where = none;
  if (s->njoints < 1 || s->nbodies < 2)
    return fb_diag_set(diag, FB_ERR_ARG, "a planar mechanism needs joints: give one "
                       "[joint.NAME] section per joint");
  fb_planar *p = fb_planar_new(s->nbodies - 1, s->njoints);
  if (!p) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for a description");
  fb_status rc = FB_OK;
  /* a body whose mass no bar gives is refused after the joints are
   * counted: a joint missing is said as such, not as that body's mass */
  int pending_body = -1;
  fb_diag pending;
  for (int b = 1; b < s->nbodies && rc == FB_OK; b++) {
    int lacks = 0;
    fb_diag bd;
    if (compile_body(p, s, b, density, travel, &lacks, &bd) < 0) {
      *diag = bd;
      where->body = b;
      rc = FB_ERR_ARG;
    } else if (lacks && pending_body < 0) {
      pending = bd;
      pending_body = b;
    }
  }
  for (int j = 0; j < s->njoints && rc == FB_OK; j++) {
    const fb_planar_spec_joint *sj = &s->joint[j];
    if (fb_planar_add_joint(p, sj->name, (fb_joint_kind)sj->kind, sj->body[0], sj->body[1],
                            sj->at, sj->axis, diag) < 0) {
      where->joint = j;
      rc = FB_ERR_ARG;
    }
  }
  for (int k = 0; k < s->npoints && rc == FB_OK; k++) { /* output points: no mass, no joint */
    const fb_planar_spec_point *sp = &s->point[k];
    if (fb_planar_add_point(p, sp->name, fb_planar_find_body(p, sp->body), sp->at, diag) < 0)
      rc = FB_ERR_ARG;
  }
  for (int k = 0; k < s->nsprings && rc == FB_OK; k++) { /* springs and loads: no constraint */
    const fb_planar_spec_spring *sp = &s->spring[k];
    const double l0 = sp->given & FB_SPEC_SPRING_FREE ? sp->free_length : -1.0;
    if (fb_planar_add_spring(p, sp->name, fb_planar_find_body(p, sp->body[0]),
                             fb_planar_find_body(p, sp->body[1]), sp->at, sp->stiffness, l0,
                             sp->damping, diag) < 0)
      rc = FB_ERR_ARG;
  }
  for (int k = 0; k < s->nloads && rc == FB_OK; k++) {
    const fb_planar_spec_load *sl = &s->load[k];
    if (fb_planar_add_load(p, sl->name, fb_planar_find_body(p, sl->body), sl->at, sl->force,
                           sl->torque, sl->active, sl->stroke, diag) < 0)
      rc = FB_ERR_ARG;
  }
  if (rc == FB_OK && s->drive < 0 && !s->undriven)
    rc = fb_diag_set(diag, FB_ERR_ARG, "no drive: name the driven joint in [drive] joint");
  if (rc == FB_OK && !s->undriven && (rc = fb_planar_set_drive(p, s->drive, diag)) != FB_OK)
    where->joint = s->drive;
  if (rc == FB_OK && s->torque_drive && s->torque_joint >= 0 &&
      (rc = fb_planar_set_drive_torque(p, s->torque_joint, s->drive_torque, diag)) != FB_OK)
    where->joint = s->torque_joint;
  if (rc == FB_OK && pending_body >= 0 && (rc = fb_planar_check_structure(p, where, diag)) == FB_OK) {
    *diag = pending;
    where->body = pending_body;
    rc = FB_ERR_ARG;
  }
  if (rc != FB_OK) {
    fb_planar_free(p);
    return rc;
  }
  *out = p;
  return FB_OK;
}

/* the slide quantity of fb_planar_extremes_of: slide i's position */
static double slide_position(const fb_planar *m, const double *q, const double *qd,
                             const double *qdd, const double *w1, int i, void *ctx) {
  (void)w1;
  double *row = ctx;
  fb_planar_outputs(row, m, q, qd, qdd);
  return row[FB_PLANAR_POINT_QUANTITIES * m->npoints + FB_PLANAR_SLIDE_QUANTITIES * i];
}

/* 1 when some body of s derives a mass property and guides a prismatic
 * joint (carries a slot): its bars then take the slot's travel */
static int slot_derived(const fb_planar_spec *s) {
  for (int j = 0; j < s->njoints; j++) {
    const int g = guide_of(&s->joint[j]);
    if (s->joint[j].kind != FB_KIND_PRISMATIC || g == FB_PLANAR_GROUND) continue;
    const int all = FB_SPEC_BODY_MASS | FB_SPEC_BODY_INERTIA | FB_SPEC_BODY_CENTRE;
    if ((s->body[g].given & all) != all) return 1;
  }
  return 0;
}

/* every slot's travel over a drive revolution of m (compiled from s with
 * the sliders where the assembly puts them) into travel; FB_OK with
 * travel left NaN when m does not turn a revolution (its own checks say
 * why) */
static fb_status slot_travel(travel_t *travel, const fb_planar *m, const fb_planar_spec *s,
                             fb_diag *diag) {
  const int ns = fb_planar_slide_count(m), nq = fb_planar_nq(m);
  for (int j = 0; j < s->njoints; j++) travel[j][0][0] = NAN;
  fb_planar_kin *k;
  fb_diag inner;
  if (fb_planar_kin_new(&k, m, &inner) != FB_OK) return FB_OK;
  double *row = malloc(((size_t)fb_planar_output_count(m) + 1) * sizeof *row);
  double *q = calloc(3 * (size_t)nq + 1, sizeof *q);
  fb_planar_extreme *e = malloc(((size_t)ns + 1) * sizeof *e);
  fb_status st = row && q && e ? FB_OK : fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  /* any speed: positions do not depend on it */
  if (st == FB_OK && fb_planar_extremes_of(e, ns, slide_position, row, k, 1.0, &inner) == FB_OK) {
    fb_planar_assembly(m, q);
    fb_planar_outputs(row, m, q, q + nq, q + 2 * nq); /* the slides at the assembly */
    for (int j = 0, i = 0; j < m->njoints; j++) {
      if (m->joint[j].kind != FB_KIND_PRISMATIC) continue;
      const double s0 = row[FB_PLANAR_POINT_QUANTITIES * m->npoints + FB_PLANAR_SLIDE_QUANTITIES * i];
      const double u[2] = {cos(s->joint[j].axis), sin(s->joint[j].axis)};
      const double end[2] = {e[i].min, e[i].max};
      for (int x = 0; x < 2 && isfinite(end[0]) && isfinite(end[1]); x++) {
        travel[j][x][0] = s->joint[j].at[0] + (end[x] - s0) * u[0];
        travel[j][x][1] = s->joint[j].at[1] + (end[x] - s0) * u[1];
      }
      i++;
    }
  }
  free(row);
  free(q);
  free(e);
  fb_planar_kin_free(k);
  return st;
}

fb_status fb_planar_compile(fb_planar **out, const fb_planar_spec *s, double density,
                            fb_planar_where *where, fb_diag *diag) {
  fb_status st = compile(out, s, density, NULL, where, diag);
  if (st != FB_OK || s->undriven || !slot_derived(s)) return st;
  /* a slot's material spans its slider's travel over a revolution, not
   * the point where the assembly puts the slider: compiled again with it */
  travel_t travel[FB_PLANAR_SPEC_MAX_JOINTS];
  st = slot_travel(travel, *out, s, diag);
  int known = 0;
  for (int j = 0; j < s->njoints; j++) known |= isfinite(travel[j][0][0]);
  fb_planar *again = NULL;
  if (st == FB_OK && known) st = compile(&again, s, density, (const travel_t *)travel, where, diag);
  if (st != FB_OK || again) {
    fb_planar_free(*out);
    *out = again;
  }
  return st;
}

fb_status fb_planar_of_case(fb_planar **out, const fb_case *c, const fb_linkage *lengths,
                            fb_diag *diag) {
  if (c->planar.on) return fb_planar_compile(out, &c->planar, c->density, NULL, diag);
  return fb_closed_form_of(c->mechanism)->planar(out, lengths, c->branch, c->link,
                                                 c->crank_angle0, diag);
}
