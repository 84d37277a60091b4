/* The kit adapter (engine.h, fb_engine_runner): any engine's binding of the
 * engine kit (src/engines/kit/kit.h) as an engine of the four-bar and
 * slider-crank run path (model_run.c). create writes the case's mechanism
 * as a planar description at the model's lengths (fb_planar_of_case:
 * nominal or the stack-up corner) and opens the kit's run of it through
 * the binding (fb_kit_open); step advances the kit one sample ahead of
 * the one it gives (fb_kit_advance: a model the harness stops early pays
 * only for the steps it took; the kit keeps a window of the last samples,
 * fb_kit_series.window) and gives them one at a time as
 * fb_samples: the crank angle, every output body's angle, omega and
 * alpha (a translating body's centre x, v, a), each clearance joint's
 * force, penetration, eccentricity and contact state. The kit's series
 * already gives each step's acceleration and contact force to the sample
 * the step started from (kit.h), so the table asks no lag correction; its
 * spikes are refined as the hand-built engines' are, but a binding's whose
 * samples are the engine's own at each sample's state (body_accel).
 *
 * What the kit builds, and so what this adapter refuses (FB_ERR_ARG, the
 * model, the key and what to change): every clearance joint of the case
 * (revolute ones, not the driven one), each with its own law, columns and
 * provenance, Coulomb friction where the binding applies it (kit.h); the
 * exact collider, the faceted and libccd colliders where the binding
 * builds them (kit.h's collide: ODE's), with the scene's rings, or the
 * engine's native contact through its native binding (engine.h
 * kit_native: MuJoCo's own constraint solver on the clearance, Siconos's
 * relation); a fixed or automatic step, or [solver] h_s = adaptive where
 * the binding takes a step of any size (kit.h step_by; its schedule in
 * persistent contact the mechanism's closed-form loads, load_scale.h;
 * step_stats the kit's steps). Its start is the model's
 * (start.h: [run] start and pin_start, an ensemble member's moved pin),
 * handed to the kit as the description's coordinates. Its joint reactions
 * and drive torque are the binding's where it reports them (the load
 * columns; kit.h's reactions), else none; of each contact's provenance the
 * effective mass range, the largest h omega_c, ERP and smallest CFM of
 * the law's rows (ERP and CFM those of a binding that takes rows, else
 * NaN) and the contact steps; its
 * drift is the kit's: the largest separation of an ideal revolute joint's
 * two points at each step's end (kit.h fb_kit_series.drift) [m]. */
#include <math.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "engine.h"
#include "kit.h"
#include "planar_case.h"
#include "planar_constraints.h"
#include "step_control.h"

typedef struct {
  const fb_model_scene *sm;
  fb_planar *m;        /* the description the kit ran */
  fb_kit_series s;     /* t, q, centre (L each) */
  size_t L, M;         /* a column's length (s.window, or n: every sample kept) and the mask
                          that takes sample i to its index in it, i & M (kit.h) */
  double *col[FB_MECH_MAX_JOINTS]; /* clearance joint j's force, penetration, ecc x, ecc y,
                          state (FB_CONTACT_COLS x L; series.h FB_C_*), NULL: an ideal joint */
  double *cols;        /* the block the clearance joints' col[] point into (owned) */
  double *force_max;   /* (FB_MECH_MAX_JOINTS x n): a sub-stepping binding's largest force of
                          each step per clearance joint, NULL: none */
  double *loads;       /* ((1 + 3 njoints) x L): the drive torque and every joint's reaction
                          (fb_kit_series' torque and reaction), NULL: the binding reports none */
  unsigned mask;       /* the clearance joints (bit j: joint j) */
  size_t reached;      /* samples the kit filled */
  size_t i;            /* the sample replayed now */
  int impacts[FB_MECH_MAX_JOINTS]; /* impact episodes up to sample i, per joint */
  fb_stop stop;        /* why the kit stopped early (kind FB_STOP_NONE: it did not) */
  fb_kit_clearance cl; /* the clearance joints' laws, columns and counts (mask 0: none) */
  fb_kit_runner *kit;  /* the kit's run while it has samples to fill, else NULL */
  fb_load_scale load;  /* [solver] h_s = adaptive: the clearance joints' ideal load time scale
                          (load_scale.h, the mechanism's closed form), else empty */
  const char *engine;  /* the binding's engine */
  int out[FB_MECH_MAX_OUTPUTS], nout; /* the output bodies (fb_mech_outputs), once */
  int translates[FB_MECH_MAX_OUTPUTS]; /* 1: output k's motion is its centre's x */
} kit_run;

