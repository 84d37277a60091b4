#include "variants.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "run.h"

fb_status fb_run_variants(fb_run *r, const fb_case *cases, int n, fb_progress_fn progress,
                          void *user, fb_diag *diag) {
  r->variant_count = 0;
  if (n > FB_MAX_VARIANTS) return fb_diag_set(diag, FB_ERR_ARG, "more than %d variants", FB_MAX_VARIANTS);
  /* an fb_run holds every model's series: one at a time, freed after its peaks are kept */
  fb_run *vr = calloc(1, sizeof *vr);
  if (!vr) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  fb_status st = FB_OK;
  for (int v = 0; v < n && st == FB_OK; v++) {
    fb_diag inner;
    st = fb_run_case(vr, &cases[v], progress, user, &inner);
    if (st != FB_OK) {
      fb_diag_set(diag, st, "variant %s: %s", r->c.variant[v].name, inner.msg);
      break;
    }
    fb_variant_result *out = &r->variant[v];
    memset(out, 0, sizeof *out);
    out->def = r->c.variant[v];
    out->h = vr->c.solver.h;
    out->n = vr->n;
    for (int i = 0; i < vr->n; i++) {
      const fb_model_result *m = &vr->model[i];
      out->model[i] = (fb_variant_model){.model = m->run.model,
                                         .has_peaks = m->has_peaks,
                                         .peaks = m->peaks,
                                         .peaks_unconverged = m->peaks_unconverged,
                                         .stop = m->run.stop};
    }
    r->variant_count = v + 1;
    fb_run_free(vr);
    memset(vr, 0, sizeof *vr);
  }
  free(vr);
  return st;
}

const fb_case_published *fb_variants_published(const fb_case *c, const fb_model *m) {
  if (m->law == FB_MODEL_LAW_IMPACT) return &c->published[FB_PUBLISHED_IMPACT];
  if (m->law == FB_MODEL_LAW_RESTITUTION) return &c->published[FB_PUBLISHED_RESTITUTION];
  return NULL;
}

int fb_variants_published_any(const fb_case_published *p) {
  if (!p) return 0;
  for (int k = 0; k < FB_MECH_MAX_OUTPUTS; k++) {
    const fb_case_body_values *b = &p->body[k];
    if (isfinite(b->omega_max) || isfinite(b->omega_min) || isfinite(b->alpha_max) ||
        isfinite(b->alpha_min))
      return 1;
  }
  return 0;
}
