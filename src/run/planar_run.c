/* A planar case's models on the planar core (planar_run.h). */
#include "planar_run.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "casefile.h"
#include "clock.h"
#include "kit.h"
#include "model_table.h"
#include "planar_case.h"
#include "planar_dims.h"
#include "planar_invdyn.h"
#include "planar_loads.h"
#include "planar_outputs.h"
#include "planar_path.h"
#include "resolution.h"
#include "run.h"
#include "series.h"
#include "start.h"
#include "step_control.h"
#include "units.h"
#include "variants.h"

/* 1: model name is the analytic model at some lengths (analytic,
 * analytic-stackup), no dynamics of its own */
static int analytic_model(const char *name) {
  const fb_model *m = fb_model_find(name);
  return m && m->engine == FB_ENGINE_ANALYTIC;
}

int fb_planar_run_takes(const char *name) {
  return analytic_model(name) || strcmp(name, "reference") == 0 ||
         strcmp(name, "reference-restitution") == 0 || fb_planar_kit_of(name) != NULL;
}

const char *fb_planar_run_refusal(const char *name) {
  if (fb_planar_run_takes(name)) return NULL;
  return fb_planar_kit_refusal(name);
}

/* why engine model name of planar case c cannot follow [solver] h_s =
 * adaptive through the engine kit (kit.h step_by, kit_adaptive.h), NULL
 * when it can or is no engine model (the analytic model and the
 * references sample the grid h_min_s sets) */
static const char *adaptive_refusal(const fb_case *c, const char *name) {
  const fb_kit_binding *b = fb_planar_kit_of(name);
  const fb_model *m = fb_model_find(name);
  if (!b || !m) return NULL;
  const char *model = fb_model_adaptive_refusal(m, fb_case_collider_of(c));
  if (model) return model;
  if (!b->step_by)
    return "its engine's binding steps at a fixed h (it would run at h_min_s, silently)";
  if (m->joints != FB_JOINTS_CLEARANCE) return NULL;
  for (int j = 0; j < c->planar.njoints; j++)
    if ((c->clearance.mask & (1 << j)) && c->planar.joint[j].kind != FB_KIND_REVOLUTE)
      return "the adaptive step follows a pin in its hole, and the case's clearance joint is a "
             "slider in its guide";
  if (b->persistent_rule == FB_PERSIST_LOAD_SCHEDULE && c->planar.undriven)
    return "its engine's step in persistent contact follows the ideal joint loads of a drive at "
           "constant speed, and the case has none";
  return NULL;
}

/* the keys a planar run does not act on, when given otherwise than their
 * planar meaning: why, into msg (size bytes), or "" */
static void keys_refused(char *msg, size_t size, const fb_case *c) {
  msg[0] = '\0';
  if (fb_casefile_given(c, "run", "ensemble") && c->ensemble > 1)
    snprintf(msg, size, "[run] ensemble = %d: a planar case's run has no ensemble yet (a "
             "clearance model's verdict rests on its one run, basis pointwise); leave [run] "
             "ensemble at 1", c->ensemble);
  else if (c->start != FB_START_STEADY)
    snprintf(msg, size, "[run] start = %s: a planar case starts every body on its ideal "
             "motion (steady); give start = steady", fb_start_name(c->start));
  else if (c->pin_start != FB_PIN_CENTRED)
    snprintf(msg, size, "[run] pin_start = %s: a planar case's clearance pins start "
             "centred in their holes; give pin_start = centred", fb_pin_start_name(c->pin_start));
  else if (fb_casefile_given(c, "clearance", "penetration_limit_um") &&
           !c->clearance.penetration_unlimited)
    snprintf(msg, size, "[clearance] penetration_limit_um = %g: a planar case's run stops "
             "no model at a penetration depth (its engines stop on a step they cannot take, its "
             "references never); remove the key, or give none",
             c->clearance.penetration_limit / FB_M_PER_UM);
  else if (c->published_source[0] || fb_variants_published_any(&c->published[0]) ||
           fb_variants_published_any(&c->published[1]))
    snprintf(msg, size, "[published.*]: published values are compared with a four-bar's "
             "or slider-crank's output bodies, and a planar case's run prints none; remove the "
             "[published.*] sections");
  else if (c->solver.builder == FB_BUILDER_HAND)
    snprintf(msg, size, "[solver] builder = hand: a planar case's engine models are built "
             "through their engine-kit bindings (no engine has a hand-built world of a planar "
             "mechanism); give builder = auto or kit");
}

