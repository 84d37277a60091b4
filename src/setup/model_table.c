#include "model_table.h"

#include <stdio.h>
#include <string.h>

#include "fb_config.h"

const char *fb_engine_name(fb_engine_id e) {
  static const char *const names[FB_ENGINE_COUNT] = {
      "analytic", "reference",
#define X(ID, name) #name,
      FB_ENGINE_LIST
#undef X
  };
  return (e >= 0 && e < FB_ENGINE_COUNT) ? names[e] : "?";
}

int fb_engine_available(fb_engine_id e) {
  switch (e) {
#define X(ID, name) \
  case FB_ENGINE_##ID: return FB_HAVE_##ID;
    FB_ENGINE_LIST
#undef X
    default: return e >= 0 && e < FB_ENGINE_COUNT;
  }
}

const char *fb_engine_howto(fb_engine_id e) {
  switch (e) {
#define X(ID, name) \
  case FB_ENGINE_##ID: return FB_##ID##_HOWTO;
    FB_ENGINE_LIST
#undef X
    default: return "";
  }
}

const char *fb_collider_name(fb_collider c) {
  static const char *const names[FB_COLLIDER_COUNT] = {"none", "exact", "faceted", "ccd", "native"};
  return (c >= 0 && c < FB_COLLIDER_COUNT) ? names[c] : "?";
}

const char *fb_lengths_name(fb_lengths_kind k) {
  return k == FB_LENGTHS_NOMINAL ? "nominal" : k == FB_LENGTHS_STACKUP ? "stackup" : "?";
}

const char *fb_joint_set_name(fb_joint_set j) {
  return j == FB_JOINTS_IDEAL ? "ideal" : j == FB_JOINTS_CLEARANCE ? "clearance" : "?";
}

const char *fb_model_law_name(fb_model_law l) {
  static const char *const names[FB_MODEL_LAW_COUNT] = {"none", "impact", "restitution"};
  return (l >= 0 && l < FB_MODEL_LAW_COUNT) ? names[l] : "?";
}

int fb_engine_steps_world(fb_engine_id e) {
  return e > FB_ENGINE_REFERENCE && e < FB_ENGINE_COUNT;
}

/* short names for the rows */
#define NOM FB_LENGTHS_NOMINAL
#define STK FB_LENGTHS_STACKUP
#define IDEAL FB_JOINTS_IDEAL
#define CLEAR FB_JOINTS_CLEARANCE
#define SC "slider-crank" /* builds the slider-crank too */

/* One row per model. The style (colour, gnuplot dash type, line width, hue)
 * is the same in every figure (docs/figures.md lists it); the MuJoCo rows take
 * the colour of their ODE counterpart, dotted; the Simbody rows dash-dot (ideal
 * stack-up dash type 5), thin. The figures draw every row of one engine in
 * shades of that engine's hue (ODE blues, MuJoCo oranges, Simbody greens,
 * Bullet purples); the yardsticks keep their colour, and so do the Siconos
 * rows (reds). Every other engine's row names its ODE row of the same
 * lengths, joints and law as its partner (omega.svg's engine differences). */
