/* fourbar mapping below the command: ERP and CFM of the restitution law's
 * spring-damper (contact.h) on a logarithmic grid of contact stiffness and
 * step size. */
#ifndef FB_MAPPING_GRID_H
#define FB_MAPPING_GRID_H

#include "contact.h"
#include "status.h"

/* Most grid points along each axis. */
#define FB_MAPPING_GRID_MAX 64

typedef struct {
  double m;                  /* effective mass [kg] */
  double cr;                 /* coefficient of restitution [-] */
  double zeta;               /* its damping ratio [-] */
  fb_mapping mapping;        /* the row: matched (fb_contact_matched) or secant/tangent */
  int nk, nh;                /* grid points along stiffness and step */
  double k[FB_MAPPING_GRID_MAX];   /* stiffness [N/m] */
  double h[FB_MAPPING_GRID_MAX];   /* step [s] */
  /* row-major by stiffness: [i * nh + j] for k[i], h[j] */
  double erp[FB_MAPPING_GRID_MAX * FB_MAPPING_GRID_MAX];   /* [-] */
  double cfm[FB_MAPPING_GRID_MAX * FB_MAPPING_GRID_MAX];   /* [m/(N s)] */
  double h_omega[FB_MAPPING_GRID_MAX * FB_MAPPING_GRID_MAX]; /* h sqrt(k / m) [-] */
} fb_mapping_grid;

/* Fills g for mass m [kg], restitution cr, stiffness k0 to k1 [N/m] and
 * step h0 to h1 [s] (0 < from < to), per points per decade, with the
 * damper c = 2 zeta sqrt(k m). Errors: FB_ERR_RANGE when the grid has more
 * than FB_MAPPING_GRID_MAX points along an axis. */
fb_status fb_mapping_grid_make(fb_mapping_grid *g, double m, double cr, double k0, double k1,
                               double h0, double h1, double per, fb_mapping mapping,
                               fb_diag *diag);

#endif