fb_status fb_planar_run_check(const fb_case *c, fb_diag *diag) {
  char refused[FB_DIAG_SIZE];
  keys_refused(refused, sizeof refused, c);
  if (refused[0]) return fb_diag_set(diag, FB_ERR_ARG, "%s", refused);
  for (int i = 0; i < c->model_count; i++) {
    const char *name = c->models[i];
    const char *adaptive = c->solver.h_mode == FB_STEP_ADAPTIVE ? adaptive_refusal(c, name)
                                                                 : NULL;
    if (adaptive)
      return fb_diag_set(diag, FB_ERR_ARG, "[solver] h_s = adaptive with [run] models %s: %s; "
                         "give [solver] h_s = auto (chosen from the case's clearance contacts) "
                         "or a step in s", name, adaptive);
    if (c->planar.undriven && strcmp(name, "analytic") == 0) /* the kit's start is free */
      return fb_diag_set(diag, FB_ERR_ARG, "[run] models: '%s' follows a drive at constant "
                         "speed, and the case is %s; it runs: reference, "
                         "reference-restitution and the engines' models", name,
                         c->planar.torque_joint >= 0 ? "driven by a torque ([drive] torque_n_m: "
                                                       "its speed follows from the dynamics)"
                                                     : "undriven ([drive] joint = none)");
    const char *ideal = strncmp(name, "reference", 9) == 0 ? fb_planar_ref_ideal_refusal(c, name)
                                                           : NULL;
    if (ideal) return fb_diag_set(diag, FB_ERR_ARG, "[run] models: '%s': %s", name, ideal);
    if (fb_model_ideal_stackup(name) && c->planar.undriven)
      return fb_diag_set(diag, FB_ERR_ARG, "[run] models: '%s' runs at the stack-up corner, "
                         "whose loop closes at the drive's start, and the case has no drive "
                         "at constant speed", name);
    if (fb_model_ideal_stackup(name) && !c->tolerance_class)
      return fb_diag_set(diag, FB_ERR_ARG, "[run] models: '%s' runs at the stack-up corner "
                         "[tolerance] stackup, and a planar case's dimensions need [tolerance] "
                         "class (f, m, c or v: ISO 2768-1; fourbar stackup lists them)", name);
    const fb_model *row = fb_model_find(name);
    const int loose = fb_case_clearance_count(c);
    if (row && fb_model_has_clearance(row) && loose > FB_PLANAR_REF_MAX_JOINTS)
      return fb_diag_set(diag, FB_ERR_ARG, "[run] models: '%s' takes %d clearance joints at most, "
                         "and [clearance] joints names %d", name, FB_PLANAR_REF_MAX_JOINTS, loose);
    const char *why = fb_planar_run_refusal(name);
    char loaded[2 * FB_PLANAR_NAME_SIZE];
    if (!why && fb_planar_spec_loaded(&c->planar, loaded, sizeof loaded) &&
        fb_planar_kit_of(name) && !fb_planar_kit_applies_loads(name)) {
      char kit[2048];
      return fb_diag_set(diag, FB_ERR_ARG, "[run] models: '%s': %s: its engine's binding does "
                         "not apply springs and loads yet; the models that do: analytic, "
                         "reference, reference-restitution, %s", name, loaded,
                         fb_planar_kit_loaded_models(kit, sizeof kit));
    }
    if (!why) continue;
    char kit[2048];
    fb_planar_kit_models(kit, sizeof kit);
    return fb_diag_set(diag, FB_ERR_ARG, "[run] models: '%s' does not run on a planar case: "
                       "%s; a planar case runs: analytic, reference, reference-restitution, %s",
                       name, why, kit);
  }
  return FB_OK;
}

