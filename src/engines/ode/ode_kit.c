/* ODE as a binding of the engine kit (kit.h): any planar description in
 * ODE as the four-bar world (ode_world.c) builds its own. A body is an ODE
 * rigid body (its moment about +z the description's; about its in-plane
 * axes half of it each, a thin plate's, which no planar motion excites);
 * a revolute joint is a hinge about +z (dJointCreateHinge), a prismatic
 * one a slider joint along its axis (dJointCreateSlider); the loops close
 * through the joints themselves (3-D hinges over-constrain a planar loop
 * by three rows each; the world CFM absorbs them, as in the four-bar); the
 * drive is the driven hinge's velocity motor (dParamVel, dParamFMax =
 * [solver] drive_torque_max_n_m). A clearance joint (kit.h's pipeline
 * computes its contact) is ODE's soft contact row as the exact collider
 * makes it (ode_clearance.c): the law mapped at the effective mass to ERP
 * and CFM (ode_contact.h), the matched-static row's drift correction, on
 * the hole wall, Coulomb friction at [clearance] friction, its force read
 * back from the row's feedback. With [clearance] collider = faceted or ccd
 * (kit.h's fb_kit_collider) a pin's contacts are ODE's generic colliders'
 * instead (ode_colliders.h, the hand-built world's): a ring of ODE boxes
 * around an ODE cylinder, or the libccd bore, built on the joint's bodies
 * by add_clearance; collide finds the contacts, add_contact hands a row per
 * contact on the effective mass along its own normal (the kit's tensor
 * fb_kit_contact.w_inv), split as the hand-built world splits them, and
 * collided tells the kit the rows. The world's ERP,
 * CFM, stepper (dWorldStep or dWorldQuickStep with its iterations) and
 * seed are the case's [solver] keys, gravity along -y; each step runs
 * under ODE's fatal-error escape (ode_env.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <ode/ode.h>

#include "effective_mass.h"
#include "kit.h"
#include "ode_colliders.h"
#include "ode_contact.h"
#include "ode_env.h"
#include "ode_kit.h"
#include "planar_spec.h"
#include "step_control.h"

/* what the binding keeps of an ideal joint for its reactions */
typedef struct {
  int b0, b1;            /* the kit's handles */
  double local[3];       /* the joint's point in the frame of b1 (b0 when b1 is the ground) [m] */
  double lever[2];       /* G - P at the last step's start: that body's centre of mass less the
                            joint's point on it [m] */
  dJointFeedback fb;     /* ODE's feedback of the last step */
} ode_kit_joint;

/* a pin whose contacts a generic collider finds (ode_colliders.h) */
typedef struct {
  ode_collider g;
  fb_contact_law law;          /* the joint's law; its damper on each row's effective mass */
  int split;                   /* the bore's rows: 0 by depth, 1 by count (fb_kit_collider) */
  double w[2][2];              /* the inverse-mass tensor of the coming step [1/kg] */
  double h;                    /* its step [s] */
  fb_contact_provenance rows;  /* its rows (contact_steps: how many) */
  double hw, wdh;              /* their largest h omega_c and omega_d h [-] */
  double c;                    /* the radial clearance [m] */
} ode_kit_gen;

