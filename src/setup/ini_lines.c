#include "ini_lines.h"

#include <string.h>

#include "textsafe.h"

/* copies a [section] name or key (up to '=', ']' or the end) without blanks */
static void copy_word(char *dst, size_t size, const char *from, const char *stop) {
  while (*from == ' ' || *from == '\t') from++;
  size_t n = strcspn(from, stop);
  while (n && (from[n - 1] == ' ' || from[n - 1] == '\t')) n--;
  if (n >= size) n = size - 1;
  memcpy(dst, from, n);
  dst[n] = '\0';
}

/* length of the name from (up to '=', ']' or the end) without blanks */
static size_t word_length(const char *from, const char *stop) {
  while (*from == ' ' || *from == '\t') from++;
  size_t n = strcspn(from, stop);
  while (n && (from[n - 1] == ' ' || from[n - 1] == '\t')) n--;
  return n;
}

/* records a name longer than inih keeps; returns NULL (the parse stops) */
static char *long_name(fb_ini_lines *s, const char *from, size_t n, int section) {
  s->problem = FB_INI_LINE_LONG_NAME;
  s->problem_line = s->line;
  s->length = (int)n;
  s->name_is_section = section;
  copy_word(s->name, sizeof s->name, from, section ? "]" : "=");
  return NULL;
}

/* 1 when what follows a header's ']' is blank or a comment */
static int header_tail_ok(const char *p) {
  while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n') p++;
  return *p == '\0' || *p == ';' || *p == '#';
}

char *fb_ini_lines_read(char *str, int num, void *state) {
  fb_ini_lines *s = state;
  if (s->problem != FB_INI_LINE_OK) return NULL;
  /* byte by byte: fgets would hide a NUL byte (the line would silently end
   * there) and does not end a line at a lone CR */
  int k = 0, ch = EOF, nul = 0, ended = 0;
  while ((ch = getc(s->f)) != EOF) {
    if (ch == '\n') {
      ended = 1;
      break;
    }
    if (ch == '\r') {
      const int next = getc(s->f);
      if (next != '\n' && next != EOF) ungetc(next, s->f);
      ended = 1;
      break;
    }
    if (k < num - 2) {
      if (ch == '\0') nul = 1;
      str[k] = ch ? (char)ch : ' ';
    }
    k++;
  }
  if (k == 0 && !ended) return NULL; /* end of file */
  s->line++;
  const size_t kept = (size_t)(k < num - 2 ? k : num - 2);
  const size_t lead0 = strspn(str, " \t");
  const int comment = lead0 < kept && (str[lead0] == ';' || str[lead0] == '#');
  if ((k > num - 2 || k > FB_INI_LINE_MAX) && comment) {
    k = (int)kept; /* a long comment loses only comment text: kept whole as one line */
    if (k > FB_INI_LINE_MAX) k = FB_INI_LINE_MAX;
  } else if (k > num - 2 || k > FB_INI_LINE_MAX) {
    s->problem = FB_INI_LINE_TOO_LONG;
    s->problem_line = s->line;
    s->length = k;
    return NULL;
  }
  if (nul) {
    s->problem = FB_INI_LINE_NUL;
    s->problem_line = s->line;
    return NULL;
  }
  size_t bad;
  if (!comment && !fb_text_utf8_ok(str, (size_t)k, &bad)) {
    s->problem = FB_INI_LINE_NOT_UTF8;
    s->problem_line = s->line;
    s->length = (int)bad + 1;
    s->bad_byte = (unsigned char)str[bad];
    return NULL;
  }
  str[k] = '\n';
  str[k + 1] = '\0';
  const size_t lead = strspn(str, " \t");
  const char *body = str + lead;
  if (*body == '[') {
    const char *close = strchr(body, ']');
    if (close && !header_tail_ok(close + 1)) {
      s->problem = FB_INI_LINE_BAD_HEADER;
      s->problem_line = s->line;
      return NULL;
    }
    const size_t n = word_length(body + 1, "]\n");
    if (n > FB_INI_NAME_MAX) return long_name(s, body + 1, n, 1);
    copy_word(s->section, sizeof s->section, body + 1, "]");
    s->key[0] = '\0';
  } else if (*body && *body != ';' && *body != '#' && *body != '\n') {
    const int continues = s->continuation && lead > 0 && s->key[0];
    if (!continues && strchr(body, '=')) {
      const size_t n = word_length(body, "=");
      if (n > FB_INI_NAME_MAX) return long_name(s, body, n, 0);
      copy_word(s->key, sizeof s->key, body, "=");
    }
  }
  /* in [study] set and a case's [variant.NAME] set, ';' separates
   * overrides: blanks before it are dropped so inih never takes " ;" for the
   * start of an inline comment */
  const int set_line = strcmp(s->key, "set") == 0 &&
                       (s->continuation ? strcmp(s->section, "study") == 0
                                        : strncmp(s->section, "variant.", 8) == 0);
  if (set_line && *body != ';' && *body != '#') {
    char *w = str + lead;
    for (const char *r = str + lead; *r; r++) {
      if (*r == ';')
        while (w > str + lead && (w[-1] == ' ' || w[-1] == '\t')) w--;
      *w++ = *r;
    }
    *w = '\0';
  }
  /* case files have no continuation lines: leading blanks are dropped, so an
   * indented key line is a key line of its own (inih would otherwise append
   * it to the previous key's value) */
  if (!s->continuation && lead) memmove(str, str + lead, strlen(str + lead) + 1);
  return str;
}

const char *fb_ini_lines_problem(const fb_ini_lines *s, const char *path, char *buf, size_t size) {
  switch (s->problem) {
    case FB_INI_LINE_TOO_LONG:
      snprintf(buf, size, "%s:%d: the line is %d characters long, longer than %d%s", path,
               s->problem_line, s->length, FB_INI_LINE_MAX,
               s->continuation ? ": split its value over continuation lines (an indented line "
                                 "continues the value above it)"
                               : ": shorten it (a value is at most 255 characters)");
      break;
    case FB_INI_LINE_NUL:
      snprintf(buf, size, "%s:%d: a NUL byte in the line (a %s file is text)", path,
               s->problem_line, s->continuation ? "study" : "case");
      break;
    case FB_INI_LINE_BAD_HEADER:
      snprintf(buf, size, "%s:%d: text after a [section] header's closing ']': a header stands "
               "alone on its line ('[section]', then 'key = value' on the next lines)", path,
               s->problem_line);
      break;
    case FB_INI_LINE_LONG_NAME:
      snprintf(buf, size, "%s:%d: the %s name '%s...' is %d characters long, longer than the "
               "%d the INI parser keeps whole (it would cut it silently)%s", path,
               s->problem_line, s->name_is_section ? "section" : "key", s->name, s->length,
               FB_INI_NAME_MAX,
               !s->name_is_section ? ""
               : strncmp(s->name, "variant.", 8) == 0
                   ? ": a [variant.NAME] name is at most 41 characters"
                   : strncmp(s->name, "axis.", 5) == 0
                         ? ": an [axis.NAME] name is at most 44 characters"
                         : "");
      break;
    case FB_INI_LINE_NOT_UTF8:
      snprintf(buf, size, "%s:%d: byte 0x%02x at column %d is not UTF-8 text: save the %s file as "
               "UTF-8 (its values go into JSON, which holds UTF-8 only)", path, s->problem_line,
               s->bad_byte, s->length, s->continuation ? "study" : "case");
      break;
    default:
      snprintf(buf, size, "%s: no problem", path);
  }
  return buf;
}
