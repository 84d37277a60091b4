/* Siconos's own options (opts_siconos.h): the check of a scene's copy. */
#include "opts_siconos.h"

fb_status fb_siconos_opts_check(const fb_siconos_opts *o, fb_diag *diag) {
  if (!(o->theta >= FB_SICONOS_THETA_MIN && o->theta <= FB_SICONOS_THETA_MAX))
    return fb_diag_set(diag, FB_ERR_RANGE, "scene: siconos.theta = %g: must lie in [%g, %g]",
                       o->theta, FB_SICONOS_THETA_MIN, FB_SICONOS_THETA_MAX);
  return FB_OK;
}
