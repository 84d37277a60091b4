#include "xmltext.h"

#include <string.h>

/* a control character XML 1.0 does not allow (2.2 [2]) */
static int forbidden(unsigned char c) { return (c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7f; }

char *fb_xml_escape(char *out, size_t size, const char *in) {
  size_t n = 0;
  if (!size) return out;
  for (const unsigned char *p = (const unsigned char *)in; *p; p++) {
    const char *rep = NULL;
    char one[2] = {(char)*p, '\0'};
    switch (*p) {
      case '&': rep = "&amp;"; break;
      case '<': rep = "&lt;"; break;
      case '>': rep = "&gt;"; break;
      case '"': rep = "&quot;"; break;
      case '\'': rep = "&apos;"; break;
      default: rep = forbidden(*p) ? "?" : one; break;
    }
    const size_t l = strlen(rep);
    if (n + l >= size) break;
    memcpy(out + n, rep, l);
    n += l;
  }
  out[n] = '\0';
  return out;
}

char *fb_xml_comment_text(char *out, size_t size, const char *in) {
  size_t n = 0;
  if (!size) return out;
  for (const unsigned char *p = (const unsigned char *)in; *p && n + 1 < size; p++) {
    if (*p == '-' && n > 0 && out[n - 1] == '-') {
      if (n + 2 >= size) break;
      out[n++] = ' ';
    }
    out[n++] = forbidden(*p) ? '?' : (char)*p;
  }
  if (n > 0 && out[n - 1] == '-') {
    if (n + 1 < size) out[n++] = ' ';
    else out[n - 1] = ' ';
  }
  out[n] = '\0';
  return out;
}
