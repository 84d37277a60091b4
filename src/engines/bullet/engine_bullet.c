/* The Bullet engine behind the engine interface (engine.h): thin wrappers
 * over the Bullet scene (bullet_scene.h, C++ behind C linkage). */
#include <stdio.h>
#include <stdlib.h>

#include "bullet_kit.h"
#include "bullet_scene.h"
#include "engine.h"
#include "impact_bullet.h"
#include "kit_impact.h"

static fb_status bullet_create(void **self, const fb_model_scene *sm, fb_diag *diag) {
  fb_bullet_scene *s = NULL;
  fb_status st = fb_bullet_scene_create(&s, sm, diag);
  if (st == FB_OK) *self = s;
  return st;
}

static fb_status bullet_step(void *self, fb_diag *diag) { return fb_bullet_scene_step(self, diag); }

static void bullet_stopped(const void *self, fb_stop *out) { fb_bullet_scene_stopped(self, out); }

static void bullet_sample(const void *self, fb_sample *x) { fb_bullet_scene_sample(self, x); }

static void bullet_contact(const void *self, fb_engine_contact *out) {
  out->penetration = fb_bullet_scene_penetration(self, &out->joint);
  for (int j = 0; j < 4; j++) out->impacts[j] = fb_bullet_scene_impacts(self, j);
}

static void bullet_provenance(const void *self, int joint, fb_contact_provenance *out) {
  fb_bullet_scene_provenance(self, joint, out);
}

static void bullet_reactions(const void *self, double force[4][2], double *drive_torque) {
  fb_bullet_scene_reactions(self, force, drive_torque);
}

static double bullet_drift(const void *self) { return fb_bullet_scene_joint_drift(self); }

static size_t bullet_steps(const void *self) { return fb_bullet_scene_steps(self); }

static void bullet_destroy(void *self) { fb_bullet_scene_destroy(self); }

/* Time per sample [s] (engine.h: CPU time, timing.json models[].cpu_s over
 * its samples; issue 54): the MLCP solver 3.4 to 4.1 us over the shipped
 * cases; sequential impulse 1.9 us + 0.107 us per iteration (3.0 us at 10,
 * 12.6 us at 100, 109 us at 1000; paper case, 2 revolutions); each rounded
 * up. */
#define BULLET_COST_S 4.5e-6
#define BULLET_COST_SI_S 2.4e-6
#define BULLET_COST_ITERATION_S 0.12e-6

static double bullet_cost_per_sample(const fb_model *m, const fb_case *c) {
  (void)m;
  return c->bullet.solver == FB_BULLET_SEQUENTIAL_IMPULSE
             ? BULLET_COST_SI_S + BULLET_COST_ITERATION_S * c->bullet.iterations
             : BULLET_COST_S;
}

/* Bullet's settings for its peer (tests/peers/peer_bullet.cpp) */
static void bullet_peer_args(const fb_model_scene *sm, double h, fb_engine_put_arg put, void *a) {
  (void)h;
  put(a, "solver", sm->bullet.solver == FB_BULLET_MLCP_DANTZIG ? "mlcp" : "si");
  fb_engine_put_number(put, a, "iterations", sm->bullet.iterations);
  fb_engine_put_number(put, a, "erp", sm->solver.world_erp);
  fb_engine_put_number(put, a, "fmax", sm->solver.drive_torque_max);
}

/* the single impact through Bullet's kit binding (kit_impact.h), its
 * solver and iterations o's, handed as a case's [bullet] options */
static fb_status bullet_impact_law(fb_impact_result *out, const fb_impact_def *d,
                                   const fb_impact_opts *o, fb_diag *diag) {
  fb_case *c = calloc(1, sizeof *c);
  if (!c) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the Bullet impact");
  c->bullet = o->bullet;
  const fb_status st = fb_kit_impact(out, &fb_bullet_kit, d, c, diag);
  free(c);
  return st;
}

static fb_status bullet_impact_row(fb_impact_result *out, const fb_impact_row *r,
                                   fb_diag *diag) {
  return fb_impact_bullet_contact(out, r->mass, r->speed, r->h, r->bullet.kp, r->bullet.kd,
                                  r->t_max, r->onset_phase, diag);
}

static const fb_engine_impact bullet_impact = {.law = bullet_impact_law,
                                               .row = bullet_impact_row};

