/* Status codes and the caller-owned diagnostic buffer shared by every module.
 *
 * Every fallible public function returns an fb_status and, on failure, fills a
 * caller-owned fb_diag with one sentence naming the field, the value and the
 * rule it breaks (the pattern of MuJoCo's mj_loadXML error buffer).
 */
#ifndef FB_STATUS_H
#define FB_STATUS_H

#include <stddef.h>

/* X-macro list: code, message. */
#define FB_STATUS_LIST(X)                                             \
  X(FB_OK, "ok")                                                      \
  X(FB_ERR_ARG, "invalid argument")                                   \
  X(FB_ERR_IO, "input/output error")                                  \
  X(FB_ERR_PARSE, "malformed input")                                  \
  X(FB_ERR_RANGE, "value out of range")                               \
  X(FB_ERR_ASSEMBLY, "linkage cannot be assembled")                   \
  X(FB_ERR_NUMERIC, "numerical failure")                              \
  X(FB_ERR_NOMEM, "out of memory")

typedef enum {
#define FB_STATUS_ENUM(code, msg) code,
  FB_STATUS_LIST(FB_STATUS_ENUM)
#undef FB_STATUS_ENUM
} fb_status;

#define FB_DIAG_SIZE 1024

/* A diagnostic message owned by the caller; empty when nothing went wrong. */
typedef struct {
  char msg[FB_DIAG_SIZE]; /* one sentence: where, what value, which rule */
} fb_diag;

/* Formats a message into diag (if diag is not NULL) and returns status s,
 * so that callers can write `return fb_diag_set(d, FB_ERR_RANGE, "...")`. */
fb_status fb_diag_set(fb_diag *diag, fb_status s, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Writes x into buf (size bytes) with the fewest significant digits (at most
 * 15) that read back as exactly x, else with 15 (a size typed as 500.0001
 * prints as 500.0001, not as %g's 500), and returns buf: for numbers a user
 * typed, quoted in messages. */
const char *fb_diag_number(char *buf, size_t size, double x);

/* As fb_diag_number with up to 17 significant digits, so that every double
 * reads back exactly: a value a user typed (a flag) echoed in the message
 * that refuses it is never rounded into the range it breaks
 * (1.0000000000000002 is not "1"). Returns buf. */
const char *fb_diag_exact(char *buf, size_t size, double x);

/* fb_diag_exact in a buffer of its own, for a printf argument ("%s"); the
 * buffer lives until the end of the enclosing block (C11 6.5.2.5). */
#define FB_NUM(x) fb_diag_exact((char[32]){0}, 32, (x))

/* Clears diag (if not NULL). */
void fb_diag_clear(fb_diag *diag);

#endif
