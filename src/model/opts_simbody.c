/* Simbody's own options (opts_simbody.h): its integrators' names and the
 * check of a scene's copy. */
#include "opts_simbody.h"

#include <stddef.h>

const char *const fb_simbody_integrator_words[] = {"rkmerson", "rkfeldberg", "rk3", "cpodes",
                                                   "verlet", NULL};

const char *fb_simbody_integrator_name(int k) {
  return k >= 0 && k < FB_SIMBODY_INTEGRATOR_COUNT ? fb_simbody_integrator_words[k] : "?";
}

fb_status fb_simbody_opts_check(const fb_simbody_opts *sb, fb_diag *diag) {
  if (sb->integrator < 0 || sb->integrator >= FB_SIMBODY_INTEGRATOR_COUNT)
    return fb_diag_set(diag, FB_ERR_RANGE, "scene: simbody.integrator = %d: not a known integrator",
                       sb->integrator);
  if (!(sb->accuracy >= FB_SIMBODY_ACCURACY_MIN && sb->accuracy <= FB_SIMBODY_ACCURACY_MAX))
    return fb_diag_set(diag, FB_ERR_RANGE, "scene: simbody.accuracy = %g: must lie in [%g, %g]",
                       sb->accuracy, FB_SIMBODY_ACCURACY_MIN, FB_SIMBODY_ACCURACY_MAX);
  return FB_OK;
}