typedef struct {
  dWorldID world;
  dBodyID *body;   /* (nbodies) */
  dJointID *joint; /* (njoints) */
  ode_kit_joint *jk; /* (njoints) */
  int nbodies, njoints;
  double h;
  fb_stepper stepper;
  double fmax;     /* drive torque limit [N m] */
  size_t steps;
  double t;        /* the time reached [s] */
  int broken;      /* an ODE error left the world mid-step */
  /* contacts by the kit's slot (kit.h: a pin's, or a slider's corner's):
   * this step's contact joint, its feedback, the share of its impulse that
   * is this step's (contact.h), the normal force of the last step [N] */
  dJointGroupID contacts;
  dJointID cj[FB_KIT_SLOTS];
  dJointFeedback fb[FB_KIT_SLOTS];
  double share[FB_KIT_SLOTS];
  double force[FB_KIT_SLOTS];
  double force_pin[FB_KIT_SLOTS][2]; /* the last step's force on the pin's body [N] */
  unsigned char pin_ground[FB_KIT_SLOTS]; /* 1: the slot's pin is the ground's (ODE reverses
                                             the joint: its feedback's body 1 is the hole's) */
  int slot[FB_KIT_SLOTS], nslots;         /* the slots with a row this step, and the last
                                             step's forces to clear */
  int last[FB_KIT_SLOTS], nlast;
  ode_kit_gen *gen[FB_PLANAR_SPEC_MAX_JOINTS]; /* a pin's generic collider by its joint, NULL:
                                                  the exact pin in its hole */
  /* the adaptive step with its rocking bound: the velocities carried
   * across a change of step (carry) */
  int rocking;     /* 1: [solver] h_s = adaptive with rocking_h_omega > 0 and clearance */
  int driven;      /* the body the drive turns against the ground, -1: none */
  double h_last;   /* the last step [s] (0 before the first) */
  double (*v_start)[4]; /* (nbodies) each body's linear velocity (x, y, z) and angular rate
                           about +z at the last step's start */
} ode_kit;

static fb_status kit_world_new(void **out, const fb_kit_world *o, fb_diag *diag) {
  ode_kit *k = calloc(1, sizeof *k);
  if (k) k->body = calloc((size_t)o->nbodies + 1, sizeof *k->body);
  if (k && k->body) k->joint = calloc((size_t)o->njoints + 1, sizeof *k->joint);
  if (k && k->joint) k->jk = calloc((size_t)o->njoints + 1, sizeof *k->jk);
  if (k && k->jk) k->v_start = calloc((size_t)o->nbodies + 1, sizeof *k->v_start);
  if (!k || !k->body || !k->joint || !k->jk || !k->v_start) {
    if (k) free(k->body), free(k->joint), free(k->jk);
    free(k);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the ODE world");
  }
  k->rocking = o->solver->h_mode == FB_STEP_ADAPTIVE && o->solver->rocking_h_omega > 0.0 &&
               o->mask != 0u;
  k->driven = -1;
  fb_ode_acquire();
  k->world = dWorldCreate();
  k->contacts = dJointGroupCreate(0);
  dWorldSetGravity(k->world, 0, -o->gravity, 0);
  dWorldSetERP(k->world, o->solver->world_erp);
  dWorldSetCFM(k->world, o->solver->world_cfm);
  dWorldSetQuickStepNumIterations(k->world, o->solver->quick_iterations);
  dRandSetSeed(o->solver->seed);
  if (o->contact_speed_max > 0.0) dWorldSetContactMaxCorrectingVel(k->world, o->contact_speed_max);
  k->h = o->h;
  k->stepper = o->solver->stepper;
  k->fmax = o->solver->drive_torque_max;
  *out = k;
  return FB_OK;
}

static fb_status kit_add_body(void *w, const fb_kit_body *b, fb_diag *diag) {
  (void)diag;
  ode_kit *k = w;
  dBodyID id = dBodyCreate(k->world);
  dMass m;
  dMassSetParameters(&m, b->mass, 0, 0, 0, 0.5 * b->inertia, 0.5 * b->inertia, b->inertia, 0, 0,
                     0);
  dBodySetMass(id, &m);
  dBodySetPosition(id, b->pos[0], b->pos[1], 0.0);
  dMatrix3 R;
  dRFromAxisAndAngle(R, 0, 0, 1, b->pos[2]);
  dBodySetRotation(id, R);
  dBodySetLinearVel(id, b->vel[0], b->vel[1], 0.0);
  dBodySetAngularVel(id, 0, 0, b->vel[2]);
  k->body[k->nbodies++] = id;
  return FB_OK;
}

/* ODE's body of a kit handle (0: the static environment) */
static dBodyID ode_body(const ode_kit *k, int b) { return b == FB_KIT_GROUND ? 0 : k->body[b]; }

/* attaches joint j between handles b0 and b1 at world point at [m]: ODE
 * wants the moving body first when one is the ground (ODE's body 1 is b1,
 * or b0 when b1 is the ground); its feedback kept for the reactions */
