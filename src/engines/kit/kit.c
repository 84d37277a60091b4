/* The engine kit's walk (kit.h): a planar description built through an
 * engine's binding, stepped, sampled. */
#include "kit.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "clock.h"
#include "kit_adaptive.h"
#include "kit_contact.h"
#include "kit_record.h"
#include "planar_constraints.h"
#include "planar_kinematics.h"
#include "planar_loads.h"
#include "series.h"

/* qd: every moving body's velocity at the assembly configuration with the
 * drive at omega (the core's velocity analysis) */
static fb_status start_velocities(double *qd, const fb_planar *m, double omega, fb_diag *diag) {
  fb_planar_kin *k;
  fb_status st = fb_planar_kin_new(&k, m, diag);
  if (st != FB_OK) return st;
  const int nq = fb_planar_nq(m);
  double *q = malloc((size_t)nq * sizeof *q);
  if (!q) st = fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  if (st == FB_OK) {
    fb_planar_assembly(m, q);
    st = fb_planar_position(k, q, 0.0, NULL, diag);
  }
  const fb_planar_drive d = {0.0, omega, 0.0};
  if (st == FB_OK) st = fb_planar_motion(k, qd, NULL, q, &d, NULL, diag);
  free(q);
  fb_planar_kin_free(k);
  return st;
}

/* the kit's handle of description body b */
static int handle(int b) { return b == FB_PLANAR_GROUND ? FB_KIT_GROUND : b - 1; }

/* bodies that no ideal joint holds are held in the plane, if the engine
 * needs it */
static fb_status hold(const fb_kit_binding *b, void *w, const fb_planar *m, unsigned mask,
                      fb_diag *diag) {
  fb_status st = FB_OK;
  for (int i = 1; i < m->nbodies && st == FB_OK && b->hold_in_plane; i++) {
    int held = 0;
    for (int j = 0; j < m->njoints; j++)
      if (!(mask & (1u << j)) && (m->joint[j].body[0] == i || m->joint[j].body[1] == i)) held = 1;
    if (!held) st = b->hold_in_plane(w, handle(i), diag);
  }
  return st;
}

/* axis: prismatic joint pj's slide direction from its body[0]'s frame into
 * the world at the start (q; moved: not the assembly) */
static void slide_axis(double axis[2], const fb_planar *m, const double *q, int moved,
                       const fb_planar_joint *pj) {
  fb_planar_rotate(axis, moved ? fb_planar_angle(q, pj->body[0]) : m->body[pj->body[0]].angle0,
                   pj->axis);
}

/* description joint index of the joint added at place (mask's joints
 * not added), or -1 */
static int joint_at(const fb_planar *m, unsigned mask, int place) {
  for (int j = 0, added = 0; m && j < m->njoints; j++) {
    if (mask & (1u << j)) continue;
    if (added++ == place) return j;
  }
  return -1;
}

/* the driven joint's place among the joints added, -1: none (undriven,
 * or clearance at the driven joint) */
static int drive_place(const fb_planar *m, unsigned mask) {
  if (m->drive < 0 || (mask & (1u << m->drive))) return -1;
  int place = 0;
  for (int j = 0; j < m->drive; j++) place += !(mask & (1u << j));
  return place;
}

const char *fb_kit_joint_name(const fb_kit_world *o, int place) {
  const int j = o->mech && place >= 0 ? joint_at(o->mech, o->mask, place) : -1;
  return j < 0 ? "?" : o->mech->joint[j].name;
}

const char *fb_kit_body_name(const fb_kit_world *o, int b) {
  if (!o->mech || b < FB_KIT_GROUND || b + 1 >= o->mech->nbodies) return "?";
  return o->mech->body[b == FB_KIT_GROUND ? FB_PLANAR_GROUND : b + 1].name;
}

/* node i's root in a union-find forest, halving the path */
static int root_of(int *set, int i) {
  while (set[i] != i) i = set[i] = set[set[i]];
  return i;
}

