#include "bar_mass.h"

#include <math.h>

fb_bar fb_bar_default(void) {
  fb_bar b;
  b.length = 0.1;
  b.width = 0.020;
  b.thickness = 0.0065;
  b.density = 7800.0;
  return b;
}

static int positive(double x) { return x > 0.0 && isfinite(x); }

fb_status fb_bar_check(const fb_bar *b, fb_diag *diag) {
  if (!positive(b->length))
    return fb_diag_set(diag, FB_ERR_RANGE, "bar length = %g m: a length must be positive",
                       b->length);
  if (!positive(b->width))
    return fb_diag_set(diag, FB_ERR_RANGE, "bar width = %g m: a width must be positive",
                       b->width);
  if (!positive(b->thickness))
    return fb_diag_set(diag, FB_ERR_RANGE, "bar thickness = %g m: a thickness must be positive",
                       b->thickness);
  if (!positive(b->density))
    return fb_diag_set(diag, FB_ERR_RANGE, "density = %g kg/m^3: a density must be positive",
                       b->density);
  return FB_OK;
}

double fb_bar_mass(const fb_bar *b) { return b->density * b->width * b->thickness * b->length; }

fb_status fb_bar_fill(fb_link_mass *out, const fb_bar *b, double m, fb_diag *diag) {
  fb_status st = fb_bar_check(b, diag);
  if (st != FB_OK) return st;
  if (!positive(m))
    return fb_diag_set(diag, FB_ERR_RANGE, "bar mass = %g kg: a mass must be positive", m);
  const double l2 = b->length * b->length, w2 = b->width * b->width;
  const double t2 = b->thickness * b->thickness;
  out->mass = m;
  out->inertia = m * (l2 + w2) / 12.0;
  out->inertia_long = m * (w2 + t2) / 12.0;
  out->inertia_transverse = m * (l2 + t2) / 12.0;
  out->com_fraction = 0.5;
  return FB_OK;
}