const fb_model fb_models[] = {
    {.name = "analytic",
     .engine = FB_ENGINE_ANALYTIC,
     .mechanisms = SC,
     .lengths = NOM,
     .joints = IDEAL,
     .law = FB_MODEL_LAW_NONE,
     .collider = FB_COLLIDER_NONE,
     .reference = NULL,
     .spikes_vs = NULL,
     .summary = "exact kinematics, nominal lengths",
     .style = {"#000000", 1, 2.6, FB_HUE_NONE}},
    {.name = "analytic-stackup",
     .engine = FB_ENGINE_ANALYTIC,
     .mechanisms = SC,
     .lengths = STK,
     .joints = IDEAL,
     .law = FB_MODEL_LAW_NONE,
     .collider = FB_COLLIDER_NONE,
     .reference = NULL,
     .spikes_vs = NULL,
     .summary = "exact kinematics, stack-up lengths",
     .style = {"#7f7f7f", 2, 2.0, FB_HUE_NONE}},
    {.name = "ode-ideal-nominal",
     .engine = FB_ENGINE_ODE,
     .mechanisms = SC,
     .lengths = NOM,
     .joints = IDEAL,
     .law = FB_MODEL_LAW_NONE,
     .collider = FB_COLLIDER_NONE,
     .reference = NULL,
     .spikes_vs = NULL,
     .summary = "ODE, ideal hinges, nominal lengths",
     .style = {"#1f77b4", 1, 1.3, FB_HUE_BLUES}},
    {.name = "ode-ideal-stackup",
     .engine = FB_ENGINE_ODE,
     .mechanisms = SC,
     .lengths = STK,
     .joints = IDEAL,
     .law = FB_MODEL_LAW_NONE,
     .collider = FB_COLLIDER_NONE,
     .reference = NULL,
     .spikes_vs = NULL,
     .summary = "ODE, ideal hinges, stack-up lengths",
     .style = {"#6baed6", 4, 1.3, FB_HUE_BLUES}},
    {.name = "ode-clearance-restitution",
     .engine = FB_ENGINE_ODE,
     .mechanisms = SC,
     .lengths = STK,
     .joints = CLEAR,
     .law = FB_MODEL_LAW_RESTITUTION,
     .collider = FB_COLLIDER_EXACT,
     .reference = "reference-restitution",
     .spikes_vs = "ode-ideal-stackup",
     .summary = "ODE, clearance joints, restitution law, exact pin-in-hole contact",
     .style = {"#2ca02c", 1, 1.3, FB_HUE_BLUES}},
    {.name = "ode-clearance-impact",
     .engine = FB_ENGINE_ODE,
     .mechanisms = SC,
     .lengths = STK,
     .joints = CLEAR,
     .law = FB_MODEL_LAW_IMPACT,
     .collider = FB_COLLIDER_EXACT,
     .reference = "reference",
     .spikes_vs = "ode-ideal-stackup",
     .summary = "ODE, clearance joints, impact law, exact pin-in-hole contact",
     .style = {"#d62728", 1, 1.3, FB_HUE_BLUES}},
    {.name = "ode-clearance-faceted",
     .engine = FB_ENGINE_ODE,
     .mechanisms = SC,
     .lengths = STK,
     .joints = CLEAR,
     .law = FB_MODEL_LAW_IMPACT,
     .collider = FB_COLLIDER_FACETED,
     .reference = NULL,
     .spikes_vs = "ode-ideal-stackup",
     .summary = "ODE, clearance joints, impact law, ring of boxes (dCollide)",
     .style = {"#ff7f0e", 3, 1.5, FB_HUE_BLUES}},
    {.name = "ode-clearance-ccd",
     .engine = FB_ENGINE_ODE,
     .mechanisms = SC,
     .lengths = STK,
     .joints = CLEAR,
     .law = FB_MODEL_LAW_IMPACT,
     .collider = FB_COLLIDER_CCD,
     .reference = "reference",
     .spikes_vs = "ode-ideal-stackup",
     .summary = "ODE, clearance joints, impact law, libccd ring of convex segments "
                "(docs/colliders.md)",
     .style = {"#e377c2", 5, 1.5, FB_HUE_BLUES}},
    {.name = "mujoco-ideal-nominal",
     .engine = FB_ENGINE_MUJOCO,
     .mechanisms = SC,
     .lengths = NOM,
     .joints = IDEAL,
     .law = FB_MODEL_LAW_NONE,
     .collider = FB_COLLIDER_NONE,
     .reference = NULL,
     .spikes_vs = NULL,
     .partner = "ode-ideal-nominal",
     .summary = "MuJoCo, hinge tree closed by a connect equality, nominal lengths",
     .style = {"#1f77b4", 3, 1.8, FB_HUE_ORANGES}},
    {.name = "mujoco-ideal-stackup",
     .engine = FB_ENGINE_MUJOCO,
     .mechanisms = SC,
     .lengths = STK,
     .joints = IDEAL,
     .law = FB_MODEL_LAW_NONE,
     .collider = FB_COLLIDER_NONE,
     .reference = NULL,
     .spikes_vs = NULL,
     .partner = "ode-ideal-stackup",
     .summary = "MuJoCo, hinge tree closed by a connect equality, stack-up lengths",
     .style = {"#6baed6", 3, 1.8, FB_HUE_ORANGES}},
    {.name = "mujoco-clearance-restitution",
     .engine = FB_ENGINE_MUJOCO,
     .mechanisms = SC,
     .lengths = STK,
     .joints = CLEAR,
     .law = FB_MODEL_LAW_RESTITUTION,
     .collider = FB_COLLIDER_EXACT,
     .reference = "reference-restitution",
     .spikes_vs = "mujoco-ideal-stackup",
     .partner = "ode-clearance-restitution",
     .summary = "MuJoCo, clearance joints, restitution law applied through mjcb_passive",
     .style = {"#2ca02c", 3, 1.8, FB_HUE_ORANGES}},
    {.name = "mujoco-clearance-impact",
     .engine = FB_ENGINE_MUJOCO,
     .mechanisms = SC,
     .lengths = STK,
     .joints = CLEAR,
     .law = FB_MODEL_LAW_IMPACT,
     .collider = FB_COLLIDER_EXACT,
     .reference = "reference",
     .spikes_vs = "mujoco-ideal-stackup",
     .partner = "ode-clearance-impact",
     .summary = "MuJoCo, clearance joints, impact law applied through mjcb_passive",
     .style = {"#d62728", 3, 1.8, FB_HUE_ORANGES}},
    {.name = "mujoco-clearance-native",
     .engine = FB_ENGINE_MUJOCO,
     .mechanisms = SC,
     .lengths = STK,
     .joints = CLEAR,
     .law = FB_MODEL_LAW_RESTITUTION,
     .collider = FB_COLLIDER_NATIVE,
     .reference = "reference-restitution",
     .spikes_vs = "mujoco-ideal-stackup",
     .partner = "ode-clearance-restitution",
     .summary = "MuJoCo's own constraint solver on the clearance (a tendon limited to it, or a ring "
                "of boxes: [mujoco] native_bore), restitution law as solref",
     .style = {"#ff7f0e", 5, 1.8, FB_HUE_ORANGES}},
    {.name = "simbody-ideal-nominal",
     .engine = FB_ENGINE_SIMBODY,
     .mechanisms = SC,
     .lengths = NOM,
     .joints = IDEAL,
     .law = FB_MODEL_LAW_NONE,
     .collider = FB_COLLIDER_NONE,
     .reference = NULL,
     .spikes_vs = NULL,
     .partner = "ode-ideal-nominal",
     .summary = "Simbody, pin tree closed by a ball constraint, nominal lengths",
     .style = {"#1f77b4", 4, 1.0, FB_HUE_GREENS}},
    {.name = "simbody-ideal-stackup",
     .engine = FB_ENGINE_SIMBODY,
     .mechanisms = SC,
     .lengths = STK,
     .joints = IDEAL,
     .law = FB_MODEL_LAW_NONE,
     .collider = FB_COLLIDER_NONE,
     .reference = NULL,
     .spikes_vs = NULL,
     .partner = "ode-ideal-stackup",
     .summary = "Simbody, pin tree closed by a ball constraint, stack-up lengths",
     .style = {"#6baed6", 5, 1.0, FB_HUE_GREENS}},
    {.name = "simbody-clearance-restitution",
     .engine = FB_ENGINE_SIMBODY,
     .mechanisms = SC,
     .lengths = STK,
     .joints = CLEAR,
     .law = FB_MODEL_LAW_RESTITUTION,
     .collider = FB_COLLIDER_EXACT,
     .reference = "reference-restitution",
     .spikes_vs = "simbody-ideal-stackup",
     .partner = "ode-clearance-restitution",
     .summary = "Simbody, tree cut at the clearance joint, restitution law as Force::Custom",
     .style = {"#2ca02c", 4, 1.0, FB_HUE_GREENS}},
    {.name = "simbody-clearance-impact",
     .engine = FB_ENGINE_SIMBODY,
     .mechanisms = SC,
     .lengths = STK,
     .joints = CLEAR,
     .law = FB_MODEL_LAW_IMPACT,
     .collider = FB_COLLIDER_EXACT,
     .reference = "reference",
     .spikes_vs = "simbody-ideal-stackup",
     .partner = "ode-clearance-impact",
     .summary = "Simbody, tree cut at the clearance joint, impact law as Force::Custom",
     .style = {"#d62728", 4, 1.0, FB_HUE_GREENS}},
    {.name = "bullet-ideal-nominal",
     .engine = FB_ENGINE_BULLET,
     .mechanisms = SC,
     .lengths = NOM,
     .joints = IDEAL,
     .law = FB_MODEL_LAW_NONE,
     .collider = FB_COLLIDER_NONE,
     .reference = NULL,
     .spikes_vs = NULL,
     .partner = "ode-ideal-nominal",
     .summary = "Bullet, planar pin constraint rows in btDiscreteDynamicsWorld, nominal lengths",
     .style = {"#1f77b4", 5, 1.6, FB_HUE_PURPLES}},
    {.name = "bullet-ideal-stackup",
     .engine = FB_ENGINE_BULLET,
     .mechanisms = SC,
     .lengths = STK,
     .joints = IDEAL,
     .law = FB_MODEL_LAW_NONE,
     .collider = FB_COLLIDER_NONE,
     .reference = NULL,
     .spikes_vs = NULL,
     .partner = "ode-ideal-stackup",
     .summary = "Bullet, planar pin constraint rows in btDiscreteDynamicsWorld, stack-up lengths",
     .style = {"#6baed6", 5, 1.6, FB_HUE_PURPLES}},
    {.name = "bullet-clearance-restitution",
     .engine = FB_ENGINE_BULLET,
     .mechanisms = SC,
     .lengths = STK,
     .joints = CLEAR,
     .law = FB_MODEL_LAW_RESTITUTION,
     .collider = FB_COLLIDER_EXACT,
     .reference = "reference-restitution",
     .spikes_vs = "bullet-ideal-stackup",
     .partner = "ode-clearance-restitution",
     .summary = "Bullet, clearance joints, restitution law as a soft constraint row (ODE's mapping)",
     .style = {"#2ca02c", 5, 1.6, FB_HUE_PURPLES}},
    {.name = "bullet-clearance-impact",
     .engine = FB_ENGINE_BULLET,
     .mechanisms = SC,
     .lengths = STK,
     .joints = CLEAR,
     .law = FB_MODEL_LAW_IMPACT,
     .collider = FB_COLLIDER_EXACT,
     .reference = "reference",
     .spikes_vs = "bullet-ideal-stackup",
     .partner = "ode-clearance-impact",
     .summary = "Bullet, clearance joints, impact law as a soft constraint row (ODE's mapping)",
     .style = {"#d62728", 5, 1.6, FB_HUE_PURPLES}},
    /* Siconos: the rigid limit. Reds, each row's own (hue FB_HUE_NONE: no
     * shading family of its own), so that they stand apart from every
     * penalty engine's family; solid ideal, dashed clearance */
    {.name = "siconos-ideal-nominal",
     .engine = FB_ENGINE_SICONOS,
     .mechanisms = SC,
     .lengths = NOM,
     .joints = IDEAL,
     .law = FB_MODEL_LAW_NONE,
     .collider = FB_COLLIDER_NONE,
     .reference = NULL,
     .spikes_vs = NULL,
     .partner = "ode-ideal-nominal",
     .summary = "Siconos, the loop closed on the driven crank by a bilateral "
                "constraint (Moreau-Jean), nominal lengths",
     .style = {"#99000d", 1, 1.4, FB_HUE_NONE}},
    {.name = "siconos-ideal-stackup",
     .engine = FB_ENGINE_SICONOS,
     .mechanisms = SC,
     .lengths = STK,
     .joints = IDEAL,
     .law = FB_MODEL_LAW_NONE,
     .collider = FB_COLLIDER_NONE,
     .reference = NULL,
     .spikes_vs = NULL,
     .partner = "ode-ideal-stackup",
     .summary = "Siconos, the loop closed on the driven crank by a bilateral "
                "constraint (Moreau-Jean), stack-up lengths",
     .style = {"#ef3b2c", 1, 1.4, FB_HUE_NONE}},
    /* the rigid limit of the restitution law: no penalty, the case's
     * restitution as Newton's coefficient (law RESTITUTION for its cr and its
     * reference; collider NATIVE: Siconos's own unilateral constraint) */
    {.name = "siconos-clearance-newton",
     .engine = FB_ENGINE_SICONOS,
     .rigid = 1,
     .mechanisms = SC,
     .lengths = STK,
     .joints = CLEAR,
     .law = FB_MODEL_LAW_RESTITUTION,
     .collider = FB_COLLIDER_NATIVE,
     .reference = "reference-restitution",
     .spikes_vs = "siconos-ideal-stackup",
     .partner = "ode-clearance-restitution",
     .summary = "Siconos, clearance joint as a unilateral constraint g = c - |e| >= 0 with "
                "Newton's impact law (e_N = [clearance] restitution), Moreau-Jean time stepping",
     .style = {"#cb181d", 2, 1.4, FB_HUE_NONE}},
    {.name = "reference",
     .engine = FB_ENGINE_REFERENCE,
     .mechanisms = SC,
     .lengths = STK,
     .joints = CLEAR,
     .law = FB_MODEL_LAW_IMPACT,
     .collider = FB_COLLIDER_EXACT,
     .reference = NULL,
     .spikes_vs = "ode-ideal-stackup",
     .summary = "minimal-coordinate dynamics (GSL rk8pd), impact law",
     .style = {"#9467bd", 2, 1.8, FB_HUE_NONE}},
    {.name = "reference-restitution",
     .engine = FB_ENGINE_REFERENCE,
     .mechanisms = SC,
     .lengths = STK,
     .joints = CLEAR,
     .law = FB_MODEL_LAW_RESTITUTION,
     .collider = FB_COLLIDER_EXACT,
     .reference = NULL,
     .spikes_vs = "ode-ideal-stackup",
     .summary = "minimal-coordinate dynamics (GSL rk8pd), restitution law",
     .style = {"#8c8c00", 2, 1.8, FB_HUE_NONE}},
    /* DART (issue 60): planar cases through the engine kit's walk, the
     * four-bar and slider-crank through the kit adapter. Browns */
    {.name = "dart-ideal-nominal",
     .engine = FB_ENGINE_DART,
     .mechanisms = SC,
     .by_name_only = 1,
     .lengths = NOM,
     .joints = IDEAL,
     .law = FB_MODEL_LAW_NONE,
     .collider = FB_COLLIDER_NONE,
     .reference = NULL,
     .spikes_vs = NULL,
     .partner = "ode-ideal-nominal",
     .summary = "DART, a skeleton tree of revolute and prismatic joints, loops closed by a "
                "BallJointConstraint, servo drive, nominal lengths",
     .style = {"#8c510a", 4, 1.4, FB_HUE_NONE}},
    /* the four-bar and slider-crank at their stack-up corner through the kit
     * adapter (a planar case's description is nominal: no planar row) */
    {.name = "dart-ideal-stackup",
     .engine = FB_ENGINE_DART,
     .mechanisms = SC,
     .by_name_only = 1,
     .lengths = STK,
     .joints = IDEAL,
     .law = FB_MODEL_LAW_NONE,
     .collider = FB_COLLIDER_NONE,
     .reference = NULL,
     .spikes_vs = NULL,
     .partner = "ode-ideal-stackup",
     .summary = "DART, a skeleton tree of revolute and prismatic joints, loops closed by a "
                "BallJointConstraint, servo drive, stack-up lengths",
     .style = {"#d8b365", 4, 1.4, FB_HUE_NONE}},
    {.name = "dart-clearance-impact",
     .engine = FB_ENGINE_DART,
     .mechanisms = SC,
     .by_name_only = 1,
     .lengths = STK,
     .joints = CLEAR,
     .law = FB_MODEL_LAW_IMPACT,
     .collider = FB_COLLIDER_EXACT,
     .reference = "reference",
     .spikes_vs = "dart-ideal-stackup",
     .partner = "ode-clearance-impact",
     .summary = "DART, clearance joint as the impact law's force through DART's external force "
                "(BodyNode::addExtForce)",
     .style = {"#bf812d", 4, 1.4, FB_HUE_NONE}},
    {.name = "dart-clearance-restitution",
     .engine = FB_ENGINE_DART,
     .mechanisms = SC,
     .by_name_only = 1,
     .lengths = STK,
     .joints = CLEAR,
     .law = FB_MODEL_LAW_RESTITUTION,
     .collider = FB_COLLIDER_EXACT,
     .reference = "reference-restitution",
     .spikes_vs = "dart-ideal-stackup",
     .partner = "ode-clearance-restitution",
     .summary = "DART, clearance joint as the restitution law's force through DART's external "
                "force (BodyNode::addExtForce)",
     .style = {"#543005", 5, 1.4, FB_HUE_NONE}},
};

