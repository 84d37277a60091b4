/* The writers of a case's published values ([published.impact],
 * [published.restitution]) and of its variants' runs ([variant.NAME],
 * variants.h): summary.json's "published" and "variants", and the printed
 * table (report.md holds the same), where every model of a law, the run's
 * and each variant's, stands beside the published value with its relative
 * difference. */
#ifndef FB_REPORT_VARIANTS_H
#define FB_REPORT_VARIANTS_H

/* jansson's object type, declared here so that includers do not get jansson
 * (C11 allows the same typedef again where <jansson.h> is included too) */
typedef struct json_t json_t;
#include <stdio.h>

#include "run.h"

/* summary.json's "published": {"source", "impact": {"coupler": {...},
 * "follower": {...}}, "restitution": ...} with the given values only
 * [rad/s, rad/s^2]; null when the case gives none. */
json_t *fb_report_published_json(const fb_case *c);

/* A model's "vs_published": {"coupler": {"omega_max_rel", ...},
 * "follower": ...}: (model's peak - published) / |published| [-] for each
 * published value; null when its law has none or it has no peaks. */
json_t *fb_report_vs_published_json(const fb_case *c, const fb_model *m, const fb_peaks *p,
                                    int has_peaks);

/* summary.json's "variants": [{"name", "set", "models_key", "description",
 * "h_s", "models": [{"name", "status", "peaks", "vs_published"}]}]. */
json_t *fb_report_variants_json(const fb_run *r);

/* The printed sections: each variant with its overrides and its models'
 * peaks, then per law with published values the published row and every
 * model of that law beside it ("-" where the publication gives none).
 * Nothing when the case has neither. W: width of the model column. */
void fb_report_print_variants(FILE *f, const fb_run *r, int W);

#endif
