/* The ODE world's generic colliders, for comparison with the exact contact
 * (ode_world.h, "Faceted variant" and "libccd variant"): the faceted hole, a
 * ring of ODE boxes around an ODE cylinder collided by dCollide, and the
 * libccd bore (collide_ccd.h); each builds its geometry and hands ODE the
 * step's contact joints with the law's rows split over the contacts. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ode_contact.h"
#include "ode_world_internal.h"

#define FACET_THICKNESS_M 2e-3 /* radial thickness of the ring's boxes */
#define FACET_MAX_CONTACTS 64   /* contacts kept per joint and step */

/* builds the faceted hole and pin of clearance joint j */
void ode_facet_create(fb_ode_world *s, int j) {
  ode_clearance *c = &s->cl[j];
  const fb_model_scene *d = &s->def;
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

void ode_facet_destroy(ode_clearance *c, int n) {
  (void)n;
  if (!c->boxes) return;
  dSpaceDestroy(c->ring); /* destroys the boxes it holds (cleanup mode on) */
  dGeomDestroy(c->cyl);
  free(c->boxes);
  free(c->fbs);
}

/* builds the libccd ring of clearance joint j */
fb_status ode_ccd_create(fb_ode_world *s, int j, fb_diag *diag) {
  const fb_model_scene *d = &s->def;
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
void ode_facet_contacts(fb_ode_world *s, int j) {
  ode_clearance *c = &s->cl[j];
  const fb_model_scene *d = &s->def;
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
    const double m_eff = ode_step_effective_mass(s, j, nn);
    const fb_contact_law law = ode_step_law(&d->law[j], m_eff);
    dContact ct;
    memset(&ct, 0, sizeof ct);
    ct.geom = g[i];
    fb_contact_row used;
    if (!fb_ode_soft_contact(&ct, &law, d->mapping, d->solver.h, m_eff, n, g[i].depth, ddot,
                             c->ep.v0, 0, c->persistence, d->friction, &used))
      continue;
    ode_note_row(c, &used, (double)n, m_eff, d->solver.h);
    dJointID cj = dJointCreateContact(s->world, s->contacts, &ct);
    dJointAttach(cj, p1, p2);
    dJointSetFeedback(cj, &c->fbs[c->nfb++]);
  }
}

/* libccd: contact joints from the generic collider for clearance joint j */
void ode_ccd_contacts(fb_ode_world *s, int j) {
  ode_clearance *c = &s->cl[j];
  const fb_model_scene *d = &s->def;
  double p[2];
  ode_pin_in_hole_frame(c, p);
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
  const double m_eff = ode_step_effective_mass(s, j, n_deep);
  const fb_contact_law law = ode_step_law(&d->law[j], m_eff);
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
    ode_note_row(c, &row, d->ccd_split == 1 ? (double)n : 1.0, m_eff, d->solver.h);
    for (int q = 0; q < 3; q++) {
      ct.geom.pos[q] = pw[i][q];
      ct.geom.normal[q] = -nw[i][q]; /* into the pin (body 1) */
    }
    dJointID cj = dJointCreateContact(s->world, s->contacts, &ct);
    dJointAttach(cj, c->pin, c->hole);
    dJointSetFeedback(cj, &c->fbs[c->nfb++]);
  }
}
