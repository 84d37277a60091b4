/* A text written into a caller's buffer piece by piece (printf formats),
 * its overflow remembered instead of checked at every piece: the MJCF and
 * SDF writers; XML comments escaped in one place (fb_text_comment). */
#ifndef FB_TEXTBUF_H
#define FB_TEXTBUF_H

#include <stddef.h>

typedef struct {
  char *buf;    /* the caller's buffer, NUL-terminated after every piece */
  size_t size;  /* its size [bytes] */
  size_t len;   /* bytes written, without the NUL */
  int overflow; /* 1: a piece did not fit; it and every later piece dropped */
} fb_text;

/* appends printf(fmt, ...) to t, or sets t->overflow when it does not fit
 * (then t->buf holds the pieces before it, whole) */
void fb_text_put(fb_text *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* appends "<!-- " + printf(fmt, ...) + " -->" as a well-formed XML comment:
 * the formatted text (at most 4095 bytes) escaped by fb_xml_comment_text
 * (xmltext.h), whatever data it holds (a case's name "x--y") */
void fb_text_comment(fb_text *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

#endif
