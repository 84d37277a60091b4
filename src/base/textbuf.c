#include "textbuf.h"

#include <stdarg.h>
#include <stdio.h>

#include "xmltext.h"

void fb_text_put(fb_text *t, const char *fmt, ...) {
  if (t->overflow) return;
  va_list ap;
  va_start(ap, fmt);
  const int n = vsnprintf(t->buf + t->len, t->size - t->len, fmt, ap);
  va_end(ap);
  if (n < 0 || (size_t)n >= t->size - t->len) {
    t->overflow = 1;
    if (t->size) t->buf[t->len] = '\0';
    return;
  }
  t->len += (size_t)n;
}

void fb_text_comment(fb_text *t, const char *fmt, ...) {
  char raw[4096], safe[2 * 4096];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(raw, sizeof raw, fmt, ap);
  va_end(ap);
  fb_text_put(t, "<!-- %s -->", fb_xml_comment_text(safe, sizeof safe, raw));
}
