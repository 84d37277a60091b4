/* The ODE engine behind the engine interface (engine.h): thin wrappers over
 * the ODE world (ode_world.h). */
#include <stdio.h>

#include "engine.h"
#include "kit_impact.h"
#include "ode_kit.h"
#include "ode_world.h"

static fb_status ode_create(void **self, const fb_model_scene *sm, fb_diag *diag) {
  fb_ode_world *s = NULL;
  fb_status st = fb_ode_world_create(&s, sm, diag);
  if (st == FB_OK) *self = s;
  return st;
}

static fb_status ode_step(void *self, fb_diag *diag) { return fb_ode_world_step(self, diag); }

static void ode_stopped(const void *self, fb_stop *out) { fb_ode_world_stopped(self, out); }

static void ode_sample(const void *self, fb_sample *x) { fb_ode_world_sample(self, x); }

static void ode_contact(const void *self, fb_engine_contact *out) {
  out->penetration = fb_ode_world_penetration(self, &out->joint);
  for (int j = 0; j < 4; j++) out->impacts[j] = fb_ode_world_impacts(self, j);
}

static void ode_provenance(const void *self, int joint, fb_contact_provenance *out) {
  fb_ode_world_provenance(self, joint, out);
}

static void ode_reactions(const void *self, double force[4][2], double *drive_torque) {
  fb_ode_world_reactions(self, force, drive_torque);
}

static double ode_drift(const void *self) { return fb_ode_world_joint_drift(self); }

static size_t ode_steps(const void *self) { return fb_ode_world_steps(self); }

static void ode_destroy(void *self) { fb_ode_world_destroy(self); }

static void ode_step_stats(const void *self, fb_step_stats *out) {
  fb_ode_world_step_stats(self, out);
}

/* Time per sample [s] (engine.h: CPU time, timing.json models[].cpu_s over
 * its samples; issue 54): dWorldStep 2.3 to 3.4 us over the shipped cases
 * (two clearance joints the most); dWorldQuickStep 1.75 us + 0.2 us per
 * iteration (5.75 us at 20, 21.7 us at 100; paper case, 2 revolutions);
 * the faceted collider 0.24 us per box beyond 4.7 us (22.2 us at 64, 128
 * us at 512), the libccd collider 2.6 us + 0.0011 us per segment (5.3 us
 * at 256, 22.8 us at 16384) beyond dWorldStep's; each rounded up. */
#define ODE_COST_S 3.2e-6
#define ODE_COST_QUICK_S 2.0e-6
#define ODE_COST_QUICK_ITERATION_S 0.22e-6
#define ODE_COST_FACETED_S 5e-6
#define ODE_COST_BOX_S 0.26e-6
#define ODE_COST_CCD_S 3e-6
#define ODE_COST_CCD_SEGMENT_S 1.2e-9

static double ode_cost_per_sample(const fb_model *m, const fb_case *c) {
  const int clearance = m->joints == FB_JOINTS_CLEARANCE;
  double s = c->solver.stepper == FB_STEPPER_QUICK
                 ? ODE_COST_QUICK_S + ODE_COST_QUICK_ITERATION_S * c->solver.quick_iterations
                 : ODE_COST_S;
  const int collider = m->collider != FB_COLLIDER_EXACT ? (int)m->collider
                       : c->clearance.collider == FB_CASE_COLLIDER_FACETED ? FB_COLLIDER_FACETED
                       : c->clearance.collider == FB_CASE_COLLIDER_CCD ? FB_COLLIDER_CCD
                                                                       : FB_COLLIDER_EXACT;
  if (clearance && collider == FB_COLLIDER_FACETED)
    s += ODE_COST_FACETED_S + ODE_COST_BOX_S * fb_case_faceted_n(c);
  if (clearance && collider == FB_COLLIDER_CCD)
    s += ODE_COST_CCD_S + ODE_COST_CCD_SEGMENT_S * c->clearance.segments;
  return s;
}

/* ODE's settings for its peer (tests/peers/peer_ode.c) */
static void ode_peer_args(const fb_model_scene *sm, double h, fb_engine_put_arg put, void *a) {
  (void)h;
  fb_engine_put_number(put, a, "erp", sm->solver.world_erp);
  fb_engine_put_number(put, a, "cfm", sm->solver.world_cfm);
  fb_engine_put_number(put, a, "fmax", sm->solver.drive_torque_max);
  put(a, "stepper", sm->solver.stepper == FB_STEPPER_QUICK ? "quick" : "world");
  fb_engine_put_number(put, a, "iterations", sm->solver.quick_iterations);
}

/* the single impact through ODE's kit binding (kit_impact.h) */
static fb_status ode_impact_law(fb_impact_result *out, const fb_impact_def *d,
                                const fb_impact_opts *o, fb_diag *diag) {
  (void)o;
  return fb_kit_impact(out, &fb_ode_kit, d, NULL, diag);
}

/* a fixed row's single impact through ODE's kit binding (kit_impact.h): its
 * ERP and CFM, ODE's contact_max_correcting_vel */
