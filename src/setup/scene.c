#include "scene.h"

#include "mech_kinematics.h"

#include "resolution.h"

#include <math.h>
#include <string.h>

#include "casefile.h"
#include "episode.h"
#include "joint_law.h"
#include "linkage.h"
#include "tolerance.h"

/* A contact that begins with a penetration rate below 1 mm/s is the pin
 * settling onto the wall, not an impact: it is counted as continuous
 * contact, and its hysteresis damping uses this rate as the impact velocity
 * (a smaller one would make the damping term of the LN-type laws, which
 * divides by it, unbounded). Pin speeds in the paper's case are ~10 m/s. */
#define IMPACT_VELOCITY_MIN_M_S 1e-3
/* crank angles per revolution for the joints' largest ideal reaction, whose
 * share is the impact floor: 0.1 deg (joint_law.c's) */
#define IMPACT_FLOOR_SAMPLES 3600

void fb_scene_default(fb_scene *def) {
  memset(def, 0, sizeof *def);
  def->case_collider = FB_COLLIDER_EXACT;
  def->impact_velocity_min = IMPACT_VELOCITY_MIN_M_S;
#define X(name) def->name = fb_##name##_opts_default();
  FB_ENGINE_OPTS_LIST
#undef X
}

/* assembles both linkages at crank_angle0, omega2 (a moved start) */
static fb_status check_assembly(const fb_scene *def, fb_diag *diag) {
  for (int k = 0; k < 2; k++) {
    double x[FB_MECH_MAX_OUTPUTS][3];
    fb_status st = fb_mech_solve(x, def->source.mechanism, &def->lengths[k], def->branch,
                                 def->crank_angle0, def->omega2, 0.0, diag);
    if (st != FB_OK) return st;
  }
  return FB_OK;
}

fb_status fb_scene_set_start(fb_scene *def, double theta0, double omega2,
                                 fb_diag *diag) {
  def->crank_angle0 = theta0;
  def->omega2 = omega2;
  def->start_given = 0;
  return check_assembly(def, diag);
}

fb_mapping fb_case_contact_mapping(const fb_case *c) {
  const fb_mapping m = (fb_mapping)c->clearance.mapping;
  return c->solver.h_mode == FB_STEP_ADAPTIVE && m == FB_MAPPING_MATCHED
             ? FB_MAPPING_MATCHED_STATIC
             : m;
}

