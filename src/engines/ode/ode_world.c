#include "ode_world.h"
#include "step_control.h"

#include <math.h>
#include <ode/ode.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "collide_ccd.h"
#include "episode.h"
#include "load_scale.h"
#include "ode_contact.h"
#include "ode_env.h"

/* one clearance joint */
typedef struct {
  dBodyID pin, hole;    /* hole 0: ground */
  double pin_local[3];  /* joint centre in the pin body's frame */
  double hole_local[3]; /* in the hole body's frame, or world point for ground */
  fb_episode ep;        /* contact episodes: state during the last step, impacts, v0 */
  dJointID cj;          /* contact joint of the last step, or 0 */
  dJointFeedback fb;
  dGeomID cyl;          /* faceted: the pin */
  dGeomID *boxes;       /* faceted: the ring (faceted_n) */
  dSpaceID ring;        /* faceted: hash space holding the ring (broadphase) */
  int nfb;              /* faceted: contact joints of the last step */
  dJointFeedback *fbs;  /* faceted: their feedback (up to FACET_MAX_CONTACTS) */
  double force;         /* contact force magnitude of the last step [N] */
  double force_pin[2];  /* contact force on the pin in the last step, x, y [N] */
  fb_ccd_bore *bore;    /* ccd: the ring of segments (hole frame) */
  fb_contact_provenance prov; /* what its contact rows received */
  double step_share;    /* share of the last row's impulse that is its step's force (contact.h) */
  double step_wdh;      /* largest omega_d h of this step's rows [-] (contact.h) */
  double step_hw;       /* largest h omega of this step's rows (all rows together) [-] */
  double phase;         /* contact phase so far, sum of step_hw over the contact [rad] */
  double persistence;   /* matched-static: weight of the static row this step (contact.h) */
  double f_mean;        /* [solver] rocking_h_omega: the contact's mean force (contact.h,
                           fb_contact_mean_force_step) [N]; 0 out of contact */
  double omega_c;       /* the last row's contact frequency sqrt(k_t / m_eff) [rad/s] */
} clearance;

/* records one contact row of a clearance joint */
static void note_row(clearance *c, const fb_contact_row *u, double share, double mass, double h) {
  fb_contact_provenance *p = &c->prov;
  if (p->contact_steps == 0 || u->erp > p->erp_max) p->erp_max = u->erp;
  if (p->contact_steps == 0 || u->cfm < p->cfm_min) p->cfm_min = u->cfm;
  const double hw = fb_contact_h_omega(h, u->kp * share, mass); /* rows in parallel */
  if (p->contact_steps == 0 || hw > p->h_omega_max) p->h_omega_max = hw;
  if (hw > c->step_hw) c->step_hw = hw;
  if (p->contact_steps == 0 || mass < p->mass_eff_min) p->mass_eff_min = mass;
  if (p->contact_steps == 0 || mass > p->mass_eff_max) p->mass_eff_max = mass;
  p->contact_steps++;
  const double wdh = fb_contact_omega_d_h(h, u->kp * share, u->kd * share, mass);
  if (wdh > c->step_wdh) c->step_wdh = wdh;
}

struct fb_ode_world {
  fb_scene_model def;
  int broken;        /* 1 after an ODE fatal error left its world mid-step: never touched again */
  fb_stop stop;      /* why the last step failed (FB_STOP_NONE while none did) */
  dWorldID world;
  dBodyID body[3];   /* crank, coupler, follower */
  dJointID hinge[4]; /* A (ground-crank, driven), B, C, D; 0 for clearance joints */
  dJointID amotor;   /* the drive when A is a clearance joint */
  dJointGroupID contacts;
  clearance cl[4];
  dJointFeedback feedback[4];
  double crank_com_before[2]; /* crank centre of mass at the start of the last step */
  size_t steps;
  double angle[3];     /* unwrapped angles [rad] */
  double omega_prev[3];
  double alpha[3];
  double w_inv[4][2][2]; /* inverse-mass tensors of the clearance joints this step [1/kg] */
  int w_valid;           /* w_inv holds the configuration now (the next step's start); reset
                            when a step moves the bodies, so the adaptive step and the contact
                            rows share one computation */
  double h_now;          /* step of the ODE step being taken [s]: solver.h, or the adaptive one */
  /* [solver] h_s = adaptive (step_control.h): each ODE step spans mc grid
   * steps of solver.h (= h_min); the samples inside it are interpolated */
  struct {
    int on;               /* 1: adaptive */
    int m_max;            /* h_max / h_min, rounded down [-] */
    int m_prev;           /* grid steps of the last ODE step [-] */
    int mc, k;            /* the last ODE step spans mc samples; sample k of them is reported */
    double ang0[3], ang1[3], w0[3], w1[3]; /* angles [rad] and omega [rad/s] at its ends */
    double pen0[4], pen1[4], ex0[4], ex1[4], ey0[4], ey1[4]; /* penetration, eccentricity [m] */
    fb_step_stats stats;  /* steps taken, shortest and longest h and their counts */
    double pen_end;       /* largest penetration at the last ODE step's end [m] */
    int pen_joint_end;    /* its joint */
    double drift_end;     /* hinge drift at the last ODE step's end [m] */
    fb_load_scale load;   /* the clearance joints' ideal load time scale (load_scale.h) */
    int rocking;          /* 1: [solver] rocking_h_omega > 0 (step_control.h) */
    double h_last;        /* the last ODE step [s]; 0 before the first */
    double v_start[3][3]; /* each body's linear velocity at the last ODE step's start [m/s] */
    double w_start[3][3]; /* and its angular velocity [rad/s] */
  } ad;
};

/* the effective mass of clearance joint j along unit n (pin minus hole
 * direction) [kg], from this step's inverse-mass tensor (effective_mass.h),
 * computed at the step's first call; the law's mass if that fails */
static double step_effective_mass(fb_ode_world *s, int j, const double n[2]) {
  if (!s->w_valid) {
    fb_mechanism m;
    fb_ode_world_mechanism(s, &m);
    if (fb_effective_mass_tensor(s->w_inv, &m, NULL) != FB_OK) return s->def.law[j].mass;
    s->w_valid = 1;
  }
  const double me = fb_effective_mass_along(s->w_inv[j], n);
  return isfinite(me) && me > 0.0 ? me : s->def.law[j].mass;
}

/* the joint's law at this step: the restitution law's damper acts on the
 * effective mass along the normal (c = 2 zeta sqrt(p m_eff)), so the
 * achieved restitution is the one asked */
static fb_contact_law step_law(const fb_contact_law *law, double m_eff) {
  fb_contact_law l = *law;
  if (l.kind == FB_LAW_RESTITUTION) l.mass = m_eff;
  return l;
}

/* sets a link body between joint points p and q, COM at fraction f */
static void place_body(dBodyID b, const fb_link_mass *lm, const double p[2], const double q[2],
                       double omega, const double vp[2]) {
  double dx = q[0] - p[0], dy = q[1] - p[1];
  double phi = atan2(dy, dx);
  double rx = lm->com_fraction * dx, ry = lm->com_fraction * dy;
  dMass m;
  /* body frame: x along the link, z the hinge axis */
  dMassSetParameters(&m, lm->mass, 0, 0, 0, lm->inertia_long, lm->inertia_transverse,
                     lm->inertia, 0, 0, 0);
  dBodySetMass(b, &m);
  dBodySetPosition(b, p[0] + rx, p[1] + ry, 0.0);
  dMatrix3 R;
  dRFromAxisAndAngle(R, 0, 0, 1, phi);
  dBodySetRotation(b, R);
  dBodySetLinearVel(b, vp[0] - omega * ry, vp[1] + omega * rx, 0.0);
  dBodySetAngularVel(b, 0, 0, omega);
}