static fb_status ode_impact_row(fb_impact_result *out, const fb_impact_row *r, fb_diag *diag) {
  return fb_kit_impact_row(out, &fb_ode_kit, r->mass, r->speed, r->h, r->ode.erp, r->ode.cfm,
                           r->max_vel, r->t_max, r->onset_phase, diag);
}

/* ---- ODE's rows of fourbar bench (engine_bench.h) ---- */

/* the stepper column of the case's own stepper, with suffix */
static void ode_stepper_name(char *out, size_t size, const fb_case *k, const char *suffix) {
  if (k->solver.stepper == FB_STEPPER_QUICK)
    snprintf(out, size, "quick-%d%s", k->solver.quick_iterations, suffix);
  else
    snprintf(out, size, "world%s", suffix);
}

/* dWorldStep with world ERP erp and CFM cfm */
static void ode_world(fb_case *k, double erp, double cfm) {
  k->solver.stepper = FB_STEPPER_WORLD;
  k->solver.world_erp = erp;
  k->solver.world_cfm = cfm;
}

/* the adaptive step keeps the matched mapping's static form */
static int ode_adaptive_mapping(const fb_case *k) {
  return k->clearance.mapping == FB_MAPPING_MATCHED ? FB_MAPPING_MATCHED_STATIC
                                                    : (int)k->clearance.mapping;
}

/* the ideal model alone at its cheapest setting for 1e-5 (issue 29): world
 * ERP 1 (the whole joint error corrected each step) lets the step double,
 * h = 1.5e-5 and 2e-5 s (i < FB_BENCH_IDEAL_TUNED) */
static void ode_tuned(int i, fb_case *k, fb_bench_point *p) {
  fb_bench_fixed_step(k, i == 0 ? 1.5e-5 : 2e-5);
  k->model_count = 1;
  ode_world(k, 1.0, 1e-10);
  snprintf(p->stepper, sizeof p->stepper, "world");
  p->mapping = 0;
}

/* the tuned ideal rows, dWorldStep with [solver] h_s = adaptive at accuracy
 * 0.3 and 0.1, and the adaptive row with the rocking bound (engine_bench.h)
 * (i < FB_BENCH_IDEAL_TUNED + FB_BENCH_ADAPTIVE + FB_BENCH_ADAPTIVE_ROCKING) */
static int ode_extra(int i, fb_case *k, fb_bench_point *p) {
  if (i < FB_BENCH_IDEAL_TUNED) {
    ode_tuned(i, k, p);
    return 1;
  }
  i -= FB_BENCH_IDEAL_TUNED;
  if (i >= FB_BENCH_ADAPTIVE + FB_BENCH_ADAPTIVE_ROCKING) return 0;
  const double accuracy = i < FB_BENCH_ADAPTIVE ? FB_BENCH_ADAPTIVE_ACCURACY(i) : 0.3;
  fb_bench_adaptive_step(k, accuracy);
  k->solver.stepper = FB_STEPPER_WORLD;
  if (i < FB_BENCH_ADAPTIVE) {
    snprintf(p->stepper, sizeof p->stepper, "world-a%g", accuracy);
  } else {
    k->solver.rocking_h_omega = FB_BENCH_ROCKING_H_OMEGA;
    snprintf(p->stepper, sizeof p->stepper, "world-a0.3-r%g", FB_BENCH_ROCKING_H_OMEGA);
  }
  p->mapping = ode_adaptive_mapping(k);
  return 1;
}

/* the solver grid: stepper (dWorldStep; dWorldQuickStep at 10, 20, 50
 * iterations) x h (1e-3 to 1e-6 s and auto) x mapping x world ERP/CFM
 * ((0.2, 1e-10), (0.8, 1e-8)); the mapping does not touch the ideal model:
 * one row for it; then the extra rows */
static int ode_solvers(int i, fb_case *k, fb_bench_point *p) {
  enum { ERPS = 2, PER_STEPPER = FB_BENCH_STEPS * FB_MAPPING_COUNT * ERPS };
  if (i >= 4 * PER_STEPPER) return ode_extra(i - 4 * PER_STEPPER, k, p);
  const double hs[FB_BENCH_STEPS] = {1e-3, 1e-4, 1e-5, 1e-6, 0.0}; /* 0: auto */
  const int iters[4] = {0, 10, 20, 50};                              /* 0: dWorldStep */
  const double erp[ERPS] = {0.2, 0.8}, cfm[ERPS] = {1e-10, 1e-8};
  const int si = i / PER_STEPPER, hi = i / (FB_MAPPING_COUNT * ERPS) % FB_BENCH_STEPS;
  const int mi = i / ERPS % FB_MAPPING_COUNT, ei = i % ERPS;
  fb_bench_fixed_step(k, hs[hi]);
  k->solver.stepper = iters[si] ? FB_STEPPER_QUICK : FB_STEPPER_WORLD;
  k->solver.quick_iterations = iters[si] ? iters[si] : 20;
  k->solver.world_erp = erp[ei];
  k->solver.world_cfm = cfm[ei];
  k->clearance.mapping = mi;
  if (iters[si]) snprintf(p->stepper, sizeof p->stepper, "quick-%d", iters[si]);
  else snprintf(p->stepper, sizeof p->stepper, "world");
  p->mapping = mi;
  p->no_ideal_row = mi != 0;
  return 1;
}

