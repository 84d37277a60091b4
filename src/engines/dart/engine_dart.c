/* The DART engine's table (engine.h): DART 6.12 builds a planar case's
 * models through the engine kit (.kit, dart_kit.c). The four-bar's and
 * slider-crank's run path (create, step, sample) is the kit's adapter of
 * issue 58 (a later slice): until then those ops are NULL, and the
 * model table's rows (model_table.c, planar_only) keep every command
 * from calling them (fb_model_builds refuses a four-bar or slider-crank
 * case's DART model; fb_model_run_one refuses an engine without create). */
#include "engine.h"
#include "dart_kit.h"

const fb_engine fb_engine_dart = {
    .name = "dart",
    .guarded = 1,
    .step_values_lag = 1,
    .refine_peaks = 1,
    .kit = &fb_dart_kit,
};
