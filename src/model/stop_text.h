/* The words of a stop reason (outcome.h): summary.json's "status", the
 * printed table, report.md and error messages. Defined in stop_text.c;
 * outcome_text.h (the writers' words) includes this header. */
#ifndef FB_STOP_TEXT_H
#define FB_STOP_TEXT_H

#include <stddef.h>

#include "outcome.h"

/* "ok", or the reason with its figures, e.g. "unstable: penetration 20.1 um
 * at the crank-coupler joint exceeds the limit 14.5 um at t = 0.0123 s (step
 * 1230)", "nan at t = ... (step k)", "ode-error: <ODE's message> at t = ...
 * (step k)", "reference integration failed at t = ... s: <GSL's message>",
 * "reference: stopped: step budget of N steps (M per sample) spent at t =
 * ... s of ... s". Writes into buf (size bytes) and returns it. */
const char *fb_stop_text(char *buf, size_t size, const fb_stop *s);

/* One word per kind: "ok", "penetration", "non-finite", "step-budget",
 * "allocation", "solver" (case files' [expect] reason uses them). */
const char *fb_stop_kind_name(fb_stop_kind k);

/* The kind named by word (fb_stop_kind_name; "nan" is non-finite), or
 * FB_STOP_COUNT when unknown. */
fb_stop_kind fb_stop_kind_parse(const char *word);

#endif
