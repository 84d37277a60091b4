/* A planar case's springs and loads (casefile_planar_loads.h). */
#include "casefile_planar_loads.h"

#include <math.h>
#include <string.h>

#include "casefile_planar_values.h"
#include "units.h"

#define SPRING_PREFIX "spring."
#define LOAD_PREFIX "load."
#define STIFF_RULE "a spring's stiffness from 0 to 1e12 N/m"
#define FREE_RULE "a free length from 0 to 1e5 mm (100 m)"
#define DAMP_RULE "a damping coefficient from 0 to 1e9 N s/m"
#define FORCE_RULE "two numbers fx, fy in N, each from -1e9 to 1e9 (the world frame)"
#define TORQUE_RULE "a torque from -1e9 to 1e9 N m, counter-clockwise positive"
#define ACTIVE_RULE "always, outstroke (while the slide rate is positive) or return (negative)"

static int prefixed(const char *s, const char *prefix) {
  return strncmp(s, prefix, strlen(prefix)) == 0;
}

int fb_casefile_planar_loads_section(const entry *e) {
  return prefixed(e->section, SPRING_PREFIX) || prefixed(e->section, LOAD_PREFIX);
}

/* one body name of key e into out (body_names' words) */
static fb_status body_word(const entry *e, const char *text, char out[FB_PLANAR_NAME_SIZE],
                           fb_diag *diag) {
  fb_status st = fb_planar_key_name(e, text, "body", diag);
  if (st == FB_OK) snprintf(out, FB_PLANAR_NAME_SIZE, "%s", text);
  return st;
}

/* a [spring.NAME] section's keys */
static fb_status spring_key(fb_planar_spec *s, const entry *e, fb_diag *diag) {
  const char *name = e->section + strlen(SPRING_PREFIX);
  fb_status st = fb_planar_key_name(e, name, "spring", diag);
  if (st != FB_OK) return st;
  const int k = fb_planar_named(s->spring, sizeof s->spring[0], &s->nsprings,
                                FB_PLANAR_SPEC_MAX_SPRINGS, name);
  if (k < 0)
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s]: more than %d springs", e->origin,
                       e->section, FB_PLANAR_SPEC_MAX_SPRINGS);
  fb_planar_spec_spring *p = &s->spring[k];
  if (strcmp(e->key, "bodies") == 0) {
    if ((st = fb_planar_key_two_bodies(e, "a spring", p->body, diag)) != FB_OK) return st;
    p->given |= FB_SPEC_SPRING_BODIES;
    return FB_OK;
  }
  if (strcmp(e->key, "at_a_mm") == 0 || strcmp(e->key, "at_b_mm") == 0) {
    const int b = strcmp(e->key, "at_b_mm") == 0;
    p->given |= b ? FB_SPEC_SPRING_AT_B : FB_SPEC_SPRING_AT_A;
    return fb_planar_key_point(e, p->at[b], diag);
  }
  if (strcmp(e->key, "stiffness_n_m") == 0) {
    p->given |= FB_SPEC_SPRING_STIFF;
    return fb_planar_key_number(e, e->value, 0.0, 1e12, 1.0, STIFF_RULE, &p->stiffness, diag);
  }
  if (strcmp(e->key, "free_length_mm") == 0) {
    p->given |= FB_SPEC_SPRING_FREE;
    return fb_planar_key_number(e, e->value, 0.0, FB_PLANAR_COORD_MAX_MM, FB_M_PER_MM, FREE_RULE,
                                &p->free_length, diag);
  }
  if (strcmp(e->key, "damping_n_s_m") == 0) {
    p->given |= FB_SPEC_SPRING_DAMP;
    return fb_planar_key_number(e, e->value, 0.0, 1e9, 1.0, DAMP_RULE, &p->damping, diag);
  }
  return fb_diag_set(diag, FB_ERR_PARSE, "%s: unknown key '%s' in [%s] (a spring has bodies, "
                     "at_a_mm, at_b_mm, stiffness_n_m, free_length_mm and damping_n_s_m)",
                     e->origin, e->key, e->section);
}