const int fb_model_count = (int)(sizeof fb_models / sizeof fb_models[0]);

/* 1 when the space-separated list names (NULL: none) holds name */
static int names_hold(const char *names, const char *name) {
  const size_t n = strlen(name);
  for (const char *p = names; p && *p; p += strcspn(p, " ")) {
    p += strspn(p, " ");
    if (strncmp(p, name, n) == 0 && (p[n] == ' ' || p[n] == '\0')) return 1;
  }
  return 0;
}

int fb_model_builds(const fb_model *m, fb_mech_type t) {
  const fb_mech_desc *d = fb_mech_of(t);
  return d->every_model_builds || names_hold(m->mechanisms, d->type);
}

const char *const fb_clearance_default_models[FB_CLEARANCE_DEFAULT_COUNT] = {
    "ode-clearance-impact", "ode-clearance-restitution", "reference", "reference-restitution"};

const fb_model *fb_model_find(const char *name) {
  if (!name) return NULL;
  for (int i = 0; i < fb_model_count; i++)
    if (strcmp(fb_models[i].name, name) == 0) return &fb_models[i];
  return NULL;
}

const char *fb_model_list(char *buf, size_t size) {
  if (size == 0) return buf;
  buf[0] = '\0';
  size_t used = 0;
  for (int i = 0; i < fb_model_count && used < size; i++) {
    int n = snprintf(buf + used, size - used, "%s%s", i ? ", " : "", fb_models[i].name);
    if (n < 0) break;
    used += (size_t)n;
  }
  return buf;
}

