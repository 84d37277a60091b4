/* The Simbody engine behind the engine interface (engine.h): thin wrappers
 * over the Simbody scene (simbody_scene.h, the folder's one C++ file). */
#include <math.h>
#include <stdio.h>

#include "engine.h"
#include "simbody_kit.h"
#include "simbody_scene.h"

static fb_status simbody_create(void **self, const fb_model_scene *sm, fb_diag *diag) {
  fb_simbody_scene *s = NULL;
  fb_status st = fb_simbody_scene_create(&s, sm, diag);
  if (st == FB_OK) *self = s;
  return st;
}

static fb_status simbody_step(void *self, fb_diag *diag) { return fb_simbody_scene_step(self, diag); }

static void simbody_stopped(const void *self, fb_stop *out) { fb_simbody_scene_stopped(self, out); }

static void simbody_sample(const void *self, fb_sample *x) { fb_simbody_scene_sample(self, x); }

static void simbody_contact(const void *self, fb_engine_contact *out) {
  fb_simbody_scene_contact(self, out);
}

static void simbody_provenance(const void *self, int joint, fb_contact_provenance *out) {
  fb_simbody_scene_provenance(self, joint, out);
}

static void simbody_reactions(const void *self, double force[4][2], double *drive_torque) {
  fb_simbody_scene_reactions(self, force, drive_torque);
}

static double simbody_drift(const void *self) { return fb_simbody_scene_drift(self); }

static size_t simbody_steps(const void *self) { return fb_simbody_scene_steps(self); }

static void simbody_destroy(void *self) { fb_simbody_scene_destroy(self); }

static double simbody_stepping_s(const void *self) { return fb_simbody_scene_stepping_s(self); }

/* guarded: the penetration limit applies as to every clearance model; the
 * samples are the integrator's own interpolant on the grid, exact in time,
 * realized exactly at the peaks, and the engine keeps the peaks between
 * samples itself: no lag, no refinement */
/* Time per sample [s] (engine.h: CPU time, timing.json models[].cpu_s over
 * its samples; issue 54): 1.35 us per sample plus 46 to 48 us per
 * integrator step (the ideal models 1.33 to 1.45 us a sample at 0.003
 * steps; the clearance impact and restitution models 12.0 and 15.6 us at
 * 0.23 and 0.30 steps a sample: simbody, engines and engines_restitution);
 * 3,752 to 90,797 steps in 2 revolutions of the clearance model at
 * accuracy 1e-4 to 1e-10 (as accuracy^-0.3), 40 to 1,047 of the ideal
 * one; each rounded up. */
#define SIMBODY_COST_SAMPLE_S 1.6e-6
#define SIMBODY_COST_STEP_S 55e-6
#define SIMBODY_COST_STEPS_REV_CLEARANCE 4200.0 /* at the default accuracy [1/rev] */
#define SIMBODY_COST_STEPS_REV_IDEAL 60.0
#define SIMBODY_COST_ACCURACY_POWER 0.3

static double simbody_cost_per_sample(const fb_model *m, const fb_case *c) {
  /* sampling, plus the integrator's own steps, which grow as the accuracy
   * tightens (measured: x2.2 to x3.6 per factor 100) */
  const int clearance = m->joints == FB_JOINTS_CLEARANCE;
  const double steps_rev = (clearance ? SIMBODY_COST_STEPS_REV_CLEARANCE
                                      : SIMBODY_COST_STEPS_REV_IDEAL) *
                           pow(FB_SIMBODY_ACCURACY_DEFAULT / c->simbody.accuracy,
                               SIMBODY_COST_ACCURACY_POWER);
  const double samples = fb_case_duration(c) / c->solver.h + 1.0;
  return SIMBODY_COST_SAMPLE_S + SIMBODY_COST_STEP_S * steps_rev * c->revolutions / samples;
}

/* Simbody's settings for its peer (tests/peers/peer_simbody.cpp) */
static void simbody_peer_args(const fb_model_scene *sm, double h, fb_engine_put_arg put, void *a) {
  (void)h;
  put(a, "integrator", fb_simbody_integrator_name(sm->simbody.integrator));
  fb_engine_put_number(put, a, "accuracy", sm->simbody.accuracy);
}