fb_status fb_scene_from_case(fb_scene *def, const fb_case *c, fb_diag *diag) {
  fb_scene_default(def);
  /* standards are applied by the case file; a "worst" stack-up becomes a
   * concrete corner here, before anything uses the stack-up lengths */
  def->source = *c;
  fb_case *r = &def->source;
  fb_status st = fb_tol_resolve_worst(r, diag);
  /* [solver] h_s = auto (or not given, with clearance joints): the step from
   * the contact at the resolved corner (resolution.h); the case is checked
   * again with it */
  const int auto_step = r->solver.h_mode == FB_STEP_AUTO ||
                        r->solver.h_mode == FB_STEP_ADAPTIVE ||
                        (r->solver.h_mode == FB_STEP_DEFAULT && r->clearance.mask);
  if (st == FB_OK) st = fb_case_resolve_step(r, diag);
  if (st == FB_OK && (c->stackup.worst || auto_step)) st = fb_case_check(r, diag);
  if (st != FB_OK) return st;
  def->stackup = r->stackup;
  def->lengths[FB_LENGTHS_NOMINAL] = r->nominal;
  fb_case_stackup_lengths(r, &def->lengths[FB_LENGTHS_STACKUP]);
  def->branch = r->branch;
  def->gravity = r->gravity;
  for (int i = 0; i < 3; i++) def->link[i] = r->link[i];
  def->solver = r->solver;
  def->duration = fb_case_duration(r);
  def->steps = (size_t)llround(def->duration / r->solver.h);
  def->clearance_mask = r->clearance.mask;
  def->radial_clearance = r->radial_clearance;
  def->pin_radius = 0.5 * r->pin_diameter;
  def->pin_length = r->pin_length;
  def->mapping = fb_case_contact_mapping(r);
  def->friction = r->clearance.friction;
  def->penetration_limit = fb_case_penetration_limit(r);
  def->faceted_n = fb_case_faceted_n(r);
  def->ccd_segments = r->clearance.segments;
  def->bore_ovality = fb_case_bore_ovality(r);
  def->case_collider = fb_case_collider_of(r);
  def->crank_angle0 = r->crank_angle0;
  def->omega2 = fb_case_omega2(r);
#define X(name) def->name = r->name;
  FB_ENGINE_OPTS_LIST
#undef X
  /* the laws the listed models use, with the penalty the run uses: the
   * inverse-dynamics reactions are solved once for all of them; the start
   * of every lengths and joint set a listed model uses */
  int want_start[2][2] = {{0, 0}, {0, 0}};
  for (int i = 0; i < r->model_count; i++) {
    const fb_model *m;
    st = fb_model_lookup(&m, r->models[i], diag);
    if (st != FB_OK) return st;
    if (m->law != FB_MODEL_LAW_NONE && r->clearance.mask) def->has_law[m->law] = 1;
    want_start[m->lengths][m->joints] = 1;
  }
  for (int k = 0; k < 2; k++)
    for (int js = 0; js < 2; js++) {
      if (!want_start[k][js]) continue;
      st = fb_start_resolve(&def->start[k][js], r, &def->lengths[k],
                            js == FB_JOINTS_CLEARANCE ? r->clearance.mask : 0, diag);
      if (st != FB_OK) return st;
    }
  def->start_given = 1;
  if (r->clearance.mask) {
    /* the force that counts as an impact: a share of the joint's largest
     * ideal reaction (episode.h) */
    double reaction[4] = {0, 0, 0, 0};
    st = fb_mech_reaction_peaks(reaction, r->mechanism, &def->lengths[FB_LENGTHS_STACKUP],
                                r->branch, r->link, r->gravity, fb_case_omega2(r),
                                IMPACT_FLOOR_SAMPLES, diag);
    if (st != FB_OK) return st;
    for (int j = 0; j < 4; j++) def->impact_floor[j] = FB_IMPACT_FLOOR_SHARE * reaction[j];
  }
  if (def->has_law[FB_MODEL_LAW_IMPACT] || def->has_law[FB_MODEL_LAW_RESTITUTION])
    st = fb_joint_laws(def->has_law[FB_MODEL_LAW_IMPACT] ? def->law[FB_MODEL_LAW_IMPACT] : NULL,
                       def->has_law[FB_MODEL_LAW_RESTITUTION] ? def->law[FB_MODEL_LAW_RESTITUTION]
                                                               : NULL,
                       r, diag);
  return st;
}

static fb_status check_mass(const fb_link_mass *m, int i, fb_diag *diag) {
  if (!(m->mass > 0.0) || !isfinite(m->mass))
    return fb_diag_set(diag, FB_ERR_RANGE, "scene: link[%d].mass = %g kg: must be positive", i,
                       m->mass);
  if (!(m->inertia > 0.0) || !(m->inertia_long > 0.0) || !(m->inertia_transverse > 0.0) ||
      !isfinite(m->inertia + m->inertia_long + m->inertia_transverse))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "scene: link[%d] inertias (%g, %g, %g) kg m^2: each must be positive", i,
                       m->inertia, m->inertia_long, m->inertia_transverse);
  if (!(m->com_fraction >= 0.0 && m->com_fraction <= 1.0))
    return fb_diag_set(diag, FB_ERR_RANGE, "scene: link[%d].com_fraction = %g: must be in [0, 1]",
                       i, m->com_fraction);
  return FB_OK;
}