static void attach(ode_kit *k, dJointID j, int b0, int b1, const double at[2]) {
  if (b1 == FB_KIT_GROUND) dJointAttach(j, ode_body(k, b0), 0);
  else dJointAttach(j, ode_body(k, b1), ode_body(k, b0));
  ode_kit_joint *q = &k->jk[k->njoints];
  q->b0 = b0;
  q->b1 = b1;
  dVector3 l;
  dBodyGetPosRelPoint(ode_body(k, b1 == FB_KIT_GROUND ? b0 : b1), at[0], at[1], 0.0, l);
  for (int i = 0; i < 3; i++) q->local[i] = l[i];
  dJointSetFeedback(j, &q->fb);
  k->joint[k->njoints++] = j;
}

static fb_status kit_add_revolute(void *w, int b0, int b1, const double at[2], fb_diag *diag) {
  (void)diag;
  ode_kit *k = w;
  dJointID j = dJointCreateHinge(k->world, 0);
  attach(k, j, b0, b1, at);
  dJointSetHingeAnchor(j, at[0], at[1], 0.0);
  dJointSetHingeAxis(j, 0, 0, b1 == FB_KIT_GROUND ? -1 : 1);
  return FB_OK;
}

static fb_status kit_add_prismatic(void *w, int b0, int b1, const double at[2],
                                   const double axis[2], fb_diag *diag) {
  (void)diag;
  ode_kit *k = w;
  dJointID j = dJointCreateSlider(k->world, 0);
  attach(k, j, b0, b1, at);
  const double s = b1 == FB_KIT_GROUND ? -1.0 : 1.0;
  dJointSetSliderAxis(j, s * axis[0], s * axis[1], 0.0);
  return FB_OK;
}

static fb_status kit_add_drive(void *w, int joint, double rate, fb_diag *diag) {
  ode_kit *k = w;
  if (joint < 0) return FB_OK; /* undriven (kit.h): nothing to drive */
  dJointID j = k->joint[joint];
  if (dJointGetType(j) != dJointTypeHinge)
    return fb_diag_set(diag, FB_ERR_ARG, "the ODE kit drives a revolute joint only");
  dJointSetHingeParam(j, dParamVel, rate);
  dJointSetHingeParam(j, dParamFMax, k->fmax);
  const ode_kit_joint *q = &k->jk[joint];
  k->driven = q->b0 == FB_KIT_GROUND ? q->b1 : q->b1 == FB_KIT_GROUND ? q->b0 : -1;
  return FB_OK;
}

/* a body that only a clearance joint holds stays in the plane */
static fb_status kit_hold_in_plane(void *w, int b, fb_diag *diag) {
  (void)diag;
  ode_kit *k = w;
  dJointAttach(dJointCreatePlane2D(k->world, 0), k->body[b], 0);
  return FB_OK;
}

/* what ODE's position update adds to the displacement of the point at x
 * [m] of body handle b over a step of h [s] beyond the linear h (v + w x r)
 * a contact row sees: ODE turns the body by theta = 2 atan(h w / 2) (its
 * quaternion update, normalised), so the point at r from the centre of
 * mass moves by (cos theta - 1) r + (sin theta - h w) z x r more [m]
 * (w taken at the start of the step); 0 for the ground */
static void point_drift(const ode_kit *k, int b, const double x[2], double h, double out[2]) {
  out[0] = out[1] = 0.0;
  if (b == FB_KIT_GROUND) return;
  const dReal *o = dBodyGetPosition(k->body[b]);
  const double r[2] = {x[0] - o[0], x[1] - o[1]};
  const double w = dBodyGetAngularVel(k->body[b])[2];
  const double th = 2.0 * atan(0.5 * h * w);
  const double cm1 = -2.0 * sin(0.5 * th) * sin(0.5 * th), sw = sin(th) - h * w;
  out[0] = cm1 * r[0] - sw * r[1];
  out[1] = cm1 * r[1] + sw * r[0];
}

