/* The DART engine's table (engine.h): DART 6.12 is a binding of the
 * engine kit alone (.kit, dart_kit.c): a planar case's models through the
 * kit's walk, the four-bar's and slider-crank's through the kit adapter
 * (src/engines/kit_engine.c, which fb_engine_runner hands for an engine
 * without create). */
#include <stdio.h>

#include "engine.h"
#include "dart_kit.h"
#include "dart_world.h"

/* DART's settings for its peer (tests/peers/peer_dart.cpp): the joints'
 * ERP, the servo's torque limit and the binding's PGS (dart_world.h) */
static void dart_peer_args(const fb_model_scene *sm, double h, fb_engine_put_arg put, void *a) {
  (void)h;
  fb_engine_put_number(put, a, "erp", sm->solver.world_erp);
  fb_engine_put_number(put, a, "fmax", sm->solver.drive_torque_max);
  fb_engine_put_number(put, a, "pgs_sweeps", FB_DART_PGS_SWEEPS);
  fb_engine_put_number(put, a, "pgs_dx", FB_DART_PGS_DX);
  fb_engine_put_number(put, a, "pgs_rel_dx", FB_DART_PGS_REL_DX);
}

const fb_engine fb_engine_dart = {
    .name = "dart",
    .guarded = 1,
    .step_values_lag = 1,
    .refine_peaks = 1,
    .peer_args = dart_peer_args,
    .kit = &fb_dart_kit,
};