/* the binding of model sm's engine that builds its collider (the engine's
 * native contact: its kit_native), which the runner picked */
static const fb_kit_binding *binding_of(const fb_model_scene *sm) {
  const fb_engine *e = fb_engine_get(sm->model->engine, NULL);
  return e ? fb_engine_kit_of(e, sm->collider) : NULL;
}

/* what the kit cannot build of model sm, as an error naming the key */
static fb_status refuse(const fb_model_scene *sm, fb_diag *diag) {
  const char *name = sm->model->name;
  if (!sm->clearance_mask) return FB_OK;
  /* the engine's native contact is its native binding's (engine.h
   * kit_native: MuJoCo's own constraint solver, Siconos's relation); a
   * faceted or libccd collider is the binding's own (kit.h's collide): the
   * kit refuses it for a binding without one */
  if (sm->collider == FB_COLLIDER_NATIVE && binding_of(sm)) return FB_OK;
  if (sm->collider == FB_COLLIDER_FACETED || sm->collider == FB_COLLIDER_CCD) return FB_OK;
  if (sm->collider != FB_COLLIDER_EXACT)
    return fb_diag_set(diag, FB_ERR_ARG, "model '%s' through the engine kit: the exact collider "
                       "only ([clearance] collider = exact), or the engine's native contact "
                       "where its binding builds it", name);
  return FB_OK;
}

/* the joint that places moving body p of m: its revolute joint with the
 * ground (a fixed pivot) when it has one, else its first revolute joint
 * with a moving body placed before it (a lower index); -1: none */
static int placing_joint(const fb_planar *m, int p) {
  int first = -1;
  for (int j = 0; j < m->njoints; j++) {
    const fb_planar_joint *pj = &m->joint[j];
    const int side = pj->body[1] == p, other = pj->body[!side];
    if (pj->body[side] != p || pj->kind != FB_KIND_REVOLUTE) continue;
    if (other == FB_PLANAR_GROUND) return j;
    if (first < 0 && other < p) first = j;
  }
  return first;
}

/* the model's start (start.h) as the coordinates q and rates qd of d's
 * description m (its moving body p is d's body p - 1): each body placed
 * by its placing_joint's centre W on the body's side (the start's pin on
 * the joint's first moving body, else its hole), with the body's angle
 * and rate from the start (the driven body's the crank's, output body
 * k's its body[k]; a translating body keeps its frame angle, at rest) and
 * W's velocity: 0 at a ground pivot; a translating body's along +x
 * (body[k]); else the start's one moving joint point's, the crank-coupler
 * hole's. centre = W - R(theta) p, its velocity v_W + omega x (centre -
 * W), p the joint's point in the body's frame. FB_ERR_ARG: more moving
 * bodies than q holds (3 (FB_MECH_MAX_BODIES - 1)), a body no joint
 * places or the start gives no angle (neither driven nor an output) */
