/* MuJoCo's own options (opts_mujoco.h): the names of their enums, the auto
 * integrator's resolution and the check of a scene's copy. */
#include "opts_mujoco.h"

#include <math.h>
#include <stddef.h>

const char *const fb_mujoco_integrator_words[] = {"euler", "implicit", "rk4", "auto", NULL};
const char *const fb_mujoco_bore_words[] = {"tendon", "facets", NULL};

const char *fb_mujoco_integrator_name(int k) {
  return k >= 0 && k <= FB_MUJOCO_AUTO ? fb_mujoco_integrator_words[k] : "?";
}

const char *fb_mujoco_bore_name(int k) {
  return k >= 0 && k <= FB_MUJOCO_BORE_FACETS ? fb_mujoco_bore_words[k] : "?";
}

int fb_mujoco_integrator_resolve(const fb_mujoco_opts *o, int clearance_mask) {
  if (o->integrator != FB_MUJOCO_AUTO) return o->integrator;
  return clearance_mask ? FB_MUJOCO_RK4 : FB_MUJOCO_EULER;
}

fb_status fb_mujoco_opts_check(const fb_mujoco_opts *mj, fb_diag *diag) {
  if (mj->integrator < FB_MUJOCO_EULER || mj->integrator > FB_MUJOCO_AUTO)
    return fb_diag_set(diag, FB_ERR_RANGE, "scene: mujoco.integrator = %d: not a known integrator",
                       mj->integrator);
  if (!(mj->loop_stiffness >= 0.0 && isfinite(mj->loop_stiffness)) ||
      !(mj->loop_damping >= 0.0 && isfinite(mj->loop_damping)))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "scene: mujoco loop stiffness %g 1/s^2, damping %g 1/s: must be finite "
                       "and >= 0 (0: 1/h^2 and 1/h)",
                       mj->loop_stiffness, mj->loop_damping);
  if (!(mj->loop_impedance > 0.0 && mj->loop_impedance < 1.0))
    return fb_diag_set(diag, FB_ERR_RANGE, "scene: mujoco.loop_impedance = %g: must lie in (0, 1)",
                       mj->loop_impedance);
  if (!(mj->drive_armature > 0.0 && isfinite(mj->drive_armature)))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "scene: mujoco.drive_armature = %g kg m^2: must be positive and finite",
                       mj->drive_armature);
  return FB_OK;
}
