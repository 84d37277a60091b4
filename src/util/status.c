#include "status.h"

#include <stdarg.h>
#include <stdio.h>

const char *fb_status_message(fb_status s) {
  switch (s) {
#define FB_STATUS_CASE(code, msg) \
  case code:                      \
    return msg;
    FB_STATUS_LIST(FB_STATUS_CASE)
#undef FB_STATUS_CASE
  }
  return "unknown status";
}

fb_status fb_diag_set(fb_diag *diag, fb_status s, const char *fmt, ...) {
  if (diag) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(diag->msg, sizeof diag->msg, fmt, ap);
    va_end(ap);
  }
  return s;
}

void fb_diag_clear(fb_diag *diag) {
  if (diag) diag->msg[0] = '\0';
}