static fb_status start_coordinates(double *q, double *qd, const fb_planar *m,
                                   const fb_mech_desc *d, const fb_start_state *st, fb_diag *diag) {
  int outs[FB_MECH_MAX_OUTPUTS];
  const int nout = fb_mech_outputs(d, outs);
  if (m->nbodies > FB_MECH_MAX_BODIES)
    return fb_diag_set(diag, FB_ERR_ARG, "the kit's start: %d moving bodies, room for %d",
                       m->nbodies - 1, FB_MECH_MAX_BODIES - 1);
  for (int b = 0; b + 1 < m->nbodies; b++) {
    const int j = placing_joint(m, b + 1);
    int k = -1; /* its output index, -1: the driven body */
    for (int i = 0; i < nout; i++)
      if (outs[i] == b) k = i;
    if (j < 0 || (k < 0 && b != d->input))
      return fb_diag_set(diag, FB_ERR_ARG, "the kit's start: %s body '%s'",
                         j < 0 ? "no revolute joint places" : "no start angle for",
                         m->body[b + 1].name);
    const fb_planar_joint *pj = &m->joint[j];
    const int side = pj->body[1] == b + 1;
    /* the start's pin is on the joint's first moving body (start.h) */
    const int pin = pj->body[0] == FB_PLANAR_GROUND ? side : !side;
    const double *w = pin ? st->pin[j] : st->hole[j];
    const int translates = k >= 0 && d->body[b].motion == FB_MOTION_TRANSLATING;
    const double angle = k < 0        ? st->crank_angle
                         : translates ? m->body[b + 1].angle0
                                      : st->body[k][FB_Q_POS];
    const double omega = k < 0 ? st->crank_omega : translates ? 0.0 : st->body[k][FB_Q_VEL];
    double v[2] = {translates ? st->body[k][FB_Q_VEL] : 0.0, 0.0}, r[2];
    if (pj->body[!side] != FB_PLANAR_GROUND && !translates)
      v[0] = st->coupler_b_vel[0], v[1] = st->coupler_b_vel[1];
    fb_planar_rotate(r, angle, pj->point[side]);
    q[3 * b] = w[0] - r[0];
    q[3 * b + 1] = w[1] - r[1];
    q[3 * b + 2] = angle;
    qd[3 * b] = v[0] + omega * r[1];
    qd[3 * b + 1] = v[1] - omega * r[0];
    qd[3 * b + 2] = omega;
  }
  return FB_OK;
}

static void kit_run_free(kit_run *r) {
  if (!r) return;
  fb_kit_close(r->kit);
  fb_load_scale_free(&r->load);
  fb_planar_free(r->m);
  free(r->s.t);
  free(r->cols);
  free(r->force_max);
  free(r->loads);
  free(r);
}

/* 1: joint j is one of the run's clearance joints */
static int loose(const kit_run *r, int j) { return (r->mask >> j) & 1u; }

/* the kit's stop (FB_ERR_NUMERIC: an engine error, or the aliasing stop
 * at omega_d h = wdh > 0 of the row at h) at the samples it reached */
static void kit_stopped_at(kit_run *r, double wdh, double h, const fb_diag *diag) {
  r->reached = fb_kit_written(r->kit);
  r->stop.kind = wdh > 0.0 ? FB_STOP_ALIASED : FB_STOP_SOLVER;
  r->stop.engine = r->engine;
  r->stop.joint = wdh > 0.0 ? r->cl.aliased_joint : -1;
  r->stop.value = wdh;
  r->stop.limit = wdh > 0.0 ? FB_MATCHED_ALIAS_BOUND : 0.0;
  r->stop.h_max = wdh > 0.0 ? h * FB_MATCHED_ALIAS_BOUND / wdh : 0.0;
  r->stop.t = r->reached ? r->s.t[(r->reached - 1) & r->M] : 0.0;
  r->stop.step = r->reached;
  snprintf(r->stop.detail, sizeof r->stop.detail, "%.150s", diag->msg);
  if (!r->reached) return;
  /* the last sample's step never came: its force, state and loads the one
   * before */
  const size_t i = (r->reached - 1) & r->M, before = (r->reached - 2) & r->M;
  const int first = r->reached == 1;
  for (int c = 0; r->loads && !first && c < 1 + 3 * r->m->njoints; c++)
    r->loads[(size_t)c * r->L + i] = r->loads[(size_t)c * r->L + before];
  for (int j = 0; j < FB_MECH_MAX_JOINTS; j++) {
    if (!loose(r, j)) continue;
    double *f = r->col[j] + (size_t)FB_C_FORCE * r->L;
    double *z = r->col[j] + (size_t)FB_C_STATE * r->L;
    f[i] = first ? 0.0 : f[before];
    z[i] = first ? FB_STATE_FREE : z[before];
  }
}

