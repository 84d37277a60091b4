/* A planar case's engine models through the engine kit (planar_run.h):
 * which models an engine builds that way, their clearance joint's law, the
 * run and its window peaks. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "casefile.h"
#include "clock.h"
#include "engine.h"
#include "joint_law.h"
#include "kit.h"
#include "model_table.h"
#include "planar_case.h"
#include "planar_free.h"
#include "planar_invdyn.h"
#include "planar_kinematics.h"
#include "planar_mass.h"
#include "planar_run.h"
#include "planar_start.h"
#include "scene.h"
#include "series.h"
#include "step_control.h"

/* the binding that builds model name on a planar case, else NULL with
 * *why (may be NULL) the reason, in words a refusal can quote */
static const fb_kit_binding *kit_of(const char *name, const char **why) {
  const char *unused;
  if (!why) why = &unused;
  *why = "it is no model of the table";
  const fb_model *m = fb_model_find(name);
  if (!m) return NULL;
  *why = "its engine is not in this build";
  fb_diag d;
  const fb_engine *e = fb_engine_get(m->engine, &d);
  if (!e) return NULL;
  *why = "its engine has no engine-kit binding, the way an engine builds a planar description";
  const fb_kit_binding *b = e->kit;
  if (!b) return NULL;
  if (m->joints == FB_JOINTS_IDEAL) return b; /* nominal or at the stack-up corner */
  /* a clearance model (its lengths the stack-up corner's on a four-bar;
   * a planar case's are its joints', the nominal description the
   * reference runs too): the exact pin in the hole (or a generic collider
   * the binding builds), a law, and a binding that takes the contact */
  *why = "it has no contact law";
  if (m->law == FB_MODEL_LAW_NONE) return NULL;
  /* or the engine's native contact, built by its native binding from the
   * description's joint (engine.h kit_native: MuJoCo's own constraint
   * solver, Siconos's unilateral constraint with Newton's law) */
  if (m->collider == FB_COLLIDER_NATIVE) {
    *why = "its collider is the engine's native contact, which no binding of its engine builds";
    return fb_engine_kit_of(e, m->collider);
  }
  /* the faceted and libccd colliders: the binding's own (kit.h collide) */
  const int generic = m->collider == FB_COLLIDER_FACETED || m->collider == FB_COLLIDER_CCD;
  *why = generic ? "its collider (a faceted ring or a libccd bore) is ODE's own, which its "
                   "engine's binding does not build"
                 : "its engine's binding takes no clearance contact";
  if (generic && !b->collide) return NULL;
  return (generic || m->collider == FB_COLLIDER_EXACT) && b->add_contact ? b : NULL;
}

const struct fb_kit_binding *fb_planar_kit_of(const char *name) { return kit_of(name, NULL); }

const char *fb_planar_kit_refusal(const char *name) {
  const char *why;
  return kit_of(name, &why) ? NULL : why;
}

int fb_planar_kit_applies_loads(const char *name) {
  const fb_kit_binding *b = fb_planar_kit_of(name);
  return b && (b->apply_wrench || b->loads_from_state);
}

/* the models that take(name), comma-separated, into buf (size) */
static const char *models_that(char *buf, size_t size, int (*take)(const char *name)) {
  size_t n = 0;
  buf[0] = '\0';
  for (int i = 0; i < fb_model_count && n < size; i++)
    if (take(fb_models[i].name))
      n += (size_t)snprintf(buf + n, size - n, "%s%s", n ? ", " : "", fb_models[i].name);
  return buf;
}

static int kit_builds(const char *name) { return fb_planar_kit_of(name) != NULL; }

const char *fb_planar_kit_models(char *buf, size_t size) {
  return models_that(buf, size, kit_builds);
}

const char *fb_planar_kit_loaded_models(char *buf, size_t size) {
  return models_that(buf, size, fb_planar_kit_applies_loads);
}

/* every moving body's omega and alpha extremes over the samples at
 * t >= r->t_window */