fb_status fb_model_lookup(const fb_model **out, const char *name, fb_diag *diag) {
  *out = fb_model_find(name);
  if (*out) return FB_OK;
  char known[768];
  return fb_diag_set(diag, FB_ERR_ARG, "unknown model '%s' (known: %s)", name ? name : "",
                     fb_model_list(known, sizeof known));
}

int fb_model_ideal_stackup(const char *name) {
  const fb_model *m = fb_model_find(name);
  return m && m->lengths == FB_LENGTHS_STACKUP && m->joints == FB_JOINTS_IDEAL;
}

int fb_model_has_clearance(const fb_model *m) { return m->joints == FB_JOINTS_CLEARANCE; }

fb_collider fb_case_collider_of(const fb_case *c) {
  switch (c->clearance.collider) {
    case FB_CASE_COLLIDER_FACETED: return FB_COLLIDER_FACETED;
    case FB_CASE_COLLIDER_CCD: return FB_COLLIDER_CCD;
    default: return FB_COLLIDER_EXACT;
  }
}

fb_collider fb_model_collider(const fb_model *m, fb_collider case_collider) {
  if (m->engine == FB_ENGINE_ODE && m->collider == FB_COLLIDER_EXACT &&
      case_collider != FB_COLLIDER_NONE)
    return case_collider;
  return m->collider;
}