/* the storage of a run of n samples of nb moving bodies, a window of the
 * last `window` samples (0: every sample, kit.h fb_kit_series.window): the
 * series (the bodies' centres only where an output translates: body_value
 * reads them there alone), each clearance joint's columns and (sub_steps:
 * a binding that sub-steps) its largest force of each step, kept whole.
 * What the adapter reads once lives in the window: columns that grew by
 * megabytes over a run cost the engine's own step its cache (ODE's
 * clearance model, 36,181 steps, callgrind: L1 misses 45.5 M with every
 * sample kept against 43.8 M with the window, last-level 0.232 M against
 * 0.101 M). A binding that sub-steps keeps every sample (window 0): the
 * spikes' refinement reads its largest forces after the run, and they
 * share the record's indexing. */
static fb_status alloc_run(kit_run *r, size_t n, size_t window, int nb, int sub_steps,
                           fb_diag *diag) {
  int nj = 0, centre = 0;
  for (int j = 0; j < FB_MECH_MAX_JOINTS; j++) nj += loose(r, j);
  for (int k = 0; k < r->nout; k++) centre |= r->translates[k];
  const size_t L = window ? window : n;
  r->s.n = n;
  r->s.window = window;
  r->L = L;
  r->M = window ? window - 1 : SIZE_MAX;
  r->s.t = malloc((2 + (size_t)nb * (centre ? 9 : 3)) * L * sizeof *r->s.t);
  double *col = nj ? calloc((size_t)nj * FB_CONTACT_COLS * L, sizeof *col) : NULL;
  if (nj && sub_steps) r->force_max = calloc((size_t)FB_MECH_MAX_JOINTS * n, sizeof *r->force_max);
  if (!r->s.t || (nj && !col) || (nj && sub_steps && !r->force_max)) {
    free(col);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for %zu kit samples", n);
  }
  r->cols = col;
  for (int j = 0, k = 0; j < FB_MECH_MAX_JOINTS; j++)
    if (loose(r, j)) r->col[j] = col + (size_t)(k++) * FB_CONTACT_COLS * L;
  r->s.q = r->s.t + L;
  r->s.centre = centre ? r->s.q + (size_t)nb * 3 * L : NULL;
  r->s.drift = r->s.q + (size_t)nb * (centre ? 9 : 3) * L;
  return FB_OK;
}

/* the kit's record of clearance joint j: its law and columns */
static fb_kit_joint_record joint_record(const kit_run *r, int j) {
  const size_t L = r->L;
  double *c = r->col[j];
  return (fb_kit_joint_record){.law = r->sm->law[j], .force = c + FB_C_FORCE * L,
                               .pen = c + FB_C_PEN * L, .ecc = c + FB_C_EX * L,
                               .state = c + FB_C_STATE * L,
                               .force_max = r->force_max ? r->force_max + (size_t)j * r->s.n
                                                         : NULL};
}

/* the kit's samples filled through i + 1 (sample i's alpha and contact
 * force are the step from it: final once sample i + 1 is there), the
 * kit's run closed at its end; a kit stop (FB_ERR_NUMERIC: an engine
 * error, or the aliasing stop) is a result: r->stop, the samples reached
 * replayed; any other error is returned with diag */
static fb_status reach(kit_run *r, size_t i, fb_diag *diag) {
  if (!r->kit) return FB_OK;
  const size_t n = i + 2 < r->s.n ? i + 2 : r->s.n;
  const fb_status st = fb_kit_advance(r->kit, n, diag);
  if (st == FB_OK) r->reached = n;
  if (st == FB_ERR_NUMERIC) { /* replay what was reached */
    r->reached = 0;
    kit_stopped_at(r, r->cl.aliased_omega_d_h, r->s.h, diag);
  }
  if (st != FB_OK || n == r->s.n) {
    fb_kit_close(r->kit);
    r->kit = NULL;
  }
  return st;
}