int fb_kit_tree(const fb_kit_world *o, int njoints, const int (*ends)[2],
                const unsigned char *prismatic, const int *order, unsigned char *tree) {
  int set[FB_PLANAR_SPEC_MAX_BODIES + 1], nodes = 1; /* the ground and every moving body */
  for (int j = 0; j < njoints; j++) {
    tree[j] = 0;
    nodes = ends[j][0] + 2 > nodes ? ends[j][0] + 2 : nodes;
    nodes = ends[j][1] + 2 > nodes ? ends[j][1] + 2 : nodes;
  }
  if (o->mech && o->mech->nbodies > nodes) nodes = o->mech->nbodies;
  if (nodes > FB_PLANAR_SPEC_MAX_BODIES + 1) nodes = FB_PLANAR_SPEC_MAX_BODIES + 1;
  for (int i = 0; i < nodes; i++) set[i] = i;
  for (int pass = 0; pass < 3; pass++) /* the drive, the prismatic joints, the revolute ones */
    for (int r = 0; r < njoints; r++) {
      const int j = order ? order[r] : r;
      const int group = j == o->drive ? 0 : prismatic[j] ? 1 : 2;
      if (group != pass) continue;
      const int a = root_of(set, ends[j][0] + 1), b = root_of(set, ends[j][1] + 1);
      if (a == b) continue;
      set[a] = b;
      tree[j] = 1;
    }
  for (int j = 0; j < njoints; j++)
    if (!tree[j] && prismatic[j]) return j;
  return -1;
}

/* the walk: bodies at q (the start's coordinates; moved: not the
 * assembly), joints (but the clearance joints of mask), loop closure,
 * drive */
static fb_status build(const fb_kit_binding *b, void *w, const fb_planar *m, double omega,
                       const double *q, const double *qd, int moved,
                       const fb_kit_clearance *cl, fb_diag *diag) {
  const unsigned mask = cl ? cl->mask : 0u;
  int added = 0, drive = -1; /* the engine's joints so far; the drive's among them */
  fb_status st = FB_OK;
  for (int i = 1; i < m->nbodies && st == FB_OK; i++) {
    const fb_planar_body *pb = &m->body[i];
    const double *x = q + 3 * (i - 1), *v = qd + 3 * (i - 1);
    const fb_kit_body kb = {pb->mass, pb->inertia, {x[0], x[1], x[2]}, {v[0], v[1], v[2]}};
    st = b->add_body(w, &kb, diag);
  }
  for (int j = 0; j < m->njoints && st == FB_OK; j++) {
    const fb_planar_joint *pj = &m->joint[j];
    const int b0 = handle(pj->body[0]), b1 = handle(pj->body[1]);
    if (mask & (1u << j)) { /* a pin in a hole or a slider in its guide: the contact each
                               step, or the engine's relation */
      fb_kit_clearance_joint cj = {b0, b1, {pj->at[0], pj->at[1]}, {pj->at[0], pj->at[1]},
                                   cl->radial_clearance, cl->pin_radius,
                                   cl->joint[j].law.restitution, cl->joint[j].law, m, cl,
                                   pj->kind, {0.0, 0.0}, {0.0, 0.0, 0.0}, cl->friction};
      if (moved) { /* each side's point where its body puts it at the start */
        fb_planar_point(cj.at, m, q, pj->body[0], pj->point[0]);
        fb_planar_point(cj.at_hole, m, q, pj->body[1], pj->point[1]);
      }
      if (pj->kind == FB_KIND_PRISMATIC) {
        slide_axis(cj.axis, m, q, moved, pj);
        if (cl->guide) cj.guide = cl->guide[j];
      }
      if (b->add_clearance) st = b->add_clearance(w, j, &cj, diag);
      continue;
    }
    if (j == m->drive) drive = added;
    added++;
    double at[2] = {pj->at[0], pj->at[1]}; /* where body[0] puts the joint at the start */
    if (moved) fb_planar_point(at, m, q, pj->body[0], pj->point[0]);
    if (pj->kind == FB_KIND_PRISMATIC) {
      double axis[2];
      slide_axis(axis, m, q, moved, pj);
      st = b->add_prismatic(w, b0, b1, at, axis, diag);
    } else {
      st = b->add_revolute(w, b0, b1, at, diag);
    }
  }
  if (st == FB_OK && b->close_loop) st = b->close_loop(w, diag);
  if (st == FB_OK) st = hold(b, w, m, mask, diag);
  if (st != FB_OK) return st;
  if (m->drive < 0) return b->add_drive(w, -1, 0.0, diag); /* undriven: the walk's end only */
  if (drive < 0)
    return fb_diag_set(diag, FB_ERR_ARG, "clearance at the driven joint '%s': the engine kit "
                       "drives an ideal joint only", m->joint[m->drive].name);
  /* the drive turns 'to' at omega relative to 'from'; the binding takes the
   * rate of the joint's body[1] relative to its body[0] */
  int from, to;
  fb_planar_drive_bodies(m, &from, &to);
  const double rate = m->joint[m->drive].body[1] == to ? omega : -omega;
  return b->add_drive(w, drive, rate, diag);
}