static void window_peaks(fb_planar_model *p, const fb_planar_run *r) {
  for (int b = 1; b < r->m->nbodies; b++) {
    fb_body_peaks k = {.omega_max = -INFINITY, .omega_min = INFINITY, .alpha_max = -INFINITY,
                       .alpha_min = INFINITY};
    for (size_t i = 0; i < p->n; i++) {
      if (p->t[i] < r->t_window) continue;
      const double *q = p->q + (size_t)(b - 1) * 3 * p->n; /* planar_run.h's layout */
      const double w = q[FB_Q_VEL * p->n + i], a = q[FB_Q_ACC * p->n + i];
      k.omega_max = fmax(k.omega_max, w);
      k.omega_min = fmin(k.omega_min, w);
      k.alpha_max = fmax(k.alpha_max, a);
      k.alpha_min = fmin(k.alpha_min, a);
    }
    p->peaks[b] = k;
  }
}

/* the clearance of model p: every clearance joint of the case, each with
 * its law at the joint's largest ideal reaction (as the reference takes
 * it; a slider's guide or an undriven case: the case's explicit law,
 * planar_free.h) and its columns in p->ref.at[] (the first's p's force,
 * pen, ecc), a prismatic joint's guide (*guide, cl->guide, owned: free()) */
static fb_status clearance(fb_kit_clearance *cl, fb_planar_guide **guide, fb_planar_model *p,
                           const fb_planar_run *r, const fb_model *mt, fb_diag *diag) {
  const fb_planar *m = p->m; /* the nominal description or its stack-up corner: the same joints */
  const double *reaction_max = fb_planar_run_reaction_max(r, m);
  const fb_case *c = &r->c;
  fb_planar_ref_result *q = &p->ref;
  unsigned char clear[FB_PLANAR_SPEC_MAX_JOINTS] = {0};
  int n = 0;
  for (int k = 0; k < m->njoints; k++)
    if ((unsigned)c->clearance.mask & (1u << k)) {
      if (n == FB_PLANAR_REF_MAX_JOINTS)
        return fb_diag_set(diag, FB_ERR_ARG, "model '%s' takes %d clearance joints at most "
                           "([clearance] joints), and the case names more", p->name,
                           FB_PLANAR_REF_MAX_JOINTS);
      clear[k] = 1;
      q->at[n++].joint = k;
    }
  if (n < 1)
    return fb_diag_set(diag, FB_ERR_ARG, "model '%s' needs a clearance joint ([clearance] joints "
                       "= a joint of the case)", p->name);
  q->njoints = n;
  /* a prismatic joint (a slider in its guide): the kit's corner contacts,
   * or refused by the kit naming the binding (kit_contact.h) */
  double *omega0 = NULL;
  int free_law = 0; /* a slider's guide or an undriven case: the law is explicit */
  fb_status st = fb_planar_free_parts(guide, &omega0, &free_law, c, m, clear, diag);
  free(omega0); /* the start takes its own (fb_planar_run_kit) */
  cl->guide = *guide;
  if (st == FB_OK && !free_law && !reaction_max)
    st = fb_diag_set(diag, FB_ERR_ARG, "model '%s': the joints' ideal reactions were not computed",
                     p->name);
  /* the columns: a block of 4 n per joint (force, penetration, a pin's
   * eccentricity x and y); a pin's eccentricity too: report.html draws its
   * orbit, and a rigid model's verdict reads its rebound (planar_verdict.c) */
  p->rigid = mt->rigid;
  p->force = st == FB_OK ? malloc(4 * p->n * (size_t)n * sizeof *p->force) : NULL;
  if (st == FB_OK && !p->force) st = fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  if (st != FB_OK) return st;
  for (size_t i = 0; i < 4 * p->n * (size_t)n; i++) p->force[i] = NAN;
  /* an injected error (scene.c's rule): the engine's law, not the reference's */
  const fb_clearance *ci = &c->clearance;
  const int damping_given = fb_casefile_given(c, "clearance", "engine_damping_scale");
  const int scaled = ci->engine_stiffness_scale != 1.0 || ci->engine_damping_scale != 1.0 ||
                     damping_given;
  for (int k = 0; k < n && st == FB_OK; k++) {
    fb_planar_ref_joint *a = &q->at[k];
    const fb_planar_joint *j = &m->joint[a->joint];
    fb_kit_joint_record *rec = &cl->joint[a->joint];
    a->force_work = !free_law ? reaction_max[a->joint] : 0.0;
    st = fb_joint_law_at(&rec->law, c, mt->law == FB_MODEL_LAW_IMPACT, a->force_work, j->name,
                         fb_planar_joint_law_mass(m, a->joint), diag);
    if (st == FB_OK && scaled)
      fb_contact_law_scale(&rec->law, ci->engine_stiffness_scale, ci->engine_damping_scale,
                           damping_given);
    a->law = rec->law;
    a->force = p->force + 4 * p->n * (size_t)k;
    a->pen = a->force + p->n;
    a->ecc = j->kind != FB_KIND_PRISMATIC ? a->force + 2 * p->n : NULL;
    a->force_sampled = a->pen_sampled = NULL;
    a->force_max = a->penetration_max = NAN;
    rec->force = a->force;
    rec->pen = a->pen;
    rec->ecc = a->ecc;
  }
  if (st != FB_OK) return st;
  fb_scene sc;
  fb_scene_default(&sc);
  cl->mask = (unsigned)c->clearance.mask;
  cl->mapping = fb_case_contact_mapping(c);
  cl->radial_clearance = c->radial_clearance;
  cl->pin_radius = 0.5 * c->pin_diameter;
  cl->impact_velocity_min = sc.impact_velocity_min;
  cl->friction = c->clearance.friction;
  /* the row's collider, or an ODE row's [clearance] collider (model_table.h),
   * with the case's ring or bore */
  cl->collider = (fb_kit_collider){fb_model_collider(mt, fb_case_collider_of(c)),
                                   fb_case_faceted_n(c), c->clearance.segments,
                                   fb_case_bore_ovality(c), 0, c->pin_length};
  p->pen = q->at[0].pen;
  p->ecc = q->at[0].ecc;
  q->joint = q->at[0].joint;
  q->law = q->at[0].law;
  q->force_work = q->at[0].force_work;
  return FB_OK;
}

