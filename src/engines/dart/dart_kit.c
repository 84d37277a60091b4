/* DART as a binding of the engine kit (kit.h): any planar description in
 * DART 6.12 as its experts build a mechanism (dart_world.h): the bodies
 * and joints are collected as the kit walks them, and close_loop makes
 * the skeleton (a tree of RevoluteJoints about +z and PrismaticJoints,
 * each loop closed at a pin by a BallJointConstraint of DART's constraint
 * solver, whose out-of-plane row is redundant: DART's CFM, relative to
 * the row's diagonal, keeps the LCP solvable). DART's constraint settings
 * are its own defaults (global ERP 0.01, CFM 1e-9 of the diagonal, error
 * reduction velocity at most 10 m/s), not the case's ODE world ERP and
 * CFM. The drive is the driven joint's SERVO actuator, tracked by the
 * constraint solver within [solver] drive_torque_max_n_m. A clearance
 * joint's contact (the kit's pipeline, kit_contact.h) is the law's force,
 * fb_contact_force, on the pin along -n and on the hole along +n at the
 * wall point, through DART's external force (BodyNode::addExtForce), as
 * MuJoCo's passive callback applies it. Each step is World::step:
 * semi-implicit Euler, the constraint impulses at the velocity level, an
 * external force held over the step, an O(h omega_c) error of a stiff
 * law. A model with a clearance joint therefore steps DART at
 * h / FB_DART_CLEARANCE_SUBSTEPS at least (World::setTimeStep), and a step
 * that starts in contact, or whose pin would reach the wall within it,
 * at as many sub-steps as the contact-adaptive step's impact rule asks
 * for (step_control.h: h omega_c <= FB_DART_SUBSTEP_H_OMEGA, omega_c at
 * the impact's depth estimate, at most FB_DART_SUBSTEPS_MAX), the law's
 * force evaluated anew at each sub-step's start from DART's state (the
 * kit's geometry on the description add_clearance hands; the law on the
 * effective mass the kit handed for the step, or for a contact within it
 * the law on the effective mass at the step's start). The kit samples
 * the grid of h as before; the ideal models step unsplit. The largest
 * force of each step's sub-steps is the kit's contact_force_max: a spike
 * sample of the force takes the largest between its neighbours, as the
 * reference's (series.h, fb_series_refine_peaks_max). Reactions (kit.h):
 * each ideal joint's from DART after each World::step (dart_world.h,
 * fb_dart_reaction: a tree joint's the wrench its child holds from its
 * parent, the servo's torque included; a loop's pin its constraint's
 * impulse over h), averaged over a sub-stepped step's sub-steps: the
 * step's impulse over h, the mean force behind the kit's acceleration
 * over the step (v_{i+1} - v_i) / h (the last sub-step's alone would be
 * the step's end, not the sample it is written at). */
#include "dart_kit.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "contact.h"
#include "contact_mass.h"
#include "dart_world.h"
#include "effective_mass.h"
#include "planar_constraints.h"
#include "planar_mass.h"
#include "planar_spec.h"
#include "step_control.h"

/* The sub-steps' accuracy, the largest h omega_c of a sub-step in contact
 * (step_control.h's impact rule) [-]: the law's force held over a step is
 * an O(h omega_c) error; on the planar four-bar (impact law, clearance at
 * crank-coupler) the second impact's peak force was +16 %, +4.4 % and
 * +2.05 % off at h = 1e-5, 2e-6 and 1e-6 s unsplit (docs/engines.md); a
 * finer rule (0.02, 0.01) brings the paper case's second impact closer
 * but moves its start-up's small impacts further (its worst matched
 * impact 0.031 -> 0.057): the approach's lag (below) was the rest */