/* a step from sample i0 to sample i (i0 < i; i - i0 grid steps of the
 * series' h, one but for an adaptive step), as the series records it: the
 * step's length [s] and the share of it at sample u between them. An
 * adaptive run's last step may end past the series' last sample, as it
 * would go on (the samples inside it are written, not its end). */
typedef struct {
  size_t i0, i;
  double h;
} kit_span;

static double share(const kit_span *sp, size_t u) {
  return (double)(u - sp->i0) / (double)(sp->i - sp->i0);
}

/* where the series s keeps its samples (kit.h fb_kit_series.window): a
 * column's length, and the mask that takes sample u to its index, u &
 * mask (all ones when every sample is kept) */
static size_t column_length(const fb_kit_series *s) { return s->window ? s->window : s->n; }
static size_t index_mask(const fb_kit_series *s) { return s->window ? s->window - 1 : SIZE_MAX; }

/* sample sp->i of one coordinate's column q (position x, rate v) after
 * the step sp: the step gives its acceleration to every sample from the
 * one it started from, sp->i0, the configuration whose forces the engine
 * solved: *a, the engine's own there (kit.h's body_accel), or NULL: the
 * step's difference; the samples inside the step lie on the straight line
 * between its ends; the last sample keeps the acceleration before it.
 * Sample 0 (sp NULL) is the start, its acceleration set by its step. */
static void put(double *q, const fb_kit_series *s, const kit_span *sp, double x, double v,
                const double *a) {
  const size_t n = s->n, L = column_length(s), M = index_mask(s), i = sp ? sp->i : 0;
  double *qv = q + L, *qa = q + 2 * L;
  if (i < n) qa[i & M] = 0.0, q[i & M] = x, qv[i & M] = v;
  if (!sp) return;
  const size_t i0 = sp->i0;
  const double x0 = q[i0 & M], v0 = qv[i0 & M];
  const double acc = a ? *a : (v - v0) / sp->h;
  for (size_t u = i0; u < i && u < n; u++) qa[u & M] = acc;
  for (size_t u = i0 + 1; u < i && u < n; u++) {
    const double f = share(sp, u);
    q[u & M] = x0 + f * (x - x0);
    qv[u & M] = v0 + f * (v - v0);
  }
  if (i == n - 1) qa[i & M] = qa[(i - 1) & M];
}

/* an angle's change d [rad] brought into [-pi, pi]: remainder(d, 2 pi),
 * which is d itself (exactly: n = 0 in d - n 2 pi, a tie to even) where
 * |d| <= pi, as a step's turn almost always is; the call only where not */
static double turn_from(double d) { return fabs(d) <= M_PI ? d : remainder(d, 2.0 * M_PI); }

/* sample sp->i (sample 0: sp NULL) of every moving body and the samples
 * inside its step: angle unwrapped from the step's start; each body's pose
 * and velocity also into state, rate (3 nb each; NULL: not kept), the
 * clearance pipeline's */