static double body_angle(dBodyID b) {
  const dReal *R = dBodyGetRotation(b);
  return atan2(R[4], R[0]);
}

#define FACET_THICKNESS_M 2e-3 /* radial thickness of the ring's boxes */
#define FACET_MAX_CONTACTS 64   /* contacts kept per joint and step */

/* builds the faceted hole and pin of clearance joint j */
static void facet_create(fb_ode_world *s, int j) {
  clearance *c = &s->cl[j];
  const fb_scene_model *d = &s->def;
  const int n = d->faceted_n;
  const double r_in = d->pin_radius + d->radial_clearance;
  const double t = FACET_THICKNESS_M;
  const double w = 2.0 * (r_in + t) * tan(M_PI / n) * 1.001; /* closes the ring */
  c->cyl = dCreateCylinder(0, d->pin_radius, d->pin_length);
  dGeomSetBody(c->cyl, c->pin);
  dGeomSetOffsetPosition(c->cyl, c->pin_local[0], c->pin_local[1], c->pin_local[2]);
  c->boxes = calloc((size_t)n, sizeof(dGeomID));
  c->ring = dHashSpaceCreate(0);
  c->fbs = calloc(FACET_MAX_CONTACTS, sizeof(dJointFeedback));
  for (int k = 0; k < n; k++) {
    const double phi = 2.0 * M_PI * k / n;
    dGeomID b = dCreateBox(c->ring, t, w, d->pin_length);
    dMatrix3 R;
    dRFromAxisAndAngle(R, 0, 0, 1, phi);
    const double cx = (r_in + 0.5 * t) * cos(phi), cy = (r_in + 0.5 * t) * sin(phi);
    if (c->hole) {
      dGeomSetBody(b, c->hole);
      /* offsets are in the hole body's frame: the ring is centred on hole_local */
      dGeomSetOffsetPosition(b, c->hole_local[0] + cx, c->hole_local[1] + cy, 0.0);
      dGeomSetOffsetRotation(b, R);
    } else {
      dGeomSetPosition(b, c->hole_local[0] + cx, c->hole_local[1] + cy, 0.0);
      dGeomSetRotation(b, R);
    }
    c->boxes[k] = b;
  }
}

static void facet_destroy(clearance *c, int n) {
  (void)n;
  if (!c->boxes) return;
  dSpaceDestroy(c->ring); /* destroys the boxes it holds (cleanup mode on) */
  dGeomDestroy(c->cyl);
  free(c->boxes);
  free(c->fbs);
}

/* builds the libccd ring of clearance joint j */
static fb_status ccd_create(fb_ode_world *s, int j, fb_diag *diag) {
  const fb_scene_model *d = &s->def;
  fb_ccd_bore_def bd = fb_ccd_bore_default();
  bd.pin_radius = d->pin_radius;
  bd.pin_length = d->pin_length;
  bd.hole_radius = d->pin_radius + d->radial_clearance;
  bd.shape = d->bore_ovality > 0.0 ? FB_BORE_ELLIPSE : FB_BORE_CIRCLE;
  bd.ovality = d->bore_ovality;
  bd.segments = d->ccd_segments;
  bd.wall = FACET_THICKNESS_M;
  fb_status st = fb_ccd_bore_create(&s->cl[j].bore, &bd, diag);
  if (st != FB_OK) return st;
  s->cl[j].fbs = calloc(FB_CCD_CONTACTS, sizeof(dJointFeedback));
  if (!s->cl[j].fbs) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for contact feedback");
  return FB_OK;
}