#define FB_DART_SUBSTEP_H_OMEGA 0.05
/* The most sub-steps of one step [-]: the bound of the cost */
#define FB_DART_SUBSTEPS_MAX 64
/* The sub-steps of every step of a model with a clearance joint, in free
 * flight too [-]: DART's semi-implicit Euler in joint coordinates lags the
 * pin's free flight across the gap by about 0.4 h (paper case at h =
 * 3.317e-6 s, centred start: eccentricity 13.377 um at 0.1658 ms against
 * the reference's 13.610 um, ODE's 13.615 um), which moves the later
 * impacts' onsets by a sample and their approach speeds. Paper case,
 * impact law, the second impact's peak force against the reference's
 * (the sub-steps' largest force): +1.37 %, +0.81 %, +0.40 % with 4, 8,
 * 16; the worst of 17 matched impacts 0.031, 0.012, 0.008; CPU 1.0, 1.4,
 * 2.3 s (docs/engines.md, DART). 8 holds the paper case's first three
 * impacts of both laws within 1 % */
#define FB_DART_CLEARANCE_SUBSTEPS 8
/* A free step is sub-stepped when the pin, at its closing rate, would reach
 * the wall within this many steps [-]: 2 leaves room for the rate's growth
 * within the step (a pin reaching the wall unforeseen is met at the next
 * sample, as without sub-steps) */
#define FB_DART_REACH 2.0

/* a clearance joint's contact for the coming step (add_contact) */
typedef struct {
  int on;             /* 1: the step starts in contact */
  fb_contact_law law; /* its law, the damper on the effective mass */
  double v0;          /* the episode's onset rate [m/s] */
} dk_contact;

/* the binding's world: DART's, and what the sub-steps read */
typedef struct {
  fb_dart_world *dart;
  double h;                    /* the grid's step [s] */
  const fb_planar *m;          /* the description (add_clearance), NULL: no clearance joint */
  const fb_kit_clearance *cl;  /* its clearance joints */
  double *q, *qd;              /* the core's coordinates and rates read from DART (nq each) */
  int nsub;                    /* sub-steps of the coming step (>= 1) */
  unsigned char off[FB_PLANAR_SPEC_MAX_JOINTS]; /* 1: a clearance joint (planar_mass.h) */
  dk_contact ct[FB_PLANAR_SPEC_MAX_JOINTS];
  double fmax[FB_PLANAR_SPEC_MAX_JOINTS]; /* the largest force applied over the last step's
                                             sub-steps [N] (contact_force_max) */
  fb_kit_world o;              /* the walk's settings: names, drive (kit.h) */
  int nj;                      /* ideal joints added */
  int ends[FB_PLANAR_SPEC_MAX_JOINTS][2];     /* their body handles */
  unsigned char slide[FB_PLANAR_SPEC_MAX_JOINTS]; /* 1: prismatic */
  double *wrench;              /* (3 per body) the springs' and loads' force and torque of the
                                  coming step (apply_wrench), NULL: none handed */
} dk_world;

static fb_status dart_error(fb_status st, const char *what, const char *err, fb_diag *diag) {
  return fb_diag_set(diag, st, "DART %s: %s", what, err);
}

static fb_dart_world *dart(void *w) { return ((dk_world *)w)->dart; }

static fb_status kit_world_new(void **out, const fb_kit_world *o, fb_diag *diag) {
  dk_world *k = calloc(1, sizeof *k);
  if (k) k->dart = fb_dart_world_new(o->gravity, o->h, o->solver->world_erp,
                                     o->solver->drive_torque_max);
  if (!k || !k->dart) {
    free(k);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the DART world");
  }
  k->h = o->h;
  k->nsub = 1;
  k->o = *o;
  *out = k;
  return FB_OK;
}

static fb_status kit_add_body(void *w, const fb_kit_body *b, fb_diag *diag) {
  char err[FB_DIAG_SIZE];
  if (fb_dart_add_body(dart(w), b->mass, b->inertia, b->pos, b->vel, err, sizeof err) != 0)
    return dart_error(FB_ERR_NOMEM, "body", err, diag);
  return FB_OK;
}

static fb_status add_joint(void *w, int prismatic, int b0, int b1, const double at[2],
                           const double axis[2], fb_diag *diag) {
  char err[FB_DIAG_SIZE];
  dk_world *k = w;
  if (k->nj >= FB_PLANAR_SPEC_MAX_JOINTS)
    return fb_diag_set(diag, FB_ERR_RANGE, "the DART kit takes %d joints at most",
                       FB_PLANAR_SPEC_MAX_JOINTS);
  if (fb_dart_add_joint(dart(w), prismatic, b0, b1, at, axis, err, sizeof err) != 0)
    return dart_error(FB_ERR_NOMEM, "joint", err, diag);
  k->ends[k->nj][0] = b0, k->ends[k->nj][1] = b1, k->slide[k->nj++] = (unsigned char)prismatic;
  return FB_OK;
}

