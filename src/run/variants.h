/* Variants of a case, run beside it ([variant.NAME] sections, case.h): each
 * is the case with more overrides, loaded by the CLI
 * (fb_casefile_load_variant) and run here after the case's own models. Only
 * each model's window peaks are kept: they are what the writers print beside
 * the published values ([published.impact], [published.restitution]). */
#ifndef FB_VARIANTS_H
#define FB_VARIANTS_H

#include "analytic.h"
#include "case.h"
#include "model_run.h"
#include "outcome.h"

/* One model of a variant's run. */
typedef struct {
  const fb_model *model;  /* its row of the model table */
  int has_peaks;          /* 1 when it reached the peak window */
  fb_peaks peaks;         /* window peaks [rad/s, rad/s^2] */
  int peaks_unconverged;  /* 1: printed marked (run.h, fb_model_result) */
  fb_stop stop;           /* why it stopped early (FB_STOP_NONE: it ran to its end) */
} fb_variant_model;

/* One variant's run. */
typedef struct {
  fb_case_variant def;    /* name, set, models, description as the case gave them */
  double h;               /* the step its models ran at [s] */
  int n;                  /* models run */
  fb_variant_model model[FB_MAX_MODELS];
} fb_variant_result;

struct fb_run_s;

/* Runs the n variant cases (each from fb_casefile_load_variant of r->c's
 * file, in r->c.variant order) with fb_run_case and keeps their models'
 * peaks in r->variant (r->variant_count = n). Errors: those of fb_run_case,
 * the message naming the variant; r keeps the variants run before. */
fb_status fb_run_variants(struct fb_run_s *r, const fb_case *cases, int n,
                          fb_progress_fn progress, void *user, fb_diag *diag);

/* The published values a model of law law compares with (NULL for a model
 * without clearance joints), and 1 when at least one of them is given. */
const fb_case_published *fb_variants_published(const fb_case *c, const fb_model *m);
int fb_variants_published_any(const fb_case_published *p);

#endif
