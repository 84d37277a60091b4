/* Text from data (case files, flags, paths, values echoed in messages) on
 * its way to a terminal or a text report, with every control character
 * escaped: no byte of data can move the cursor, clear the screen, hide
 * text, set a window title or write the clipboard (ECMA-48 control
 * functions: C0 and C1 controls, CSI and OSC sequences start with them).
 *
 * Escaped: the C0 controls U+0000 to U+001F except TAB and LF, DEL
 * (U+007F) and every byte that is not part of well-formed UTF-8 (RFC 3629:
 * no overlong form, no surrogate, nothing above U+10FFFF), each as \xHH;
 * the C1 controls U+0080 to U+009F (UTF-8 C2 80 to C2 9F) as \u00HH.
 * Printable ASCII, well-formed UTF-8 of other code points, TAB and LF pass
 * unchanged. The program's own terminal codes (a progress line's CR and
 * erase-line) go to fb_text_raw_stderr(), never through a safe stream. */
#ifndef FB_TEXTSAFE_H
#define FB_TEXTSAFE_H

#include <stddef.h>
#include <stdio.h>

/* Longest escape of one byte ("\u009b" is 6 characters). */
#define FB_TEXT_ESCAPE_MAX 6

/* Writes in (NUL-terminated) escaped into out (size bytes, always
 * NUL-terminated; the text is cut at a whole escape when out is too small)
 * and returns out. */
char *fb_text_escape(char *out, size_t size, const char *in);

/* The unit of text at p (n >= 1 bytes): returns 1 when it is escaped by the
 * rule above, 0 when it passes; *len receives its length in bytes (a
 * well-formed UTF-8 character whole, an escaped byte alone, a C1 control's
 * two bytes). For writers with their own escape syntax (a shell word). */
int fb_text_unit(const char *p, size_t n, size_t *len);

/* 1 when p[0..n) is well-formed UTF-8 (RFC 3629), else 0 with *bad_at (may
 * be NULL) the offset of the first byte that is not. */
int fb_text_utf8_ok(const char *p, size_t n, size_t *bad_at);

/* A write-only stream that passes what is written to it on to `to` with
 * every control character escaped (above). Closing it flushes it and, with
 * close_to = 1, closes `to`; with close_to = 0 `to` stays open (and holds
 * everything written). A write error of `to` is the stream's error (ferror,
 * errno). Returns NULL (errno set) when the stream cannot be made. Uses
 * glibc's fopencookie. */
FILE *fb_text_safe_stream(FILE *to, int close_to);

/* Replaces stdout and stderr by safe streams over the process's standard
 * output and error (stdout keeps line buffering on a terminal, full
 * buffering elsewhere; stderr stays unbuffered). Call once, first thing in
 * main; without it (a test executable) both stay as they are. */
void fb_text_safe_std(void);

/* The process's standard error as it was before fb_text_safe_std (stderr
 * itself when that was not called): for the program's own terminal codes
 * only, never for data. */
FILE *fb_text_raw_stderr(void);

#endif