fb_status fb_ode_world_create(fb_ode_world **out, const fb_scene_model *sm, fb_diag *diag) {
  fb_status rc0 = fb_scene_def_check(sm->def, diag);
  if (rc0 != FB_OK) return rc0;
  if (sm->clearance_mask && sm->collider != FB_COLLIDER_EXACT &&
      sm->collider != FB_COLLIDER_FACETED && sm->collider != FB_COLLIDER_CCD)
    return fb_diag_set(diag, FB_ERR_ARG, "model '%s': the ODE engine has no such collider",
                       sm->model->name);
  if (sm->solver.h_mode == FB_STEP_ADAPTIVE && sm->clearance_mask &&
      sm->collider != FB_COLLIDER_EXACT)
    return fb_diag_set(diag, FB_ERR_ARG,
                       "model '%s': [solver] h_s = adaptive follows the exact collider's contact "
                       "only; run the %s collider at a fixed or auto step",
                       sm->model->name, fb_collider_name(sm->collider));
  const fb_scene_model *def = sm;
  fb_start_state st;
  fb_status rc = fb_scene_model_start(&st, def, diag);
  if (rc != FB_OK) return rc;
  fb_ode_world *s = calloc(1, sizeof *s);
  if (!s) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the scene");
  fb_ode_acquire();
  s->def = *sm;
  s->world = dWorldCreate();
  dWorldSetGravity(s->world, 0, -def->gravity, 0);
  dWorldSetERP(s->world, def->solver.world_erp);
  dWorldSetCFM(s->world, def->solver.world_cfm);
  dWorldSetQuickStepNumIterations(s->world, def->solver.quick_iterations);
  dRandSetSeed(def->solver.seed);
  if (def->settle_damping > 0.0) {
    dWorldSetLinearDamping(s->world, def->settle_damping);
    dWorldSetAngularDamping(s->world, def->settle_damping);
    /* ODE damps only above these speeds (default 0.01): damp everything */
    dWorldSetLinearDampingThreshold(s->world, 0.0);
    dWorldSetAngularDampingThreshold(s->world, 0.0);
  }

  /* each body between its joints' pin or hole centres (start.h): crank A_pin
   * to B_pin, coupler B_hole to C_pin, follower D_pin to C_hole */
  const double zero[2] = {0, 0};
  for (int i = 0; i < 3; i++) s->body[i] = dBodyCreate(s->world);
  place_body(s->body[FB_CRANK], &def->link[FB_CRANK], st.pin[FB_JOINT_A], st.pin[FB_JOINT_B],
             st.crank_omega, zero);
  place_body(s->body[FB_COUPLER], &def->link[FB_COUPLER], st.hole[FB_JOINT_B], st.pin[FB_JOINT_C],
             st.coupler_omega, st.coupler_b_vel);
  place_body(s->body[FB_FOLLOWER], &def->link[FB_FOLLOWER], st.pin[FB_JOINT_D],
             st.hole[FB_JOINT_C], st.follower_omega, zero);

  const dBodyID b1[4] = {s->body[FB_CRANK], s->body[FB_CRANK], s->body[FB_COUPLER],
                         s->body[FB_FOLLOWER]};
  const dBodyID b2[4] = {0, s->body[FB_COUPLER], s->body[FB_FOLLOWER], 0};
  const double *anchor[4] = {st.pin[0], st.pin[1], st.pin[2], st.pin[3]};
  s->contacts = dJointGroupCreate(0);
  for (int j = 0; j < 4; j++) {
    if (def->clearance_mask & (1 << j)) {
      /* pin and hole centres at t = 0 (the start's eccentricity) */
      clearance *c = &s->cl[j];
      c->pin = b1[j];
      c->hole = b2[j];
      dVector3 lp;
      dBodyGetPosRelPoint(c->pin, st.pin[j][0], st.pin[j][1], 0.0, lp);
      for (int q = 0; q < 3; q++) c->pin_local[q] = lp[q];
      if (c->hole) {
        dBodyGetPosRelPoint(c->hole, st.hole[j][0], st.hole[j][1], 0.0, lp);
        for (int q = 0; q < 3; q++) c->hole_local[q] = lp[q];
      } else {
        c->hole_local[0] = st.hole[j][0];
        c->hole_local[1] = st.hole[j][1];
        c->hole_local[2] = 0.0;
      }
      continue;
    }
    s->hinge[j] = dJointCreateHinge(s->world, 0);
    dJointAttach(s->hinge[j], b1[j], b2[j]);
    dJointSetHingeAnchor(s->hinge[j], anchor[j][0], anchor[j][1], 0.0);
    dJointSetHingeAxis(s->hinge[j], 0, 0, 1);
    dJointSetFeedback(s->hinge[j], &s->feedback[j]);
  }
  if (def->faceted_n > 0)
    for (int j = 0; j < 4; j++)
      if (def->clearance_mask & (1 << j)) facet_create(s, j);
  if (def->ccd_segments > 0)
    for (int j = 0; j < 4; j++) {
      if (!(def->clearance_mask & (1 << j))) continue;
      fb_status bst = ccd_create(s, j, diag);
      if (bst != FB_OK) {
        fb_ode_world_destroy(s);
        return bst;
      }
    }
  /* the drive: velocity motor on the ground-crank hinge, or an angular motor
   * on the crank when that joint has clearance */
  if (s->hinge[0]) {
    dJointSetHingeParam(s->hinge[0], dParamVel, def->omega2);
    dJointSetHingeParam(s->hinge[0], dParamFMax, def->solver.drive_torque_max);
  } else {
    s->amotor = dJointCreateAMotor(s->world, 0);
    dJointAttach(s->amotor, s->body[FB_CRANK], 0);
    dJointSetAMotorNumAxes(s->amotor, 1);
    dJointSetAMotorAxis(s->amotor, 0, 0, 0, 0, 1);
    dJointSetAMotorParam(s->amotor, dParamVel, def->omega2);
    dJointSetAMotorParam(s->amotor, dParamFMax, def->solver.drive_torque_max);
  }
  /* a body with no hinge left is held in the plane */
  const int joints_of[3][2] = {{FB_JOINT_A, FB_JOINT_B}, {FB_JOINT_B, FB_JOINT_C},
                               {FB_JOINT_C, FB_JOINT_D}};
  for (int i = 0; i < 3; i++) {
    if (s->hinge[joints_of[i][0]] || s->hinge[joints_of[i][1]]) continue;
    dJointID p2 = dJointCreatePlane2D(s->world, 0);
    dJointAttach(p2, s->body[i], 0);
  }

  for (int i = 0; i < 3; i++) {
    s->angle[i] = body_angle(s->body[i]);
    s->omega_prev[i] = dBodyGetAngularVel(s->body[i])[2];
    s->alpha[i] = 0.0;
  }
  s->h_now = def->solver.h;
  if (def->solver.h_mode == FB_STEP_ADAPTIVE) {
    s->ad.on = 1;
    s->ad.m_max = (int)floor(def->solver.h_max / def->solver.h * (1.0 + 1e-9));
    if (s->ad.m_max < 1) s->ad.m_max = 1;
    s->ad.m_prev = 1;
    s->ad.rocking = def->solver.rocking_h_omega > 0.0 && def->clearance_mask != 0;
    /* persistent contact steps on the ideal load's schedule (step_control.h) */
    fb_status lst = fb_load_scale_build(&s->ad.load, &def->lengths, def->branch, def->link,
                                        def->gravity, def->omega2, def->clearance_mask,
                                        FB_STEP_LOAD_LOOKAHEAD * def->solver.h_max, diag);
    if (lst != FB_OK) {
      fb_ode_world_destroy(s);
      return lst;
    }
  }
  *out = s;
  return FB_OK;
}

/* eccentricity, penetration rate and hole-wall point of clearance joint c */
static void clearance_geometry(const clearance *c, double e[2], double *ddot_num, double ev[2]) {
  dVector3 p, q, vp, vq = {0, 0, 0, 0};
  dBodyGetRelPointPos(c->pin, c->pin_local[0], c->pin_local[1], c->pin_local[2], p);
  dBodyGetRelPointVel(c->pin, c->pin_local[0], c->pin_local[1], c->pin_local[2], vp);
  if (c->hole) {
    dBodyGetRelPointPos(c->hole, c->hole_local[0], c->hole_local[1], c->hole_local[2], q);
    dBodyGetRelPointVel(c->hole, c->hole_local[0], c->hole_local[1], c->hole_local[2], vq);
  } else {
    q[0] = c->hole_local[0];
    q[1] = c->hole_local[1];
  }
  e[0] = p[0] - q[0];
  e[1] = p[1] - q[1];
  ev[0] = vp[0] - vq[0];
  ev[1] = vp[1] - vq[1];
  *ddot_num = e[0] * ev[0] + e[1] * ev[1]; /* |e| times the rate of |e| */
}

/* what ODE's position update adds to a body point's displacement over a
 * step beyond the linear h (v + w x r) a contact row's Jacobian sees: ODE
 * turns the body by theta = 2 atan(h w / 2) (its quaternion update,
 * normalised), so the point at r from the centre of mass moves by
 * (cos theta - 1) r + (sin theta - h w) z x r more [m] (w taken at the
 * start of the step) */
static void point_drift(dBodyID b, const double local[3], double h, double out[2]) {
  out[0] = out[1] = 0.0;
  if (!b) return; /* the ground */
  dVector3 p;
  dBodyGetRelPointPos(b, local[0], local[1], local[2], p);
  const dReal *x = dBodyGetPosition(b);
  const double r[2] = {p[0] - x[0], p[1] - x[1]};
  const double w = dBodyGetAngularVel(b)[2];
  const double th = 2.0 * atan(0.5 * h * w);
  const double cm1 = -2.0 * sin(0.5 * th) * sin(0.5 * th), sw = sin(th) - h * w;
  out[0] = cm1 * r[0] - sw * r[1];
  out[1] = cm1 * r[1] + sw * r[0];
}

/* The change of the penetration |e| - c over the coming step that a contact
 * row on the normal n does not see [m]: a row constrains the normal rate
 * n . de/dt at the start of the step (J v_{n+1}), while the penetration
 * also moves by the rotation's second-order terms of both bodies' points
 * (point_drift) and by the curvature of the circle |e| = const under the
 * tangential rate, h^2 |de/dt_t|^2 / (2 |e|). In continuous contact the
 * row then holds a steady rate u = -drift / h, and its damper b turns that
 * into a force error b drift / h: on the paper case at 1000 rpm with the
 * heavily damped restitution law (cr 0.14, zeta 0.99) that is +10 % of the
 * persistent-contact penetration with a statically exact row. */