static void sample(const fb_kit_binding *b, const void *w, fb_kit_series *s, int nb,
                   const kit_span *sp, double *state, double *rate) {
  const size_t n = s->n, L = column_length(s), M = index_mask(s), i = sp ? sp->i : 0;
  for (size_t u = sp ? sp->i0 + 1 : 0; u <= i && u < n; u++) s->t[u & M] = (double)u * s->h;
  const int own = sp && b->body_accel; /* the engine's accelerations at the step's start */
  for (int k = 0; k < nb; k++) {
    double pos[3], vel[3], acc[3];
    b->body_state(w, k, pos, vel);
    if (own) b->body_accel(w, k, acc);
    if (state) memcpy(state + 3 * k, pos, sizeof pos), memcpy(rate + 3 * k, vel, sizeof vel);
    double *q = s->q + (size_t)k * 3 * L;
    const double a = sp ? q[sp->i0 & M] + turn_from(pos[2] - q[sp->i0 & M]) : pos[2];
    put(q, s, sp, a, vel[2], own ? &acc[2] : NULL);
    if (!s->centre) continue;
    put(s->centre + (size_t)k * 3 * L, s, sp, pos[0], vel[0], own ? &acc[0] : NULL);
    put(s->centre + (size_t)(nb + k) * 3 * L, s, sp, pos[1], vel[1], own ? &acc[1] : NULL);
  }
}

/* A kit run under way (kit.h, fb_kit_open). */
struct fb_kit_runner {
  const fb_kit_binding *b;
  const fb_planar *m;
  void *w;               /* the engine's world */
  fb_kit_clearance *cl;  /* NULL: every joint ideal */
  fb_kit_series *s;
  fb_kit_pipe p;         /* the clearance pipeline's state between steps */
  fb_kit_world o;        /* the caller's world settings, the walk's fields set (kit.h) */
  fb_kit_adapt ad;       /* the adaptive step's state (ad.on 0: every step the series' h) */
  int mc;                /* the coming step's grid steps */
  kit_span last;         /* the last step (last.i 0 before the first) */
  size_t i;              /* samples filled; the coming step starts from sample i - 1 */
  size_t written;        /* samples whose time and motion are written (fb_kit_written) */
  fb_status st;          /* FB_OK, or what stopped the run (sticky) */
  double *lq;            /* (3 nq) a description with springs or loads: the state a step
                            starts from (q, q') and their generalised forces; NULL: none */
};

/* the springs' and loads' forces on every moving body over the coming
 * step, from the state it starts from (kit.h apply_wrench) */
static void wrenches(fb_kit_runner *k) {
  const fb_planar *m = k->m;
  const int nq = fb_planar_nq(m), nb = m->nbodies - 1;
  double *q = k->lq, *qd = q + nq, *f = qd + nq;
  for (int b = 0; b < nb; b++) k->b->body_state(k->w, b, q + 3 * b, qd + 3 * b);
  fb_planar_applied(f, m, q, qd, 0.0); /* gravity: the engine's own */
  for (int b = 0; b < nb; b++) k->b->apply_wrench(k->w, b, f + 3 * b);
}

/* clearance joint j's columns at sample sp->i (kit.h,
 * fb_kit_joint_record): the step sp gives its force, largest force and
 * contact state to every sample from the one it started from; the state
 * read now its penetration and eccentricity, those inside the step on the
 * straight line from its start; the last sample keeps its step's force and
 * state from the one before. Sample 0: sp NULL. */
static void record(fb_kit_runner *k, int j, const kit_span *sp) {
  const fb_kit_binding *b = k->b;
  const fb_kit_series *s = k->s;
  const size_t n = s->n, L = column_length(s), M = index_mask(s), i = sp ? sp->i : 0;
  fb_kit_joint_record *r = &k->cl->joint[j];
  if (sp) {
    const double f = fb_kit_pipe_force(&k->p, b, k->w, k->m, j);
    const double fm = b->contact_force_max ? fmax(b->contact_force_max(k->w, j), f) : f;
    /* the episode of the step from sp->i0 */
    const double z = f > 0.0 ? (double)fb_kit_pipe_state(&k->p, k->m, j) : FB_STATE_FREE;
    for (size_t u = sp->i0; u < i && u < n; u++) {
      if (r->force) r->force[u & M] = f;
      if (r->force_max) r->force_max[u & M] = fm;
      if (r->state) r->state[u & M] = z;
    }
  }
  if (r->pen && i < n) r->pen[i & M] = k->p.pen[j];
  if (r->ecc && i < n) r->ecc[i & M] = k->p.ecc[j][0], r->ecc[L + (i & M)] = k->p.ecc[j][1];
  for (size_t u = sp ? sp->i0 + 1 : i; u < i && u < n; u++) {
    const double f = share(sp, u);
    if (r->pen) r->pen[u & M] = r->pen[sp->i0 & M] + f * (k->p.pen[j] - r->pen[sp->i0 & M]);
    for (int c = 0; r->ecc && c < 2; c++) {
      double *e = r->ecc + (size_t)c * L;
      e[u & M] = e[sp->i0 & M] + f * (k->p.ecc[j][c] - e[sp->i0 & M]);
    }
  }
  if (i + 1 != n) return;
  if (r->force) r->force[i & M] = i > 0 ? r->force[(i - 1) & M] : 0.0;
  if (r->force_max) r->force_max[i & M] = r->force ? r->force[i & M] : 0.0;
  if (r->state) r->state[i & M] = i > 0 ? r->state[(i - 1) & M] : FB_STATE_FREE;
}

