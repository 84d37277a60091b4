/* fourbar models' output: the model table (model_table.h) as a Markdown
 * table or as JSON, with which engines this build has and, for those it
 * lacks, how to get them. */
#ifndef FB_TABLES_MODELS_H
#define FB_TABLES_MODELS_H

#include <stdio.h>

/* The model table as Markdown on f: one row per model (name, engine, whether
 * this build has it, lengths, joints, contact law, collider, reference model,
 * one-line description), then the how-to of each engine this build lacks. */
void fb_report_models_text(FILE *f);

/* The same as one JSON object on f: "models" (one object per row: name,
 * engine, available, lengths, joints, law, collider, reference, spikes_vs,
 * summary; reference and spikes_vs null when the row has none) and
 * "engines" (name, available, steps_world, howto; howto null when
 * available). */
void fb_report_models_json(FILE *f);

#endif
