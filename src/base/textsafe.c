#include "textsafe.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

/* what the next bytes are: passed as they are, one byte escaped as \xHH, a
 * C1 control escaped as \u00HH, or the start of a UTF-8 sequence whose end
 * has not been written yet */
enum { UNIT_RAW, UNIT_HEX, UNIT_C1, UNIT_MORE };

/* bytes of the UTF-8 sequence lead byte b starts; 0 when b cannot lead one */
static int utf8_length(unsigned char b) {
  if (b < 0x80) return 1;
  if (b >= 0xC2 && b <= 0xDF) return 2;
  if (b >= 0xE0 && b <= 0xEF) return 3;
  if (b >= 0xF0 && b <= 0xF4) return 4;
  return 0;
}

/* 1 when b1 may follow lead byte b0 (RFC 3629, section 4: no overlong
 * form, no surrogate, nothing above U+10FFFF) */
static int utf8_second_ok(unsigned char b0, unsigned char b1) {
  if (b0 == 0xE0) return b1 >= 0xA0 && b1 <= 0xBF;
  if (b0 == 0xED) return b1 >= 0x80 && b1 <= 0x9F;
  if (b0 == 0xF0) return b1 >= 0x90 && b1 <= 0xBF;
  if (b0 == 0xF4) return b1 >= 0x80 && b1 <= 0x8F;
  return b1 >= 0x80 && b1 <= 0xBF;
}

/* classifies the unit at p (n >= 1 bytes; at_end: no more bytes follow)
 * and its length in *len */
static int next_unit(const unsigned char *p, size_t n, int at_end, size_t *len) {
  const unsigned char b = p[0];
  *len = 1;
  if (b < 0x80) return (b < 0x20 && b != '\t' && b != '\n') || b == 0x7f ? UNIT_HEX : UNIT_RAW;
  const int need = utf8_length(b);
  if (need == 0) return UNIT_HEX;
  for (int k = 1; k < need; k++) {
    if ((size_t)k >= n) return at_end ? UNIT_HEX : UNIT_MORE;
    if (k == 1 ? !utf8_second_ok(b, p[1]) : (p[k] & 0xC0) != 0x80) return UNIT_HEX;
  }
  *len = (size_t)need;
  return need == 2 && b == 0xC2 && p[1] <= 0x9F ? UNIT_C1 : UNIT_RAW;
}

int fb_text_unit(const char *p, size_t n, size_t *len) {
  return next_unit((const unsigned char *)p, n, 1, len) != UNIT_RAW;
}

int fb_text_utf8_ok(const char *p, size_t n, size_t *bad_at) {
  const unsigned char *u = (const unsigned char *)p;
  for (size_t i = 0; i < n;) {
    size_t len;
    if (u[i] >= 0x80 && next_unit(u + i, n - i, 1, &len) == UNIT_HEX) {
      if (bad_at) *bad_at = i;
      return 0;
    }
    i += u[i] < 0x80 ? 1 : len;
  }
  return 1;
}

/* where escaped text goes: a stream, or a string */
typedef struct {
  FILE *f;     /* a stream, or NULL */
  char *s;     /* else a string of size bytes */
  size_t size;
  size_t len;
  int full;    /* the string is full: the rest is dropped */
} sink;

static int put(sink *k, const char *p, size_t n) {
  if (k->f) return fwrite(p, 1, n, k->f) == n;
  if (k->full || k->len + n + 1 > k->size) {
    k->full = 1; /* cut at a whole unit */
    return 1;
  }
  memcpy(k->s + k->len, p, n);
  k->len += n;
  k->s[k->len] = '\0';
  return 1;
}

/* escapes p[0..n) into k; an unfinished UTF-8 sequence at the end (only
 * when !at_end) is left in pend (up to 3 bytes, *npend). 0 on a write error. */
static int escape_into(sink *k, const unsigned char *p, size_t n, int at_end, unsigned char *pend,
                       int *npend) {
  size_t i = 0;
  while (i < n) {
    size_t run = 0, len;
    int u;
    /* a run of bytes that pass as they are, written at once */
    while (i + run < n && (u = next_unit(p + i + run, n - i - run, at_end, &len)) == UNIT_RAW)
      run += len;
    if (run && !put(k, (const char *)p + i, run)) return 0;
    i += run;
    if (i >= n) break;
    u = next_unit(p + i, n - i, at_end, &len);
    if (u == UNIT_MORE) {
      *npend = (int)(n - i);
      memcpy(pend, p + i, n - i);
      return 1;
    }
    char e[FB_TEXT_ESCAPE_MAX + 1];
    if (u == UNIT_C1) snprintf(e, sizeof e, "\\u00%02x", p[i + 1]);
    else snprintf(e, sizeof e, "\\x%02x", p[i]);
    if (!put(k, e, strlen(e))) return 0;
    i += len;
  }
  return 1;
}