static double step_drift(const clearance *c, const double n[2], const double ev[2], double ecc,
                         double h) {
  double dp[2], dq[2];
  point_drift(c->pin, c->pin_local, h, dp);
  point_drift(c->hole, c->hole_local, h, dq);
  return fb_contact_step_drift(n, dp, dq, ev, ecc, h);
}

typedef struct {
  dContactGeom *g;
  int n;
} facet_hits;

/* broadphase callback: narrowphase of the pin against one box */
static void facet_near(void *data, dGeomID o1, dGeomID o2) {
  facet_hits *h = data;
  if (h->n >= FACET_MAX_CONTACTS) return;
  h->n += dCollide(o1, o2, FACET_MAX_CONTACTS - h->n, &h->g[h->n], sizeof(dContactGeom));
}

/* faceted: contact joints from ODE's collider for clearance joint j */
static void facet_contacts(fb_ode_world *s, int j) {
  clearance *c = &s->cl[j];
  const fb_scene_model *d = &s->def;
  dContactGeom g[FACET_MAX_CONTACTS];
  facet_hits hits = {g, 0};
  dSpaceCollide2(c->cyl, (dGeomID)c->ring, &hits, facet_near);
  const int n = hits.n;
  c->nfb = 0;
  if (n == 0) {
    fb_episode_update(&c->ep, 0, 0.0, d->impact_velocity_min);
    return;
  }
  for (int i = 0; i < n; i++) {
    dBodyID p1 = dGeomGetBody(g[i].g1), p2 = dGeomGetBody(g[i].g2);
    dVector3 v1 = {0, 0, 0, 0}, v2 = {0, 0, 0, 0};
    if (p1) dBodyGetPointVel(p1, g[i].pos[0], g[i].pos[1], g[i].pos[2], v1);
    if (p2) dBodyGetPointVel(p2, g[i].pos[0], g[i].pos[1], g[i].pos[2], v2);
    /* normal points into body 1: approach rate along it */
    const double ddot = (v2[0] - v1[0]) * g[i].normal[0] + (v2[1] - v1[1]) * g[i].normal[1] +
                        (v2[2] - v1[2]) * g[i].normal[2];
    if (i == 0) fb_episode_update(&c->ep, 1, ddot, d->impact_velocity_min);
    /* the collider's normal points into the pin: the pin-minus-hole direction is -normal */
    const double nn[2] = {-g[i].normal[0], -g[i].normal[1]};
    const double m_eff = step_effective_mass(s, j, nn);
    const fb_contact_law law = step_law(&d->law[j], m_eff);
    dContact ct;
    memset(&ct, 0, sizeof ct);
    ct.geom = g[i];
    fb_contact_row used;
    if (!fb_ode_soft_contact(&ct, &law, d->mapping, d->solver.h, m_eff, n, g[i].depth, ddot,
                             c->ep.v0, 0, c->persistence, d->friction, &used))
      continue;
    note_row(c, &used, (double)n, m_eff, d->solver.h);
    dJointID cj = dJointCreateContact(s->world, s->contacts, &ct);
    dJointAttach(cj, p1, p2);
    dJointSetFeedback(cj, &c->fbs[c->nfb++]);
  }
}

/* pin centre relative to the hole centre, in the hole body's frame (the
 * world's for a ground hole) [m] */
static void pin_in_hole_frame(const clearance *c, double p[2]) {
  dVector3 w, l;
  dBodyGetRelPointPos(c->pin, c->pin_local[0], c->pin_local[1], c->pin_local[2], w);
  if (c->hole) {
    dBodyGetPosRelPoint(c->hole, w[0], w[1], w[2], l);
    p[0] = l[0] - c->hole_local[0];
    p[1] = l[1] - c->hole_local[1];
  } else {
    p[0] = w[0] - c->hole_local[0];
    p[1] = w[1] - c->hole_local[1];
  }
}

/* libccd: contact joints from the generic collider for clearance joint j */
static void ccd_contacts(fb_ode_world *s, int j) {
  clearance *c = &s->cl[j];
  const fb_scene_model *d = &s->def;
  double p[2];
  pin_in_hole_frame(c, p);
  fb_ccd_contact hit[FB_CCD_CONTACTS];
  const int n = fb_ccd_bore_collide(c->bore, p, hit, FB_CCD_CONTACTS);
  c->nfb = 0;
  if (n == 0) {
    fb_episode_update(&c->ep, 0, 0.0, d->impact_velocity_min);
    return;
  }
  dVector3 nw[FB_CCD_CONTACTS], pw[FB_CCD_CONTACTS];
  double rate[FB_CCD_CONTACTS] = {0}, sum = 0.0;
  int deep = 0;
  for (int i = 0; i < n; i++) {
    /* to the world: normal (pin into wall) and point */
    if (c->hole) {
      dBodyVectorToWorld(c->hole, hit[i].normal[0], hit[i].normal[1], 0.0, nw[i]);
      dBodyGetRelPointPos(c->hole, c->hole_local[0] + hit[i].point[0],
                          c->hole_local[1] + hit[i].point[1], c->hole_local[2], pw[i]);
    } else {
      nw[i][0] = hit[i].normal[0];
      nw[i][1] = hit[i].normal[1];
      nw[i][2] = 0.0;
      pw[i][0] = c->hole_local[0] + hit[i].point[0];
      pw[i][1] = c->hole_local[1] + hit[i].point[1];
      pw[i][2] = 0.0;
    }
    /* approach rate: pin velocity minus hole velocity at the point, along the normal */
    dVector3 vp, vh = {0, 0, 0, 0};
    dBodyGetPointVel(c->pin, pw[i][0], pw[i][1], pw[i][2], vp);
    if (c->hole) dBodyGetPointVel(c->hole, pw[i][0], pw[i][1], pw[i][2], vh);
    rate[i] = (vp[0] - vh[0]) * nw[i][0] + (vp[1] - vh[1]) * nw[i][1];
    sum += hit[i].depth;
    if (hit[i].depth > hit[deep].depth) deep = i;
  }
  fb_episode_update(&c->ep, 1, rate[deep], d->impact_velocity_min);
  /* the effective mass along the deepest contact's normal (pin into wall) */
  const double n_deep[2] = {nw[deep][0], nw[deep][1]};
  const double m_eff = step_effective_mass(s, j, n_deep);
  const fb_contact_law law = step_law(&d->law[j], m_eff);
  /* the one row the exact collider would hand ODE at the deepest contact */
  fb_contact_row base;
  const int have_row = fb_contact_map(&base, &law, d->mapping, d->solver.h, m_eff, 1,
                                      hit[deep].depth, rate[deep], c->ep.v0, NULL) == FB_OK;
  if (have_row && c->persistence > 0.0 && d->mapping == FB_MAPPING_MATCHED_STATIC)
    fb_contact_row_static(&base, d->solver.h, m_eff, c->persistence);
  for (int i = 0; i < n; i++) {
    dContact ct;
    memset(&ct, 0, sizeof ct);
    fb_contact_row row = base;
    if (d->ccd_split == 1) {
      /* the faceted model's rule: own depth, spring divided by the count */
      if (!fb_ode_soft_contact(&ct, &law, d->mapping, d->solver.h, m_eff, n, hit[i].depth,
                               rate[i], c->ep.v0, 0, c->persistence, d->friction, &row))
        continue;
    } else {
      /* share w of the row: a and b = 1/CFM scale by w, ERP = h a / b does not */
      if (!have_row) continue;
      row.cfm = base.cfm * sum / hit[i].depth;
      fb_ode_soft_fill(&ct, &row, d->friction);
    }
    note_row(c, &row, d->ccd_split == 1 ? (double)n : 1.0, m_eff, d->solver.h);
    for (int q = 0; q < 3; q++) {
      ct.geom.pos[q] = pw[i][q];
      ct.geom.normal[q] = -nw[i][q]; /* into the pin (body 1) */
    }
    dJointID cj = dJointCreateContact(s->world, s->contacts, &ct);
    dJointAttach(cj, c->pin, c->hole);
    dJointSetFeedback(cj, &c->fbs[c->nfb++]);
  }
}

