/* fourbar export of a planar case (export.h): the MJCF the MuJoCo binding
 * of the engine kit composes and runs (mujoco_kit.c), written as it is. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "export.h"
#include "kit.h"
#include "planar_case.h"
#include "planar_run.h"
#include "textbuf.h"

/* the model the planar export writes: the one mujoco-ideal-nominal runs */
#define PLANAR_MJCF_MODEL "mujoco-ideal-nominal"

/* the leading comment: what the file is (the MuJoCo binding's own comment
 * follows: names, start, drive and step, mujoco_kit.c) */
static void put_header(fb_text *t, const fb_case *c) {
  fb_text_comment(t, "fourbar export of case %s ([linkage] type = planar): the ideal mechanism "
                  "as model %s builds it (docs/contact-params.md), for MuJoCo 2.2 and 3.x.",
                  c->name, PLANAR_MJCF_MODEL);
  fb_text_put(t, "\n");
}

fb_status fb_export_planar_mjcf(char *buf, size_t size, const fb_case *c, int ideal,
                                fb_diag *diag) {
  if (!ideal && c->clearance.mask)
    return fb_diag_set(diag, FB_ERR_ARG, "the MJCF export of a planar case ([linkage] type = "
                       "planar) writes its ideal mechanism only: a clearance joint's law comes "
                       "from the ideal mechanism's largest reaction there, which a run computes "
                       "and the export does not; give --ideal, or run the clearance models by "
                       "fourbar run (mujoco-clearance-native: MuJoCo's own bore)");
  char loaded[2 * FB_PLANAR_NAME_SIZE];
  if (fb_planar_spec_loaded(&c->planar, loaded, sizeof loaded))
    return fb_diag_set(diag, FB_ERR_ARG, "%s: the MJCF export does not carry a case's springs "
                       "and loads yet; export the case without its [spring.*] and [load.*] "
                       "sections", loaded);
  const struct fb_kit_binding *b = fb_planar_kit_of(PLANAR_MJCF_MODEL);
  if (!b || !b->model_text)
    return fb_diag_set(diag, FB_ERR_ARG, "the MJCF export needs MuJoCo in the build: "
                       "install libmujoco-dev and rebuild (bash scripts/quickstart.sh build)");
  fb_planar *m = NULL;
  fb_status st = fb_planar_of_case(&m, c, NULL, diag);
  if (st != FB_OK) return st;
  const double h = fb_planar_run_step(c);
  const fb_kit_world o = {.gravity = c->gravity, .h = h, .solver = &c->solver,
                          .nbodies = m->nbodies - 1, .njoints = m->njoints, .c = c};
  fb_text t = {buf, size, 0, 0};
  put_header(&t, c);
  if (t.overflow) st = fb_diag_set(diag, FB_ERR_RANGE, "MJCF text longer than %zu bytes", size);
  if (st == FB_OK) st = fb_kit_model_text(b, m, fb_case_omega2(c), &o, buf + t.len, size - t.len, diag);
  fb_planar_free(m);
  if (st == FB_OK) diag->msg[0] = '\0';
  return st;
}
