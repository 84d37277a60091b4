/* The single impact in MuJoCo with pasted solref/solimp (see impact_mujoco.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "clock.h"
#include "impact_mujoco.h"
#include "mujoco_load.h"

/* radius of the sphere [m]: any; the contact is at its lowest point */
#define SPHERE_R 0.01

fb_status fb_impact_mujoco(fb_impact_result *out, double mass, double speed, double h,
                           const double solref[2], const double solimp[5], double t_max,
                           double onset_phase, fb_diag *diag) {
  memset(out, 0, sizeof *out);
  if (!(mass > 0.0) || !(speed > 0.0) || !(h > 0.0) || !(t_max > h) || !isfinite(mass) ||
      !isfinite(speed) || !isfinite(solref[0]) || !isfinite(solref[1]))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "MuJoCo impact: mass %g kg, speed %g m/s, h %g s, solref (%g, %g), "
                       "t_max %g s: need positive, finite values",
                       mass, speed, h, solref[0], solref[1], t_max);
  if (!(onset_phase >= 0.0 && onset_phase < 1.0))
    return fb_diag_set(diag, FB_ERR_RANGE, "MuJoCo impact: onset phase %g: must lie in [0, 1)",
                       onset_phase);
  /* the sphere touches the plane (phase 0), or is a free step short of the
   * crossing: the first step that sees the contact sees the depth phase h v */
  const double t_free = onset_phase > 0.0 ? (1.0 - onset_phase) * h : 0.0;
  const double steps_max = ceil((t_max + t_free) / h);
  if (steps_max > FB_IMPACT_MAX_STEPS)
    return fb_diag_set(diag, FB_ERR_RANGE, "MuJoCo impact: %g steps of %g s: more than %g",
                       steps_max, h, FB_IMPACT_MAX_STEPS);
  const double t_wall = fb_clock_s();
  char mjcf[2048];
  const char *sol = "solref=\"%.17g %.17g\" solimp=\"%.17g %.17g %.17g %.17g %.17g\"";
  char solattr[256];
  snprintf(solattr, sizeof solattr, sol, solref[0], solref[1], solimp[0], solimp[1], solimp[2],
           solimp[3], solimp[4]);
  snprintf(mjcf, sizeof mjcf,
           "<mujoco model=\"impact\">\n"
           "  <option timestep=\"%.17g\" gravity=\"0 0 0\" integrator=\"Euler\"/>\n"
           "  <worldbody>\n"
           "    <geom name=\"ground\" type=\"plane\" size=\"1 1 0.1\" condim=\"1\" %s/>\n"
           "    <body name=\"body\" pos=\"0 0 %.17g\">\n"
           "      <joint name=\"z\" type=\"slide\" axis=\"0 0 1\"/>\n"
           "      <geom name=\"ball\" type=\"sphere\" size=\"%.17g\" mass=\"%.17g\" condim=\"1\" %s/>\n"
           "    </body>\n"
           "  </worldbody>\n"
           "</mujoco>\n",
           h, solattr, SPHERE_R, SPHERE_R, mass, solattr);
  mjModel *m = fb_mujoco_load_mjcf(mjcf, diag);
  if (!m) return FB_ERR_ARG;
  mjData *d = mj_makeData(m);
  if (!d) {
    mj_deleteModel(m);
    return fb_diag_set(diag, FB_ERR_NOMEM, "MuJoCo impact: out of memory for mjData");
  }
  /* no hook of a four-bar scene may act on this model */
  mjfGeneric passive = mjcb_passive;
  mjcb_passive = NULL;
  d->qpos[0] = t_free * speed;
  d->qvel[0] = -speed;
  fb_status st = FB_OK;
  fb_impact_tally tally = {0, 0, 0.0, 0.0};
  size_t k;
  for (k = 0; (double)k < steps_max && !tally.done; k++) {
    mj_step(m, d);
    const double depth = -d->qpos[0];
    if (!isfinite(depth) || !isfinite(d->qvel[0])) {
      st = fb_diag_set(diag, FB_ERR_NUMERIC, "MuJoCo impact: non-finite state at step %zu",
                       k + 1);
      break;
    }
    /* the contact force of this step's constraint stage (state at its start) */
    double force = 0.0;
    for (int i = 0; i < d->ncon; i++) {
      mjtNum f[6];
      mj_contactForce(m, d, i, f);
      if (f[0] > force) force = f[0];
    }
    fb_impact_tally_depth(&tally, out, (double)(k + 1) * h - t_free, h, depth, force);
  }
  out->steps = k;
  out->contact_duration = tally.t_end;
  out->restitution = d->qvel[0] / speed;
  mjcb_passive = passive;
  mj_deleteData(d);
  mj_deleteModel(m);
  if (st == FB_OK && !tally.done)
    st = fb_diag_set(diag, FB_ERR_NUMERIC,
                     "MuJoCo impact: the body has not left the contact after %zu steps (%g s)", k,
                     (double)k * h);
  out->wall_s = fb_clock_s() - t_wall;
  return st;
}
