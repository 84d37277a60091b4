/* The generic colliders of a pin in its hole (ode_colliders.h). */
#include "ode_colliders.h"

#include <math.h>
#include <string.h>

#include "contact_mass.h"
#include "ode_contact.h"

#define FACET_THICKNESS_M 2e-3 /* radial thickness of the ring's boxes and the bore's segments */

/* g's pin centre or hole centre: the body's local point in the world (a
 * ground's: the point itself) */
static void world_point(dBodyID b, const double local[3], dVector3 out) {
  if (b) {
    dBodyGetRelPointPos(b, local[0], local[1], local[2], out);
    return;
  }
  out[0] = local[0];
  out[1] = local[1];
  out[2] = local[2];
}

fb_status ode_collider_faceted(ode_collider *g, int n, double pin_radius, double hole_radius,
                               double pin_length, fb_diag *diag) {
  const double t = FACET_THICKNESS_M;
  const double w = 2.0 * (hole_radius + t) * tan(M_PI / n) * 1.001; /* closes the ring */
  g->cyl = dCreateCylinder(0, pin_radius, pin_length);
  g->ring = dHashSpaceCreate(0);
  if (!g->cyl || !g->ring) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for a ring");
  if (g->pin) {
    dGeomSetBody(g->cyl, g->pin);
    dGeomSetOffsetPosition(g->cyl, g->pin_local[0], g->pin_local[1], g->pin_local[2]);
  } else {
    dGeomSetPosition(g->cyl, g->pin_local[0], g->pin_local[1], g->pin_local[2]);
  }
  for (int k = 0; k < n; k++) {
    const double phi = 2.0 * M_PI * k / n;
    dGeomID b = dCreateBox(g->ring, t, w, pin_length);
    dMatrix3 R;
    dRFromAxisAndAngle(R, 0, 0, 1, phi);
    const double cx = (hole_radius + 0.5 * t) * cos(phi), cy = (hole_radius + 0.5 * t) * sin(phi);
    if (g->hole) {
      dGeomSetBody(b, g->hole);
      /* offsets are in the hole body's frame: the ring is centred on hole_local */
      dGeomSetOffsetPosition(b, g->hole_local[0] + cx, g->hole_local[1] + cy, 0.0);
      dGeomSetOffsetRotation(b, R);
    } else {
      dGeomSetPosition(b, g->hole_local[0] + cx, g->hole_local[1] + cy, 0.0);
      dGeomSetRotation(b, R);
    }
  }
  return FB_OK;
}

fb_status ode_collider_ccd(ode_collider *g, int segments, double ovality, double pin_radius,
                           double hole_radius, double pin_length, fb_diag *diag) {
  fb_ccd_bore_def bd = fb_ccd_bore_default();
  bd.pin_radius = pin_radius;
  bd.pin_length = pin_length;
  bd.hole_radius = hole_radius;
  bd.shape = ovality > 0.0 ? FB_BORE_ELLIPSE : FB_BORE_CIRCLE;
  bd.ovality = ovality;
  bd.segments = segments;
  bd.wall = FACET_THICKNESS_M;
  return fb_ccd_bore_create(&g->bore, &bd, diag);
}

void ode_collider_free(ode_collider *g) {
  if (g->ring) dSpaceDestroy(g->ring); /* destroys the boxes it holds (cleanup mode on) */
  if (g->cyl) dGeomDestroy(g->cyl);
  fb_ccd_bore_destroy(g->bore);
  g->ring = 0;
  g->cyl = 0;
  g->bore = NULL;
}

void ode_collider_pin_in_hole(const ode_collider *g, double p[2]) {
  dVector3 w, l;
  world_point(g->pin, g->pin_local, w);
  if (g->hole) {
    dBodyGetPosRelPoint(g->hole, w[0], w[1], w[2], l);
    p[0] = l[0] - g->hole_local[0];
    p[1] = l[1] - g->hole_local[1];
  } else {
    p[0] = w[0] - g->hole_local[0];
    p[1] = w[1] - g->hole_local[1];
  }
}

/* broadphase callback: narrowphase of the pin against one box, into the
 * collider's hits */
static void facet_near(void *data, dGeomID o1, dGeomID o2) {
  ode_collider *g = data;
  if (g->nhit >= ODE_FACET_CONTACTS) return;
  g->nhit += dCollide(o1, o2, ODE_FACET_CONTACTS - g->nhit, &g->hit[g->nhit].geom, sizeof(ode_hit));
}