/* clearance joint k's generic collider (kit.h's fb_kit_collider): a ring
 * of boxes or a libccd bore on the hole's body around the pin's cylinder,
 * their centres the joint's points in each body's frame; the exact pin in
 * its hole (the kit's contact) otherwise, and a slider in its guide,
 * whose collider the kit refuses */
static fb_status kit_add_clearance(void *w, int k, const fb_kit_clearance_joint *c,
                                   fb_diag *diag) {
  ode_kit *kk = w;
  const fb_kit_collider *col = &c->cl->collider;
  if (c->kind != FB_KIND_REVOLUTE ||
      (col->kind != FB_COLLIDER_FACETED && col->kind != FB_COLLIDER_CCD))
    return FB_OK;
  ode_kit_gen *q = calloc(1, sizeof *q);
  if (!q) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for a collider");
  kk->gen[k] = q;
  const fb_planar_joint *pj = &c->m->joint[k];
  q->g.pin = ode_body(kk, c->pin);
  q->g.hole = ode_body(kk, c->hole);
  for (int i = 0; i < 2; i++) {
    q->g.pin_local[i] = pj->point[0][i];
    q->g.hole_local[i] = pj->point[1][i];
  }
  q->law = c->law;
  q->split = col->split;
  q->c = c->radial_clearance;
  const double r_hole = c->pin_radius + c->radial_clearance;
  if (col->kind == FB_COLLIDER_FACETED)
    return ode_collider_faceted(&q->g, col->facets, c->pin_radius, r_hole, col->pin_length, diag);
  return ode_collider_ccd(&q->g, col->segments, col->ovality, c->pin_radius, r_hole,
                          col->pin_length, diag);
}

/* clearance joint k's generic collider's contacts now (kit.h collide) */
static int kit_collide(void *w, int k, double *rate) {
  ode_kit_gen *q = ((ode_kit *)w)->gen[k];
  const int n = ode_collider_hits(&q->g);
  *rate = n > 0 ? q->g.hit[q->g.lead].rate : 0.0;
  return n;
}

/* a row's effective mass along unit n from the kit's tensor, the law's own
 * mass where it gives none (as the kit's and the hand-built world's) */
static double gen_mass(void *user, const double n[2]) {
  ode_kit_gen *q = user;
  const double me = fb_effective_mass_along(q->w, n);
  return isfinite(me) && me > 0.0 ? me : q->law.mass;
}

static void gen_note(void *user, const fb_contact_row *row, double share, double mass) {
  ode_kit_gen *q = user;
  ode_note_row(&q->rows, &q->hw, &q->wdh, row, share, mass, q->h);
}

/* the rows of joint j's generic collider's contacts (kit_collide) for the
 * coming step, on the kit's episode and persistence */
static fb_status gen_contact(ode_kit *k, int j, const fb_kit_contact *c) {
  ode_kit_gen *q = k->gen[j];
  memcpy(q->w, c->w_inv, sizeof q->w);
  q->h = c->h;
  memset(&q->rows, 0, sizeof q->rows);
  q->hw = q->wdh = 0.0;
  const ode_collider_step x = {.world = k->world, .group = k->contacts, .mass = gen_mass,
                               .note = gen_note, .user = q, .law = &q->law,
                               .mapping = c->mapping, .h = c->h, .friction = c->friction,
                               .persistence = c->persistence, .v0 = c->v0, .split = q->split};
  ode_collider_rows(&q->g, &x);
  k->pin_ground[j] = c->pin == FB_KIT_GROUND;
  k->slot[k->nslots++] = j;
  return FB_OK;
}

/* the rows joint k's last add_contact made (kit.h collided) */
static void kit_collided(const void *w, int k, fb_kit_rows *out) {
  const ode_kit_gen *q = ((const ode_kit *)w)->gen[k];
  const fb_contact_provenance *r = &q->rows;
  *out = (fb_kit_rows){.rows = r->contact_steps, .m_eff_min = r->mass_eff_min,
                       .m_eff_max = r->mass_eff_max, .erp_max = r->erp_max,
                       .cfm_min = r->cfm_min, .h_omega_max = q->hw, .omega_d_h_max = q->wdh};
}

