#include "ode_env.h"

#include <ode/ode.h>
#include <stdarg.h>
#include <stdio.h>

static int ode_users = 0;

static void ode_report(int errnum, const char *msg, va_list ap) {
  fprintf(stderr, "fourbar: ODE message %d: ", errnum);
  vfprintf(stderr, msg, ap);
  fputc('\n', stderr);
}

void fb_ode_acquire(void) {
  if (ode_users++ == 0) {
    dInitODE2(0);
    dSetErrorHandler(ode_report);
    dSetDebugHandler(ode_report);
    dSetMessageHandler(ode_report);
  }
}

void fb_ode_release(void) {
  if (ode_users > 0 && --ode_users == 0) dCloseODE();
}
