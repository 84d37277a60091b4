/* The analytic and reference engines behind the engine interface, and the
 * registry of engines. Both compute exact or high-accuracy answers rather
 * than step a world: in create, the analytic engine samples the exact loop
 * solution over the run (analytic.h) and the reference engine integrates it
 * (GSL rk8pd with error control, reference.h); step then replays one sample.
 * And which of an engine's kit bindings builds a model's collider
 * (fb_engine_kit_of). */
#include "engine.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analytic.h"
#include "closed_form.h"
#include "mech_kinematics.h"
#include "fb_config.h"
#include "reference.h"

/* the table of engine ID when this build has it (FB_HAVE_ID 1), else NULL */
#define FB_ENGINE_IF_1(name) &fb_engine_##name
#define FB_ENGINE_IF_0(name) NULL
#define FB_ENGINE_IF_(have, name) FB_ENGINE_IF_##have(name)
#define FB_ENGINE_IF(have, name) FB_ENGINE_IF_(have, name)

/* the registry: the one list of engine tables, by fb_engine_id */
static const fb_engine *const registry[FB_ENGINE_COUNT] = {
    [FB_ENGINE_ANALYTIC] = &fb_engine_analytic,
    [FB_ENGINE_REFERENCE] = &fb_engine_reference,
#define X(ID, name) [FB_ENGINE_##ID] = FB_ENGINE_IF(FB_HAVE_##ID, name),
    FB_ENGINE_LIST
#undef X
};

const fb_engine *fb_engine_get(fb_engine_id id, fb_diag *diag) {
  if (id >= 0 && id < FB_ENGINE_COUNT && registry[id]) return registry[id];
  fb_diag_set(diag, FB_ERR_ARG, "engine '%s' is not part of this build%s%s", fb_engine_name(id),
              fb_engine_howto(id)[0] ? ": " : "", fb_engine_howto(id));
  return NULL;
}

const struct fb_kit_binding *fb_engine_kit_of(const fb_engine *e, fb_collider collider) {
  return collider == FB_COLLIDER_NATIVE ? e->kit_native : e->kit;
}

fb_status fb_engine_advance(const fb_engine *e, void *self, double t, double h, fb_diag *diag) {
  fb_sample x;
  e->sample(self, &x);
  while (x.t < t - 0.5 * h) {
    fb_status st = e->step(self, diag);
    if (st != FB_OK) return st;
    e->sample(self, &x);
  }
  return FB_OK;
}

/* ---- a series computed in create, replayed one sample per step ---------- */

typedef struct {
  fb_series s;
  const fb_model_scene *sm; /* the model (the analytic its inverse dynamics, the reference its joint) */
  size_t steps;      /* samples computed (analytic), accepted integrator steps (reference) */
  size_t i;          /* sample replayed now */
  int failed;        /* the computation stopped early */
  char why[FB_DIAG_SIZE];
  fb_stop stop;      /* why (the reference's reason) */
} replay;

static fb_status replay_step(void *self, fb_diag *diag) {
  replay *r = self;
  if (r->i + 1 >= r->s.n)
    return fb_diag_set(diag, FB_ERR_NUMERIC, "%s",
                       r->failed ? r->why : "no sample beyond the run's duration");
  r->i++;
  return FB_OK;
}

static void replay_sample(const void *self, fb_sample *x) {
  const replay *r = self;
  fb_series_get(&r->s, r->i, x);
}

static void replay_stopped(const void *self, fb_stop *out) { *out = ((const replay *)self)->stop; }

static size_t replay_steps(const void *self) { return ((const replay *)self)->steps; }

static void replay_destroy(void *self) {
  replay *r = self;
  if (!r) return;
  fb_series_free(&r->s);
  free(r);
}

static void no_contact(const void *self, fb_engine_contact *out) {
  (void)self;
  memset(out, 0, sizeof *out);
  out->joint = -1;
}

static double no_drift(const void *self) {
  (void)self;
  return 0.0;
}

/* ---- analytic ------------------------------------------------------------ */

static fb_status analytic_create(void **self, const fb_model_scene *sm, fb_diag *diag) {
  const fb_scene *d = sm->def;
  fb_status st = fb_scene_check(d, diag);
  if (st != FB_OK) return st;
  replay *r = calloc(1, sizeof *r);
  if (!r) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the analytic engine");
  r->steps = d->steps + 1;
  st = fb_mech_sample(&r->s, d->source.mechanism, &sm->lengths, sm->branch, sm->crank_angle0,
                      sm->omega2, sm->solver.h, r->steps, diag);
  if (st != FB_OK) {
    free(r);
    return st;
  }
  r->sm = sm;
  *self = r;
  return FB_OK;
}

/* joint reactions and drive torque of the ideal mechanism at the replayed
 * sample's crank angle: inverse dynamics (invdyn.h), gravity included */
/* the slider-crank's (slider_crank_invdyn.h): the pins' forces, and at the
 * slider-ground joint the force on the ground from the slider, -N along y */
/* the closed form's inverse dynamics at the replayed sample's crank angle;
 * NAN when it does not assemble there */
