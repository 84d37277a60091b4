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

/* Time per sample [s] (engine.h: CPU time, timing.json models[].cpu_s over
 * its samples): on cases/dart.ini (3 revolutions at the automatic step,
 * 54,273 samples) the ideal models 7.7 and 7.9 us; the clearance models,
 * their world sub-stepped 8 times a grid step at least (dart_kit.c), 34.7
 * and 34.9 us; rounded up. */
#define DART_COST_S 9e-6
#define DART_COST_CLEARANCE_S 40e-6

static double dart_cost_per_sample(const fb_model *m, const fb_case *c) {
  (void)c;
  return m->joints == FB_JOINTS_CLEARANCE ? DART_COST_CLEARANCE_S : DART_COST_S;
}

/* DART's rows of fourbar bench (engine_bench.h): World::step with PGS run
 * to convergence (its only configuration: docs/engines.md, "DART") at
 * 1e-5 s and the case's automatic step (the default grid), at the
 * frontier's steps (the solver grids) */
static int dart_bench_point(fb_bench_set s, int i, const fb_case *c, fb_case *k,
                            fb_bench_point *p) {
  (void)c;
  if (s == FB_BENCH_SET_DEFAULT) {
    if (i >= 2) return 0;
    fb_bench_fixed_step(k, i == 0 ? 1e-5 : 0.0);
  } else if (s == FB_BENCH_SET_SOLVERS) {
    if (i >= FB_BENCH_FRONTIER_STEPS) return 0; /* 1e-5, 3e-6, 1e-6 s and auto */
    fb_bench_fixed_step(k, FB_BENCH_FRONTIER_H(i));
  } else {
    return 0;
  }
  snprintf(p->stepper, sizeof p->stepper, "pgs-%d", FB_DART_PGS_SWEEPS);
  return 1;
}

static const fb_engine_bench dart_bench = {.point = dart_bench_point};

const fb_engine fb_engine_dart = {
    .name = "dart",
    .guarded = 1,
    .step_values_lag = 1,
    .refine_peaks = 1,
    .cost_per_sample = dart_cost_per_sample,
    .peer_args = dart_peer_args,
    .bench = &dart_bench,
    .kit = &fb_dart_kit,
};