static fb_status adapter_create(void **self, const fb_model_scene *sm, fb_diag *diag) {
  fb_status st = fb_scene_check(sm->def, diag);
  if (st != FB_OK) return st;
  const fb_kit_binding *b = binding_of(sm);
  if (!b)
    return fb_diag_set(diag, FB_ERR_ARG, "model '%s': engine '%s' has no engine-kit binding",
                       sm->model->name, fb_engine_name(sm->model->engine));
  kit_run *r = calloc(1, sizeof *r);
  if (!r) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the kit adapter");
  r->sm = sm;
  r->engine = b->engine;
  const fb_mech_desc *desc = fb_case_mech(&sm->def->source);
  r->nout = fb_mech_outputs(desc, r->out);
  for (int k = 0; k < r->nout; k++) r->translates[k] = fb_mech_output_translates(desc, k);
  r->mask = (unsigned)sm->clearance_mask & ((1u << FB_MECH_MAX_JOINTS) - 1u);
  st = refuse(sm, diag);
  if (st == FB_OK) st = fb_planar_of_case(&r->m, &sm->def->source, &sm->lengths, diag);
  /* a binding that sub-steps keeps every sample and its largest force of
   * each step, for the spikes' refinement (adapter_refine, alloc_run) */
  const fb_kit_world o = {.gravity = sm->gravity, .h = sm->solver.h, .solver = &sm->solver,
                          .c = &sm->def->source};
  const size_t n = sm->def->steps + 1;
  size_t window = b->contact_force_max ? 0 : fb_kit_window(&o);
  if (window >= n) window = 0;
  if (st == FB_OK)
    st = alloc_run(r, n, window, r->m->nbodies - 1, b->contact_force_max != NULL, diag);
  if (st == FB_OK && b->reactions) { /* the load columns (adapter_reactions) */
    r->loads = calloc((1 + 3 * (size_t)r->m->njoints) * r->L, sizeof *r->loads);
    if (!r->loads) st = fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for %zu kit samples", n);
    r->s.torque = r->loads;
    r->s.reaction = r->loads ? r->loads + r->L : NULL;
  }
  if (st == FB_OK && r->mask) {
    r->cl = (fb_kit_clearance){.mask = r->mask, .mapping = sm->mapping,
                               .radial_clearance = sm->radial_clearance,
                               .pin_radius = sm->pin_radius,
                               .impact_velocity_min = sm->impact_velocity_min,
                               .aliased_joint = -1, .friction = sm->friction,
                               .mass_tensors = fb_planar_instance_mass,
                               .collider = {sm->collider, sm->faceted_n, sm->ccd_segments,
                                            sm->bore_ovality, sm->ccd_split, sm->pin_length}};
    for (int j = 0; j < FB_MECH_MAX_JOINTS; j++)
      if (loose(r, j)) r->cl.joint[j] = joint_record(r, j);
    /* the adaptive step's schedule in persistent contact (step_control.h):
     * the mechanism's closed-form loads, as the crank's angle indexes them */
    if (sm->solver.h_mode == FB_STEP_ADAPTIVE && b->persistent_rule == FB_PERSIST_LOAD_SCHEDULE) {
      st = fb_load_scale_build_mech(&r->load, sm->def->source.mechanism, &sm->lengths,
                                    sm->branch, sm->link, sm->gravity, sm->omega2,
                                    (int)r->mask, FB_STEP_LOAD_LOOKAHEAD * sm->solver.h_max, diag);
      r->cl.load = &r->load;
    }
  }
  fb_start_state start;
  if (st == FB_OK) st = fb_model_scene_start(&start, sm, diag);
  double q0[3 * (FB_MECH_MAX_BODIES - 1)], qd0[3 * (FB_MECH_MAX_BODIES - 1)]; /* moving bodies */
  if (st == FB_OK)
    st = start_coordinates(q0, qd0, r->m, fb_case_mech(&sm->def->source), &start, diag);
  if (st == FB_OK) {
    const fb_kit_world w = {.gravity = sm->gravity, .h = sm->solver.h, .solver = &sm->solver,
                            .nbodies = r->m->nbodies - 1, .njoints = r->m->njoints,
                            .c = &sm->def->source, .q0 = q0, .qd0 = qd0};
    r->s.h = sm->solver.h;
    st = fb_kit_open(&r->kit, b, r->m, sm->omega2, &w, r->mask ? &r->cl : NULL, &r->s, diag);
    if (st == FB_OK) st = reach(r, 0, diag);
    if (st == FB_ERR_NUMERIC) st = r->reached ? FB_OK : FB_ERR_NUMERIC;
  }
  if (st != FB_OK) {
    kit_run_free(r);
    return st;
  }
  *self = r;
  return FB_OK;
}