/* the joint reactions and the drive torque of step sp, at every sample
 * from the one it started from (the last sample keeps them): an ideal
 * joint's from the binding (reactions, by its place among the joints
 * added), a clearance joint's from its contact at the state last read, the
 * step's start (fb_kit_pipe_reaction); the drive's torque on the driven
 * body, the driven joint's moment (kit.h's fb_kit_series) */
static void loads(fb_kit_runner *k, const kit_span *sp) {
  const fb_kit_binding *b = k->b;
  const fb_planar *m = k->m;
  fb_kit_series *s = k->s;
  const size_t n = s->n, L = column_length(s), M = index_mask(s), i = sp->i;
  const unsigned mask = k->cl ? k->cl->mask : 0u;
  double torque = 0.0;
  for (int j = 0, added = 0; j < m->njoints; j++) {
    double r[3] = {0.0, 0.0, 0.0};
    if (mask & (1u << j)) fb_kit_pipe_reaction(&k->p, b, k->w, m, j, r);
    else b->reactions(k->w, added++, r);
    if (j == m->drive) { /* the driven body's side of the joint's couple */
      int from, to;
      fb_planar_drive_bodies(m, &from, &to);
      torque = m->joint[j].body[1] == to ? r[2] : -r[2];
    }
    for (int c = 0; c < 3; c++) {
      double *col = s->reaction + (size_t)(3 * j + c) * L;
      for (size_t u = sp->i0; u < i && u < n; u++) col[u & M] = r[c];
      if (i + 1 == n) col[i & M] = r[c];
    }
  }
  if (m->torque_joint >= 0) { /* a torque drive: its torque on the body it turns */
    const fb_planar_joint *jt = &m->joint[m->torque_joint];
    torque = jt->body[1] != FB_PLANAR_GROUND ? m->drive_torque : -m->drive_torque;
  }
  for (size_t u = sp->i0; u < i && u < n; u++) s->torque[u & M] = torque;
  if (i + 1 == n) s->torque[i & M] = torque;
}

/* the loop-closure drift at sample sp->i (sample 0: sp NULL) into
 * s->drift (kit.h): the largest separation of an ideal revolute joint's two
 * points at the state read (k->p.q), each body's rotation formed once a
 * read (the clearance contacts' and closed form's too); the samples inside
 * the step on the straight line from its start */
static void drift_at(fb_kit_runner *k, const kit_span *sp) {
  const fb_planar *m = k->m;
  fb_kit_series *s = k->s;
  const size_t n = s->n, M = index_mask(s), i = sp ? sp->i : 0;
  const unsigned mask = k->cl ? k->cl->mask : 0u;
  double worst2 = 0.0; /* the largest squared separation [m^2] */
  for (int j = 0; j < m->njoints; j++) {
    const fb_planar_joint *pj = &m->joint[j];
    if ((mask & (1u << j)) || pj->kind != FB_KIND_REVOLUTE) continue;
    double x[2][2];
    for (int e = 0; e < 2; e++)
      fb_planar_point_at(x[e], k->p.q, pj->body[e], pj->point[e],
                         fb_kit_pipe_rotation(&k->p, pj->body[e]));
    const double dx = x[0][0] - x[1][0], dy = x[0][1] - x[1][1], d2 = dx * dx + dy * dy;
    if (d2 > worst2) worst2 = d2;
  }
  const double worst = sqrt(worst2);
  if (i < n) s->drift[i & M] = worst;
  if (!sp) return;
  const double d0 = s->drift[sp->i0 & M];
  for (size_t u = sp->i0 + 1; u < i && u < n; u++)
    s->drift[u & M] = d0 + share(sp, u) * (worst - d0);
}