/* Simbody's own choices as a model used them */
static int simbody_settings(fb_engine_setting *out, const fb_case *c, int clearance_mask,
                            fb_collider collider, double h) {
  (void)clearance_mask, (void)collider, (void)h;
  out[0] = (fb_engine_setting){.key = "integrator", .kind = FB_SETTING_TEXT,
                               .text = fb_simbody_integrator_name(c->simbody.integrator)};
  out[1] = (fb_engine_setting){.key = "accuracy", .kind = FB_SETTING_NUMBER,
                               .number = c->simbody.accuracy};
  return 2;
}

/* the run's table: Simbody's integrator */
static void simbody_settings_lines(const fb_case *c, const fb_engine_models_used *u,
                                   fb_engine_put_line put, void *a) {
  (void)u;
  char line[256];
  snprintf(line, sizeof line,
           "Simbody models: integrator %s, accuracy %g (error-controlled internal steps, "
           "sampled every h)",
           fb_simbody_integrator_name(c->simbody.integrator), c->simbody.accuracy);
  put(a, line);
}

/* the clearance contact: the project's law as an applied force */
static const char *simbody_mapping_text(fb_collider collider) {
  (void)collider;
  return "none (applied force)";
}

/* ---- Simbody's rows of fourbar bench (engine_bench.h): its integrator and
 * accuracy on the case's own output grid (its steps are its integrator's) ---- */
static int simbody_bench_point(fb_bench_set s, int i, const fb_case *c, fb_case *k,
                               fb_bench_point *p) {
  enum { ACCURACIES = 6 };
  if (s == FB_BENCH_SET_DEFAULT) { /* rkmerson at 1e-4 and 1e-6, cpodes at 1e-6 */
    if (i >= 3) return 0;
    k->simbody.integrator = i == 2 ? FB_SIMBODY_CPODES : FB_SIMBODY_RKMERSON;
    k->simbody.accuracy = i == 0 ? 1e-4 : 1e-6;
  } else if (s == FB_BENCH_SET_OWN) { /* integrator x accuracy 1e-3 to 1e-8 */
    if (i >= FB_SIMBODY_INTEGRATOR_COUNT * ACCURACIES) return 0;
    const double acc[ACCURACIES] = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8};
    k->simbody.integrator = i / ACCURACIES;
    k->simbody.accuracy = acc[i % ACCURACIES];
  } else {
    return 0;
  }
  k->solver.h = c->solver.h; /* the case's output step, as run */
  k->solver.h_mode = c->solver.h_mode;
  snprintf(p->stepper, sizeof p->stepper, "%s %.0e",
           fb_simbody_integrator_name(k->simbody.integrator), k->simbody.accuracy);
  return 1;
}

/* --grid simbody (and solvers, all): its own grid, then alone ODE's (or any
 * engine's) rows at fixed steps for the comparison */
static const fb_engine_bench simbody_bench = {.point = simbody_bench_point,
                                              .own_grid = FB_BENCH_SIMBODY,
                                              .alone_after = FB_BENCH_SET_STEP_ROWS};

const fb_engine fb_engine_simbody = {
    .name = "simbody",
    .guarded = 1,
    .step_values_lag = 0,
    .refine_peaks = 0,
    .create = simbody_create,
    .step = simbody_step,
    .stopped = simbody_stopped,
    .sample = simbody_sample,
    .contact = simbody_contact,
    .provenance = simbody_provenance,
    .reactions = simbody_reactions,
    .drift = simbody_drift,
    .steps = simbody_steps,
    .destroy = simbody_destroy,
    .stepping_s = simbody_stepping_s,
    .cost_per_sample = simbody_cost_per_sample,
    .drive_key = "[solver] drive_torque_max_n_m",
    .peer_args = simbody_peer_args,
    .settings = simbody_settings,
    .settings_lines = simbody_settings_lines,
    .mapping_text = simbody_mapping_text,
    .bench = &simbody_bench,
    .kit = &fb_simbody_kit,
    .own_one_pin = 1, /* the tree is cut at the reference joint (simbody_scene.cpp) */
};
