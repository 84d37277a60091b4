/* Process-wide ODE set-up shared by the ODE worlds: dInitODE2 on first use,
 * dCloseODE on last release, and ODE's error, debug and message handlers
 * routed to the project's stderr reporting with a "fourbar: ODE" prefix.
 * Only files that build or step ODE worlds (ode_world.c, ode_step.c,
 * ode_kit.c) use it. */
#ifndef FB_ODE_ENV_H
#define FB_ODE_ENV_H

/* Initialises ODE on the first call; counts users. Not thread-safe. */
void fb_ode_acquire(void);

/* Releases one user; closes ODE when none is left. */
void fb_ode_release(void);

#include <setjmp.h>

/* ODE's dError and dDebug (a failed internal check such as dxNormalize4's
 * "!bSafeNormalize4Fault") end the process with abort() once their handler
 * returns. While fb_ode_escape points at a jmp_buf, the handler keeps the
 * message (fb_ode_last_error) and longjmps there instead, so the caller can
 * stop that model with a named reason and destroy its world; outside such a
 * guard ODE's behaviour is unchanged. Set it only around calls into ODE,
 * restore it right after. */
extern jmp_buf *fb_ode_escape;

/* The message of the last ODE error caught by the guard. */
const char *fb_ode_last_error(void);

/* Keeps ODE objects that an escaped error left mid-step and that must never
 * be touched again (destroying them fails ODE's own checks): they stay
 * reachable for the life of the process, so leak checkers see retained
 * memory, not a leak. At most 64 are kept; later ones are dropped. */
void fb_ode_quarantine(void *object);

#endif