static fb_status kit_add_revolute(void *w, int b0, int b1, const double at[2], fb_diag *diag) {
  const double z[2] = {0.0, 0.0};
  return add_joint(w, 0, b0, b1, at, z, diag);
}

static fb_status kit_add_prismatic(void *w, int b0, int b1, const double at[2],
                                   const double axis[2], fb_diag *diag) {
  return add_joint(w, 1, b0, b1, at, axis, diag);
}

/* the tree (fb_kit_tree: the drive, the prismatic joints, then the
 * revolute ones in the order added), then the skeleton */
static fb_status kit_close_loop(void *w, fb_diag *diag) {
  char err[FB_DIAG_SIZE];
  dk_world *k = w;
  unsigned char tree[FB_PLANAR_SPEC_MAX_JOINTS];
  const int cut = fb_kit_tree(&k->o, k->nj, (const int (*)[2])k->ends, k->slide, NULL, tree);
  if (cut >= 0)
    return fb_diag_set(diag, FB_ERR_ARG, "DART cannot close a loop at prismatic joint '%s': "
                       "it closes a loop at a pin (BallJointConstraint), and the description's "
                       "prismatic joints (with the drive) form a loop, so one of them must close "
                       "it; make one of that loop's joints revolute", fb_kit_joint_name(&k->o, cut));
  if (fb_dart_build(dart(w), tree, err, sizeof err) != 0)
    return dart_error(FB_ERR_ARG, "skeleton", err, diag);
  return FB_OK;
}

static fb_status kit_add_drive(void *w, int joint, double rate, fb_diag *diag) {
  char err[FB_DIAG_SIZE];
  if (joint < 0) return FB_OK; /* undriven (kit.h): nothing to drive */
  if (fb_dart_drive(dart(w), joint, rate, err, sizeof err) != 0)
    return dart_error(FB_ERR_ARG, "drive", err, diag);
  return FB_OK;
}

/* clearance joint j: the description and the run's clearance joints,
 * which outlive the world (kit.h), for the sub-steps' own contact */
static fb_status kit_add_clearance(void *w, int j, const fb_kit_clearance_joint *cj,
                                   fb_diag *diag) {
  dk_world *k = w;
  if (j < 0 || j >= FB_PLANAR_SPEC_MAX_JOINTS)
    return fb_diag_set(diag, FB_ERR_ARG, "clearance joint %d out of range", j);
  if (cj->kind != FB_KIND_REVOLUTE) /* its sub-steps evaluate a pin in its hole */
    return fb_diag_set(diag, FB_ERR_ARG, "clearance at prismatic joint '%s' (a slider in its "
                       "guide): the DART binding's sub-steps take a pin in its hole only; ODE, "
                       "Bullet and MuJoCo build the slider's corners", cj->m->joint[j].name);
  if (!k->q) k->q = calloc(2 * (size_t)fb_planar_nq(cj->m), sizeof *k->q);
  if (!k->q) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the DART world");
  k->qd = k->q + fb_planar_nq(cj->m);
  k->m = cj->m;
  k->cl = cj->cl;
  k->off[j] = 1;
  return FB_OK;
}

/* DART's state now into the core's coordinates */
static void read_state(dk_world *k) {
  for (int b = 0; b < k->m->nbodies - 1; b++)
    fb_dart_body_state(k->dart, b, k->q + 3 * b, k->qd + 3 * b);
}

/* clearance joint j at the state read (the kit's geometry, kit_contact.c):
 * returns the penetration |e| - c [m] (< 0: the gap), its rate
 * n . (v_pin - v_hole) [m/s], the normal n and the wall point hole centre
 * + (pin radius + c) n [m] */
