/* The words of a stop reason (outcome.h): model floor, so that code below
 * the writers that reports a stop in an error message (the reference's
 * integration, physics/reference.c) says it in the writers' words. The
 * warnings' words need the run's constants and stay in outcome_text.c. */
#include "stop_text.h"

#include <stdio.h>
#include <string.h>

#include "case.h"

const char *fb_stop_text(char *buf, size_t size, const fb_stop *s) {
  const char *engine = s->engine ? s->engine : "engine";
  const char *joint = s->joint_name ? s->joint_name : fb_joint_name(s->joint);
  char at[48] = "";
  if (s->step > 0) snprintf(at, sizeof at, " (step %zu)", s->step);
  switch (s->kind) {
    case FB_STOP_NONE: snprintf(buf, size, "ok"); break;
    case FB_STOP_PENETRATION:
      snprintf(buf, size,
               "unstable: penetration %.4g um at the %s joint exceeds the limit %.4g um at "
               "t = %.6g s%s",
               s->value * 1e6, joint, s->limit * 1e6, s->t, at);
      break;
    case FB_STOP_NONFINITE:
      if (s->step > 0) snprintf(buf, size, "nan at t = %.6g s%s", s->t, at);
      else snprintf(buf, size, "%s: non-finite state at t = %g s", engine, s->t);
      break;
    case FB_STOP_STEP_BUDGET:
      snprintf(buf, size,
               "%s: stopped: step budget of %.0f steps (%.0f per sample) spent at t = %g s of "
               "%g s",
               engine, s->value, s->limit, s->t, s->t_end);
      break;
    case FB_STOP_ALLOCATION:
      snprintf(buf, size, "%s: out of memory at t = %.6g s%s", engine, s->t, at);
      break;
    case FB_STOP_SOLVER:
      if (s->step > 0) snprintf(buf, size, "%s-error: %s at t = %.6g s%s", engine, s->detail, s->t, at);
      else snprintf(buf, size, "%s integration failed at t = %g s: %s", engine, s->t, s->detail);
      break;
    case FB_STOP_ALIASED:
      snprintf(buf, size,
               "aliased: the matched contact row at the %s joint met omega_d h = %.3g at "
               "t = %.6g s%s, past %.3g (pi would lose the row's spring); the largest usable "
               "step is %.3g s (or h_s = auto)",
               joint, s->value, s->t, at, s->limit, s->h_max);
      break;
    case FB_STOP_WALL_TIME:
      snprintf(buf, size,
               "%s: stopped: the run's wall-time limit [run] max_wall_s = %g s was reached at "
               "t = %.6g s of %g s%s (raise max_wall_s, or lower revolutions or the cost of a step)",
               engine, s->limit, s->t, s->t_end, at);
      break;
    default: snprintf(buf, size, "stopped (%d)", (int)s->kind); break;
  }
  return buf;
}

static const char *const stop_names[FB_STOP_COUNT] = {"ok", "penetration", "non-finite",
                                                      "step-budget", "allocation", "solver",
                                                      "aliased", "wall-time"};

const char *fb_stop_kind_name(fb_stop_kind k) {
  return (k >= 0 && k < FB_STOP_COUNT) ? stop_names[k] : "?";
}

fb_stop_kind fb_stop_kind_parse(const char *word) {
  if (!word) return FB_STOP_COUNT;
  if (strcmp(word, "nan") == 0) return FB_STOP_NONFINITE;
  for (int k = 0; k < FB_STOP_COUNT; k++)
    if (strcmp(word, stop_names[k]) == 0) return (fb_stop_kind)k;
  return FB_STOP_COUNT;
}
