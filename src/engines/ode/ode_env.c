#include "ode_env.h"

#include <ode/ode.h>
#include <stdarg.h>
#include <stdio.h>

static int ode_users = 0;

jmp_buf *fb_ode_escape = NULL;
static char last_error[512];

const char *fb_ode_last_error(void) { return last_error; }

static void *quarantined[64];
static int nquarantined;

void fb_ode_quarantine(void *object) {
  if (object && nquarantined < 64) quarantined[nquarantined++] = object;
}

/* inside a guard: keep the message and jump back instead of returning to
 * ODE's abort() */
static void escape(int errnum, const char *msg, va_list ap) {
  if (!fb_ode_escape) return;
  int n = snprintf(last_error, sizeof last_error, "ODE error %d: ", errnum);
  vsnprintf(last_error + n, sizeof last_error - (size_t)n, msg, ap);
  jmp_buf *to = fb_ode_escape;
  fb_ode_escape = NULL;
  longjmp(*to, 1);
}

static void report(const char *kind, int errnum, const char *msg, va_list ap) {
  fprintf(stderr, "fourbar: ODE %s %d: ", kind, errnum);
  vfprintf(stderr, msg, ap);
  fputc('\n', stderr);
  fflush(stderr);
}

/* dError and dDebug end the process after their handler returns (ODE 0.16,
 * ode/src/error.cpp): the message says so instead of a silent exit */
static void on_error(int errnum, const char *msg, va_list ap) {
  escape(errnum, msg, ap);
  report("error (fatal, the run ends)", errnum, msg, ap);
}
static void on_debug(int errnum, const char *msg, va_list ap) {
  escape(errnum, msg, ap);
  report("internal error (fatal, the run ends)", errnum, msg, ap);
}
static void on_message(int errnum, const char *msg, va_list ap) { report("message", errnum, msg, ap); }

void fb_ode_acquire(void) {
  if (ode_users++ == 0) {
    dInitODE2(0);
    dSetErrorHandler(on_error);
    dSetDebugHandler(on_debug);
    dSetMessageHandler(on_message);
  }
}

void fb_ode_release(void) {
  if (ode_users > 0 && --ode_users == 0) dCloseODE();
}
