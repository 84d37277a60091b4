/* fourbar export below the command (export.h). */
#include "export.h"

#include <stdio.h>
#include <stdlib.h>

#include "fb_config.h"
#include "model_table.h"
#include "scene_def.h"
#if FB_HAVE_MUJOCO
#include "mujoco_scene.h"
#endif

fb_status fb_export_mjcf(char *buf, size_t size, const fb_case *c, int ideal, fb_diag *diag) {
#if FB_HAVE_MUJOCO
  const char *name = ideal || !c->clearance.mask ? "mujoco-ideal-nominal"
                                                 : "mujoco-clearance-native";
  fb_case *k = malloc(sizeof *k);
  fb_scene_def *def = malloc(sizeof *def);
  if (!k || !def) {
    free(k);
    free(def);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the export");
  }
  /* the case with the one model exported (its law and start resolved) */
  *k = *c;
  k->model_count = 1;
  snprintf(k->models[0], sizeof k->models[0], "%s", name);
  k->mujoco.native_bore = FB_MUJOCO_BORE_TENDON;
  fb_status st = fb_scene_def_from_case(def, k, diag);
  fb_scene_model sm;
  if (st == FB_OK) st = fb_scene_def_select(&sm, def, fb_model_find(name), diag);
  if (st == FB_OK) st = fb_mujoco_export(buf, size, &sm, diag);
  free(k);
  free(def);
  return st;
#else
  (void)buf, (void)size, (void)c, (void)ideal;
  return fb_diag_set(diag, FB_ERR_ARG, "the MJCF export needs MuJoCo in the build: "
                     "install libmujoco-dev and rebuild (bash scripts/quickstart.sh build)");
#endif
}

fb_status fb_export_sdf(char *buf, size_t size, const fb_case *c, int ideal, fb_diag *diag) {
  const char *name = ideal || !c->clearance.mask ? "ode-ideal-nominal" : "ode-clearance-restitution";
  fb_case *k = malloc(sizeof *k);
  fb_scene_def *def = malloc(sizeof *def);
  if (!k || !def) {
    free(k);
    free(def);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the export");
  }
  /* the case with the one model exported (its law and start resolved) */
  *k = *c;
  k->model_count = 1;
  snprintf(k->models[0], sizeof k->models[0], "%s", name);
  fb_status st = fb_scene_def_from_case(def, k, diag);
  fb_scene_model sm;
  if (st == FB_OK) st = fb_scene_def_select(&sm, def, fb_model_find(name), diag);
  if (st == FB_OK) st = fb_export_sdf_model(buf, size, &sm, diag);
  free(k);
  free(def);
  return st;
}