static void analytic_reactions(const void *self, double force[4][2], double *drive_torque) {
  const replay *r = self;
  const fb_model_scene *sm = r->sm;
  const fb_closed_form *cf = fb_closed_form_of(sm->def->source.mechanism);
  if (cf->reactions(force, drive_torque, &sm->lengths, sm->branch, sm->link, sm->gravity,
                    r->s.crank_angle[r->i], sm->omega2, NULL) != FB_OK) {
    for (int j = 0; j < 4; j++) force[j][0] = force[j][1] = NAN;
    *drive_torque = NAN;
  }
}

/* Time per sample [s] (engine.h: CPU time, timing.json models[].cpu_s over
 * its samples; issue 54): 1.17 to 1.54 us over the shipped cases (the
 * closed form and its inverse dynamics); rounded up. */
static double analytic_cost_per_sample(const fb_model *m, const fb_case *c) {
  (void)m, (void)c;
  return 1.6e-6;
}

const fb_engine fb_engine_analytic = {
    .name = "analytic",
    .guarded = 0,
    .computes_in_create = 1,
    .create = analytic_create,
    .step = replay_step,
    .sample = replay_sample,
    .contact = no_contact,
    .provenance = NULL,
    .reactions = analytic_reactions,
    .drift = no_drift,
    .steps = replay_steps,
    .destroy = replay_destroy,
    .cost_per_sample = analytic_cost_per_sample,
};

/* ---- reference ----------------------------------------------------------- */

static fb_status reference_create(void **self, const fb_model_scene *sm, fb_diag *diag) {
  fb_status st = fb_scene_check(sm->def, diag);
  if (st != FB_OK) return st;
  if (sm->model->law == FB_MODEL_LAW_NONE || !sm->clearance_mask)
    return fb_diag_set(diag, FB_ERR_ARG, "model '%s': the reference engine needs a contact law "
                       "at a clearance joint ([clearance] joints)", sm->model->name);
  replay *r = calloc(1, sizeof *r);
  if (!r) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the reference engine");
  r->sm = sm;
  double tol;
  st = fb_reference_tolerance(&tol, diag);
  if (st != FB_OK) {
    free(r);
    return st;
  }
  st = fb_reference_run_joints(&r->s, &r->steps, &sm->def->source, sm->law, tol, &r->stop, diag);
  if (st == FB_ERR_NUMERIC) { /* the reference failing is a result, not an error */
    r->failed = 1;
    snprintf(r->why, sizeof r->why, "%.200s", diag ? diag->msg : "reference integration failed");
    st = r->s.n ? FB_OK : fb_diag_set(diag, FB_ERR_NUMERIC, "%s", r->why);
  }
  if (st != FB_OK) {
    fb_series_free(&r->s);
    free(r);
    return st;
  }
  *self = r;
  return FB_OK;
}

static void reference_contact(const void *self, fb_engine_contact *out) {
  const replay *r = self;
  const int cj = fb_case_compared_joint(&r->sm->def->source);
  memset(out, 0, sizeof *out);
  out->joint = cj;
  out->penetration = r->s.contact[cj][FB_C_PEN] ? r->s.contact[cj][FB_C_PEN][r->i] : 0.0;
}

/* Time per sample [s] (engine.h: CPU time, timing.json models[].cpu_s over
 * its samples; issue 54): 1.4 to 2.6 us over the shipped cases (about one
 * rk8pd step per sample, and the spikes' refinement), rounded up; its check
 * integration (not in an ensemble's member) costs the same again (1.3 to
 * 2.2 us: reference.h). */
#define REFERENCE_COST_S 2.6e-6
#define REFERENCE_COST_CHECK 0.9 /* the check integration, in reference runs [-] */
/* With clearance at several pins (the planar path, reference.h
 * fb_reference_run_joints): 14.1 and 17.5 us a sample for the impact and
 * restitution references of cases/two_clearance_joints.ini, the check
 * integration 0.95 and 1.03 times that (timing.json), rounded up. */
#define REFERENCE_PLANAR_COST_S 18e-6
#define REFERENCE_PLANAR_COST_CHECK 1.05

static double reference_cost_per_sample(const fb_model *m, const fb_case *c) {
  (void)m;
  if (c->clearance.mask != (1 << fb_case_mech(c)->reference_joint))
    return REFERENCE_PLANAR_COST_S * (c->member ? 1.0 : 1.0 + REFERENCE_PLANAR_COST_CHECK);
  return REFERENCE_COST_S * (c->member ? 1.0 : 1.0 + REFERENCE_COST_CHECK);
}

const fb_engine fb_engine_reference = {
    .name = "reference",
    .guarded = 0,
    .computes_in_create = 1,
    .create = reference_create,
    .step = replay_step,
    .stopped = replay_stopped,
    .sample = replay_sample,
    .contact = reference_contact,
    .provenance = NULL,
    .reactions = NULL,
    .drift = no_drift,
    .steps = replay_steps,
    .destroy = replay_destroy,
    .cost_per_sample = reference_cost_per_sample,
};