/* the faceted ring's contacts: ODE's collider, each with its approach rate */
static int facet_hits(ode_collider *g) {
  dSpaceCollide2(g->cyl, (dGeomID)g->ring, g, facet_near);
  for (int i = 0; i < g->nhit; i++) {
    const dContactGeom *c = &g->hit[i].geom;
    dBodyID p1 = dGeomGetBody(c->g1), p2 = dGeomGetBody(c->g2);
    dVector3 v1 = {0, 0, 0, 0}, v2 = {0, 0, 0, 0};
    if (p1) dBodyGetPointVel(p1, c->pos[0], c->pos[1], c->pos[2], v1);
    if (p2) dBodyGetPointVel(p2, c->pos[0], c->pos[1], c->pos[2], v2);
    /* normal points into body 1: approach rate along it */
    g->hit[i].rate = (v2[0] - v1[0]) * c->normal[0] + (v2[1] - v1[1]) * c->normal[1] +
                     (v2[2] - v1[2]) * c->normal[2];
  }
  g->lead = 0; /* the episode follows the first contact */
  return g->nhit;
}

/* the bore's contacts from libccd (hole frame) in the world, each with its
 * approach rate; the deepest leads */
static int ccd_hits(ode_collider *g) {
  double p[2];
  ode_collider_pin_in_hole(g, p);
  fb_ccd_contact hit[FB_CCD_CONTACTS];
  const int n = fb_ccd_bore_collide(g->bore, p, hit, FB_CCD_CONTACTS);
  g->lead = 0;
  for (int i = 0; i < n; i++) {
    /* to the world: normal (pin into wall) and point */
    dVector3 nw, pw;
    if (g->hole) {
      dBodyVectorToWorld(g->hole, hit[i].normal[0], hit[i].normal[1], 0.0, nw);
      dBodyGetRelPointPos(g->hole, g->hole_local[0] + hit[i].point[0],
                          g->hole_local[1] + hit[i].point[1], g->hole_local[2], pw);
    } else {
      nw[0] = hit[i].normal[0];
      nw[1] = hit[i].normal[1];
      nw[2] = 0.0;
      pw[0] = g->hole_local[0] + hit[i].point[0];
      pw[1] = g->hole_local[1] + hit[i].point[1];
      pw[2] = 0.0;
    }
    /* approach rate: pin velocity minus hole velocity at the point, along the normal */
    dVector3 vp = {0, 0, 0, 0}, vh = {0, 0, 0, 0};
    if (g->pin) dBodyGetPointVel(g->pin, pw[0], pw[1], pw[2], vp);
    if (g->hole) dBodyGetPointVel(g->hole, pw[0], pw[1], pw[2], vh);
    ode_hit *h = &g->hit[i];
    memset(&h->geom, 0, sizeof h->geom);
    h->rate = (vp[0] - vh[0]) * nw[0] + (vp[1] - vh[1]) * nw[1];
    h->geom.depth = hit[i].depth;
    for (int q = 0; q < 3; q++) {
      h->geom.pos[q] = pw[q];
      h->geom.normal[q] = -nw[q]; /* into the pin (body 1) */
    }
    if (hit[i].depth > hit[g->lead].depth) g->lead = i;
  }
  return g->nhit = n;
}

int ode_collider_hits(ode_collider *g) {
  g->nhit = 0;
  g->nfb = 0;
  return g->bore ? ccd_hits(g) : facet_hits(g);
}

/* a contact joint of contact ct between bodies b1 and b2, with the next
 * feedback */
static void add_row(ode_collider *g, const ode_collider_step *x, const dContact *ct, dBodyID b1,
                    dBodyID b2) {
  dJointID cj = dJointCreateContact(x->world, x->group, ct);
  dJointAttach(cj, b1, b2);
  dJointSetFeedback(cj, &g->fb[g->nfb++]);
}