char *fb_text_escape(char *out, size_t size, const char *in) {
  if (size == 0) return out;
  out[0] = '\0';
  sink k = {.s = out, .size = size};
  unsigned char pend[4];
  int npend = 0;
  escape_into(&k, (const unsigned char *)in, strlen(in), 1, pend, &npend);
  return out;
}

/* ---- the stream ---------------------------------------------------------------- */

typedef struct {
  FILE *to;
  int close_to;
  unsigned char pend[4]; /* an unfinished UTF-8 sequence of the last write */
  int npend;
} safe_cookie;

static ssize_t safe_write(void *cookie, const char *buf, size_t size) {
  safe_cookie *c = cookie;
  const unsigned char *p = (const unsigned char *)buf;
  size_t n = size;
  unsigned char *joined = NULL;
  if (c->npend) { /* a character split between two writes */
    joined = malloc((size_t)c->npend + size);
    if (!joined) return 0;
    memcpy(joined, c->pend, (size_t)c->npend);
    memcpy(joined + c->npend, buf, size);
    p = joined;
    n = (size_t)c->npend + size;
    c->npend = 0;
  }
  sink k = {.f = c->to};
  const int ok = escape_into(&k, p, n, 0, c->pend, &c->npend);
  free(joined);
  return ok ? (ssize_t)size : 0; /* 0: an error (fopencookie(3)); errno is the write's */
}

static int safe_close(void *cookie) {
  safe_cookie *c = cookie;
  sink k = {.f = c->to};
  unsigned char pend[4];
  int npend = 0, rc = 0;
  if (c->npend && !escape_into(&k, c->pend, (size_t)c->npend, 1, pend, &npend)) rc = EOF;
  if (c->close_to) {
    if (fclose(c->to) != 0) rc = EOF;
  } else if (fflush(c->to) != 0) {
    rc = EOF;
  }
  free(c);
  return rc;
}

FILE *fb_text_safe_stream(FILE *to, int close_to) {
  safe_cookie *c = calloc(1, sizeof *c);
  if (!c) return NULL;
  c->to = to;
  c->close_to = close_to;
  const cookie_io_functions_t io = {.read = NULL, .write = safe_write, .seek = NULL,
                                    .close = safe_close};
  FILE *f = fopencookie(c, "w", io);
  if (!f) free(c);
  return f;
}

static FILE *raw_stdout, *raw_stderr;

/* at exit: the safe streams are closed (flushing what they hold into the
 * originals, freeing their cookies) and the originals put back, so nothing
 * written at exit is lost and a leak checker finds nothing held */
static void close_safe_std(void) {
  FILE *so = stdout, *se = stderr;
  if (!raw_stderr || so == raw_stdout) return;
  stdout = raw_stdout;
  stderr = raw_stderr;
  fclose(so);
  fclose(se);
  raw_stderr = NULL;
}

void fb_text_safe_std(void) {
  if (raw_stderr) return;
  FILE *out = stdout, *err = stderr;
  /* the originals write at once what the safe streams hand them, so an
   * error (a full disk, a closed pipe) is the safe stream's at once */
  setvbuf(out, NULL, _IONBF, 0);
  setvbuf(err, NULL, _IONBF, 0);
  FILE *so = fb_text_safe_stream(out, 0);
  FILE *se = so ? fb_text_safe_stream(err, 0) : NULL;
  if (!so || !se) { /* out of memory at start-up: plain streams */
    if (so) fclose(so);
    return;
  }
  /* whole lines on a terminal, and where stdout and stderr share a file or
   * pipe (2>&1): a message on stderr (unbuffered) then never lands inside a
   * line of stdout; elsewhere full buffering */
  struct stat o, e;
  const int shared = fstat(fileno(out), &o) == 0 && fstat(fileno(err), &e) == 0 &&
                     o.st_dev == e.st_dev && o.st_ino == e.st_ino;
  setvbuf(so, NULL, isatty(fileno(out)) || shared ? _IOLBF : _IOFBF, BUFSIZ);
  setvbuf(se, NULL, _IONBF, 0);
  stdout = so;
  stderr = se;
  raw_stdout = out;
  raw_stderr = err;
  atexit(close_safe_std);
}

FILE *fb_text_raw_stderr(void) { return raw_stderr ? raw_stderr : stderr; }
