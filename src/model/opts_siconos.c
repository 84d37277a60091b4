/* Siconos's own options (opts_siconos.h): the schemes' names and the check
 * of a scene's copy. */
#include "opts_siconos.h"

#include <stddef.h>

const char *const fb_siconos_scheme_words[] = {"moreau-jean", "combined-projection", NULL};

const char *const fb_siconos_coordinates_words[] = {"absolute", "angles", NULL};

const char *const fb_siconos_newton_words[] = {"converged", "example", NULL};

const char *fb_siconos_scheme_name(int k) {
  return k >= 0 && k <= FB_SICONOS_COMBINED_PROJECTION ? fb_siconos_scheme_words[k] : "?";
}

fb_status fb_siconos_opts_check(const fb_siconos_opts *o, fb_diag *diag) {
  if (!(o->theta >= FB_SICONOS_THETA_MIN && o->theta <= FB_SICONOS_THETA_MAX))
    return fb_diag_set(diag, FB_ERR_RANGE, "scene: siconos.theta = %g: must lie in [%g, %g]",
                       o->theta, FB_SICONOS_THETA_MIN, FB_SICONOS_THETA_MAX);
  if (o->scheme < FB_SICONOS_MOREAU_JEAN || o->scheme > FB_SICONOS_COMBINED_PROJECTION)
    return fb_diag_set(diag, FB_ERR_RANGE, "scene: siconos.scheme = %d: not a known scheme",
                       o->scheme);
  if (o->coordinates < FB_SICONOS_ABSOLUTE || o->coordinates > FB_SICONOS_ANGLES)
    return fb_diag_set(diag, FB_ERR_RANGE, "scene: siconos.coordinates = %d: not known",
                       o->coordinates);
  if (o->newton < FB_SICONOS_NEWTON_CONVERGED || o->newton > FB_SICONOS_NEWTON_EXAMPLE)
    return fb_diag_set(diag, FB_ERR_RANGE, "scene: siconos.newton = %d: not known", o->newton);
  return FB_OK;
}