/* faceted: each contact its own row, at its own depth and effective mass */
static void facet_rows(ode_collider *g, const ode_collider_step *x) {
  const int n = g->nhit;
  for (int i = 0; i < n; i++) {
    const dContactGeom *c = &g->hit[i].geom;
    /* the collider's normal points into the pin: the pin-minus-hole direction is -normal */
    const double nn[2] = {-c->normal[0], -c->normal[1]};
    const double m_eff = x->mass(x->user, nn);
    const fb_contact_law law = fb_contact_law_on_mass(x->law, m_eff);
    dContact ct;
    memset(&ct, 0, sizeof ct);
    ct.geom = *c;
    fb_contact_row used;
    if (!fb_ode_soft_contact(&ct, &law, x->mapping, x->h, m_eff, n, c->depth, g->hit[i].rate, x->v0,
                             0, x->persistence, x->friction, &used))
      continue;
    x->note(x->user, &used, (double)n, m_eff);
    add_row(g, x, &ct, dGeomGetBody(c->g1), dGeomGetBody(c->g2));
  }
}

/* libccd: the deepest contact's row, shared by depth (or split by count) */
static void ccd_rows(ode_collider *g, const ode_collider_step *x) {
  const int n = g->nhit, deep = g->lead;
  double sum = 0.0;
  for (int i = 0; i < n; i++) sum += g->hit[i].geom.depth;
  /* the effective mass along the deepest contact's normal (pin into wall) */
  const double n_deep[2] = {-g->hit[deep].geom.normal[0], -g->hit[deep].geom.normal[1]};
  const double m_eff = x->mass(x->user, n_deep);
  const fb_contact_law law = fb_contact_law_on_mass(x->law, m_eff);
  /* the one row the exact collider would hand ODE at the deepest contact */
  fb_contact_row base;
  const int have_row = fb_contact_map(&base, &law, x->mapping, x->h, m_eff, 1,
                                      g->hit[deep].geom.depth, g->hit[deep].rate, x->v0,
                                      NULL) == FB_OK;
  if (have_row && x->persistence > 0.0 && x->mapping == FB_MAPPING_MATCHED_STATIC)
    fb_contact_row_static(&base, x->h, m_eff, x->persistence);
  for (int i = 0; i < n; i++) {
    const ode_hit *h = &g->hit[i];
    dContact ct;
    memset(&ct, 0, sizeof ct);
    fb_contact_row row = base;
    if (x->split == 1) {
      /* the faceted model's rule: own depth, spring divided by the count */
      if (!fb_ode_soft_contact(&ct, &law, x->mapping, x->h, m_eff, n, h->geom.depth, h->rate,
                               x->v0, 0, x->persistence, x->friction, &row))
        continue;
    } else {
      /* share w of the row: a and b = 1/CFM scale by w, ERP = h a / b does not */
      if (!have_row) continue;
      row.cfm = base.cfm * sum / h->geom.depth;
      fb_ode_soft_fill(&ct, &row, x->friction);
    }
    x->note(x->user, &row, x->split == 1 ? (double)n : 1.0, m_eff);
    for (int q = 0; q < 3; q++) {
      ct.geom.pos[q] = h->geom.pos[q];
      ct.geom.normal[q] = h->geom.normal[q];
    }
    add_row(g, x, &ct, g->pin, g->hole);
  }
}

void ode_collider_rows(ode_collider *g, const ode_collider_step *x) {
  g->nfb = 0;
  if (g->bore) ccd_rows(g, x);
  else facet_rows(g, x);
}

int ode_collider_force(ode_collider *g, double f[2]) {
  f[0] = f[1] = 0.0;
  for (int i = 0; i < g->nfb; i++) {
    f[0] += g->fb[i].f1[0];
    f[1] += g->fb[i].f1[1];
  }
  const int n = g->nfb;
  g->nfb = 0;
  return n;
}

void ode_note_row(fb_contact_provenance *p, double *step_hw, double *step_wdh,
                  const fb_contact_row *u, double share, double mass, double h) {
  if (p->contact_steps == 0 || u->erp > p->erp_max) p->erp_max = u->erp;
  if (p->contact_steps == 0 || u->cfm < p->cfm_min) p->cfm_min = u->cfm;
  const double hw = fb_contact_h_omega(h, u->kp * share, mass); /* rows in parallel */
  if (p->contact_steps == 0 || hw > p->h_omega_max) p->h_omega_max = hw;
  if (hw > *step_hw) *step_hw = hw;
  if (p->contact_steps == 0 || mass < p->mass_eff_min) p->mass_eff_min = mass;
  if (p->contact_steps == 0 || mass > p->mass_eff_max) p->mass_eff_max = mass;
  p->contact_steps++;
  const double wdh = fb_contact_omega_d_h(h, u->kp * share, u->kd * share, mass);
  if (wdh > *step_wdh) *step_wdh = wdh;
}