fb_status fb_scene_check(const fb_scene *def, fb_diag *diag) {
  for (int k = 0; k < 2; k++) {
    fb_status st = fb_mech_check_lengths(def->source.mechanism, &def->lengths[k], diag);
    if (st != FB_OK) return st;
  }
  if (!def->start_given) {
    fb_status st = check_assembly(def, diag);
    if (st != FB_OK) return st;
  }
  if (!isfinite(def->omega2) || !isfinite(def->crank_angle0))
    return fb_diag_set(diag, FB_ERR_RANGE, "scene: crank angle %g rad, speed %g rad/s: must be finite",
                       def->crank_angle0, def->omega2);
  if (!(def->gravity >= 0.0) || !isfinite(def->gravity))
    return fb_diag_set(diag, FB_ERR_RANGE, "scene: gravity = %g m/s^2: must be finite and >= 0",
                       def->gravity);
  for (int i = 0; i < 3; i++) {
    fb_status st = check_mass(&def->link[i], i, diag);
    if (st != FB_OK) return st;
  }
  const fb_solver *s = &def->solver;
  if (!(s->h > 0.0) || !isfinite(s->h))
    return fb_diag_set(diag, FB_ERR_RANGE, "scene: solver.h = %g s: must be positive", s->h);
  if (!(s->world_erp >= 0.0 && s->world_erp <= 1.0))
    return fb_diag_set(diag, FB_ERR_RANGE, "scene: solver.world_erp = %g: must be in [0, 1]",
                       s->world_erp);
  if (!(s->world_cfm >= 0.0) || !isfinite(s->world_cfm))
    return fb_diag_set(diag, FB_ERR_RANGE, "scene: solver.world_cfm = %g: must be >= 0",
                       s->world_cfm);
  if (s->stepper == FB_STEPPER_QUICK && s->quick_iterations < 1)
    return fb_diag_set(diag, FB_ERR_RANGE, "scene: solver.quick_iterations = %d: must be >= 1",
                       s->quick_iterations);
  if (!(s->drive_torque_max > 0.0))
    return fb_diag_set(diag, FB_ERR_RANGE, "scene: solver.drive_torque_max = %g N m: must be > 0",
                       s->drive_torque_max);
  if (def->duration > 0.0 && !(s->h < def->duration))
    return fb_diag_set(diag, FB_ERR_RANGE, "scene: solver.h = %g s: must be below the duration %g s",
                       s->h, def->duration);
  if (def->clearance_mask & ~0xF)
    return fb_diag_set(diag, FB_ERR_RANGE, "scene: clearance_mask = %#x: only bits 0..3 (joints A..D)",
                       (unsigned)def->clearance_mask);
  if (def->clearance_mask) {
    if (!(def->pin_radius > 0.0) || !isfinite(def->pin_radius))
      return fb_diag_set(diag, FB_ERR_RANGE, "scene: pin_radius = %g m: must be positive",
                         def->pin_radius);
    if (!(def->radial_clearance >= 0.0) || !(def->radial_clearance < def->pin_radius))
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "scene: radial_clearance = %g m: must be >= 0 and below the pin radius %g m",
                         def->radial_clearance, def->pin_radius);
    if (!(def->impact_velocity_min > 0.0))
      return fb_diag_set(diag, FB_ERR_RANGE, "scene: impact_velocity_min = %g m/s: must be > 0",
                         def->impact_velocity_min);
    if (!(def->friction >= 0.0) || !isfinite(def->friction))
      return fb_diag_set(diag, FB_ERR_RANGE, "scene: friction = %g: must be >= 0", def->friction);
    if (!(def->mapping >= 0 && def->mapping < FB_MAPPING_COUNT))
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "scene: mapping = %d: secant (0), tangent (1), matched (2) or "
                         "matched-static (3)",
                         (int)def->mapping);
    for (int k = 0; k < FB_MODEL_LAW_COUNT; k++) {
      if (!def->has_law[k]) continue;
      for (int j = 0; j < 4; j++) {
        if (!(def->clearance_mask & (1 << j))) continue;
        fb_diag inner;
        if (fb_contact_law_check(&def->law[k][j], &inner) != FB_OK)
          return fb_diag_set(diag, FB_ERR_RANGE, "scene: law of the %s joint: %s",
                             fb_case_joint_name(&def->source, j), inner.msg);
      }
    }
  }
  if (!(def->penetration_limit > 0.0) && def->clearance_mask)
    return fb_diag_set(diag, FB_ERR_RANGE, "scene: penetration_limit = %g m: must be > 0",
                       def->penetration_limit);
  if (!(def->settle_damping >= 0.0 && def->settle_damping < 1.0))
    return fb_diag_set(diag, FB_ERR_RANGE, "scene: settle_damping = %g: must be in [0, 1)",
                       def->settle_damping);
