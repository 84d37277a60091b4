#include "outcome_text.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "case.h"
#include "resolution.h"
#include "run.h"

/* The under-resolved warning says what the user can change: with a fixed
 * step, auto or a smaller step; with auto, why auto did not keep the bound
 * (its contact estimate, resolution.h, fell short of the contact the run
 * met) and the fixed step that would. */
static void under_resolved_text(char *buf, size_t size, const fb_warning *w) {
  /* the step that keeps the bound at this contact's measured h omega_c, with
   * the margin h_s = auto re-chooses with (run.h, FB_H_AUTO_MARGIN): the
   * smaller step meets the stiffer states a little more often, and the
   * advice followed must not draw the warning again */
  const double h_fix =
      w->h > 0.0 && w->value > 0.0 ? w->h * w->limit / w->value * FB_H_AUTO_MARGIN : NAN;
  int n = snprintf(buf, size,
                   "under-resolved: h omega_c = %.3g at the %s joint exceeds %g (a contact "
                   "lasts about %.2g steps); ",
                   w->value, w->what[0] ? w->what : "clearance", w->limit, w->ratio);
  if (n < 0 || (size_t)n >= size) return;
  buf += n, size -= (size_t)n;
  switch (w->h_auto) {
    case FB_WARN_STEP_AUTO_CONTACT:
      snprintf(buf, size,
               "[solver] h_s = auto chose h = %.3g s for a force of 2 x the joint's largest "
               "ideal reaction and the contacts were stiffer; set [solver] h_s = %.2g or "
               "smaller to keep it below",
               w->h, h_fix);
      break;
    case FB_WARN_STEP_AUTO_CAP:
      snprintf(buf, size,
               "[solver] h_s = auto ran at its cap of one revolution / %g steps (h = %.3g s), "
               "its contact estimate asking for no smaller step; set [solver] h_s = %.2g or "
               "smaller to keep it below",
               FB_H_AUTO_STEPS_PER_REV, w->h, h_fix);
      break;
    default:
      snprintf(buf, size, "set [solver] h_s = auto, or a fixed step of %.2g s or smaller, to keep it below",
               h_fix);
      break;
  }
}

const char *fb_warning_text(char *buf, size_t size, const fb_warning *w) {
  switch (w->kind) {
    case FB_WARN_PENALTY_VALIDITY:
      snprintf(buf, size,
               "outside the penalty model's validity: penetration %.4g um is %.2f times the "
               "radial clearance %.4g um (above %g times)",
               w->value * 1e6, w->ratio, w->limit * 1e6, w->factor);
      break;
    case FB_WARN_DRIVE_SATURATED:
      snprintf(buf, size,
               "crank drive saturated: the crank is %.3g rad off its prescribed angle at "
               "t = %.6g s (raise %s)",
               w->value, w->t, w->what[0] ? w->what : "the drive's limit");
      break;
    case FB_WARN_ERROR_BOUND:
      snprintf(buf, size, "%s error %.3g is beyond the bound %.3g", w->what[0] ? w->what : "the",
               w->value, w->limit);
      break;
    case FB_WARN_UNDER_RESOLVED:
      under_resolved_text(buf, size, w);
      break;
    case FB_WARN_DIVERGENT:
      snprintf(buf, size,
               "divergent: the trajectory leaves %s's at t = %.6g s (crank angle %.1f deg; pin "
               "eccentricity or coupler angle beyond tolerance, %d impacts matched before it); "
               "peaks after it compare two different impact sequences",
               w->what[0] ? w->what : "the reference", w->t, w->value * 180.0 / M_PI,
               (int)w->ratio);
      break;
    default: snprintf(buf, size, "warning (%d)", (int)w->kind); break;
  }
  return buf;
}
