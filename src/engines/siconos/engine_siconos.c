/* The Siconos engine behind the engine interface (engine.h): thin wrappers
 * over the Siconos scene (siconos_scene.h, the folder's one C++ file). */
#include <stdio.h>

#include "engine.h"
#include "engine_bench.h"
#include "siconos_kit.h"
#include "siconos_scene.h"

static fb_status siconos_create(void **self, const fb_model_scene *sm, fb_diag *diag) {
  fb_siconos_scene *s = NULL;
  fb_status st = fb_siconos_scene_create(&s, sm, diag);
  if (st == FB_OK) *self = s;
  return st;
}

static fb_status siconos_step(void *self, fb_diag *diag) { return fb_siconos_scene_step(self, diag); }

static void siconos_stopped(const void *self, fb_stop *out) { fb_siconos_scene_stopped(self, out); }

static void siconos_sample(const void *self, fb_sample *x) { fb_siconos_scene_sample(self, x); }

static void siconos_contact(const void *self, fb_engine_contact *out) {
  fb_siconos_scene_contact(self, out);
}

static void siconos_provenance(const void *self, int joint, fb_contact_provenance *out) {
  fb_siconos_scene_provenance(self, joint, out);
}

static double siconos_drift(const void *self) { return fb_siconos_scene_drift(self); }

static size_t siconos_steps(const void *self) { return fb_siconos_scene_steps(self); }

static void siconos_destroy(void *self) { fb_siconos_scene_destroy(self); }

/* Siconos's own choices as a model used them (summary.json "siconos") */
static int siconos_settings(fb_engine_setting *out, const fb_case *c, int clearance_mask,
                            fb_collider collider, double h) {
  (void)collider, (void)h;
  const int projected = c->siconos.scheme == FB_SICONOS_COMBINED_PROJECTION;
  out[0] = (fb_engine_setting){.key = "integrator", .kind = FB_SETTING_TEXT,
                               .text = projected ? "MoreauJeanCombinedProjectionOSI"
                                                 : "MoreauJeanOSI"};
  out[1] = (fb_engine_setting){.key = "theta", .kind = FB_SETTING_NUMBER,
                               .number = c->siconos.theta};
  out[2] = (fb_engine_setting){.key = "contact", .kind = FB_SETTING_TEXT,
                               .text = !clearance_mask ? "EqualityConditionNSL (loop closure)"
                                       : c->clearance.friction > 0.0 ? "NewtonImpactFrictionNSL"
                                                                     : "NewtonImpactNSL"};
  out[3] = (fb_engine_setting){.key = "scheme", .kind = FB_SETTING_TEXT,
                               .text = fb_siconos_scheme_name(c->siconos.scheme)};
  return 4;
}

/* the run's table: Moreau-Jean's theta and the rigid contact's law */
static void siconos_settings_lines(const fb_case *c, const fb_engine_models_used *u,
                                   fb_engine_put_line put, void *a) {
  (void)u;
  char line[256];
  snprintf(line, sizeof line,
           "Siconos models: Moreau-Jean theta %g%s, fixed step h; clearance: g = c - |e| >= 0 "
           "with Newton's impact law, e_N = %g%s (rigid: no penalty)",
           c->siconos.theta,
           c->siconos.scheme == FB_SICONOS_COMBINED_PROJECTION
               ? " with the positions projected (combined projection)"
               : "",
           c->clearance.restitution, c->clearance.friction > 0.0 ? " and Coulomb friction" : "");
  put(a, line);
}

/* the clearance contact: no penalty, no ERP/CFM mapping; of the restitution
 * law only its coefficient reaches Newton's law */
static const char *siconos_mapping_text(fb_collider collider) {
  (void)collider;
  return "none (rigid: Newton's law, cr only)";
}

/* guarded: the penetration limit applies as to every clearance model (a
 * rigid contact stays far inside it unless the solver fails); a step reports
 * its (omega_{k+1} - omega_k) / h and its impulse / h at t_{k+1}, as ODE does,
 * and its spikes lie on a discrete motion (refined by the harness). No
 * drive_key: the crank is prescribed exactly (it is no coordinate), so it
 * never lags */
/* Time per sample [s] (engine.h: CPU time, timing.json models[].cpu_s over
 * its samples; issue 54): the ideal models 15.5 to 21.2 us (siconos and
 * engines_restitution; 52 us the first Siconos model of cases/engines.ini,
 * whose libraries start then), the rigid clearance model 12.4 to 12.9 us;
 * its linear algebra's threads count their CPU time too (10.3 us with one);
 * rounded up. */
#define SICONOS_COST_S 20e-6
#define SICONOS_COST_CLEARANCE_S 16e-6

static double siconos_cost_per_sample(const fb_model *m, const fb_case *c) {
  (void)c;
  return m->joints == FB_JOINTS_CLEARANCE ? SICONOS_COST_CLEARANCE_S : SICONOS_COST_S;
}

/* ---- Siconos's rows of fourbar bench (engine_bench.h): Moreau-Jean at the
 * case's theta, at the case's automatic step (the default grid) and at
 * fixed steps (the solver grids); its clearance rows are the rigid model
 * against the restitution reference (fb_bench_models) ---- */
static int siconos_bench_point(fb_bench_set s, int i, const fb_case *c, fb_case *k,
                               fb_bench_point *p) {
  (void)c;
  if (s == FB_BENCH_SET_DEFAULT) {
    if (i >= 1) return 0; /* the case's automatic step */
  } else if (s == FB_BENCH_SET_SOLVERS) {
    if (i >= FB_BENCH_FRONTIER_STEPS) return 0; /* 1e-5, 3e-6, 1e-6 s and auto */
    fb_bench_fixed_step(k, FB_BENCH_FRONTIER_H(i));
  } else {
    return 0;
  }
  snprintf(p->stepper, sizeof p->stepper, "%s %g", fb_siconos_scheme_name(k->siconos.scheme),
           k->siconos.theta);
  return 1;
}

static const fb_engine_bench siconos_bench = {.point = siconos_bench_point};

const fb_engine fb_engine_siconos = {
    .name = "siconos",
    .guarded = 1,
    .step_values_lag = 1,
    .refine_peaks = 1,
    .create = siconos_create,
    .step = siconos_step,
    .stopped = siconos_stopped,
    .sample = siconos_sample,
    .contact = siconos_contact,
    .provenance = siconos_provenance,
    .reactions = NULL,
    .drift = siconos_drift,
    .steps = siconos_steps,
    .destroy = siconos_destroy,
    .settings = siconos_settings,
    .settings_lines = siconos_settings_lines,
    .mapping_text = siconos_mapping_text,
    .cost_per_sample = siconos_cost_per_sample,
    .bench = &siconos_bench,
    .kit = &fb_siconos_kit,
    .own_one_pin = 1, /* the relation is written at the reference joint (siconos_scene.cpp) */
    .kit_native = &fb_siconos_kit, /* its clearance is its own relation (kit.h add_clearance) */
};
