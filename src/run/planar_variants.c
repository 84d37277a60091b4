/* A planar case's variants run beside it (planar_run.h
 * fb_planar_run_variants): each variant's case through the planar run, one
 * at a time, its models' peaks, contact peaks, verdicts and stops kept, its
 * series freed. */
#include <stdlib.h>
#include <string.h>

#include "planar_run.h"

fb_status fb_planar_run_variants(fb_planar_run *r, const fb_case *cases, int n, fb_diag *diag) {
  if (n > FB_MAX_VARIANTS) return fb_diag_set(diag, FB_ERR_ARG, "more than %d variants", FB_MAX_VARIANTS);
  if (n <= 0) return FB_OK;
  r->variant = calloc((size_t)n, sizeof *r->variant);
  fb_planar_run *vr = calloc(1, sizeof *vr); /* a run holds every model's series */
  if (!r->variant || !vr) {
    free(vr);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the variants");
  }
  fb_status st = FB_OK;
  for (int v = 0; v < n && st == FB_OK; v++) {
    fb_diag inner;
    st = fb_planar_run_case(vr, &cases[v], &inner);
    if (st != FB_OK) {
      fb_diag_set(diag, st, "variant %s: %s", r->c.variant[v].name, inner.msg);
      break;
    }
    fb_planar_variant *out = &r->variant[v];
    out->def = r->c.variant[v];
    out->h = fb_planar_run_step(&vr->c);
    const size_t nb = (size_t)vr->m->nbodies;
    for (int i = 0; i < vr->n && st == FB_OK; i++) {
      const fb_planar_model *p = &vr->model[i];
      fb_planar_variant_model *q = &out->model[i];
      memcpy(q->name, p->name, sizeof q->name);
      q->reference = p->reference;
      q->engine = p->engine;
      q->contact = fb_planar_model_has_contact(p);
      q->ref = p->ref;
      q->verdict = p->verdict;
      q->peaks = malloc(nb * sizeof *q->peaks);
      if (!q->peaks) st = fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the variants");
      else memcpy(q->peaks, p->peaks, nb * sizeof *q->peaks);
      out->n = i + 1;
    }
    r->variant_count = v + 1;
    fb_planar_run_free(vr);
    memset(vr, 0, sizeof *vr);
  }
  free(vr);
  return st;
}
