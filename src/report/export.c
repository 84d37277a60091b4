/* fourbar export below the command (export.h). */
#include "export.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "contact_params.h"
#include "engine.h"
#include "fb_config.h"
#include "resolution.h"
#include "model_table.h"
#include "scene.h"

/* after a successful export: diag->msg empty, or the note that a clearance
 * contact of sm is not faithful at the exported step: beyond the run's
 * resolution rule (h sqrt(k / m) > FB_H_OMEGA_C_BOUND with the law's spring
 * k and design mass m), or, within it, failing contact-params' own
 * verification of the restitution law's single impact over the joint's
 * effective-mass range and every onset phase (fb_cp_run, the same answer
 * as fourbar contact-params --case). The file is then not the verified
 * contact, and says so nowhere else a user looks first. */
static void resolution_note(const fb_case *c, const fb_model_scene *sm, fb_diag *diag) {
  if (!diag) return;
  diag->msg[0] = '\0';
  static const char more[] = "fourbar contact-params --case gives the largest faithful step and "
                             "the stiffest faithful contact at yours";
  for (int j = 0; j < 4; j++) {
    if (!(sm->clearance_mask & (1 << j))) continue;
    const double w = sm->solver.h * sqrt(sm->law[j].stiffness / sm->law[j].mass);
    if (w > FB_H_OMEGA_C_BOUND) {
      snprintf(diag->msg, sizeof diag->msg,
               "%s: h omega_c = %.3g at h = %.4g s passes %g, the bound a run holds its contacts "
               "to: this contact is not faithful at this step (%s)",
               fb_case_joint_name(c, j), w, sm->solver.h, FB_H_OMEGA_C_BOUND, more);
      return;
    }
    fb_cp_request q;
    fb_cp_request_default(&q);
    q.h = sm->solver.h;
    q.engine_steps = 0;
    q.rows_of = "ode"; /* read: whether the given contact is recommended */
    fb_cp_result *o = malloc(sizeof *o);
    fb_diag dg;
    if (!o) return;
    if (fb_cp_request_from_case(&q, c, j, &dg) == FB_OK && fb_cp_run(o, &q, &dg) == FB_OK &&
        !o->given.recommended) {
      char largest[48] = "none found";
      if (isfinite(o->largest_step)) snprintf(largest, sizeof largest, "%.3g s", o->largest_step);
      snprintf(diag->msg, sizeof diag->msg,
               "%s: at h = %.4g s this contact fails contact-params' verification (restitution "
               "within 1 %%, penetration within 2 %%, over the joint's effective masses and every "
               "onset phase); its largest faithful step: %s (%s)", fb_case_joint_name(c, j), sm->solver.h,
               largest, more);
      free(o);
      return;
    }
    free(o);
  }
}

/* the case with the one model exported (its law and start resolved) into
 * *sm, its scene definition in *def (the caller frees it, also on error) */
static fb_status one_model(fb_model_scene *sm, fb_scene **def, const fb_case *c,
                           const char *name, int mujoco_tendon, fb_diag *diag) {
  fb_case *k = malloc(sizeof *k);
  *def = malloc(sizeof **def);
  if (!k || !*def) {
    free(k);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the export");
  }
  *k = *c;
  k->model_count = 1;
  snprintf(k->models[0], sizeof k->models[0], "%s", name);
  if (mujoco_tendon) k->mujoco.native_bore = FB_MUJOCO_BORE_TENDON;
  fb_status st = fb_scene_from_case(*def, k, diag);
  if (st == FB_OK) st = fb_scene_select(sm, *def, fb_model_find(name), diag);
  free(k);
  return st;
}

/* the engine of this build that reads model files of format (its table's
 * model_format), or NULL */
static const fb_engine *engine_reading(const char *format) {
  for (int id = 0; id < FB_ENGINE_COUNT; id++) {
    const fb_engine *e = fb_engine_available((fb_engine_id)id) ? fb_engine_get((fb_engine_id)id, NULL)
                                                               : NULL;
    if (e && e->model_format && e->export_model && strcmp(e->model_format, format) == 0) return e;
  }
  return NULL;
}

/* FB_OK when model `name` builds case c's mechanism, else FB_ERR_ARG naming
 * both (the case check would refuse the model as if the case listed it) */
static fb_status builds(const fb_case *c, const char *name, const char *format, fb_diag *diag) {
  const fb_model *m = fb_model_find(name);
  if (m && fb_model_builds(m, c->mechanism))
    return FB_OK;
  return fb_diag_set(diag, FB_ERR_ARG, "the %s export writes model %s, which does not build a %s "
                     "yet ([linkage] type = %s; fourbar models lists each model's mechanisms)",
                     format, name, fb_case_mech(c)->type, fb_case_mech(c)->type);
}

fb_status fb_export_mjcf(char *buf, size_t size, const fb_case *c, int ideal, fb_diag *diag) {
  if (c->planar.on) return fb_export_planar_mjcf(buf, size, c, ideal, diag);
  const fb_engine *e = engine_reading("mjcf");
  if (!e)
    return fb_diag_set(diag, FB_ERR_ARG, "the MJCF export needs MuJoCo in the build: "
                       "install libmujoco-dev and rebuild (bash scripts/quickstart.sh build)");
  const char *name = ideal || !c->clearance.mask ? "mujoco-ideal-nominal"
                                                 : "mujoco-clearance-native";
  if (builds(c, name, "MJCF", diag) != FB_OK) return FB_ERR_ARG;
  fb_scene *def = NULL;
  fb_model_scene sm;
  fb_status st = one_model(&sm, &def, c, name, 1, diag);
  if (st == FB_OK) st = e->export_model(buf, size, &sm, diag);
  if (st == FB_OK) resolution_note(c, &sm, diag);
  free(def);
  return st;
}

fb_status fb_export_sdf(char *buf, size_t size, const fb_case *c, int ideal, fb_diag *diag) {
  const char *name = ideal || !c->clearance.mask ? "ode-ideal-nominal" : "ode-clearance-restitution";
  if (c->planar.on)
    return fb_diag_set(diag, FB_ERR_ARG, "--format sdf: the SDF export of a planar case ([linkage] "
                       "type = planar, case %s) is not built: the SDF world written is the "
                       "four-bar's; --format mjcf writes a planar case's ideal mechanism", c->name);
  if (!fb_case_mech(c)->sdf_export) return fb_export_sdf_refusal(c->mechanism, diag);
  fb_scene *def = NULL;
  fb_model_scene sm;
  fb_status st = one_model(&sm, &def, c, name, 0, diag);
  if (st == FB_OK) st = fb_export_sdf_model(buf, size, &sm, diag);
  if (st == FB_OK) resolution_note(c, &sm, diag);
  free(def);
  return st;
}