/* the output grid's step [s]: [solver] h_s as given (1e-5 s by default),
 * an adaptive run's h_min_s; auto: the step the case file chose from its
 * clearance contacts (casefile_planar.c, planar_resolution.h), one
 * revolution / 6000 on a case without them */
double fb_planar_run_step(const fb_case *c) {
  if (c->solver.h_mode == FB_STEP_ADAPTIVE) return c->solver.h_min;
  if (!(c->solver.h > 0.0) || (c->solver.h_mode == FB_STEP_AUTO && !c->clearance.mask))
    return 2.0 * M_PI / c->crank_speed / FB_H_AUTO_STEPS_PER_REV;
  return c->solver.h;
}

int fb_planar_run_step_auto(const fb_case *c) {
  return !c->planar.undriven && c->solver.h_mode == FB_STEP_AUTO;
}

double fb_planar_run_h_rate(const fb_planar_run *r, const fb_planar_contact_estimate *e) {
  return fb_planar_run_step(&r->c) * e->rates.rate;
}

/* every moving body's angle, omega and alpha at position q, and the
 * output points and slides there */
static void store(fb_planar_model *p, const fb_planar *m, size_t i, const double *q,
                  const double *qd, const double *qdd) {
  for (int b = 1; b < m->nbodies; b++) {
    const int a = 3 * (b - 1) + 2; /* the body's angle among q */
    const double v[3] = {q[a], qd[a], qdd[a]};
    for (int k = 0; k < 3; k++) p->q[((size_t)(b - 1) * 3 + (size_t)k) * p->n + i] = v[k];
  }
  fb_planar_model_store_outputs(p, m, i, q, qd, qdd);
}

/* sample i's drive torque and joint reactions at the motion q, qd, qdd that
 * fb_planar_motion(k) has just solved (planar_invdyn.h, with its LU), rx a
 * scratch row of the joints' reactions */
static fb_status store_loads(fb_planar_model *p, const fb_planar_run *r, fb_planar_kin *k,
                             size_t i, fb_planar_reaction *rx, const double *q,
                             const double *qd, const double *qdd, fb_diag *diag) {
  const fb_planar *m = p->m;
  fb_status st = fb_planar_invdyn_kin(rx, &p->torque[i], k, q, qd, qdd, r->c.gravity, diag);
  for (int j = 0; j < m->njoints && st == FB_OK; j++) {
    const double v[3] = {rx[j].force[0], rx[j].force[1], rx[j].moment};
    for (int c = 0; c < 3; c++) p->reaction[((size_t)j * 3 + (size_t)c) * p->n + i] = v[c];
  }
  return st;
}

/* the analytic model's samples: the drive at constant speed from the
 * assembly configuration, followed from one sample to the next, with the
 * loads of each */
static fb_status sample(fb_planar_model *p, fb_planar_kin *k, const fb_planar_run *r,
                        fb_diag *diag) {
  const fb_planar *m = p->m;
  const int nq = fb_planar_nq(m);
  const size_t nj = (size_t)m->njoints;
  double *q = malloc(3 * (size_t)nq * sizeof *q);
  fb_planar_reaction *rx = malloc(nj * sizeof *rx);
  p->torque = malloc((1 + 3 * nj) * p->n * sizeof *p->torque);
  if (!q || !rx || !p->torque) {
    free(q);
    free(rx);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for %zu samples' loads", p->n);
  }
  p->reaction = p->torque + p->n;
  double *qd = q + nq, *qdd = qd + nq;
  fb_planar_assembly(m, q);
  fb_status st = fb_planar_position(k, q, 0.0, NULL, diag);
  for (size_t i = 0; i < p->n && st == FB_OK; i++) {
    const double t = (double)i * p->h, angle = r->omega * t;
    fb_path_end end;
    if (i > 0) st = fb_planar_follow(k, q, p->drive[i - 1], angle, NULL, &end, diag);
    const fb_planar_drive d = {angle, r->omega, 0.0};
    if (st == FB_OK) st = fb_planar_motion(k, qd, qdd, q, &d, NULL, diag);
    p->t[i] = t;
    p->drive[i] = angle;
    if (st == FB_OK) store(p, m, i, q, qd, qdd);
    if (st == FB_OK) st = store_loads(p, r, k, i, rx, q, qd, qdd, diag);
  }
  free(q);
  free(rx);
  return st;
}