/* after sample i (sp: the step to it; NULL for sample 0): the springs'
 * and loads' forces, the clearance joints' columns, the drift, and before
 * the next step its size (the adaptive step's) and the clearance contacts
 * for it */
static fb_status after_sample(fb_kit_runner *k, const kit_span *sp, fb_diag *diag) {
  const fb_kit_binding *b = k->b;
  const fb_planar *m = k->m;
  fb_kit_clearance *cl = k->cl;
  fb_kit_series *s = k->s;
  const size_t i = sp ? sp->i : 0;
  if (k->lq && i + 1 < s->n) wrenches(k);
  if (cl) {
    fb_kit_pipe_read(&k->p, b, k->w, m, cl);
    for (int j = 0; j < m->njoints; j++)
      if (cl->mask & (1u << j)) record(k, j, sp);
  } else {
    fb_kit_pipe_rotations(&k->p, b, k->w, m); /* sample() wrote the state anew (kept for
                                                 the drift) */
  }
  if (s->drift) drift_at(k, sp);
  if (i + 1 >= s->n) return FB_OK;
  k->mc = 1;
  fb_status st = FB_OK;
  if (k->ad.on && (st = fb_kit_adapt_multiple(&k->mc, &k->ad, &k->p, b, m, cl, diag)) != FB_OK)
    return st;
  if (cl) st = fb_kit_pipe_contacts(&k->p, b, k->w, m, cl, k->mc * s->h, diag);
  return st;
}

/* 1: the samples' states go to the pipeline's q, qd (the clearance
 * contacts read them; the drift is taken there) */
static int kept(const fb_kit_runner *k) { return k->cl || k->s->drift; }

/* sample 0, the start */
static fb_status first_sample(fb_kit_runner *k, fb_diag *diag) {
  const fb_planar *m = k->m;
  fb_kit_series *s = k->s;
  sample(k->b, k->w, s, m->nbodies - 1, NULL, kept(k) ? k->p.q : NULL,
         kept(k) ? k->p.qd : NULL);
  k->written = 1;
  if (s->torque && s->n == 1) { /* no step: no loads */
    s->torque[0] = 0.0;
    for (int c = 0; c < 3 * m->njoints; c++) s->reaction[(size_t)c * column_length(s)] = 0.0;
  }
  return after_sample(k, NULL, diag);
}

/* column x inside step sp (index mask M): on the straight line between
 * its ends */
static void line(double *x, size_t M, const kit_span *sp) {
  for (size_t u = sp->i0 + 1; u < sp->i; u++)
    x[u & M] = x[sp->i0 & M] + share(sp, u) * (x[sp->i & M] - x[sp->i0 & M]);
}

/* a binding whose samples are the engine's own at each state (kit.h
 * body_accel): the accelerations, contact forces and loads of the samples
 * inside step sp on the straight line between its ends' (each end's its
 * own), once the step after it has given its end's; its positions and
 * rates are already (put) */
static void inside_lines(fb_kit_runner *k, const kit_span *sp) {
  fb_kit_series *s = k->s;
  const size_t n = s->n, L = column_length(s), M = index_mask(s);
  if (!k->b->body_accel || sp->i - sp->i0 < 2 || sp->i >= n) return;
  const int nb = k->m->nbodies - 1;
  for (int b = 0; b < nb; b++) {
    line(s->q + ((size_t)b * 3 + 2) * L, M, sp);
    for (int c = 0; s->centre && c < 2; c++)
      line(s->centre + ((size_t)(c * nb + b) * 3 + 2) * L, M, sp);
  }
  for (int j = 0; k->cl && j < k->m->njoints; j++) {
    const fb_kit_joint_record *r = &k->cl->joint[j];
    if (!(k->cl->mask & (1u << j))) continue;
    if (r->force) line(r->force, M, sp);
    if (r->force_max) line(r->force_max, M, sp);
  }
  if (!s->torque) return;
  line(s->torque, M, sp);
  for (int c = 0; c < 3 * k->m->njoints; c++) line(s->reaction + (size_t)c * L, M, sp);
}