static double joint_now(const dk_world *k, int j, double *rate, double n[2], double at[2]) {
  const fb_planar *m = k->m;
  const fb_planar_joint *pj = &m->joint[j];
  double xp[2], vp[2], xh[2], vh[2];
  fb_planar_point(xp, m, k->q, pj->body[0], pj->point[0]);
  fb_planar_point_velocity(vp, m, k->q, k->qd, pj->body[0], pj->point[0]);
  fb_planar_point(xh, m, k->q, pj->body[1], pj->point[1]);
  fb_planar_point_velocity(vh, m, k->q, k->qd, pj->body[1], pj->point[1]);
  const double e[2] = {xp[0] - xh[0], xp[1] - xh[1]}, ecc = hypot(e[0], e[1]);
  const double r = k->cl->pin_radius + k->cl->radial_clearance;
  n[0] = ecc > 0.0 ? e[0] / ecc : 1.0;
  n[1] = ecc > 0.0 ? e[1] / ecc : 0.0;
  *rate = n[0] * (vp[0] - vh[0]) + n[1] * (vp[1] - vh[1]);
  at[0] = xh[0] + r * n[0];
  at[1] = xh[1] + r * n[1];
  return ecc - k->cl->radial_clearance;
}

/* the sub-steps of a step of h the contact state (delta, rate) on m_eff
 * asks for (step_control.h's impact rule) */
static int substeps(const fb_contact_law *law, double delta, double rate, double m_eff,
                    double h) {
  const fb_step_joint sj = {.delta = delta, .ddot = rate, .m_eff = m_eff,
                            .rule = FB_PERSIST_DEPTH_CHANGE, .tau_load = INFINITY};
  const double hs = fb_step_adaptive(law, &sj, FB_DART_SUBSTEP_H_OMEGA,
                                     h / FB_DART_SUBSTEPS_MAX, h);
  const int n = (int)ceil(h / hs * (1.0 - 1e-12));
  return n > FB_DART_SUBSTEPS_MAX ? FB_DART_SUBSTEPS_MAX : n;
}

/* the step's contact at joint j: its law and onset rate, and the
 * sub-steps the impact rule asks for (step_control.h) */
static fb_status kit_add_contact(void *w, int j, const fb_kit_contact *c, fb_diag *diag) {
  dk_world *k = w;
  if (j < 0 || j >= FB_PLANAR_SPEC_MAX_JOINTS || !k->m)
    return fb_diag_set(diag, FB_ERR_ARG, "the DART kit has no clearance joint %d", j);
  k->ct[j] = (dk_contact){.on = 1, .law = c->law, .v0 = c->v0};
  const int n = substeps(&c->law, c->depth, c->rate, c->m_eff, c->h);
  if (n > k->nsub) k->nsub = n;
  return FB_OK;
}

/* a free clearance joint j whose pin reaches the wall within the step at
 * its closing rate (FB_DART_REACH steps of it): the step is sub-stepped
 * from its start with the law on the effective mass now, as the kit's
 * pipeline puts it (the onset then falls on a sub-step, not on the next
 * sample) */
static fb_status onset_within(dk_world *k, int j, fb_diag *diag) {
  double rate, n[2], at[2];
  const double delta = joint_now(k, j, &rate, n, at);
  if (!(delta + FB_DART_REACH * rate * k->h > 0.0)) return FB_OK;
  double wi[2][2];
  fb_status st = fb_planar_effective_mass_tensor(wi, k->m, k->q, k->off, j, diag);
  if (st != FB_OK) return st;
  const double me = fb_effective_mass_along(wi, n);
  const fb_contact_law *law = &k->cl->joint[j].law;
  const double m_eff = isfinite(me) && me > 0.0 ? me : law->mass;
  k->ct[j] = (dk_contact){.on = 1, .law = fb_contact_law_on_mass(law, m_eff),
                          .v0 = rate};
  const int ns = substeps(&k->ct[j].law, delta, rate, m_eff, k->h);
  if (ns > k->nsub) k->nsub = ns;
  return FB_OK;
}

/* the law's force of every clearance joint handed or predicted for the
 * step at the state read_state read last (DART's now), on the pin along
 * -n and on the hole along +n at the wall point; none while the pin is off
 * the wall */
