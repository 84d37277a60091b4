#include "json_columns.h"

#include <jansson.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "numfmt.h"

int fb_json_open_object(FILE *f, const json_t *o, size_t flags) {
  if (!json_is_object(o) || json_object_size(o) == 0) return -1;
  char *s = json_dumps(o, flags);
  if (!s) return -1;
  const size_t n = strlen(s);
  const int bad = n < 2 || s[n - 1] != '}' || fwrite(s, 1, n - 1, f) != n - 1;
  free(s);
  return bad ? -1 : 0;
}

/* a key the page can read and no text can break out of */
static int plain_key(const char *key) {
  if (!*key) return 0;
  for (const char *p = key; *p; p++)
    if (*p < 0x20 || *p >= 0x7f || *p == '"' || *p == '\\' || *p == '/') return 0;
  return 1;
}

/* bytes gathered before one fwrite: a few thousand numbers */
#define COLUMN_BUFFER 65536

int fb_json_column(FILE *f, const char *key, const double *y, const size_t *idx, size_t m, double scale,
                   int digits) {
  if (!plain_key(key) || fprintf(f, ",\"%s\":[", key) < 0) return -1;
  char buf[COLUMN_BUFFER];
  size_t used = 0;
  for (size_t k = 0; k < m; k++) {
    if (used + FB_NUMFMT_G12_SIZE + 1 > sizeof buf) {
      if (fwrite(buf, 1, used, f) != used) return -1;
      used = 0;
    }
    if (k) buf[used++] = ',';
    const double v = y[idx[k]] * scale;
    if (isfinite(v)) {
      used += fb_numfmt_g(buf + used, v, digits);
    } else {
      memcpy(buf + used, "null", 4);
      used += 4;
    }
  }
  buf[used++] = ']';
  return fwrite(buf, 1, used, f) == used ? 0 : -1;
}