/* joint k's pin's depth into its collider's hole now (kit.h penetration):
 * into the libccd bore, its closed form (fb_ccd_bore_depth); with the ring
 * of boxes |e| - c, as the hand-built world reports them */
static double kit_penetration(const void *w, int k) {
  const ode_kit_gen *q = ((const ode_kit *)w)->gen[k];
  double p[2];
  ode_collider_pin_in_hole(&q->g, p);
  if (q->g.bore) return fb_ccd_bore_depth(q->g.bore, p);
  const double d = hypot(p[0], p[1]) - q->c;
  return d > 0.0 ? d : 0.0;
}

/* the exact collider's row as ode_clearance.c makes it: the law mapped to
 * one soft contact row (ode_contact.h) at the effective mass (the
 * matched-static row blended by the contact's persistence, its depth
 * carrying the step's drift that the row cannot see, contact.h's
 * fb_contact_step_drift), on the hole wall, its normal into the pin,
 * Coulomb friction mu with ODE's friction pyramid */
static fb_status kit_add_contact(void *w, int j, const fb_kit_contact *c, fb_diag *diag) {
  (void)diag;
  ode_kit *k = w;
  if (j < FB_PLANAR_SPEC_MAX_JOINTS && k->gen[j]) return gen_contact(k, j, c);
  dContact ct;
  memset(&ct, 0, sizeof ct);
  fb_contact_row used = c->row; /* the kit's, when it mapped the law already */
  if (c->has_row) fb_ode_soft_fill(&ct, &used, c->friction);
  else if (!fb_ode_soft_contact(&ct, &c->law, c->mapping, c->h, c->m_eff, 1, c->depth, c->rate,
                                c->v0, c->onset, c->persistence, c->friction, &used))
    return FB_OK;
  if (c->mapping == FB_MAPPING_MATCHED_STATIC && used.erp > 0.0 && !c->wall && !c->mean_force) {
    /* the row's lambda = a d_n + b u: handing it d_n + drift / ERP makes its
     * b act on the penetration's true rate u + drift / h (contact.h) */
    double dp[2], dq[2];
    point_drift(k, c->pin, c->centre[0], c->h, dp);
    point_drift(k, c->hole, c->centre[1], c->h, dq);
    const double e[2] = {c->centre[0][0] - c->centre[1][0], c->centre[0][1] - c->centre[1][1]};
    ct.geom.depth = used.depth +
                    fb_contact_step_drift(c->normal, dp, dq, c->ecc_rate, hypot(e[0], e[1]), c->h) /
                        used.erp;
  }
  ct.geom.pos[0] = c->point[0];
  ct.geom.pos[1] = c->point[1];
  ct.geom.normal[0] = -c->normal[0];
  ct.geom.normal[1] = -c->normal[1];
  k->cj[j] = dJointCreateContact(k->world, k->contacts, &ct);
  dJointAttach(k->cj[j], ode_body(k, c->pin), ode_body(k, c->hole));
  dJointSetFeedback(k->cj[j], &k->fb[j]);
  k->share[j] = used.step_share;
  k->pin_ground[j] = c->pin == FB_KIT_GROUND;
  k->slot[k->nslots++] = j;
  return FB_OK;
}

static double kit_contact_force(const void *w, int j) { return ((const ode_kit *)w)->force[j]; }

static void kit_contact_force_vec(const void *w, int j, double f[2]) {
  const ode_kit *k = w;
  f[0] = k->force_pin[j][0];
  f[1] = k->force_pin[j][1];
}

/* the contact forces the step left (on the pin: ODE's body 1 of each row,
 * the hole's when the pin is the ground's), over the slots that had a row;
 * the slots of the step before, none this step, cleared */
