#include "ode_contact.h"

int fb_ode_soft_contact(dContact *ct, const fb_contact_law *law, fb_mapping mapping, double h,
                        double m_eff, int n_rows, double delta, double ddot, double v0,
                        int onset, double persistence, double friction,
                        fb_contact_row *row) {
  fb_contact_row r;
  if (fb_contact_row_step(&r, law, mapping, h, m_eff, n_rows, delta, ddot, v0, onset,
                          persistence) != FB_OK)
    return 0;
  fb_ode_soft_fill(ct, &r, friction);
  if (row) *row = r;
  return 1;
}

void fb_ode_soft_fill(dContact *ct, const fb_contact_row *row, double friction) {
  ct->surface.mode = dContactSoftERP | dContactSoftCFM;
  if (friction > 0.0) ct->surface.mode |= dContactApprox1;
  ct->surface.mu = friction;
  ct->surface.soft_erp = row->erp;
  ct->surface.soft_cfm = row->cfm;
  ct->geom.depth = row->depth;
}
