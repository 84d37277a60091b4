/* A contact law's damper on the effective mass (contact_mass.h). */
#include "contact_mass.h"

int fb_contact_law_wants_mass(const fb_contact_law *law) {
  return law->kind == FB_LAW_RESTITUTION;
}

fb_contact_law fb_contact_law_on_mass(const fb_contact_law *law, double m_eff) {
  fb_contact_law l = *law;
  if (fb_contact_law_wants_mass(law)) l.mass = m_eff;
  return l;
}