/* a [load.NAME] section's keys */
static fb_status load_key(fb_planar_spec *s, const entry *e, fb_diag *diag) {
  const char *name = e->section + strlen(LOAD_PREFIX);
  fb_status st = fb_planar_key_name(e, name, "load", diag);
  if (st != FB_OK) return st;
  const int k = fb_planar_named(s->load, sizeof s->load[0], &s->nloads,
                                FB_PLANAR_SPEC_MAX_LOADS, name);
  if (k < 0)
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s]: more than %d loads", e->origin,
                       e->section, FB_PLANAR_SPEC_MAX_LOADS);
  fb_planar_spec_load *p = &s->load[k];
  if (strcmp(e->key, "body") == 0) {
    char word[sizeof e->value];
    snprintf(word, sizeof word, "%s", e->value);
    p->given |= FB_SPEC_LOAD_BODY;
    return body_word(e, trim(word), p->body, diag);
  }
  if (strcmp(e->key, "at_mm") == 0) {
    p->given |= FB_SPEC_LOAD_AT;
    return fb_planar_key_point(e, p->at, diag);
  }
  if (strcmp(e->key, "force_n") == 0) {
    p->given |= FB_SPEC_LOAD_FORCE;
    return fb_planar_key_pair(e, -1e9, 1e9, 1.0, FORCE_RULE, "fx, fy in N (for example -250, 0)",
                              p->force, diag);
  }
  if (strcmp(e->key, "torque_n_m") == 0) {
    p->given |= FB_SPEC_LOAD_TORQUE;
    return fb_planar_key_number(e, e->value, -1e9, 1e9, 1.0, TORQUE_RULE, &p->torque, diag);
  }
  if (strcmp(e->key, "active") == 0) {
    char word[sizeof e->value];
    snprintf(word, sizeof word, "%s", e->value);
    const char *w = trim(word);
    p->given |= FB_SPEC_LOAD_ACTIVE;
    if (strcmp(w, "always") == 0) p->active = FB_PLANAR_LOAD_ALWAYS;
    else if (strcmp(w, "outstroke") == 0) p->active = FB_PLANAR_LOAD_OUTSTROKE;
    else if (strcmp(w, "return") == 0) p->active = FB_PLANAR_LOAD_RETURN;
    else
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] active = '%s': %s", e->origin,
                         e->section, e->value, ACTIVE_RULE);
    return FB_OK;
  }
  return fb_diag_set(diag, FB_ERR_PARSE, "%s: unknown key '%s' in [%s] (a load has body, "
                     "at_mm, force_n, torque_n_m and active)", e->origin, e->key, e->section);
}

/* the index of body name in s (the ground 0), or -1 with the case's
 * moving bodies listed in bodies */
static int spec_body(const fb_planar_spec *s, const char *name, char *bodies, size_t size) {
  int at = strcmp(name, "ground") == 0 ? 0 : -1;
  bodies[0] = '\0';
  for (int b = 1; b < s->nbodies; b++) {
    if (strcmp(s->body[b].name, name) == 0) at = b;
    snprintf(bodies + strlen(bodies), size - strlen(bodies), "%s%s", b > 1 ? ", " : "",
             s->body[b].name);
  }
  return at;
}

/* the prismatic joint a load on one stroke follows: the one its body
 * slides in, else the case's only prismatic joint on a ground guide;
 * -1 with the candidates named in why */
static int stroke_joint(const fb_planar_spec *s, int body, char *why, size_t size) {
  int own = -1, owns = 0, grounded = -1, grounds = 0;
  char names[1024] = "";
  for (int j = 0; j < s->njoints; j++) {
    const fb_planar_spec_joint *sj = &s->joint[j];
    if (sj->kind != FB_KIND_PRISMATIC) continue;
    snprintf(names + strlen(names), sizeof names - strlen(names), "%s%s", names[0] ? ", " : "",
             sj->name);
    if (sj->body[0] == body || sj->body[1] == body) own = j, owns++;
    if (sj->body[0] == 0 || sj->body[1] == 0) grounded = j, grounds++;
  }
  if (owns == 1) return own;
  if (owns == 0 && grounds == 1) return grounded;
  if (!names[0]) snprintf(why, size, "the case has no prismatic joint, so no stroke");
  else
    snprintf(why, size, "its stroke is that of the prismatic joint its body slides in, else "
             "of the case's one prismatic joint on a ground guide; here none is one (prismatic "
             "joints: %s)", names);
  return -1;
}

/* every spring has its bodies, ends and stiffness, its bodies the case's
 * and its ends apart; every load its moving body, a force or a torque
 * (a force its point) and, on one stroke, a prismatic joint to follow */
