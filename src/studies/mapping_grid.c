/* fourbar mapping's grid (mapping_grid.h); the mapping is contact.c's. */
#include "mapping_grid.h"

#include <math.h>

#include "contact.h"

fb_status fb_mapping_grid_make(fb_mapping_grid *g, double m, double cr, double k0, double k1,
                               double h0, double h1, double per, fb_mapping mapping,
                               fb_diag *diag) {
  const int nk = (int)floor(log10(k1 / k0) * per + 1e-9) + 1;
  const int nh = (int)floor(log10(h1 / h0) * per + 1e-9) + 1;
  if (nk > FB_MAPPING_GRID_MAX || nh > FB_MAPPING_GRID_MAX)
    return fb_diag_set(diag, FB_ERR_RANGE, "grid larger than %d x %d", FB_MAPPING_GRID_MAX,
                       FB_MAPPING_GRID_MAX);
  g->m = m;
  g->cr = cr;
  g->mapping = mapping;
  g->nk = nk;
  g->nh = nh;
  for (int i = 0; i < nk; i++) g->k[i] = k0 * pow(10.0, i / per);
  for (int j = 0; j < nh; j++) g->h[j] = h0 * pow(10.0, j / per);
  g->zeta = fb_contact_restitution_zeta(cr);
  for (int i = 0; i < nk; i++)
    for (int j = 0; j < nh; j++) {
      const double c = 2.0 * g->zeta * sqrt(g->k[i] * m);
      double *erp = &g->erp[i * nh + j], *cfm = &g->cfm[i * nh + j];
      if (fb_mapping_is_matched(mapping)) /* a map of the impulsive row */
        fb_contact_matched(g->h[j], g->k[i], c, m, erp, cfm, NULL);
      else
        fb_contact_erp_cfm(g->h[j], g->k[i], c, erp, cfm, NULL);
      g->h_omega[i * nh + j] = fb_contact_h_omega(g->h[j], g->k[i], m);
    }
  return FB_OK;
}
