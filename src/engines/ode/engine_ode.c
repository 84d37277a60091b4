/* The ODE engine behind the engine interface (engine.h): thin wrappers over
 * the ODE world (ode_world.h). */
#include "engine.h"
#include "impact_ode.h"
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

/* Wall time per sample on an idle 2-core machine [s] (engine.h): measured on
 * the paper's case, dWorldStep 3 to 4.3 us, dWorldQuickStep 0.57 to 0.63 us
 * per iteration (22 us at 20, 1257 us at 2000), the faceted collider 0.66 us
 * per box (43 us at 64, 2716 us at 4096), the libccd collider 15 us + 0.0033
 * us per segment (221 us at 65536); each rounded up. */
#define ODE_COST_S 5e-6
#define ODE_COST_QUICK_S 2e-6
#define ODE_COST_QUICK_ITERATION_S 0.65e-6
#define ODE_COST_BOX_S 0.7e-6
#define ODE_COST_CCD_S 15e-6
#define ODE_COST_CCD_SEGMENT_S 3.5e-9

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
    s += ODE_COST_BOX_S * (c->clearance.segments_given ? c->clearance.segments : c->clearance.faceted_n);
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

/* the single impact (impact_ode.h) */
static fb_status ode_impact_law(fb_impact_result *out, const fb_impact_def *d,
                                const fb_impact_opts *o, fb_diag *diag) {
  (void)o;
  return fb_impact_ode(out, d, diag);
}

static fb_status ode_impact_row(fb_impact_result *out, const fb_impact_row *r, fb_diag *diag) {
  return fb_impact_ode_row(out, r->mass, r->speed, r->h, r->ode.erp, r->ode.cfm, r->max_vel,
                           r->t_max, r->onset_phase, diag);
}

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
};