/* *y0 (2 nq, owned: free()) = an undriven case's free start (planar_start.h):
 * the assembly, the case's angular rates, the linear rates from the joints
 * but cl's clearance joints (cl NULL: every joint ideal) */
static fb_status free_start(double **y0, const fb_planar_run *r, const fb_kit_clearance *cl,
                            fb_diag *diag) {
  const fb_planar *m = r->m;
  double *omega0 = NULL;
  unsigned char *off = calloc((size_t)m->njoints, 1);
  *y0 = malloc(2 * (size_t)fb_planar_nq(m) * sizeof **y0);
  fb_status st = off && *y0 ? fb_planar_free_omega0(&omega0, &r->c, m, diag)
                            : fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  for (int j = 0; j < m->njoints && off; j++) off[j] = cl && (cl->mask & (1u << j));
  if (st == FB_OK) st = fb_planar_free_start(*y0, m, off, omega0, diag);
  free(omega0);
  free(off);
  return st;
}

/* *q0 (nq, owned: free()) = a stack-up model's start (p->m at the corner):
 * its assembly pose, which the corner's lengths leave open, closed by
 * Newton at the drive's start, as the analytic model's first sample */
static fb_status closed_start(double **q0, const fb_planar *m, fb_diag *diag) {
  fb_planar_kin *k;
  fb_status st = fb_planar_kin_new(&k, m, diag);
  if (st != FB_OK) return st;
  *q0 = malloc((size_t)fb_planar_nq(m) * sizeof **q0);
  if (!*q0) st = fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  if (st == FB_OK) {
    fb_planar_assembly(m, *q0);
    st = fb_planar_position(k, *q0, 0.0, NULL, diag);
  }
  fb_planar_kin_free(k);
  return st;
}