/* penetration of clearance joint c now [m]: into the faceted bore for the
 * libccd collider, |e| - c otherwise; 0 when free */
static double clearance_penetration(const fb_ode_world *s, const clearance *c) {
  if (c->bore) {
    double p[2];
    pin_in_hole_frame(c, p);
    return fb_ccd_bore_depth(c->bore, p);
  }
  double e[2], ev[2], num;
  clearance_geometry(c, e, &num, ev);
  const double pen = hypot(e[0], e[1]) - s->def.radial_clearance;
  return pen > 0.0 ? pen : 0.0;
}

/* creates the contact joint of clearance joint j for this step, if in contact */
static void clearance_contact(fb_ode_world *s, int j) {
  clearance *c = &s->cl[j];
  const fb_scene_model *d = &s->def;
  if (c->bore) {
    ccd_contacts(s, j);
    return;
  }
  if (d->faceted_n > 0) {
    facet_contacts(s, j);
    return;
  }
  double e[2], ev[2], num;
  clearance_geometry(c, e, &num, ev);
  const double ecc = hypot(e[0], e[1]);
  const double delta = ecc - d->radial_clearance;
  c->cj = 0;
  if (!(delta > 0.0) || ecc == 0.0) {
    fb_episode_update(&c->ep, 0, 0.0, d->impact_velocity_min);
    return;
  }
  const double n[2] = {e[0] / ecc, e[1] / ecc};
  const double ddot = num / ecc;
  const int onset = !c->ep.in_contact;
  fb_episode_update(&c->ep, 1, ddot, d->impact_velocity_min);
  const double m_eff = step_effective_mass(s, j, n);
  const fb_contact_law law = step_law(&d->law[j], m_eff);
  dContact ct;
  memset(&ct, 0, sizeof ct);
  fb_contact_row used;
  if (!fb_ode_soft_contact(&ct, &law, d->mapping, s->h_now, m_eff, 1, delta, ddot, c->ep.v0,
                           onset, c->persistence, d->friction, &used))
    return;
  c->omega_c = sqrt(used.kp / m_eff);
  if (s->ad.rocking) {
    /* the matched row throughout, its static depth the law's (contact.h) */
    fb_contact_row_mean_force(&used, s->h_now, c->f_mean);
    ct.geom.depth = used.depth;
  } else if (d->mapping == FB_MAPPING_MATCHED_STATIC && used.erp > 0.0) {
    /* the row's lambda = a d_n + b u: handing it d_n + drift / ERP makes its
     * b act on the penetration's true rate u + drift / h (contact.h) */
    used.depth += step_drift(c, n, ev, ecc, s->h_now) / used.erp;
    ct.geom.depth = used.depth;
  }
  c->step_share = used.step_share;
  note_row(c, &used, 1.0, m_eff, s->h_now);
  /* hole centre + R_hole n, on the hole wall */
  const double r_hole = d->pin_radius + d->radial_clearance;
  dVector3 q;
  if (c->hole)
    dBodyGetRelPointPos(c->hole, c->hole_local[0], c->hole_local[1], c->hole_local[2], q);
  else
    q[0] = c->hole_local[0], q[1] = c->hole_local[1];
  ct.geom.pos[0] = q[0] + r_hole * n[0];
  ct.geom.pos[1] = q[1] + r_hole * n[1];
  ct.geom.pos[2] = 0.0;
  ct.geom.normal[0] = -n[0]; /* into the pin: moving it along -n removes the depth */
  ct.geom.normal[1] = -n[1];
  ct.geom.normal[2] = 0.0;
  c->cj = dJointCreateContact(s->world, s->contacts, &ct);
  dJointAttach(c->cj, c->pin, c->hole);
  dJointSetFeedback(c->cj, &c->fb);
}

/* one ODE step of size h from the state now (the step's contact rows,
 * dWorldStep or dWorldQuickStep, the forces and accelerations it left) */
static fb_status world_step(fb_ode_world *s, double h, fb_diag *diag) {
  s->h_now = h;
  for (int j = 0; j < 4; j++) {
    if (!(s->def.clearance_mask & (1 << j))) continue;
    clearance *c = &s->cl[j];
    c->step_wdh = c->step_hw = 0.0;
    c->persistence = s->def.mapping == FB_MAPPING_MATCHED_STATIC && !s->ad.rocking
                         ? fb_contact_persistence(c->phase)
                         : 0.0;
    clearance_contact(s, j);
    /* the contact's phase: a step without a row ends the contact */
    c->phase = c->step_hw > 0.0 ? c->phase + c->step_hw : 0.0;
  }
  /* a matched row past the aliasing bound has lost its spring's meaning:
   * stop, naming the largest usable step (contact.h) */
  for (int j = 0; j < 4; j++) {
    const double wdh = s->cl[j].step_wdh;
    if (!fb_mapping_is_matched(s->def.mapping) || !(wdh > FB_MATCHED_ALIAS_BOUND)) continue;
    dJointGroupEmpty(s->contacts);
    for (int q = 0; q < 4; q++) s->cl[q].cj = 0, s->cl[q].nfb = 0;
    s->stop.kind = FB_STOP_ALIASED;
    s->stop.t = (double)s->steps * h;
    s->stop.step = s->steps + 1;
    s->stop.joint = j;
    s->stop.value = wdh;
    s->stop.limit = FB_MATCHED_ALIAS_BOUND;
    s->stop.h_max = h * FB_MATCHED_ALIAS_BOUND / wdh;
    return fb_diag_set(diag, FB_ERR_NUMERIC,
                       "aliased: omega_d h = %.3g at the %s joint (bound %.3g); largest usable "
                       "step %.3g s",
                       wdh, fb_joint_name(j), FB_MATCHED_ALIAS_BOUND, s->stop.h_max);
  }
  const dReal *g1 = dBodyGetPosition(s->body[FB_CRANK]);
  s->crank_com_before[0] = g1[0];
  s->crank_com_before[1] = g1[1];
  /* an ODE fatal error (a failed internal check) stops this world with its
   * message instead of aborting the process (ode_env.h); the caller then
   * only destroys the world */
  jmp_buf escape;
  if (setjmp(escape) != 0) {
    s->broken = 1;
    s->stop.kind = FB_STOP_SOLVER;
    s->stop.t = (double)s->steps * s->def.solver.h;
    s->stop.step = s->steps + 1;
    snprintf(s->stop.detail, sizeof s->stop.detail, "%s", fb_ode_last_error());
    return fb_diag_set(diag, FB_ERR_NUMERIC, "ode-error: %s at t = %.6g s (step %zu)",
                       fb_ode_last_error(), (double)s->steps * s->def.solver.h, s->steps + 1);
  }
  fb_ode_escape = &escape;
  int ok = s->def.solver.stepper == FB_STEPPER_WORLD ? dWorldStep(s->world, h)
                                                     : dWorldQuickStep(s->world, h);
  fb_ode_escape = NULL;
  s->w_valid = 0; /* the bodies moved: the next step's tensors are its own */
  for (int j = 0; j < 4; j++) {
    clearance *c = &s->cl[j];
    if (s->def.faceted_n > 0 || c->bore) {
      /* force on the pin (body 1: dCollide(pin, box) keeps that order),
       * summed over the step's contacts */
      double fx = 0.0, fy = 0.0;
      for (int i = 0; i < c->nfb; i++) {
        fx += c->fbs[i].f1[0];
        fy += c->fbs[i].f1[1];
      }
      c->force = c->nfb ? hypot(fx, fy) : 0.0;
      c->force_pin[0] = c->nfb ? fx : 0.0;
      c->force_pin[1] = c->nfb ? fy : 0.0;
      c->nfb = 0;
    } else {
      /* an onset row's impulse also covers the contact before the step (contact.h) */
      const double share = c->cj ? c->step_share : 0.0;
      c->force = share * hypot(c->fb.f1[0], c->fb.f1[1]);
      c->f_mean = c->cj && s->ad.rocking
                      ? fb_contact_mean_force_step(c->f_mean, c->force, h, c->omega_c)
                      : 0.0;
      c->force_pin[0] = share * c->fb.f1[0]; /* body 1 is the pin */
      c->force_pin[1] = share * c->fb.f1[1];
    }
    c->cj = 0;
  }
  dJointGroupEmpty(s->contacts);
  if (!ok) {
    s->stop.kind = FB_STOP_ALLOCATION;
    s->stop.t = (double)s->steps * s->def.solver.h;
    s->stop.step = s->steps + 1;
    return fb_diag_set(diag, FB_ERR_NOMEM, "ODE could not allocate memory for step %zu",
                       s->steps + 1);
  }
  for (int i = 0; i < 3; i++) {
    double w = dBodyGetAngularVel(s->body[i])[2];
    s->alpha[i] = (w - s->omega_prev[i]) / h;
    s->omega_prev[i] = w;
    double a = body_angle(s->body[i]);
    double prev = s->angle[i];
    double d = remainder(a - prev, 2.0 * M_PI);
    s->angle[i] = prev + d;
  }
  return FB_OK;
}