static int ode_bench_point(fb_bench_set s, int i, const fb_case *c, fb_case *k,
                           fb_bench_point *p) {
  switch (s) {
    case FB_BENCH_SET_DEFAULT: /* 1e-5 s, auto, adaptive 0.3 at the case's stepper */
      if (i >= 3) return 0;
      fb_bench_fixed_step(k, i == 0 ? 1e-5 : 0.0);
      if (i == 2) fb_bench_adaptive_step(k, 0.3);
      ode_stepper_name(p->stepper, sizeof p->stepper, k, i == 2 ? "-a0.3" : "");
      p->mapping = i == 2 ? ode_adaptive_mapping(k) : (int)k->clearance.mapping;
      return 1;
    case FB_BENCH_SET_DEFAULT_LAST:
      if (i >= FB_BENCH_IDEAL_TUNED) return 0;
      ode_tuned(i, k, p);
      return 1;
    case FB_BENCH_SET_SOLVERS: return ode_solvers(i, k, p);
    case FB_BENCH_SET_FRONTIER: /* the case's settings at the frontier's steps; the ideal
                                   model at ERP 0.8, CFM 1e-8, h = 1e-5 s */
      if (i < FB_BENCH_FRONTIER_STEPS) {
        fb_bench_fixed_step(k, FB_BENCH_FRONTIER_H(i));
        snprintf(p->stepper, sizeof p->stepper, "%s",
                 k->solver.stepper == FB_STEPPER_WORLD ? "world" : "quick");
        p->mapping = (int)k->clearance.mapping;
        return 1;
      }
      if (i > FB_BENCH_FRONTIER_STEPS) return 0;
      fb_bench_fixed_step(k, 1e-5);
      k->model_count = 1;
      ode_world(k, 0.8, 1e-8);
      snprintf(p->stepper, sizeof p->stepper, "world");
      p->mapping = 0;
      return 1;
    case FB_BENCH_SET_FRONTIER_LAST: return ode_extra(i, k, p);
    case FB_BENCH_SET_CASE_ROW: /* the case's own settings (a fixed step, else auto) */
      if (i >= 1) return 0;
      fb_bench_fixed_step(k, c->solver.h_mode == FB_STEP_FIXED ? c->solver.h : 0.0);
      ode_stepper_name(p->stepper, sizeof p->stepper, c, "");
      p->mapping = (int)k->clearance.mapping;
      return 1;
    case FB_BENCH_SET_STEP_ROWS: /* dWorldStep, matched, h 1e-4, 1e-5, 1e-6 s and auto */
      if (i >= 4) return 0;
      fb_bench_fixed_step(k, i == 0 ? 1e-4 : i == 1 ? 1e-5 : i == 2 ? 1e-6 : 0.0);
      ode_world(k, 0.2, 1e-10);
      k->clearance.mapping = FB_MAPPING_MATCHED;
      snprintf(p->stepper, sizeof p->stepper, "world");
      p->mapping = FB_MAPPING_MATCHED;
      return 1;
    case FB_BENCH_SET_COLLIDERS: /* dWorldStep, world ERP/CFM (0.2, 1e-10), h 1e-5, 1e-6 s */
      if (i >= 2) return 0;
      fb_bench_fixed_step(k, i == 0 ? 1e-5 : 1e-6);
      ode_world(k, 0.2, 1e-10);
      snprintf(p->stepper, sizeof p->stepper, "world");
      p->mapping = (int)k->clearance.mapping;
      return 1;
    default: return 0;
  }
}

static const fb_engine_bench ode_bench = {.point = ode_bench_point, .names_world_erp = 1};

static const fb_engine_impact ode_impact = {.law = ode_impact_law, .row = ode_impact_row};

const fb_engine fb_engine_ode = {
    .name = "ode",
    .guarded = 1,
    .step_values_lag = 1,
    .refine_peaks = 1,
    .create = ode_create,
    .step = ode_step,
    .stopped = ode_stopped,
    .sample = ode_sample,
    .contact = ode_contact,
    .provenance = ode_provenance,
    .reactions = ode_reactions,
    .drift = ode_drift,
    .steps = ode_steps,
    .destroy = ode_destroy,
    .step_stats = ode_step_stats,
    .cost_per_sample = ode_cost_per_sample,
    .drive_key = "[solver] drive_torque_max_n_m",
    .peer_args = ode_peer_args,
    .impact = &ode_impact,
    .bench = &ode_bench,
    .kit = &fb_ode_kit,
    /* the kit builds ODE's four-bar and slider-crank by default: its binding
     * has every feature of the hand-built world but the drive of a clearance
     * joint (fb_engine_runner keeps the hand-built world there), at its cost
     * (callgrind 1.049x and 1.035x on the paper case's clearance and ideal
     * models) and within the committed baselines (docs/architecture.md) */
    .kit_default = FB_KIT_DEFAULT_ALL,
};
