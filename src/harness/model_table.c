#include "model_table.h"

#include <stdio.h>
#include <string.h>

#include "fb_config.h"

const char *fb_engine_name(fb_engine_id e) {
  static const char *const names[FB_ENGINE_COUNT] = {"analytic", "reference", "ode", "mujoco"};
  return (e >= 0 && e < FB_ENGINE_COUNT) ? names[e] : "?";
}

int fb_engine_available(fb_engine_id e) {
  return e == FB_ENGINE_MUJOCO ? FB_HAVE_MUJOCO : (e >= 0 && e < FB_ENGINE_COUNT);
}

int fb_engine_steps_world(fb_engine_id e) { return e == FB_ENGINE_ODE || e == FB_ENGINE_MUJOCO; }

/* short names for the rows */
#define NOM FB_LENGTHS_NOMINAL
#define STK FB_LENGTHS_STACKUP
#define IDEAL FB_JOINTS_IDEAL
#define CLEAR FB_JOINTS_CLEARANCE

/* name, engine, lengths, joints, law, collider, reference, spikes_vs, summary */
const fb_model fb_models[] = {
    {"analytic", FB_ENGINE_ANALYTIC, NOM, IDEAL, FB_MODEL_LAW_NONE, FB_COLLIDER_NONE, NULL, NULL,
     "exact kinematics, nominal lengths"},
    {"analytic-stackup", FB_ENGINE_ANALYTIC, STK, IDEAL, FB_MODEL_LAW_NONE, FB_COLLIDER_NONE, NULL,
     NULL, "exact kinematics, stack-up lengths"},
    {"ode-ideal-nominal", FB_ENGINE_ODE, NOM, IDEAL, FB_MODEL_LAW_NONE, FB_COLLIDER_NONE, NULL, NULL,
     "ODE, ideal hinges, nominal lengths"},
    {"ode-ideal-stackup", FB_ENGINE_ODE, STK, IDEAL, FB_MODEL_LAW_NONE, FB_COLLIDER_NONE, NULL, NULL,
     "ODE, ideal hinges, stack-up lengths"},
    {"ode-clearance-restitution", FB_ENGINE_ODE, STK, CLEAR, FB_MODEL_LAW_RESTITUTION,
     FB_COLLIDER_EXACT, "reference-restitution", "ode-ideal-stackup",
     "ODE, clearance joints, restitution law, exact pin-in-hole contact"},
    {"ode-clearance-impact", FB_ENGINE_ODE, STK, CLEAR, FB_MODEL_LAW_IMPACT, FB_COLLIDER_EXACT,
     "reference", "ode-ideal-stackup",
     "ODE, clearance joints, impact law, exact pin-in-hole contact"},
    {"ode-clearance-faceted", FB_ENGINE_ODE, STK, CLEAR, FB_MODEL_LAW_IMPACT, FB_COLLIDER_FACETED,
     NULL, "ode-ideal-stackup", "ODE, clearance joints, impact law, ring of boxes (dCollide)"},
    {"mujoco-ideal-nominal", FB_ENGINE_MUJOCO, NOM, IDEAL, FB_MODEL_LAW_NONE, FB_COLLIDER_NONE,
     NULL, NULL, "MuJoCo, hinge tree closed by a connect equality, nominal lengths"},
    {"mujoco-ideal-stackup", FB_ENGINE_MUJOCO, STK, IDEAL, FB_MODEL_LAW_NONE, FB_COLLIDER_NONE,
     NULL, NULL, "MuJoCo, hinge tree closed by a connect equality, stack-up lengths"},
    {"mujoco-clearance-restitution", FB_ENGINE_MUJOCO, STK, CLEAR, FB_MODEL_LAW_RESTITUTION,
     FB_COLLIDER_EXACT, "reference-restitution", "mujoco-ideal-stackup",
     "MuJoCo, clearance joints, restitution law applied through mjcb_passive"},
    {"mujoco-clearance-impact", FB_ENGINE_MUJOCO, STK, CLEAR, FB_MODEL_LAW_IMPACT,
     FB_COLLIDER_EXACT, "reference", "mujoco-ideal-stackup",
     "MuJoCo, clearance joints, impact law applied through mjcb_passive"},
    {"mujoco-clearance-native", FB_ENGINE_MUJOCO, STK, CLEAR, FB_MODEL_LAW_RESTITUTION,
     FB_COLLIDER_NATIVE, "reference-restitution", "mujoco-ideal-stackup",
     "MuJoCo's own contacts (pin sphere in a ring of boxes), restitution law as direct solref"},
    {"reference", FB_ENGINE_REFERENCE, STK, CLEAR, FB_MODEL_LAW_IMPACT, FB_COLLIDER_EXACT, NULL,
     "ode-ideal-stackup", "minimal-coordinate dynamics (GSL rk8pd), impact law"},
    {"reference-restitution", FB_ENGINE_REFERENCE, STK, CLEAR, FB_MODEL_LAW_RESTITUTION,
     FB_COLLIDER_EXACT, NULL, "ode-ideal-stackup",
     "minimal-coordinate dynamics (GSL rk8pd), restitution law"},
};

const int fb_model_count = (int)(sizeof fb_models / sizeof fb_models[0]);

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

int fb_model_has_clearance(const fb_model *m) { return m->joints == FB_JOINTS_CLEARANCE; }
