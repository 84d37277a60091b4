/* The line reader that case and study files are read through (inih's
 * ini_parse_stream), so that no line is ever dropped, split or cut without
 * an error naming it.
 *
 * inih (Debian's build: INI_MAX_LINE 200, inline comments after " ;",
 * continuation lines) would, left alone, split a line longer than its
 * buffer into two lines, read a file with CR-only line endings as one line,
 * take "[drive] speed_rpm = 500" as the header [drive] and drop the rest,
 * and cut "set = a=1 ; b=2" at " ;". This reader:
 * - ends a line at LF, CR LF or a lone CR (classic Mac text);
 * - stops the parse at the first line longer than FB_INI_LINE_MAX, holding
 *   a NUL byte, whose [section] header has text after its closing ']'
 *   (other than a comment), whose section or key name is longer than
 *   FB_INI_NAME_MAX, or which (not a comment) is not UTF-8 text (its value
 *   would be dropped by a JSON writer), recording which line and why;
 * - in a case file (continuation = 0) drops leading blanks, so an indented
 *   key line is a key of its own;
 * - in a study file (continuation = 1) keeps them (an indented line
 *   continues the value), and in [study] set, where ';' separates the
 *   overrides, never lets " ;" start an inline comment. */
#ifndef FB_INI_LINES_H
#define FB_INI_LINES_H

#include <stdio.h>

/* Longest line, newline excluded, that inih can take whole [characters]. */
#define FB_INI_LINE_MAX 198
/* Longest [section] name and key name inih keeps whole (its MAX_SECTION
 * and MAX_NAME, 50 with the NUL, in Debian's build): a longer one it cuts
 * silently, so two long names could become one [characters]. */
#define FB_INI_NAME_MAX 49

typedef enum {
  FB_INI_LINE_OK = 0,
  FB_INI_LINE_TOO_LONG,   /* longer than FB_INI_LINE_MAX */
  FB_INI_LINE_NUL,        /* holds a NUL byte */
  FB_INI_LINE_BAD_HEADER, /* [section] followed by other text */
  FB_INI_LINE_LONG_NAME,  /* a section or key name longer than FB_INI_NAME_MAX */
  FB_INI_LINE_NOT_UTF8,   /* a line other than a comment holds a byte that is not UTF-8 */
} fb_ini_line_problem;

/* State of one file being read. Zero it, then set f and continuation. */
typedef struct {
  FILE *f;                      /* the file, opened for reading */
  int continuation;             /* 1: study file (indented lines continue a value); 0: case file */
  int line;                     /* lines read so far (1-based number of the last line) */
  fb_ini_line_problem problem;  /* why the parse stopped early, FB_INI_LINE_OK if it did not */
  int problem_line;             /* the line of the problem */
  int length;                   /* length of a too-long line or name [characters] */
  char name[FB_INI_NAME_MAX + 16]; /* the start of a too-long name */
  int name_is_section;          /* 1: the too-long name is a [section]'s, 0: a key's */
  int bad_byte;                 /* FB_INI_LINE_NOT_UTF8: the byte; its column is length */
  char section[64];             /* the section being read (as the reader saw its header) */
  char key[64];                 /* the key of the last key line */
} fb_ini_lines;

/* An ini_reader for ini_parse_stream(fb_ini_lines_read, &state, ...).
 * Returns NULL at the end of the file or at the first problem (recorded in
 * state). */
char *fb_ini_lines_read(char *str, int num, void *state);

/* One sentence for a recorded problem: "<path>:<line>: <what> ...; <fix>".
 * Returns buf. */
const char *fb_ini_lines_problem(const fb_ini_lines *s, const char *path, char *buf, size_t size);

#endif