fb_status fb_casefile_planar_loads_whole(fb_planar_spec *s, const entry *e, int n,
                                         fb_diag *diag) {
  char bodies[1024], why[1200];
  for (int k = 0; k < s->nsprings; k++) {
    const fb_planar_spec_spring *p = &s->spring[k];
    const entry *at = fb_planar_entry_first(e, n, SPRING_PREFIX, p->name);
    const char *miss = !(p->given & FB_SPEC_SPRING_BODIES) ? "bodies = A, B (ground allowed)"
                       : !(p->given & FB_SPEC_SPRING_AT_A) ? "at_a_mm = x, y (its end on A)"
                       : !(p->given & FB_SPEC_SPRING_AT_B) ? "at_b_mm = x, y (its end on B)"
                       : !(p->given & FB_SPEC_SPRING_STIFF) ? "stiffness_n_m"
                                                             : NULL;
    if (miss)
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] has no %s", at->origin, at->section, miss);
    for (int b = 0; b < 2; b++)
      if (spec_body(s, p->body[b], bodies, sizeof bodies) < 0) {
        const entry *key = fb_planar_entry_of(e, n, at->section, "bodies");
        return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] bodies: '%s' is not a body of the "
                           "case (ground, %s)", key->origin, key->section, p->body[b], bodies);
      }
    const double d = hypot(p->at[1][0] - p->at[0][0], p->at[1][1] - p->at[0][1]);
    if (d < FB_PLANAR_SPRING_MIN_M) {
      const entry *key = fb_planar_entry_of(e, n, at->section, "at_b_mm");
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] at_b_mm = %s: the spring's ends meet in "
                         "the assembly configuration (at_a_mm is the same point): it has no "
                         "line to pull along; give ends apart", key->origin, key->section,
                         key->value);
    }
  }
  for (int k = 0; k < s->nloads; k++) {
    fb_planar_spec_load *p = &s->load[k];
    const entry *at = fb_planar_entry_first(e, n, LOAD_PREFIX, p->name);
    const char *miss =
        !(p->given & FB_SPEC_LOAD_BODY) ? "body = NAME (the moving body it acts on)"
        : !(p->given & (FB_SPEC_LOAD_FORCE | FB_SPEC_LOAD_TORQUE)) ? "force_n = fx, fy or "
                                                                     "torque_n_m (it loads nothing)"
        : (p->given & FB_SPEC_LOAD_FORCE) && !(p->given & FB_SPEC_LOAD_AT)
            ? "at_mm = x, y (where its force_n acts, in the assembly configuration)"
            : NULL;
    if (miss)
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] has no %s", at->origin, at->section, miss);
    const int b = spec_body(s, p->body, bodies, sizeof bodies);
    const entry *key = fb_planar_entry_of(e, n, at->section, "body");
    if (b <= 0)
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] body = %s: %s (bodies: %s)", key->origin,
                         key->section, p->body,
                         b == 0 ? "the ground does not move; a load acts on a moving body"
                                : "not a moving body of the case", bodies);
    if (!(p->given & FB_SPEC_LOAD_AT)) { /* a torque alone: its point does not matter */
      const double *c = s->body[b].given & FB_SPEC_BODY_CENTRE ? s->body[b].centre : NULL;
      for (int j = 0; j < s->njoints && !c; j++)
        if (s->joint[j].body[0] == b || s->joint[j].body[1] == b) c = s->joint[j].at;
      p->at[0] = c ? c[0] : 0.0;
      p->at[1] = c ? c[1] : 0.0;
    }
    p->stroke = -1;
    if (p->active == FB_PLANAR_LOAD_ALWAYS) continue;
    if ((p->stroke = stroke_joint(s, b, why, sizeof why)) < 0) {
      const entry *act = fb_planar_entry_of(e, n, at->section, "active");
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] active = %s: %s", act->origin,
                         act->section, act->value, why);
    }
  }
  return FB_OK;
}

fb_status fb_casefile_planar_loads_take(fb_planar_spec *s, const entry *e, fb_diag *diag) {
  return prefixed(e->section, SPRING_PREFIX) ? spring_key(s, e, diag) : load_key(s, e, diag);
}

void fb_casefile_planar_loads_write_keys(FILE *f) {
  static const char *const spring_rows[][5] = {
      {"bodies", "-", "(required)", "two different body names, ground or a body of the case",
       "the two bodies a spring-damper joins (A, B)"},
      {"at_a_mm", "mm", "(required)", FB_PLANAR_POINT_RULE,
       "the spring's end on A in the assembly configuration"},
      {"at_b_mm", "mm", "(required)", FB_PLANAR_POINT_RULE "; not at_a_mm's point",
       "the spring's end on B in the assembly configuration"},
      {"stiffness_n_m", "N/m", "(required)", STIFF_RULE,
       "its stiffness: the tension is stiffness (l - free length) + damping l', l its length"},
      {"free_length_mm", "mm", "(the assembly distance)", FREE_RULE,
       "its length without force"},
      {"damping_n_s_m", "N s/m", "0", DAMP_RULE, "its damping along its line"}};
  for (size_t i = 0; i < sizeof spring_rows / sizeof spring_rows[0]; i++)
    fprintf(f, "| [spring.NAME] %s | %s | %s | %s | planar case: %s; in the analytic model, "
            "the references and every engine's models |\n", spring_rows[i][0],
            spring_rows[i][1], spring_rows[i][2], spring_rows[i][3], spring_rows[i][4]);
  static const char *const load_rows[][5] = {
      {"body", "-", "(required)", "a moving body of the case", "the body a constant load acts on"},
      {"at_mm", "mm", "(required with force_n)", FB_PLANAR_POINT_RULE,
       "where its force acts, in the assembly configuration"},
      {"force_n", "N", "0, 0", FORCE_RULE, "its force fx, fy"},
      {"torque_n_m", "N m", "0", TORQUE_RULE, "its torque about +z"},
      {"active", "-", "always", ACTIVE_RULE,
       "when it acts: on every sample, or on one stroke of the prismatic joint its body slides "
       "in (else the case's one prismatic joint on a ground guide)"}};
  for (size_t i = 0; i < sizeof load_rows / sizeof load_rows[0]; i++)
    fprintf(f, "| [load.NAME] %s | %s | %s | %s | planar case: %s; in the analytic model, "
            "the references and every engine's models |\n", load_rows[i][0],
            load_rows[i][1], load_rows[i][2], load_rows[i][3], load_rows[i][4]);
}