fb_status fb_planar_run_kit(fb_planar_model *p, const fb_planar_run *r, fb_diag *diag) {
  const fb_model *mt = fb_model_find(p->name);
  const fb_kit_binding *b = fb_planar_kit_of(p->name);
  fb_kit_world o = {.gravity = r->c.gravity, .h = p->h, .solver = &r->c.solver,
                    .nbodies = r->m->nbodies - 1, .njoints = r->m->njoints,
                    .c = &r->c}; /* the assembly start */
  fb_kit_series s = {.n = p->n, .h = p->h, .t = p->t, .q = p->q}; /* centres: below */
  /* a binding that reports joint reactions gives the analytic model's load
   * columns (planar_run.h's torque and reaction) */
  const size_t nl = (1 + 3 * (size_t)r->m->njoints) * p->n;
  const int loads = b->reactions && (!b->reactions_in || b->reactions_in(&o));
  if (loads && !(p->torque = calloc(nl, sizeof *p->torque)))
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for %zu samples' loads", p->n);
  if (p->torque) s.torque = p->torque, s.reaction = p->reaction = p->torque + p->n;
  fb_kit_clearance cl = {0};
  double *y0 = NULL; /* an undriven case's free start */
  fb_planar_guide *guide = NULL; /* a prismatic clearance joint's */
  const double t0 = fb_clock_s();
  p->engine = 1;
  /* what a stop leaves unreached reads as no value (NaN) */
  const size_t nq = (size_t)(r->m->nbodies - 1) * 3 * p->n;
  for (size_t i = 0; i < p->n; i++) p->t[i] = (double)i * p->h;
  for (size_t i = 0; i < nq; i++) p->q[i] = NAN;
  fb_kit_clearance *run_cl = mt->joints == FB_JOINTS_CLEARANCE ? &cl : NULL;
  fb_status st = run_cl ? clearance(&cl, &guide, p, r, mt, diag) : FB_OK;
  /* the adaptive step's schedule in persistent contact (step_control.h):
   * the joints' ideal loads over a revolution of the drive */
  fb_load_scale load = {0};
  const int adaptive = r->c.solver.h_mode == FB_STEP_ADAPTIVE;
  if (st == FB_OK && adaptive && run_cl && b->persistent_rule == FB_PERSIST_LOAD_SCHEDULE &&
      r->m->drive >= 0 && r->m->torque_joint < 0) {
    st = fb_load_scale_build_planar(&load, p->m, r->c.gravity, r->omega, cl.mask,
                                    FB_STEP_LOAD_LOOKAHEAD * r->c.solver.h_max, diag);
    cl.load = &load;
  }
  /* a binding that sub-steps keeps its largest force of each step (the
   * verdict's peaks), a block of n per clearance joint (the first's p's) */
  const int ncl = p->force ? p->ref.njoints : 0;
  if (st == FB_OK && ncl && b->contact_force_max &&
      !(p->force_max = calloc(p->n * (size_t)ncl, sizeof *p->force_max)))
    st = fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  for (int k = 0; k < ncl && p->force_max; k++)
    cl.joint[p->ref.at[k].joint].force_max = p->force_max + p->n * (size_t)k;
  /* undriven: the case's velocities at the assembly, as the reference's
   * free start takes them (q0 NULL: the assembly itself) */
  if (st == FB_OK && r->m->drive < 0 && (st = free_start(&y0, r, run_cl, diag)) == FB_OK)
    o.qd0 = y0 + fb_planar_nq(r->m);
  if (st == FB_OK && p->m != r->m && (st = closed_start(&y0, p->m, diag)) == FB_OK)
    o.q0 = y0; /* a stack-up model: p->m's pose closed (a driven case: planar_run.c) */
  const double before = fb_clock_s() - t0; /* the law, the columns, the start */
  /* the output points and slides need the bodies' centres too */
  if (st == FB_OK && p->out &&
      !(s.centre = malloc(6 * (size_t)(r->m->nbodies - 1) * p->n * sizeof *s.centre)))
    st = fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for %zu samples' points", p->n);
  for (size_t i = 0; s.centre && i < 6 * (size_t)(r->m->nbodies - 1) * p->n; i++)
    s.centre[i] = NAN;
  if (st == FB_OK) st = fb_kit_run(b, p->m, r->omega, &o, run_cl, &s, diag);
  fb_load_scale_free(&load);
  p->has_step_stats = adaptive;
  p->step_stats = s.stats;
  if (s.centre && (st == FB_OK || st == FB_ERR_NUMERIC))
    fb_planar_model_outputs_from(p, p->m, s.centre);
  free(s.centre);
  free(y0);
  free(guide);
  p->h_omega_max = p->m_eff_min = p->m_eff_max = NAN;
  /* what each contact met; the model's: the range over its joints' */
  for (int q = 0; run_cl && q < ncl && (st == FB_OK || st == FB_ERR_NUMERIC); q++) {
    const fb_kit_joint_record *k = &cl.joint[p->ref.at[q].joint];
    fb_planar_ref_joint *a = &p->ref.at[q];
    a->h_omega_max = a->m_eff_min = a->m_eff_max = NAN;
    a->contact_steps = k->contact_steps;
    if (!(k->contact_steps > 0)) continue;
    a->m_eff_min = k->m_eff_min, a->m_eff_max = k->m_eff_max;
    if (b->contact_rows || b->explicit_law) a->h_omega_max = k->h_omega_max;
    p->m_eff_min = isnan(p->m_eff_min) ? k->m_eff_min : fmin(p->m_eff_min, k->m_eff_min);
    p->m_eff_max = isnan(p->m_eff_max) ? k->m_eff_max : fmax(p->m_eff_max, k->m_eff_max);
    if (!isnan(a->h_omega_max))
      p->h_omega_max = isnan(p->h_omega_max) ? a->h_omega_max : fmax(p->h_omega_max, a->h_omega_max);
  }
  p->setup_s = before + s.setup_s;
  for (size_t i = 0; i < p->n; i++) p->drive[i] = r->omega * p->t[i];
  if (st == FB_ERR_NUMERIC) { /* a stop (aliased, the engine's error) is a result, not an error */
    p->ref.failed = 1;
    snprintf(p->ref.stop, sizeof p->ref.stop, "%.200s", diag->msg);
    for (int k = 1; k < r->m->nbodies; k++)
      p->peaks[k] = (fb_body_peaks){.omega_max = NAN, .omega_min = NAN, .alpha_max = NAN,
                                    .alpha_min = NAN};
    p->ref.force_max = p->ref.penetration_max = NAN;
    for (int k = 0; k < ncl; k++) p->ref.at[k].force_max = p->ref.at[k].penetration_max = NAN;
    p->ref.steps = cl.contact_steps; /* the contact steps before the stop */
    return FB_OK;
  }
  if (st != FB_OK) return st;
  window_peaks(p, r);
  /* each clearance joint's window peaks, the model's the largest of them */
  for (int k = 0; k < ncl; k++) {
    fb_planar_ref_joint *a = &p->ref.at[k];
    a->force_max = a->penetration_max = 0.0;
    for (size_t i = 0; i < p->n; i++) {
      if (p->t[i] < r->t_window) continue;
      a->force_max = fmax(a->force_max, a->force[i]);
      a->penetration_max = fmax(a->penetration_max, a->pen[i]);
    }
    p->ref.force_max = fmax(p->ref.force_max, a->force_max);
    p->ref.penetration_max = fmax(p->ref.penetration_max, a->penetration_max);
  }
  p->ref.steps = cl.contact_steps;
  return FB_OK;
}