/* a model's columns: n samples every h over the run */
static fb_status model_alloc(fb_planar_model *p, const fb_planar_run *r, fb_diag *diag) {
  const double h = fb_planar_run_step(&r->c);
  const double steps = floor(r->duration / h + 1e-9);
  if (!(steps + 1.0 <= FB_PLANAR_RUN_MAX_SAMPLES))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "model '%s' would hold %.3g samples (%.6g s every %.3g s), more than %d: "
                       "raise [solver] h_s or lower [run] revolutions",
                       p->name, steps + 1.0, r->duration, h, FB_PLANAR_RUN_MAX_SAMPLES);
  p->h = h;
  p->n = (size_t)steps + 1;
  const size_t nb = (size_t)r->m->nbodies;
  p->peaks = calloc(nb, sizeof *p->peaks);
  p->t = malloc((2 + 3 * (nb - 1)) * p->n * sizeof *p->t);
  if (!p->peaks || !p->t) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for %zu samples", p->n);
  p->drive = p->t + p->n;
  p->q = p->drive + p->n;
  p->nout = fb_planar_output_count(r->m) + FB_PLANAR_SPRING_QUANTITIES * r->m->nsprings;
  if (p->nout > 0 && !(p->out = malloc((size_t)p->nout * p->n * sizeof *p->out)))
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for %zu samples' points", p->n);
  for (size_t i = 0; i < (size_t)p->nout * p->n; i++) p->out[i] = NAN;
  return FB_OK;
}

/* the analytic model: its peaks over a revolution and its samples */
static fb_status analytic(fb_planar_model *p, const fb_planar_run *r, fb_diag *diag) {
  const fb_planar *m = p->m;
  const size_t nb = (size_t)m->nbodies;
  fb_planar_kin *k;
  fb_status st = fb_planar_kin_new(&k, m, diag);
  if (st != FB_OK) return st;
  fb_planar_peaks *pk = calloc(nb, sizeof *pk);
  st = pk ? fb_planar_peaks_of(pk, k, r->omega, diag) : fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  for (size_t b = 0; pk && b < nb; b++) {
    p->peaks[b].omega_max = pk[b].omega_max;
    p->peaks[b].omega_min = pk[b].omega_min;
    p->peaks[b].alpha_max = pk[b].alpha_max;
    p->peaks[b].alpha_min = pk[b].alpha_min;
  }
  free(pk);
  if (st == FB_OK) st = sample(p, k, r, diag);
  fb_planar_kin_free(k);
  return st;
}

static void model_free(fb_planar_model *p) {
  free(p->peaks);
  free(p->t);
  free(p->force);
  free(p->force_max);
  free(p->torque);
  free(p->out);
  memset(p, 0, sizeof *p);
}

/* r->reaction_max, once, when a driven case runs a model other than the
 * analytic one (its clearance joint's law takes the joint's largest ideal
 * reaction; an ideal engine model does not, and costs the computation
 * only on a case that has no clearance model) */
static fb_status reactions(fb_planar_run *r, const fb_case *c, fb_diag *diag) {
  int needed = 0;
  for (int i = 0; i < c->model_count; i++) needed |= !analytic_model(c->models[i]);
  if (!needed || c->planar.undriven || !c->clearance.mask) return FB_OK;
  r->reaction_max = malloc((size_t)r->m->njoints * sizeof *r->reaction_max);
  if (!r->reaction_max) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  return fb_planar_reaction_max(r->reaction_max, r->m, r->omega, c->gravity, diag);
}

