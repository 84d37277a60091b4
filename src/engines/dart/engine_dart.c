/* The DART engine's table (engine.h): DART 6.12 is a binding of the
 * engine kit alone (.kit, dart_kit.c): a planar case's models through the
 * kit's walk, the four-bar's and slider-crank's through the kit adapter
 * (src/engines/kit_engine.c, which fb_engine_runner hands for an engine
 * without create). */
#include "engine.h"
#include "dart_kit.h"

const fb_engine fb_engine_dart = {
    .name = "dart",
    .guarded = 1,
    .step_values_lag = 1,
    .refine_peaks = 1,
    .kit = &fb_dart_kit,
};