/* penetration (0 when free) and eccentricity of every clearance joint now */
static void adapt_geometry(const fb_ode_world *s, double pen[4], double ex[4], double ey[4]) {
  for (int j = 0; j < 4; j++) {
    pen[j] = ex[j] = ey[j] = 0.0;
    if (!(s->def.clearance_mask & (1 << j))) continue;
    double e[2], ev[2], num;
    clearance_geometry(&s->cl[j], e, &num, ev);
    pen[j] = clearance_penetration(s, &s->cl[j]);
    ex[j] = e[0];
    ey[j] = e[1];
  }
}

static double penetration_now(const fb_ode_world *s, int *joint);
static double joint_drift_now(const fb_ode_world *s);

/* the next adaptive step as grid steps: the shortest any clearance joint's
 * contact asks for (step_control.h), ramped */
static int adapt_multiple(fb_ode_world *s) {
  const fb_scene_model *d = &s->def;
  const double hg = d->solver.h;
  double h = d->solver.h_max;
  int impulsive = 0; /* a joint penetrating with the matched row (step_control.h) */
  for (int j = 0; j < 4; j++) {
    if (!(d->clearance_mask & (1 << j))) continue;
    const clearance *c = &s->cl[j];
    double e[2], ev[2], num;
    clearance_geometry(c, e, &num, ev);
    const double ecc = hypot(e[0], e[1]);
    const double n[2] = {ecc > 0.0 ? e[0] / ecc : 1.0, ecc > 0.0 ? e[1] / ecc : 0.0};
    fb_step_joint sj = {.rule = FB_PERSIST_LOAD_SCHEDULE};
    fb_load_scale_at(&s->ad.load, j, s->angle[FB_CRANK], &sj.tau_load, &sj.load_force);
    sj.delta = ecc - d->radial_clearance;
    sj.ddot = ecc > 0.0 ? num / ecc : 0.0;
    sj.m_eff = step_effective_mass(s, j, n);
    if (d->mapping == FB_MAPPING_MATCHED_STATIC && sj.delta > 0.0) {
      sj.persistence = fb_contact_persistence(c->phase);
      if (sj.persistence < 1.0) impulsive = 1;
    }
    if (s->ad.rocking) {
      /* the rocking along the wall: the effective mass along the tangent */
      const double t[2] = {-n[1], n[0]};
      sj.rocking_h_omega = d->solver.rocking_h_omega;
      sj.m_t = step_effective_mass(s, j, t);
      sj.ecc = ecc;
    }
    const fb_contact_law law = step_law(&d->law[j], sj.m_eff);
    h = fmin(h, fb_step_adaptive(&law, &sj, d->solver.accuracy, hg, d->solver.h_max));
  }
  int want = (int)floor(h / hg * (1.0 + 1e-9));
  want = fb_step_hold_in_impact(want < 1 ? 1 : want, s->ad.m_prev, impulsive);
  return fb_step_ramp(want, s->ad.m_prev, s->ad.m_max);
}

/* ODE's step moves positions as leapfrog does, its velocities acting as
 * the half-step ones: v_{n+1} = v_n + h_n a_n. When the step changes from
 * h_{n-1} to h_n, leapfrog's half-step velocity takes (h_{n-1} + h_n) / 2 of
 * the acceleration, ODE's h_n: a first-order error at every change, which
 * on the paper case spoiled the rocking's phase wherever the step follows
 * the load (docs/step-size.md). Before a step of h that follows one of
 * h_last, the moving links' velocities get (h_last - h) / 2 times the last
 * step's acceleration, (v now - v at its start) / h_last; the driven crank
 * keeps its speed. */
static void carry_velocities(fb_ode_world *s, double h) {
  const double hl = s->ad.h_last;
  if (hl > 0.0 && fabs(h - hl) > 1e-9 * hl) {
    const double g = 0.5 * (hl - h) / hl;
    for (int i = FB_COUPLER; i <= FB_FOLLOWER; i++) {
      const dReal *v = dBodyGetLinearVel(s->body[i]), *w = dBodyGetAngularVel(s->body[i]);
      dBodySetLinearVel(s->body[i], v[0] + g * (v[0] - s->ad.v_start[i][0]),
                        v[1] + g * (v[1] - s->ad.v_start[i][1]), v[2]);
      dBodySetAngularVel(s->body[i], w[0], w[1], w[2] + g * (w[2] - s->ad.w_start[i][2]));
    }
  }
  for (int i = 0; i < 3; i++) {
    const dReal *v = dBodyGetLinearVel(s->body[i]), *w = dBodyGetAngularVel(s->body[i]);
    for (int q = 0; q < 3; q++) s->ad.v_start[i][q] = v[q], s->ad.w_start[i][q] = w[q];
  }
  s->ad.h_last = h;
}