#define X(name)                                                \
  {                                                            \
    const fb_status opts_st = fb_##name##_opts_check(&def->name, diag); \
    if (opts_st != FB_OK) return opts_st;                      \
  }
  FB_ENGINE_OPTS_LIST
#undef X
  return FB_OK;
}

fb_status fb_scene_select(fb_model_scene *out, const fb_scene *def, const fb_model *m,
                              fb_diag *diag) {
  memset(out, 0, sizeof *out);
  out->def = def;
  out->model = m;
  out->lengths = def->lengths[m->lengths];
  out->start = def->start[m->lengths][m->joints];
  out->start_given = def->start_given;
#define X(name) out->name = def->name;
  FB_ENGINE_OPTS_LIST
#undef X
  out->clearance = &def->source.clearance;
  out->branch = def->branch;
  out->crank_angle0 = def->crank_angle0;
  out->omega2 = def->omega2;
  out->gravity = def->gravity;
  for (int i = 0; i < 3; i++) out->link[i] = def->link[i];
  out->solver = def->solver;
  out->settle_damping = def->settle_damping;
  out->impact_velocity_min = def->impact_velocity_min;
  if (!fb_model_has_clearance(m)) return FB_OK;
  if (!def->clearance_mask)
    return fb_diag_set(diag, FB_ERR_ARG,
                       "model '%s' needs at least one clearance joint ([clearance] joints)",
                       m->name);
  if (m->law != FB_MODEL_LAW_NONE && !def->has_law[m->law])
    return fb_diag_set(diag, FB_ERR_ARG,
                       "model '%s': the scene has no resolved law for it (build the scene from "
                       "a case that lists the model)",
                       m->name);
  const fb_collider col = fb_model_collider(m, def->case_collider);
  if (col == FB_COLLIDER_FACETED && def->faceted_n < 3)
    return fb_diag_set(diag, FB_ERR_RANGE, "model '%s': faceted_n = %d: a ring needs >= 3 boxes",
                       m->name, def->faceted_n);
  if (col == FB_COLLIDER_CCD && def->ccd_segments < 3)
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "model '%s': ccd_segments = %d: a bore ring needs >= 3 segments",
                       m->name, def->ccd_segments);
  out->clearance_mask = def->clearance_mask;
  if (m->law != FB_MODEL_LAW_NONE)
    for (int j = 0; j < 4; j++) out->law[j] = def->law[m->law][j];
  /* an injected error: every engine model's law, never a reference's; a
   * rigid model has no stiffness or damper to scale */
  const fb_clearance *cl = &def->source.clearance;
  const int damping_given = fb_casefile_given(&def->source, "clearance", "engine_damping_scale");
  if (fb_engine_steps_world(m->engine) && !m->rigid && m->law != FB_MODEL_LAW_NONE &&
      (cl->engine_stiffness_scale != 1.0 || cl->engine_damping_scale != 1.0 || damping_given))
    for (int j = 0; j < 4; j++)
      if (def->clearance_mask & (1 << j))
        fb_contact_law_scale(&out->law[j], cl->engine_stiffness_scale, cl->engine_damping_scale,
                             damping_given);
  out->radial_clearance = def->radial_clearance;
  out->pin_radius = def->pin_radius;
  out->mapping = def->mapping;
  out->friction = def->friction;
  out->pin_length = def->pin_length;
  out->collider = col;
  out->faceted_n = col == FB_COLLIDER_FACETED ? def->faceted_n : 0;
  if (col == FB_COLLIDER_CCD) {
    out->ccd_segments = def->ccd_segments;
    out->bore_ovality = def->bore_ovality;
    out->ccd_split = def->ccd_split;
  }
  return FB_OK;
}

fb_status fb_model_scene_start(fb_start_state *out, const fb_model_scene *sm, fb_diag *diag) {
  if (sm->start_given) {
    *out = sm->start;
    return FB_OK;
  }
  /* the steady start with every pin centred, from the exact solver */
  return fb_start_steady(out, sm->def->source.mechanism, &sm->lengths, sm->branch,
                         sm->crank_angle0, sm->omega2, diag);
}