/* the coming step, from sample k->i - 1 over k->mc grid steps, and the
 * samples it reaches: its end's and those inside it */
static fb_status next_step(fb_kit_runner *k, fb_diag *diag) {
  const fb_kit_binding *b = k->b;
  fb_kit_series *s = k->s;
  const kit_span sp = {k->i - 1, k->i - 1 + (size_t)k->mc, k->mc * s->h};
  fb_status st = k->ad.on ? b->step_by(k->w, sp.h, diag) : b->step(k->w, diag);
  if (st != FB_OK) return st;
  fb_kit_stats_add(&s->stats, sp.h);
  fb_kit_pipe_stepped(&k->p, b, k->w, sp.h);
  if (s->torque) loads(k, &sp); /* at the step's start: before the pipe reads anew */
  sample(b, k->w, s, k->m->nbodies - 1, &sp, kept(k) ? k->p.q : NULL,
         kept(k) ? k->p.qd : NULL);
  k->written = sp.i < s->n ? sp.i + 1 : s->n;
  st = after_sample(k, &sp, diag);
  if (k->last.i > 0) inside_lines(k, &k->last); /* its end's values are this step's start's */
  k->last = sp;
  return st;
}

fb_status fb_kit_open(fb_kit_runner **out, const fb_kit_binding *b, const fb_planar *m,
                      double omega, const fb_kit_world *o, fb_kit_clearance *cl,
                      fb_kit_series *s, fb_diag *diag) {
  *out = NULL;
  const unsigned mask = cl ? cl->mask : 0u;
  if (mask && !b->add_contact && !(b->add_clearance && b->contact_force))
    return fb_diag_set(diag, FB_ERR_ARG, "the %s engine's binding has no clearance contact yet",
                       b->engine);
  if (fb_planar_has_loads(m) && !b->apply_wrench && !b->loads_from_state)
    return fb_diag_set(diag, FB_ERR_ARG, "the %s engine's binding applies no springs or loads "
                       "yet", b->engine);
  if (s->torque && !b->reactions)
    return fb_diag_set(diag, FB_ERR_ARG, "the %s engine's binding reports no joint reactions",
                       b->engine);
  if (s->torque && mask && b->add_clearance && !b->add_contact && !b->clearance_reaction)
    return fb_diag_set(diag, FB_ERR_ARG, "the %s engine's binding reports no clearance joint's "
                       "reaction", b->engine);
  const size_t window = fb_kit_window(o);
  if (s->window && (s->window & (s->window - 1) || s->window < window))
    return fb_diag_set(diag, FB_ERR_ARG, "a kit series' window of %zu samples: it must be a power "
                       "of two of at least %zu (fb_kit_window)", s->window, window);
  const double t0 = fb_clock_s();
  fb_kit_runner *k = calloc(1, sizeof *k);
  const int nq = fb_planar_nq(m);
  double *q = malloc(2 * (size_t)nq * sizeof *q);
  if (!k || !q) {
    free(k);
    free(q);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  }
  *k = (fb_kit_runner){.b = b, .m = m, .cl = cl, .s = s};
  double *qd = q + nq;
  fb_status st = FB_OK;
  if (o->q0) memcpy(q, o->q0, (size_t)nq * sizeof *q);
  else fb_planar_assembly(m, q);
  if (o->qd0) memcpy(qd, o->qd0, (size_t)nq * sizeof *qd);
  else if (m->drive < 0)
    st = fb_diag_set(diag, FB_ERR_ARG, "the %s engine's kit run of an undriven description "
                     "([drive] joint = none) needs its start velocities (the case's "
                     "initial_omega_rad_s, fb_kit_world's qd0)", b->engine);
  else st = start_velocities(qd, m, omega, diag);
  k->o = *o;
  k->o.mech = m;
  k->o.mask = mask;
  k->o.drive = drive_place(m, mask);
  if (st == FB_OK) st = b->world_new(&k->w, &k->o, diag);
  if (st == FB_OK) st = build(b, k->w, m, omega, q, qd, o->q0 != NULL, cl, diag);
  free(q);
  const fb_kit_clearance none = {0};
  if (st == FB_OK) st = fb_kit_pipe_new(&k->p, b, m, cl ? cl : &none, diag);
  if (st == FB_OK) st = fb_kit_adapt_open(&k->ad, &k->p, b, m, &k->o, cl, diag);
  const int held = fb_planar_has_loads(m) && !b->loads_from_state; /* apply_wrench's state */
  if (st == FB_OK && held && !(k->lq = malloc(3 * (size_t)nq * sizeof *k->lq)))
    st = fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  if (st != FB_OK) {
    fb_kit_close(k);
    return st;
  }
  s->stats = (fb_step_stats){0};
  s->setup_s = fb_clock_s() - t0;
  *out = k;
  return FB_OK;
}