/* 1 when model name runs at the stack-up corner on case c: an ideal
 * stack-up model always (it needs [tolerance] class, fb_planar_run_check);
 * any other model whose row takes the stack-up lengths (the clearance
 * models, the references: model_table.h) when the case gives [tolerance]
 * class on a driven case, as the four-bar's run them at its stack-up
 * lengths (without tolerances they are its nominal ones, as here; an
 * undriven case has no stack-up corner: its stack-up models are refused) */
static int at_stackup(const char *name, const fb_case *c) {
  const fb_model *row = fb_model_find(name);
  return fb_model_ideal_stackup(name) || (c->tolerance_class && !c->planar.undriven && row &&
                                          row->lengths == FB_LENGTHS_STACKUP);
}

/* r->stackup, once, when a model runs at the stack-up corner
 * (at_stackup): the description at the case's corner (planar_dims.h),
 * the angles' legs from the nominal mechanism's slides at the run's speed */
static fb_status stackup(fb_planar_run *r, const fb_case *c, fb_diag *diag) {
  int needed = 0;
  for (int i = 0; i < c->model_count; i++) needed |= at_stackup(c->models[i], c);
  if (!needed) return FB_OK;
  return fb_planar_dims_corner(&r->stackup, r->m, c->tolerance_class, r->omega,
                               c->stackup.planar, diag);
}

static fb_status run_once(fb_planar_run *r, const fb_case *c, fb_diag *diag) {
  memset(r, 0, sizeof *r);
  fb_status st = fb_planar_run_check(c, diag);
  if (st != FB_OK) return st;
  r->c = *c;
  if ((st = fb_planar_of_case(&r->m, c, NULL, diag)) != FB_OK) return st;
  const int free = c->planar.undriven; /* no drive: no speed, no run-in revolution */
  r->omega = free ? 0.0 : fb_case_omega2(c);
  r->duration = fb_case_duration(c);
  /* the four-bar's window (run.c); an undriven case has no revolution */
  r->t_window = free ? 0.0 : fb_case_peak_window_from(c);
  st = reactions(r, c, diag);
  if (st == FB_OK && !free && c->clearance.mask) {
    r->est = malloc(2 * (size_t)r->m->njoints * sizeof *r->est);
    st = r->est ? fb_planar_contact_estimates(r->est, &r->nest, c, r->m, diag)
                : fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  }
  if (st == FB_OK) st = stackup(r, c, diag);
  if (st == FB_OK && r->stackup && r->reaction_max) { /* the same at the corner */
    r->stackup_reaction_max = malloc((size_t)r->m->njoints * sizeof *r->stackup_reaction_max);
    st = r->stackup_reaction_max
             ? fb_planar_reaction_max(r->stackup_reaction_max, r->stackup, r->omega, c->gravity, diag)
             : fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  }
  for (int i = 0; i < c->model_count && st == FB_OK; i++) {
    fb_planar_model *p = &r->model[r->n++];
    snprintf(p->name, sizeof p->name, "%s", c->models[i]);
    p->m = at_stackup(p->name, c) ? r->stackup : r->m;
    const double t0 = fb_clock_s();
    st = model_alloc(p, r, diag);
    if (st == FB_OK)
      st = analytic_model(p->name) ? analytic(p, r, diag)
           : fb_planar_kit_of(p->name) ? fb_planar_run_kit(p, r, diag)
                                       : fb_planar_run_reference(p, r, strcmp(p->name, "reference") == 0, diag);
    p->wall_s = fb_clock_s() - t0;
  }
  if (st == FB_OK) fb_planar_verdicts(r);
  else fb_planar_run_free(r);
  return st;
}

/* the largest h omega_c an engine's clearance model met at its contact
 * steps (0: none measured) */
static double h_omega_met(const fb_planar_run *r) {
  double hw = 0.0;
  for (int i = 0; i < r->n; i++)
    if (r->model[i].engine && r->model[i].force && isfinite(r->model[i].h_omega_max))
      hw = fmax(hw, r->model[i].h_omega_max);
  return hw;
}