fb_status fb_ode_world_step(fb_ode_world *s, fb_diag *diag) {
  if (!s->ad.on) {
    fb_status st = world_step(s, s->def.solver.h, diag);
    if (st == FB_OK) s->steps++;
    return st;
  }
  if (s->ad.k < s->ad.mc) { /* a sample inside the last ODE step */
    s->ad.k++;
    s->steps++;
    return FB_OK;
  }
  const int m = adapt_multiple(s);
  if (s->ad.rocking) carry_velocities(s, m * s->def.solver.h);
  for (int i = 0; i < 3; i++) s->ad.ang0[i] = s->angle[i], s->ad.w0[i] = s->omega_prev[i];
  adapt_geometry(s, s->ad.pen0, s->ad.ex0, s->ad.ey0);
  const double h = m * s->def.solver.h;
  fb_status st = world_step(s, h, diag);
  if (st != FB_OK) return st;
  for (int i = 0; i < 3; i++) s->ad.ang1[i] = s->angle[i], s->ad.w1[i] = s->omega_prev[i];
  adapt_geometry(s, s->ad.pen1, s->ad.ex1, s->ad.ey1);
  s->ad.pen_end = penetration_now(s, &s->ad.pen_joint_end);
  s->ad.drift_end = joint_drift_now(s);
  fb_step_stats *t = &s->ad.stats;
  if (t->steps == 0 || h < t->h_min * (1.0 - 1e-9)) t->h_min = h, t->n_h_min = 0;
  if (t->steps == 0 || h > t->h_max * (1.0 + 1e-9)) t->h_max = h, t->n_h_max = 0;
  t->n_h_min += fabs(h - t->h_min) <= 1e-9 * h;
  t->n_h_max += fabs(h - t->h_max) <= 1e-9 * h;
  t->steps++;
  s->ad.m_prev = m;
  s->ad.mc = m;
  s->ad.k = 1;
  s->steps++;
  return FB_OK;
}

void fb_ode_world_step_stats(const fb_ode_world *s, fb_step_stats *out) {
  if (s->ad.on) {
    *out = s->ad.stats;
    return;
  }
  out->steps = s->steps;
  out->h_min = out->h_max = s->def.solver.h;
  out->n_h_min = out->n_h_max = s->steps;
}

void fb_ode_world_sample(const fb_ode_world *s, fb_sample *x) {
  x->t = (double)s->steps * s->def.solver.h;
  x->crank_angle = s->angle[FB_CRANK];
  x->coupler_angle = s->angle[FB_COUPLER];
  x->coupler_omega = s->omega_prev[FB_COUPLER];
  x->coupler_alpha = s->alpha[FB_COUPLER];
  x->follower_angle = s->angle[FB_FOLLOWER];
  x->follower_omega = s->omega_prev[FB_FOLLOWER];
  x->follower_alpha = s->alpha[FB_FOLLOWER];
  if (s->ad.on && s->ad.k < s->ad.mc) {
    /* inside an ODE step: angles and omega linear, alpha the step's */
    const double f = (double)s->ad.k / (double)s->ad.mc;
    double *ang[3] = {&x->crank_angle, &x->coupler_angle, &x->follower_angle};
    for (int i = 0; i < 3; i++) *ang[i] = s->ad.ang0[i] + f * (s->ad.ang1[i] - s->ad.ang0[i]);
    x->coupler_omega = s->ad.w0[FB_COUPLER] + f * (s->ad.w1[FB_COUPLER] - s->ad.w0[FB_COUPLER]);
    x->follower_omega =
        s->ad.w0[FB_FOLLOWER] + f * (s->ad.w1[FB_FOLLOWER] - s->ad.w0[FB_FOLLOWER]);
  }
  for (int j = 0; j < 4; j++) {
    for (int q = 0; q < FB_CONTACT_COLS; q++) x->contact[j][q] = 0.0;
    if (!(s->def.clearance_mask & (1 << j))) continue;
    const clearance *c = &s->cl[j];
    if (s->ad.on && s->ad.k < s->ad.mc) { /* inside an ODE step: interpolated */
      const double f = (double)s->ad.k / (double)s->ad.mc;
      x->contact[j][FB_C_FORCE] = c->force;
      x->contact[j][FB_C_PEN] = s->ad.pen0[j] + f * (s->ad.pen1[j] - s->ad.pen0[j]);
      x->contact[j][FB_C_EX] = s->ad.ex0[j] + f * (s->ad.ex1[j] - s->ad.ex0[j]);
      x->contact[j][FB_C_EY] = s->ad.ey0[j] + f * (s->ad.ey1[j] - s->ad.ey0[j]);
      x->contact[j][FB_C_STATE] = c->force > 0.0 ? (double)c->ep.state : (double)FB_STATE_FREE;
      continue;
    }
    double e[2], ev[2], num;
    clearance_geometry(c, e, &num, ev);
    x->contact[j][FB_C_FORCE] = c->force;
    x->contact[j][FB_C_PEN] = clearance_penetration(s, c);
    x->contact[j][FB_C_EX] = e[0];
    x->contact[j][FB_C_EY] = e[1];
    x->contact[j][FB_C_STATE] = c->force > 0.0 ? (double)c->ep.state : (double)FB_STATE_FREE;
  }
}

static double penetration_now(const fb_ode_world *s, int *joint) {
  double worst = 0.0;
  *joint = -1;
  for (int j = 0; j < 4; j++) {
    if (!(s->def.clearance_mask & (1 << j))) continue;
    const double pen = clearance_penetration(s, &s->cl[j]);
    if (*joint < 0 || pen > worst) {
      worst = pen;
      *joint = j;
    }
  }
  return worst;
}

void fb_ode_world_ccd_calls(const fb_ode_world *s, unsigned long *calls, unsigned long *contacts) {
  *calls = *contacts = 0;
  for (int j = 0; j < 4; j++) {
    if (!s->cl[j].bore) continue;
    *calls += fb_ccd_bore_calls(s->cl[j].bore);
    *contacts += fb_ccd_bore_contacts(s->cl[j].bore);
  }
}

int fb_ode_world_impacts(const fb_ode_world *s, int j) { return s->cl[j].ep.impacts; }

void fb_ode_world_stopped(const fb_ode_world *s, fb_stop *out) {
  *out = s->stop;
  out->engine = "ode";
  if (out->kind != FB_STOP_ALIASED) out->joint = -1;
}

void fb_ode_world_provenance(const fb_ode_world *s, int j, fb_contact_provenance *out) {
  *out = s->cl[j].prov;
  if (out->contact_steps == 0)
    out->mass_eff_min = out->mass_eff_max = out->erp_max = out->cfm_min = out->h_omega_max = NAN;
}

static double joint_drift_now(const fb_ode_world *s) {
  double worst = 0.0;
  for (int j = 0; j < 4; j++) {
    if (!s->hinge[j]) continue;
    dVector3 p1, p2;
    dJointGetHingeAnchor(s->hinge[j], p1);
    dJointGetHingeAnchor2(s->hinge[j], p2);
    double d = sqrt((p1[0] - p2[0]) * (p1[0] - p2[0]) + (p1[1] - p2[1]) * (p1[1] - p2[1]) +
                    (p1[2] - p2[2]) * (p1[2] - p2[2]));
    if (d > worst) worst = d;
  }
  return worst;
}

/* inside an adaptive ODE step the bodies rest at its end: the values of
 * its end, kept when it was taken */