fb_status fb_planar_kit_model_text(char *buf, size_t size, const fb_case *c, const char *name,
                                   double h, fb_diag *diag) {
  const fb_kit_binding *b = fb_planar_kit_of(name);
  const fb_model *mt = fb_model_find(name);
  if (!b || !mt)
    return fb_diag_set(diag, FB_ERR_ARG, "model '%s' does not build a planar case in this build: "
                       "%s", name, fb_planar_kit_refusal(name) ? fb_planar_kit_refusal(name) : "");
  fb_planar_run *r = calloc(1, sizeof *r);
  if (!r) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  r->c = *c;
  fb_status st = fb_planar_of_case(&r->m, c, NULL, diag);
  const int clear = mt->joints == FB_JOINTS_CLEARANCE;
  if (st == FB_OK) r->omega = c->planar.undriven ? 0.0 : fb_case_omega2(c);
  /* a clearance model's law takes its joint's largest ideal reaction, as a run's (planar_run.c) */
  if (st == FB_OK && clear && !c->planar.undriven && c->clearance.mask) {
    r->reaction_max = malloc((size_t)r->m->njoints * sizeof *r->reaction_max);
    st = r->reaction_max ? fb_planar_reaction_max(r->reaction_max, r->m, r->omega, c->gravity, diag)
                         : fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  }
  fb_planar_model *p = &r->model[0];
  snprintf(p->name, sizeof p->name, "%s", name);
  p->m = r->m;
  p->n = 1; /* clearance() sizes its columns: no sample is taken */
  p->h = h;
  fb_kit_clearance cl = {0};
  fb_planar_guide *guide = NULL;
  if (st == FB_OK && clear) st = clearance(&cl, &guide, p, r, mt, diag);
  const fb_kit_world o = {.gravity = c->gravity, .h = p->h, .solver = &r->c.solver,
                          .nbodies = st == FB_OK ? r->m->nbodies - 1 : 0,
                          .njoints = st == FB_OK ? r->m->njoints : 0, .c = &r->c};
  if (st == FB_OK)
    st = fb_kit_model_text(b, r->m, r->omega, &o, clear ? &cl : NULL, buf, size, diag);
  free(p->force);
  free(guide);
  free(r->reaction_max);
  fb_planar_free(r->m);
  free(r);
  return st;
}
