/* Process-wide ODE set-up shared by the ODE scenes: dInitODE2 on first use,
 * dCloseODE on last release, and ODE's error, debug and message handlers
 * routed to the project's stderr reporting with a "fourbar: ODE" prefix.
 * Only files that build ODE worlds (scene.c, impact_ode.c) use it. */
#ifndef FB_ODE_ENV_H
#define FB_ODE_ENV_H

/* Initialises ODE on the first call; counts users. Not thread-safe. */
void fb_ode_acquire(void);

/* Releases one user; closes ODE when none is left. */
void fb_ode_release(void);

#endif