static fb_status adapter_step(void *self, fb_diag *diag) {
  kit_run *r = self;
  fb_status st = reach(r, r->i + 1, diag);
  if (st != FB_OK && st != FB_ERR_NUMERIC) return st;
  if (r->i + 1 >= r->reached)
    return fb_diag_set(diag, FB_ERR_NUMERIC, "%s", r->stop.kind != FB_STOP_NONE
                                                       ? r->stop.detail
                                                       : "no sample beyond the run's duration");
  r->i++;
  for (int j = 0; j < FB_MECH_MAX_JOINTS; j++) {
    if (!loose(r, j)) continue;
    const double *state = r->col[j] + (size_t)FB_C_STATE * r->L;
    if (state[r->i & r->M] == FB_STATE_IMPACT && state[(r->i - 1) & r->M] != FB_STATE_IMPACT)
      r->impacts[j]++;
  }
  return FB_OK;
}

static void adapter_stopped(const void *self, fb_stop *out) { *out = ((const kit_run *)self)->stop; }

/* the value of body handle b's quantity k at sample i: its angle's, or its
 * centre's x for a translating body */
static double body_value(const kit_run *r, int b, int k, int translates) {
  const double *q = translates ? r->s.centre : r->s.q;
  return q[((size_t)b * 3 + (size_t)k) * r->L + (r->i & r->M)];
}

static void adapter_sample(const void *self, fb_sample *x) {
  const kit_run *r = self;
  const fb_mech_desc *d = fb_case_mech(&r->sm->def->source);
  memset(x, 0, sizeof *x);
  x->t = r->s.t[r->i & r->M];
  x->crank_angle = body_value(r, d->input, FB_Q_POS, 0);
  for (int k = 0; k < r->nout; k++)
    for (int q = 0; q < 3; q++) x->body[k][q] = body_value(r, r->out[k], q, r->translates[k]);
  for (int j = 0; j < FB_MECH_MAX_JOINTS; j++)
    for (int c = 0; loose(r, j) && c < FB_CONTACT_COLS; c++)
      x->contact[j][c] = r->col[j][(size_t)c * r->L + (r->i & r->M)];
}

/* the deepest clearance joint now (the first of equals) and every joint's
 * impacts so far */
static void adapter_contact(const void *self, fb_engine_contact *out) {
  const kit_run *r = self;
  memset(out, 0, sizeof *out);
  out->joint = -1;
  for (int j = 0; j < FB_MECH_MAX_JOINTS; j++) {
    if (!loose(r, j)) continue;
    const double pen = r->col[j][(size_t)FB_C_PEN * r->L + (r->i & r->M)];
    if (out->joint < 0 || pen > out->penetration) out->penetration = pen, out->joint = j;
    out->impacts[j] = r->impacts[j];
  }
}

/* the largest separation of an ideal revolute joint's two points now [m]
 * (the kit's, kit.h fb_kit_series.drift) */
static double adapter_drift(const void *self) {
  const kit_run *r = self;
  return r->s.drift[r->i & r->M];
}

/* the kit's figures of a clearance joint over the whole run (ERP and
 * CFM those of the rows a binding that takes rows was handed, kit.h's
 * contact_rows; none otherwise, or before a contact) */
static void adapter_provenance(const void *self, int joint, fb_contact_provenance *out) {
  const kit_run *r = self;
  *out = (fb_contact_provenance){NAN, NAN, NAN, NAN, NAN, 0};
  if (joint < 0 || joint >= FB_MECH_MAX_JOINTS || !loose(r, joint)) return;
  const fb_kit_joint_record *k = &r->cl.joint[joint];
  const int rows = k->contact_steps > 0 && binding_of(r->sm)->contact_rows;
  *out = (fb_contact_provenance){k->m_eff_min, k->m_eff_max, rows ? k->erp_max : NAN,
                                 rows ? k->cfm_min : NAN, k->h_omega_max, k->contact_steps};
}

/* the series' spikes refined as the hand-built engines' are, but the
 * contact force of a binding that sub-steps from its own largest force
 * between samples (series.h, fb_series_refine_peaks_max); a binding whose
 * samples are the engine's own at each sample's state (kit.h's
 * body_accel: instantaneous accelerations, and the law's force there) lies
 * on no step's difference: its spikes are its samples', as the hand-built
 * MuJoCo world's */