static void contact_forces(ode_kit *k) {
  for (int i = 0; i < k->nlast; i++) {
    const int j = k->last[i];
    k->force[j] = k->force_pin[j][0] = k->force_pin[j][1] = 0.0;
  }
  for (int i = 0; i < k->nslots; i++) {
    const int j = k->slot[i];
    ode_kit_gen *q = j < FB_PLANAR_SPEC_MAX_JOINTS ? k->gen[j] : NULL;
    double f[2] = {k->fb[j].f1[0], k->fb[j].f1[1]}, share = k->share[j];
    if (q) share = ode_collider_force(&q->g, f) > 0 ? 1.0 : 0.0; /* its rows' sum */
    const double s = k->pin_ground[j] ? -share : share;
    k->force[j] = fabs(s) * hypot(f[0], f[1]);
    k->force_pin[j][0] = s * f[0];
    k->force_pin[j][1] = s * f[1];
    k->cj[j] = 0;
    k->last[i] = j;
  }
  k->nlast = k->nslots;
  k->nslots = 0;
  dJointGroupEmpty(k->contacts);
}

/* the levers G - P of every ideal joint at the coming step's start (the
 * configuration its feedback belongs to) */
static void note_levers(ode_kit *k) {
  for (int j = 0; j < k->njoints; j++) {
    ode_kit_joint *q = &k->jk[j];
    const dBodyID b = ode_body(k, q->b1 == FB_KIT_GROUND ? q->b0 : q->b1);
    dVector3 p;
    dBodyGetRelPointPos(b, q->local[0], q->local[1], q->local[2], p);
    const dReal *g = dBodyGetPosition(b);
    q->lever[0] = g[0] - p[0];
    q->lever[1] = g[1] - p[1];
  }
}

/* ideal joint j's reaction over the last step (kit.h): the force on its
 * b1 from its b0 and the moment about the joint's point P on b1 (b0 when
 * b1 is the ground). ODE's body 1 is b1 (b0 when b1 is the ground), its
 * feedback the force f1 and the torque t1 about that body's centre G at
 * the step's start: about P, t1 + (G - P) x f1, with the sign of the side
 * asked */
static void kit_reactions(const void *w, int j, double out[3]) {
  const ode_kit *k = w;
  const ode_kit_joint *q = &k->jk[j];
  const dReal *f = q->fb.f1, *t = q->fb.t1;
  const double s = q->b1 == FB_KIT_GROUND ? -1.0 : 1.0;
  out[0] = s * f[0];
  out[1] = s * f[1];
  out[2] = s * (t[2] + q->lever[0] * f[1] - q->lever[1] * f[0]);
}

/* one step of h [s] */
static fb_status step_of(ode_kit *k, double h, fb_diag *diag) {
  jmp_buf escape;
  if (setjmp(escape) != 0) {
    k->broken = 1;
    return fb_diag_set(diag, FB_ERR_NUMERIC, "ode-error: %s at t = %.6g s (step %zu)",
                       fb_ode_last_error(), k->t, k->steps + 1);
  }
  note_levers(k);
  fb_ode_escape = &escape;
  const int ok = k->stepper == FB_STEPPER_WORLD ? dWorldStep(k->world, h)
                                                : dWorldQuickStep(k->world, h);
  fb_ode_escape = NULL;
  contact_forces(k);
  if (!ok)
    return fb_diag_set(diag, FB_ERR_NOMEM, "ODE could not allocate memory for step %zu",
                       k->steps + 1);
  k->steps++;
  k->t += h;
  return FB_OK;
}

static fb_status kit_step(void *w, fb_diag *diag) {
  ode_kit *k = w;
  return step_of(k, k->h, diag);
}

/* ODE's step moves positions as leapfrog does, its velocities acting as the
 * half-step ones: v_{n+1} = v_n + h_n a_n. When the step changes from
 * h_{n-1} to h_n, leapfrog's half-step velocity takes (h_{n-1} + h_n) / 2 of
 * the acceleration, ODE's h_n: a first-order error at every change, which
 * spoils the rocking's phase wherever the step follows the load
 * (docs/step-size.md). Under the rocking bound, before a step of h that
 * follows one of h_last, every body but the one the drive turns against
 * the ground gets (h_last - h) / 2 times the last step's acceleration,
 * (v now - v at its start) / h_last. */