double fb_ode_world_joint_drift(const fb_ode_world *s) {
  return s->ad.on ? s->ad.drift_end : joint_drift_now(s);
}

double fb_ode_world_penetration(const fb_ode_world *s, int *joint) {
  if (!s->ad.on) return penetration_now(s, joint);
  *joint = s->ad.pen_joint_end;
  return s->ad.pen_end;
}

void fb_ode_world_reactions(const fb_ode_world *s, double force[4][2], double *drive_torque) {
  if (s->steps == 0) {
    for (int j = 0; j < 4; j++) force[j][0] = force[j][1] = 0.0;
    *drive_torque = 0.0;
    return;
  }
  /* A: on the crank (body 1); B: on the coupler (body 2); C: on the follower
   * (body 2); D: on the follower (body 1) */
  const int on_body2[4] = {0, 1, 1, 0};
  for (int j = 0; j < 4; j++) {
    if (!s->hinge[j]) {
      /* a clearance joint: the contact force; its pin is on body 1 (the
       * crank at A and B, the coupler at C, the follower at D) */
      const double sign = on_body2[j] ? -1.0 : 1.0;
      force[j][0] = sign * s->cl[j].force_pin[0];
      force[j][1] = sign * s->cl[j].force_pin[1];
      continue;
    }
    const dReal *f = on_body2[j] ? s->feedback[j].f2 : s->feedback[j].f1;
    force[j][0] = f[0];
    force[j][1] = f[1];
  }
  /* ODE's torque is about the crank's centre of mass; move it to the pivot */
  const double r[2] = {-s->crank_com_before[0], -s->crank_com_before[1]}; /* A - G */
  *drive_torque = s->hinge[0] ? s->feedback[0].t1[2] - (r[0] * force[0][1] - r[1] * force[0][0])
                              : 0.0;
}

size_t fb_ode_world_steps(const fb_ode_world *s) { return s->steps; }

void fb_ode_world_mechanism(const fb_ode_world *s, fb_mechanism *out) {
  memset(out, 0, sizeof *out);
  for (int i = 0; i < 3; i++) {
    const dReal *p = dBodyGetPosition(s->body[i]);
    out->mass[i] = s->def.link[i].mass;
    out->inertia[i] = s->def.link[i].inertia;
    out->com[i][0] = p[0];
    out->com[i][1] = p[1];
  }
  for (int j = 0; j < 4; j++) {
    dVector3 q;
    if (s->hinge[j]) {
      dJointGetHingeAnchor(s->hinge[j], q);
    } else {
      const clearance *c = &s->cl[j];
      dBodyGetRelPointPos(c->pin, c->pin_local[0], c->pin_local[1], c->pin_local[2], q);
    }
    out->joint[j][0] = q[0];
    out->joint[j][1] = q[1];
  }
  out->clearance_mask = s->def.clearance_mask;
  out->crank_driven = 1;
}

/* penetration rate n . (v_pin - v_hole) at the pin centre of clearance joint c */
static double probe_rate(const clearance *c, const double n[2]) {
  dVector3 p, vp, vh = {0, 0, 0, 0};
  dBodyGetRelPointPos(c->pin, c->pin_local[0], c->pin_local[1], c->pin_local[2], p);
  dBodyGetRelPointVel(c->pin, c->pin_local[0], c->pin_local[1], c->pin_local[2], vp);
  if (c->hole) dBodyGetPointVel(c->hole, p[0], p[1], p[2], vh);
  return n[0] * (vp[0] - vh[0]) + n[1] * (vp[1] - vh[1]);
}

fb_status fb_ode_world_probe_inverse_mass(fb_ode_world *s, int j, const double n[2], double force,
                                      double *inv_mass, fb_diag *diag) {
  if (j < 0 || j > 3 || !(s->def.clearance_mask & (1 << j)) || !(force > 0.0))
    return fb_diag_set(diag, FB_ERR_ARG,
                       "probe: joint %d must be a clearance joint and force %g N positive", j,
                       force);
  const clearance *c = &s->cl[j];
  dReal pos[3][3], quat[3][4], lin[3][3], ang[3][3];
  for (int i = 0; i < 3; i++) {
    memcpy(pos[i], dBodyGetPosition(s->body[i]), sizeof pos[i]);
    memcpy(quat[i], dBodyGetQuaternion(s->body[i]), sizeof quat[i]);
    memcpy(lin[i], dBodyGetLinearVel(s->body[i]), sizeof lin[i]);
    memcpy(ang[i], dBodyGetAngularVel(s->body[i]), sizeof ang[i]);
  }
  double rate[2];
  int ok = 1;
  for (int trial = 0; trial < 2 && ok; trial++) {
    for (int i = 0; i < 3; i++) {
      dBodySetPosition(s->body[i], pos[i][0], pos[i][1], pos[i][2]);
      dBodySetQuaternion(s->body[i], quat[i]);
      dBodySetLinearVel(s->body[i], lin[i][0], lin[i][1], lin[i][2]);
      dBodySetAngularVel(s->body[i], ang[i][0], ang[i][1], ang[i][2]);
    }
    if (trial == 1) {
      dVector3 p;
      dBodyGetRelPointPos(c->pin, c->pin_local[0], c->pin_local[1], c->pin_local[2], p);
      dBodyAddForceAtPos(c->pin, -force * n[0], -force * n[1], 0.0, p[0], p[1], p[2]);
      if (c->hole) dBodyAddForceAtPos(c->hole, force * n[0], force * n[1], 0.0, p[0], p[1], p[2]);
    }
    ok = dWorldStep(s->world, s->def.solver.h);
    rate[trial] = probe_rate(c, n);
  }
  for (int i = 0; i < 3; i++) {
    dBodySetPosition(s->body[i], pos[i][0], pos[i][1], pos[i][2]);
    dBodySetQuaternion(s->body[i], quat[i]);
    dBodySetLinearVel(s->body[i], lin[i][0], lin[i][1], lin[i][2]);
    dBodySetAngularVel(s->body[i], ang[i][0], ang[i][1], ang[i][2]);
  }
  if (!ok) return fb_diag_set(diag, FB_ERR_NOMEM, "probe: ODE could not step");
  *inv_mass = (rate[0] - rate[1]) / (s->def.solver.h * force);
  return FB_OK;
}

void fb_ode_world_destroy(fb_ode_world *s) {
  if (!s) return;
  if (s->broken) {
    /* ODE's world was left mid-step (its job list still holds the step):
     * destroying it would fail ODE's own checks, so it is leaked, and ODE is
     * never closed in this process; the project's own allocations are freed */
    fb_ode_quarantine(s->world);
    fb_ode_quarantine(s->contacts);
    for (int j = 0; j < 4; j++) {
      free(s->cl[j].boxes);
      if (s->cl[j].bore) fb_ccd_bore_destroy(s->cl[j].bore);
      free(s->cl[j].fbs);
    }
    fb_load_scale_free(&s->ad.load);
    free(s);
    return;
  }
  for (int j = 0; j < 4; j++) {
    facet_destroy(&s->cl[j], s->def.faceted_n);
    if (s->cl[j].bore) {
      fb_ccd_bore_destroy(s->cl[j].bore);
      free(s->cl[j].fbs);
    }
  }
  dJointGroupDestroy(s->contacts);
  dWorldDestroy(s->world);
  fb_load_scale_free(&s->ad.load);
  free(s);
  fb_ode_release();
}