const char *fb_model_adaptive_refusal(const fb_model *m, fb_collider case_collider) {
  if (m->engine == FB_ENGINE_BULLET)
    return "Bullet steps at a fixed h (it would run at h_min_s, silently)";
  if (m->engine == FB_ENGINE_SICONOS)
    return "Siconos's Moreau-Jean time stepping steps at a fixed h (it would run at h_min_s, "
           "silently)";
  if (m->engine == FB_ENGINE_MUJOCO && m->collider == FB_COLLIDER_NATIVE)
    return "MuJoCo's native contacts are its own";
  if (m->engine == FB_ENGINE_ODE && fb_model_has_clearance(m) &&
      fb_model_collider(m, case_collider) != FB_COLLIDER_EXACT)
    return "the faceted and libccd colliders are not followed";
  return NULL;
}

const fb_model *fb_model_match(fb_engine_id engine, fb_lengths_kind lengths, fb_joint_set joints,
                               fb_model_law law, fb_collider collider) {
  for (int i = 0; i < fb_model_count; i++) {
    const fb_model *m = &fb_models[i];
    if (m->engine == engine && m->lengths == lengths && m->joints == joints && m->law == law &&
        m->collider == collider)
      return m;
  }
  return NULL;
}

const fb_model *fb_model_reference_of(const fb_model *m) { return fb_model_find(m->reference); }

const fb_model *fb_model_ideal_of(const fb_model *m) { return fb_model_find(m->spikes_vs); }

const fb_model *fb_model_partner_of(const fb_model *m) { return fb_model_find(m->partner); }

fb_status fb_model_clearance_at_drive(const fb_model *m, int kit_built, const char *joint,
                                      fb_diag *diag) {
  if (!kit_built || !fb_engine_steps_world(m->engine) || m->joints != FB_JOINTS_CLEARANCE)
    return FB_OK;
  return fb_diag_set(diag, FB_ERR_ARG,
                     "[clearance] joints names '%s', the driven joint, and [run] models runs "
                     "'%s', which the engine kit builds: the kit drives an ideal joint only; put "
                     "the clearance at another joint, or run the models that take it there "
                     "(analytic, the references, a hand-built engine model)", joint, m->name);
}
