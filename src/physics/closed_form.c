/* The one map from a mechanism type to its closed forms (closed_form.h). */
#include "closed_form.h"

const fb_closed_form *fb_closed_form_of(fb_mech_type t) {
  return t == FB_MECH_SLIDER_CRANK ? &fb_closed_form_slider_crank : &fb_closed_form_fourbar;
}

const fb_closed_form *fb_closed_form_of_desc(const fb_mech_desc *m) {
  const int t = m ? fb_mech_find(m->type) : -1;
  return t < 0 ? &fb_closed_form_fourbar : fb_closed_form_of((fb_mech_type)t);
}