static void adapter_refine(const void *self, fb_series *s, double fraction, double t_split) {
  const kit_run *r = self;
  if (binding_of(r->sm)->body_accel) return;
  fb_series_refine_peaks_max(s, fraction, t_split, r->force_max, r->s.n);
}

/* the joint reactions and drive torque of sample i's step in the
 * four-bar's or slider-crank's convention: the force on each joint's
 * second-named body from its first, but where the description says the
 * other way (fb_mech_joint.load_on_first: invdyn.h's D); the drive's torque
 * on the crank about +z */
static void adapter_reactions(const void *self, double force[4][2], double *drive_torque) {
  const kit_run *r = self;
  const fb_mech_desc *d = fb_case_mech(&r->sm->def->source);
  const size_t L = r->L, i = r->i & r->M;
  for (int j = 0; j < FB_MECH_MAX_JOINTS; j++)
    for (int k = 0; k < 2; k++)
      force[j][k] = j < d->njoints ? (d->joint[j].load_on_first ? -1.0 : 1.0) *
                                         r->s.reaction[(size_t)(3 * j + k) * L + i]
                                   : 0.0;
  *drive_torque = r->s.torque[i];
}

/* the engine steps the kit took (an adaptive run's sizes) */
static void adapter_step_stats(const void *self, fb_step_stats *out) {
  *out = ((const kit_run *)self)->s.stats;
}

/* the steps replayed (a model the harness stopped: those before its stop) */
static size_t adapter_steps(const void *self) { return ((const kit_run *)self)->i; }

static void adapter_destroy(void *self) { kit_run_free(self); }

/* the adapter's ops, the same over every binding */
#define KIT_ADAPTER_OPS                                                                           \
  .name = "kit", .guarded = 1, .step_values_lag = 0, .refine_peaks = 1, .create = adapter_create, \
  .step = adapter_step, .stopped = adapter_stopped, .sample = adapter_sample,                     \
  .contact = adapter_contact, .provenance = adapter_provenance, .drift = adapter_drift,           \
  .steps = adapter_steps, .destroy = adapter_destroy, .refine = adapter_refine,             \
  .step_stats = adapter_step_stats

const fb_engine fb_engine_kit_adapter = {KIT_ADAPTER_OPS};

/* the adapter over a binding that reports joint reactions: the same, with
 * the load columns */
static const fb_engine kit_adapter_loads = {KIT_ADAPTER_OPS, .reactions = adapter_reactions};

int fb_engine_is_kit_adapter(const fb_engine *e) {
  return e == &fb_engine_kit_adapter || e == &kit_adapter_loads;
}

const fb_engine *fb_engine_runner(const fb_engine *e, const fb_model *m, const fb_case *c,
                                  fb_diag *diag) {
  /* auto: the kit where the engine's table names the model's kind, or
   * where the engine's own world takes one pin and the case looses
   * others, and the kit builds the case (it drives an ideal joint only: a
   * clearance at the driven joint keeps the engine's own world, which
   * drives the crank by an angular motor) */
  const int driven = fb_mech_driven_joint(fb_case_mech(c));
  const int drive_free = driven < 0 || !((c->clearance.mask >> driven) & 1);
  const int kind = m->joints == FB_JOINTS_CLEARANCE ? FB_KIT_DEFAULT_CLEARANCE
                                                     : FB_KIT_DEFAULT_IDEAL;
  /* the engine's own world takes one pin, the case has others */
  const int pins = e->own_one_pin && m->joints == FB_JOINTS_CLEARANCE &&
                   (c->clearance.mask & ~(1 << fb_case_mech(c)->reference_joint));
  const int kit = c->solver.builder == FB_BUILDER_KIT ||
                  (c->solver.builder == FB_BUILDER_AUTO &&
                   drive_free && ((e->kit_default & kind) || pins));
  if (e->kit && (!e->create || kit))
    return e->kit->reactions ? &kit_adapter_loads : &fb_engine_kit_adapter;
  if (e->create) return e;
  fb_diag_set(diag, FB_ERR_ARG, "engine '%s' has neither models of its own nor an engine-kit "
              "binding", e->name);
  return NULL;
}
