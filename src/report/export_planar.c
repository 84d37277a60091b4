/* fourbar export of a planar case (export.h): the MJCF the MuJoCo binding
 * of the engine kit composes and runs (mujoco_kit.c), written as it is:
 * the ideal mechanism (mujoco-ideal-nominal), or with its clearance joints
 * as MuJoCo's own bore (mujoco-clearance-native, mujoco_kit_native.c). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "export.h"
#include "kit.h"
#include "model_table.h"
#include "planar_case.h"
#include "planar_resolution.h"
#include "planar_run.h"
#include "textbuf.h"

/* the models the planar export writes: the ideal mechanism, and the one
 * whose clearance joints are MuJoCo's own contacts (an MJCF element) */
#define PLANAR_MJCF_IDEAL "mujoco-ideal-nominal"
#define PLANAR_MJCF_CLEARANCE "mujoco-clearance-native"

/* the leading comment: what the file is (the MuJoCo binding's own comment
 * follows: names, start, drive and step, mujoco_kit.c) */
static void put_header(fb_text *t, const fb_case *c, const char *model) {
  fb_text_comment(t, "fourbar export of case %s ([linkage] type = planar): the %s as model %s "
                  "builds it (docs/contact-params.md), for MuJoCo 2.2 and 3.x.", c->name,
                  strcmp(model, PLANAR_MJCF_IDEAL) == 0 ? "ideal mechanism"
                                                        : "mechanism with its clearance joints",
                  model);
  fb_text_put(t, "\n");
}

/* after a clearance export of model: diag->msg empty, or the note that a
 * clearance joint's contact is beyond the run's resolution rule at the
 * written step (planar_resolution.h: h times the contact's fastest rate at
 * its smallest effective mass, under the model's law, above
 * FB_H_OMEGA_C_BOUND), naming the step that resolves it: the note a planar
 * run's header gives */
static void resolution_note(const fb_case *c, const fb_planar *m, const char *model, double h,
                            fb_diag *diag) {
  diag->msg[0] = '\0';
  if (c->planar.undriven) return;
  const int impact = fb_model_find(model)->law == FB_MODEL_LAW_IMPACT;
  fb_planar_contact_estimate *est = malloc(2 * (size_t)m->njoints * sizeof *est);
  int n = 0;
  fb_diag dg;
  if (!est || fb_planar_contact_estimates(est, &n, c, m, &dg) != FB_OK) n = 0;
  for (int i = 0; i < n; i++) {
    const fb_planar_contact_estimate *e = &est[i];
    const double hr = h * e->rates.rate;
    if (e->impact != impact || !(hr > FB_H_OMEGA_C_BOUND)) continue;
    snprintf(diag->msg, sizeof diag->msg,
             "%s: h x %s = %.3g at h = %.4g s passes %g, the bound a run holds its contacts to: "
             "this contact is not faithful at this step; a fixed step of %.3g s or smaller "
             "resolves it ([solver] h_s, or h_s = auto)", m->joint[e->joint].name,
             e->rates.by_damper ? "c/m_eff" : "omega_c", hr, h, FB_H_OMEGA_C_BOUND,
             e->h_resolving);
    break;
  }
  free(est);
}

fb_status fb_export_planar_mjcf(char *buf, size_t size, const fb_case *c, int ideal,
                                fb_diag *diag) {
  char loaded[2 * FB_PLANAR_NAME_SIZE];
  if (fb_planar_spec_loaded(&c->planar, loaded, sizeof loaded))
    return fb_diag_set(diag, FB_ERR_ARG, "%s: the MJCF export does not carry a case's springs "
                       "and loads yet; export the case without its [spring.*] and [load.*] "
                       "sections", loaded);
  const int clear = !ideal && c->clearance.mask;
  const char *model = clear ? PLANAR_MJCF_CLEARANCE : PLANAR_MJCF_IDEAL;
  const struct fb_kit_binding *b = fb_planar_kit_of(PLANAR_MJCF_IDEAL);
  if (!b || !b->model_text)
    return fb_diag_set(diag, FB_ERR_ARG, "the MJCF export needs MuJoCo in the build: "
                       "install libmujoco-dev and rebuild (bash scripts/quickstart.sh build)");
  fb_case *k = malloc(sizeof *k);
  if (!k) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the export");
  *k = *c;
  k->mujoco.native_bore = FB_MUJOCO_BORE_TENDON; /* the bore as an MJCF element, no hook */
  fb_text t = {buf, size, 0, 0};
  put_header(&t, k, model);
  fb_status st = FB_OK;
  if (t.overflow) st = fb_diag_set(diag, FB_ERR_RANGE, "MJCF text longer than %zu bytes", size);
  /* the file's step: the case's; an ideal model has no contact to resolve,
   * so where the case's step is chosen from its contacts (h_s = auto) it
   * takes the step of a case without clearance joints (a revolution /
   * FB_H_AUTO_STEPS_PER_REV): the timestep a user runs the file at, with
   * no contact's cost (the template's: 1e-5 s, not 3.32e-6 s; written at
   * either, the file holds from it to 2 ms in MuJoCo 2.2.2 and 3.3.8) */
  double h = fb_planar_run_step(k);
  if (!clear && k->solver.h_mode == FB_STEP_AUTO) {
    const int mask = k->clearance.mask;
    k->clearance.mask = 0;
    h = fb_planar_run_step(k);
    k->clearance.mask = mask;
  }
  if (st == FB_OK) st = fb_planar_kit_model_text(buf + t.len, size - t.len, k, model, h, diag);
  if (st == FB_OK) diag->msg[0] = '\0';
  if (st == FB_ERR_ARG && clear) { /* a joint the native bore cannot be */
    const size_t len = strlen(diag->msg);
    snprintf(diag->msg + len, sizeof diag->msg - len, "; fourbar export --ideal writes the "
             "ideal mechanism");
  }
  if (st == FB_OK && clear) {
    fb_planar *m = NULL;
    if (fb_planar_of_case(&m, k, NULL, diag) == FB_OK)
      resolution_note(k, m, model, fb_planar_run_step(k), diag);
    else diag->msg[0] = '\0';
    fb_planar_free(m);
  }
  free(k);
  return st;
}
