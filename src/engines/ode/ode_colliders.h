/* The generic colliders of a pin in its hole in ODE, shared by the
 * hand-built world (ode_world.h, its faceted and libccd variants) and the
 * engine kit's binding (ode_kit.c): the faceted hole, a ring of ODE boxes
 * around an ODE cylinder collided by dCollide, and the libccd bore
 * (collide_ccd.h). A collider is built once; each step, ode_collider_hits
 * finds its contacts at the bodies' state, the caller updates the joint's
 * contact episode from them (the rate of hit[lead]), and
 * ode_collider_rows hands ODE their contact joints with the law's rows
 * split over them: the faceted ring each contact its own row at its own
 * depth and effective mass, spring and damper divided by their count; the
 * bore the deepest contact's row shared in proportion to depth (split 0),
 * or the faceted ring's rule (split 1). The rule that keeps it correct:
 * every buffer is part of the collider, sized when it is built, so a step
 * allocates nothing. Private to src/engines/ode (includes ODE's header). */
#ifndef FB_ODE_COLLIDERS_H
#define FB_ODE_COLLIDERS_H

#include <ode/ode.h>

#include "collide_ccd.h"
#include "contact.h"
#include "engine.h"
#include "ode_world.h"

/* Most contacts the faceted ring keeps per step (the bore keeps
 * FB_CCD_CONTACTS). */
#define ODE_FACET_CONTACTS 64

/* One contact found this step, in the world. */
typedef struct {
  dContactGeom geom; /* ODE's: point [m], unit normal into the pin (ODE's body 1), depth [m]
                        (the ring's: its geoms; the bore's: none) */
  double rate;       /* penetration rate along the normal [m/s] (> 0 approaching) */
} ode_hit;

/* One pin in its hole with a generic collider. */
typedef struct {
  dBodyID pin, hole;    /* 0: the ground */
  double pin_local[3];  /* the pin's centre in the pin body's frame (the world's for the
                           ground) [m] */
  double hole_local[3]; /* the hole's centre in the hole body's frame (likewise) [m] */
  dGeomID cyl;          /* faceted: the pin, an ODE cylinder; 0: none */
  dSpaceID ring;        /* faceted: the hash space holding the ring's boxes; 0: none */
  fb_ccd_bore *bore;    /* libccd: the ring of segments in the hole's frame; NULL: none */
  ode_hit hit[ODE_FACET_CONTACTS]; /* this step's contacts (ode_collider_hits) */
  int nhit;             /* how many */
  int lead;             /* the one whose rate the episode follows: the ring's first, the
                           bore's deepest */
  dJointFeedback fb[ODE_FACET_CONTACTS]; /* the feedback of this step's rows */
  int nfb;              /* rows made this step */
} ode_collider;

/* What one step's rows are made with. */
typedef struct {
  dWorldID world;
  dJointGroupID group;                           /* the contact joints' group */
  double (*mass)(void *user, const double n[2]); /* the effective mass along unit n [kg] */
  void (*note)(void *user, const fb_contact_row *row, double share, double mass);
                                                 /* each row made: its share of the spring
                                                    (rows in parallel) and its mass [kg] */
  void *user;
  const fb_contact_law *law; /* the joint's law; its damper on each row's mass (contact_mass.h) */
  fb_mapping mapping;
  double h;                  /* step [s] */
  double friction;           /* Coulomb's mu (0: frictionless) [-] */
  double persistence;        /* the matched-static row's weight (contact.h) [-] */
  double v0;                 /* the episode's onset rate (episode.h) [m/s] */
  int split;                 /* the bore: 0 by depth, 1 by count */
} ode_collider_step;

/* Builds the faceted hole of g (its pin, hole and centres set, the rest
 * zero): n boxes, each 2 mm thick radially, tangent inside to the hole of
 * hole_radius [m] around its centre on the hole's body, and the pin's
 * cylinder of pin_radius [m] on the pin's, both pin_length [m] long along
 * z. Errors: FB_ERR_NOMEM. */
fb_status ode_collider_faceted(ode_collider *g, int n, double pin_radius, double hole_radius,
                               double pin_length, fb_diag *diag);

/* Builds the libccd bore of g (collide_ccd.h: fb_ccd_bore_default's
 * solver settings, 2 mm walls): segments convex segments tangent to the
 * hole of hole_radius [m], an ellipse ovality [m] wider along the hole
 * body's x axis when ovality > 0, against a pin of pin_radius [m], both
 * pin_length [m] long. Errors: those of fb_ccd_bore_create. */
fb_status ode_collider_ccd(ode_collider *g, int segments, double ovality, double pin_radius,
                           double hole_radius, double pin_length, fb_diag *diag);

/* Frees what g's builder made (a g never built is ignored). */
void ode_collider_free(ode_collider *g);

/* g's contacts at the bodies' state now into g->hit; returns how many. */
int ode_collider_hits(ode_collider *g);

/* Hands ODE one contact joint per row of g's hits (ode_collider_hits,
 * g->nhit > 0), each with its feedback; x says how. */
void ode_collider_rows(ode_collider *g, const ode_collider_step *x);

/* The force of the last step's rows on the pin's body when it is ODE's
 * body 1 of each row (the hole's otherwise), summed into f (x, y) [N];
 * returns how many rows, and forgets them. */
int ode_collider_force(ode_collider *g, double f[2]);

/* The pin's centre relative to the hole's centre in the hole body's frame
 * (the world's for a ground hole) [m]. */
void ode_collider_pin_in_hole(const ode_collider *g, double p[2]);

/* Records one contact row of a clearance joint: its ERP, CFM, effective
 * mass mass [kg] and h omega_c (its spring kp times share, rows in
 * parallel) into p (p->contact_steps counts the rows), and the step's
 * largest h omega_c and omega_d h into *step_hw and *step_wdh; h the step
 * [s]. */
void ode_note_row(fb_contact_provenance *p, double *step_hw, double *step_wdh,
                  const fb_contact_row *u, double share, double mass, double h);

#endif