static void apply_contacts(dk_world *k) {
  for (int j = 0; j < k->m->njoints; j++) {
    if (!k->ct[j].on) continue;
    double rate, n[2], at[2];
    const double delta = joint_now(k, j, &rate, n, at);
    if (!(delta > 0.0)) continue;
    const double f = fb_contact_force(&k->ct[j].law, delta, rate, k->ct[j].v0);
    k->fmax[j] = fmax(k->fmax[j], f);
    const double on_pin[2] = {-f * n[0], -f * n[1]};
    const fb_planar_joint *pj = &k->m->joint[j];
    fb_dart_add_force(k->dart, pj->body[0] - 1, pj->body[1] - 1, at, on_pin);
  }
}

/* one grid step of h: nsub World::step calls of h / nsub, the contacts'
 * forces at each one's start */
static fb_status kit_step(void *w, fb_diag *diag) {
  dk_world *k = w;
  char err[FB_DIAG_SIZE];
  fb_status st = FB_OK;
  if (k->m) read_state(k);
  for (int j = 0; j < FB_PLANAR_SPEC_MAX_JOINTS; j++) k->fmax[j] = 0.0;
  for (int j = 0; k->m && j < k->m->njoints && st == FB_OK; j++)
    if (k->off[j] && !k->ct[j].on) st = onset_within(k, j, diag);
  if (k->m && k->nsub < FB_DART_CLEARANCE_SUBSTEPS) k->nsub = FB_DART_CLEARANCE_SUBSTEPS;
  const int n = k->nsub;
  if (n > 1) fb_dart_set_step(k->dart, k->h / n);
  fb_dart_reactions_clear(k->dart);
  for (int i = 0; i < n && st == FB_OK; i++) {
    if (k->m && i > 0) read_state(k); /* the first sub-step's state is read above */
    if (k->m) apply_contacts(k);
    for (int b = 0; k->wrench && b < k->o.nbodies; b++) /* every sub-step: DART clears them */
      fb_dart_add_wrench(k->dart, b, k->wrench + 3 * b);
    if (fb_dart_step(k->dart, err, sizeof err) != 0)
      st = dart_error(FB_ERR_NUMERIC, "step", err, diag);
  }
  if (n > 1) fb_dart_set_step(k->dart, k->h);
  for (int j = 0; j < FB_PLANAR_SPEC_MAX_JOINTS; j++) k->ct[j].on = 0;
  k->nsub = 1;
  return st;
}

static double kit_contact_force_max(const void *w, int j) {
  return j >= 0 && j < FB_PLANAR_SPEC_MAX_JOINTS ? ((const dk_world *)w)->fmax[j] : 0.0;
}

/* ideal joint j's reaction over the last step (kit.h): its sub-steps' mean */
static void kit_reactions(const void *w, int j, double out[3]) {
  fb_dart_reaction(((const dk_world *)w)->dart, j, out);
}

static void kit_body_state(const void *w, int b, double pos[3], double vel[3]) {
  fb_dart_body_state(((const dk_world *)w)->dart, b, pos, vel);
}

/* kept for every sub-step of the coming step (kit_step) */
static void kit_apply_wrench(void *w, int b, const double f[3]) {
  dk_world *k = w;
  if (!k->wrench) k->wrench = calloc(3 * (size_t)k->o.nbodies, sizeof *k->wrench);
  if (k->wrench) memcpy(k->wrench + 3 * b, f, 3 * sizeof *f);
}

static void kit_world_free(void *w) {
  dk_world *k = w;
  if (!k) return;
  fb_dart_world_free(k->dart);
  free(k->wrench);
  free(k->q);
  free(k);
}

const fb_kit_binding fb_dart_kit = {
    .engine = "dart",
    .world_new = kit_world_new,
    .add_body = kit_add_body,
    .add_revolute = kit_add_revolute,
    .add_prismatic = kit_add_prismatic,
    .close_loop = kit_close_loop,
    .add_drive = kit_add_drive,
    .hold_in_plane = NULL, /* DART's joints are planar: a free body is a PlanarJoint root */
    .add_contact = kit_add_contact,
    .contact_force = NULL, /* the law's force at each step's start, as the kit computes it */
    .step = kit_step,
    .body_state = kit_body_state,
    .world_free = kit_world_free,
    .add_clearance = kit_add_clearance,
    .contact_force_max = kit_contact_force_max,
    .apply_wrench = kit_apply_wrench,
    .reactions = kit_reactions,
};