size_t fb_kit_window(const fb_kit_world *o) {
  /* after fb_kit_advance(k, j) a reader needs samples j - 3 on; the kit
   * writes up to two steps ahead of the last final sample (an adaptive
   * run whose samples inside a step wait for the next, inside_lines) and
   * reads back to the start of the step before */
  const size_t need = 2 * (size_t)fb_kit_adapt_m_max(o) + 4;
  size_t w = 1;
  while (w < need) w *= 2;
  return w;
}

/* the samples final so far: every one filled, but those inside the last
 * step and its end where they wait for the next step's start (inside_lines:
 * an adaptive run of a binding with body_accel) */
static size_t final_samples(const fb_kit_runner *k) {
  if (k->i < k->s->n && k->ad.on && k->b->body_accel && k->last.i > 0) return k->last.i0 + 1;
  return k->i;
}

fb_status fb_kit_advance(fb_kit_runner *k, size_t n, fb_diag *diag) {
  if (k->st != FB_OK)
    return fb_diag_set(diag, k->st, "the %s engine's kit run stopped at sample %zu", k->b->engine,
                       k->i);
  while (final_samples(k) < n && k->i < k->s->n) {
    size_t to = k->i == 0 ? 1 : k->i + (size_t)k->mc;
    if (to > k->s->n) to = k->s->n; /* an adaptive step past the last sample */
    fb_status st = k->i == 0 ? first_sample(k, diag) : next_step(k, diag);
    if (st != FB_OK) return k->st = st;
    k->i = to;
  }
  return FB_OK;
}

size_t fb_kit_written(const fb_kit_runner *k) { return k->written; }

void fb_kit_close(fb_kit_runner *k) {
  if (!k) return;
  fb_kit_pipe_free(&k->p);
  if (k->w) k->b->world_free(k->w);
  free(k->lq);
  free(k);
}

fb_status fb_kit_run(const fb_kit_binding *b, const fb_planar *m, double omega,
                     const fb_kit_world *o, fb_kit_clearance *cl, fb_kit_series *s,
                     fb_diag *diag) {
  fb_kit_runner *k;
  fb_status st = fb_kit_open(&k, b, m, omega, o, cl, s, diag);
  if (st == FB_OK) st = fb_kit_advance(k, s->n, diag);
  fb_kit_close(k);
  return st;
}

fb_status fb_kit_model_text(const fb_kit_binding *b, const fb_planar *m, double omega,
                            const fb_kit_world *o, fb_kit_clearance *cl, char *buf, size_t size,
                            fb_diag *diag) {
  if (!b->model_text)
    return fb_diag_set(diag, FB_ERR_ARG, "the %s engine's binding writes no model file",
                       b->engine);
  fb_kit_series none = {0}; /* opened, never advanced: no sample is taken */
  fb_kit_world file = *o;
  file.model_file = 1;
  fb_kit_runner *k;
  fb_status st = fb_kit_open(&k, b, m, omega, &file, cl, &none, diag);
  if (st == FB_OK) st = b->model_text(k->w, buf, size, diag);
  fb_kit_close(k);
  return st;
}