fb_status fb_planar_run_case(fb_planar_run *r, const fb_case *c, fb_diag *diag) {
  fb_status st = run_once(r, c, diag);
  if (st != FB_OK || !fb_planar_run_step_auto(c) || !c->clearance.mask) return st;
  /* h_s = auto: the stiffest contact the run met decides, as the
   * four-bar's (run.c): a run past the bound is redone at the step that
   * keeps it, with the margin */
  const double estimate = fb_planar_run_step(c);
  for (int tries = 1; tries <= FB_H_AUTO_RETRIES; tries++) {
    const double hw = h_omega_met(r);
    if (!(hw > FB_H_OMEGA_C_BOUND)) break;
    fb_case again = r->c;
    again.solver.h = fb_planar_run_step(&r->c) * FB_H_OMEGA_C_BOUND / hw * FB_H_AUTO_MARGIN;
    fb_planar_run_free(r);
    if ((st = run_once(r, &again, diag)) != FB_OK) return st;
    r->h_rechosen = tries;
  }
  r->h_auto_estimate = estimate;
  return FB_OK;
}

void fb_planar_run_free(fb_planar_run *r) {
  for (int i = 0; i < r->n; i++) model_free(&r->model[i]);
  for (int v = 0; v < r->variant_count; v++)
    for (int i = 0; i < r->variant[v].n; i++) free(r->variant[v].model[i].peaks);
  free(r->variant);
  r->variant = NULL;
  r->variant_count = 0;
  fb_planar_free(r->m);
  fb_planar_free(r->stackup);
  r->stackup = NULL;
  free(r->reaction_max);
  r->reaction_max = NULL;
  free(r->stackup_reaction_max);
  r->stackup_reaction_max = NULL;
  free(r->est);
  r->est = NULL;
  r->nest = 0;
  r->m = NULL;
  r->n = 0;
}

double fb_planar_model_value(const fb_planar_run *r, const fb_planar_model *p, int b, int k,
                             size_t i) {
  (void)r;
  return p->q[((size_t)(b - 1) * 3 + (size_t)k) * p->n + i];
}

double fb_planar_model_reaction(const fb_planar_model *p, int j, int k, size_t i) {
  const double *f = p->reaction + (size_t)j * 3 * p->n;
  if (k == 2) return hypot(f[i], f[p->n + i]);
  return f[(size_t)(k == 3 ? 2 : k) * p->n + i];
}

/* how the run's step was chosen, in the four-bar's warning's terms */
static int step_kind(const fb_planar_run *r) {
  if (!fb_planar_run_step_auto(&r->c)) return FB_WARN_STEP_FIXED;
  for (int k = 0; k < r->nest; k++)
    if (r->est[k].h_resolving <= fb_planar_run_step(&r->c) * (1.0 + 1e-12))
      return FB_WARN_STEP_AUTO_CONTACT;
  return FB_WARN_STEP_AUTO_CAP;
}

int fb_planar_model_joint_resolution(const fb_planar_run *r, const fb_planar_model *p, int k,
                                     fb_warning *w) {
  const double hw = p->ref.at[k].h_omega_max;
  if (!isfinite(hw) || !(hw > 0.0)) return -1;
  if (hw <= FB_H_OMEGA_C_BOUND) return 1;
  if (w) {
    *w = (fb_warning){.kind = FB_WARN_UNDER_RESOLVED, .value = hw, .limit = FB_H_OMEGA_C_BOUND,
                      .ratio = M_PI / hw, .t = NAN, .h = p->h, .h_auto = step_kind(r)};
    snprintf(w->what, sizeof w->what, "%s", r->m->joint[p->ref.at[k].joint].name);
  }
  return 0;
}

int fb_planar_model_resolution(const fb_planar_run *r, const fb_planar_model *p, fb_warning *w) {
  int worst = -1;
  for (int k = 0; k < p->ref.njoints; k++)
    if (isfinite(p->ref.at[k].h_omega_max) &&
        (worst < 0 || p->ref.at[k].h_omega_max > p->ref.at[worst].h_omega_max))
      worst = k;
  return worst < 0 ? -1 : fb_planar_model_joint_resolution(r, p, worst, w);
}