/* Bullet's own choices as a model used them */
static int bullet_settings(fb_engine_setting *out, const fb_case *c, int clearance_mask,
                           fb_collider collider, double h) {
  (void)clearance_mask, (void)collider, (void)h;
  out[0] = (fb_engine_setting){.key = "solver", .kind = FB_SETTING_TEXT,
                               .text = fb_bullet_solver_name(c->bullet.solver)};
  out[1] = (fb_engine_setting){.key = "iterations", .kind = FB_SETTING_INTEGER,
                               .integer = c->bullet.iterations};
  out[2] = (fb_engine_setting){.key = "world", .kind = FB_SETTING_TEXT,
                               .text = "btDiscreteDynamicsWorld"};
  return 3;
}

/* the run's table: Bullet's solver */
static void bullet_settings_lines(const fb_case *c, const fb_engine_models_used *u,
                                  fb_engine_put_line put, void *a) {
  (void)u;
  char line[256];
  snprintf(line, sizeof line,
           "Bullet models: %s, %d iterations (sequential impulse; the MLCP's fallback)",
           fb_bullet_solver_name(c->bullet.solver), c->bullet.iterations);
  put(a, line);
}

/* ---- Bullet's rows of fourbar bench (engine_bench.h): the case's mapping;
 * its pin rows are hard, whatever the case's world CFM ---- */
static int bullet_bench_point(fb_bench_set s, int i, const fb_case *c, fb_case *k,
                              fb_bench_point *p) {
  p->mapping = (int)k->clearance.mapping;
  p->hard_pins = 1;
  if (s == FB_BENCH_SET_DEFAULT) { /* MLCP at 1e-5 s and auto */
    if (i >= 2) return 0;
    fb_bench_fixed_step(k, i == 0 ? 1e-5 : 0.0);
    k->bullet.solver = FB_BULLET_MLCP_DANTZIG;
    snprintf(p->stepper, sizeof p->stepper, "mlcp");
    return 1;
  }
  if (s != FB_BENCH_SET_SOLVERS && s != FB_BENCH_SET_OWN) return 0;
  /* its own knobs: solver (and its iterations) x h */
  if (i >= FB_BENCH_BULLET_SOLVERS * FB_BENCH_BULLET_STEPS) return 0;
  const double bh[FB_BENCH_BULLET_STEPS] = {1e-4, 1e-5, 1e-6, 0.0}; /* 0: auto */
  const int iters[FB_BENCH_BULLET_SOLVERS] = {10, 50, 100, 0};   /* 0: mlcp-dantzig */
  const int si = i / FB_BENCH_BULLET_STEPS;
  fb_bench_fixed_step(k, bh[i % FB_BENCH_BULLET_STEPS]);
  k->bullet.solver = iters[si] ? FB_BULLET_SEQUENTIAL_IMPULSE : FB_BULLET_MLCP_DANTZIG;
  k->bullet.iterations = iters[si] ? iters[si] : c->bullet.iterations;
  if (iters[si]) snprintf(p->stepper, sizeof p->stepper, "si-%d", iters[si]);
  else snprintf(p->stepper, sizeof p->stepper, "mlcp");
  return 1;
}

/* --grid bullet: its grid alone, after ODE (or any engine) at the case's
 * own settings */
static const fb_engine_bench bullet_bench = {.point = bullet_bench_point,
                                             .own_grid = FB_BENCH_BULLET,
                                             .alone_before = FB_BENCH_SET_CASE_ROW};

const fb_engine fb_engine_bullet = {
    .name = "bullet",
    .guarded = 1,
    .step_values_lag = 1,
    .refine_peaks = 1,
    .create = bullet_create,
    .step = bullet_step,
    .stopped = bullet_stopped,
    .sample = bullet_sample,
    .contact = bullet_contact,
    .provenance = bullet_provenance,
    .reactions = bullet_reactions,
    .drift = bullet_drift,
    .steps = bullet_steps,
    .destroy = bullet_destroy,
    .cost_per_sample = bullet_cost_per_sample,
    .drive_key = "[solver] drive_torque_max_n_m",
    .peer_args = bullet_peer_args,
    .impact = &bullet_impact,
    .settings = bullet_settings,
    .settings_lines = bullet_settings_lines,
    .bench = &bullet_bench,
    .kit = &fb_bullet_kit,
};