static void carry(ode_kit *k, double h) {
  const double hl = k->h_last;
  for (int b = 0; b < k->nbodies; b++) {
    const dReal *v = dBodyGetLinearVel(k->body[b]), *om = dBodyGetAngularVel(k->body[b]);
    double *s = k->v_start[b];
    if (hl > 0.0 && fabs(h - hl) > 1e-9 * hl && b != k->driven) {
      const double g = 0.5 * (hl - h) / hl;
      dBodySetLinearVel(k->body[b], v[0] + g * (v[0] - s[0]), v[1] + g * (v[1] - s[1]), v[2]);
      dBodySetAngularVel(k->body[b], om[0], om[1], om[2] + g * (om[2] - s[3]));
    }
    s[0] = v[0], s[1] = v[1], s[2] = v[2], s[3] = om[2];
  }
  k->h_last = h;
}

/* one step of h, a whole multiple of the world's (kit.h step_by) */
static fb_status kit_step_by(void *w, double h, fb_diag *diag) {
  ode_kit *k = w;
  if (k->rocking) carry(k, h);
  return step_of(k, h, diag);
}

static void kit_body_state(const void *w, int b, double pos[3], double vel[3]) {
  const ode_kit *k = w;
  const dReal *p = dBodyGetPosition(k->body[b]), *R = dBodyGetRotation(k->body[b]);
  const dReal *v = dBodyGetLinearVel(k->body[b]), *om = dBodyGetAngularVel(k->body[b]);
  pos[0] = p[0];
  pos[1] = p[1];
  pos[2] = atan2(R[4], R[0]);
  vel[0] = v[0];
  vel[1] = v[1];
  vel[2] = om[2];
}

/* cos and sin of the body's angle as ODE holds it: its rotation matrix's
 * first column (R is 3 x 4, row-major), the atan2 body_state takes */
static void kit_body_rotation(const void *w, int b, double cs[2]) {
  const ode_kit *k = w;
  const dReal *R = dBodyGetRotation(k->body[b]);
  cs[0] = R[0];
  cs[1] = R[4];
}

/* ODE clears a body's force and torque accumulators after each step */
static void kit_apply_wrench(void *w, int b, const double f[3]) {
  ode_kit *k = w;
  dBodyAddForce(k->body[b], f[0], f[1], 0.0);
  dBodyAddTorque(k->body[b], 0.0, 0.0, f[2]);
}

static void kit_world_free(void *w) {
  ode_kit *k = w;
  for (int j = 0; j < FB_PLANAR_SPEC_MAX_JOINTS; j++) { /* its geoms before the bodies */
    if (!k->gen[j]) continue;
    if (k->broken) fb_ccd_bore_destroy(k->gen[j]->g.bore); /* ODE's never touched again */
    else ode_collider_free(&k->gen[j]->g);
    free(k->gen[j]);
  }
  if (k->broken) {
    fb_ode_quarantine(k->world); /* left mid-step: never touched again (ode_env.h) */
    fb_ode_quarantine(k->contacts);
  } else {
    dJointGroupDestroy(k->contacts);
    dWorldDestroy(k->world);
    fb_ode_release();
  }
  free(k->body);
  free(k->joint);
  free(k->jk);
  free(k->v_start);
  free(k);
}

const fb_kit_binding fb_ode_kit = {
    .engine = "ode",
    .world_new = kit_world_new,
    .add_body = kit_add_body,
    .add_revolute = kit_add_revolute,
    .add_prismatic = kit_add_prismatic,
    .add_drive = kit_add_drive,
    .hold_in_plane = kit_hold_in_plane,
    .add_contact = kit_add_contact,
    .contact_force = kit_contact_force,
    .step = kit_step,
    .body_state = kit_body_state,
    .body_rotation = kit_body_rotation,
    .world_free = kit_world_free,
    .contact_rows = 1,
    .contact_speed_limit = 1,
    .reactions = kit_reactions,
    .contact_force_vec = kit_contact_force_vec,
    .friction = 1,
    .apply_wrench = kit_apply_wrench,
    .add_clearance = kit_add_clearance,
    .collide = kit_collide,
    .collided = kit_collided,
    .penetration = kit_penetration,
    .step_by = kit_step_by,
    .persistent_rule = FB_PERSIST_LOAD_SCHEDULE,
};
