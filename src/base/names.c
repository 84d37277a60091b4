/* Names as column and key words, and their one rule (names.h). */
#include "names.h"

#include <stdio.h>

const char *fb_name_word(char *buf, size_t size, const char *name) {
  snprintf(buf, size, "%s", name);
  for (char *p = buf; *p; p++)
    if (*p == '-') *p = '_';
  return buf;
}

int fb_name_same_word(const char *a, const char *b) {
  for (;; a++, b++) {
    const char x = *a == '-' ? '_' : *a, y = *b == '-' ? '_' : *b;
    if (x != y) return 0;
    if (!x) return 1;
  }
}

int fb_name_clash(const char *const *names, int n, const char *name) {
  for (int k = 0; k < n; k++)
    if (fb_name_same_word(names[k], name)) return k;
  return -1;
}

const char *fb_name_fixed(const char *name, const char **what) {
  static const struct {
    const char *word, *what;
  } fixed[] = {{"drive", "the drive's columns drive_angle_rad and drive_torque_n_m"}};
  for (size_t k = 0; k < sizeof fixed / sizeof fixed[0]; k++)
    if (fb_name_same_word(fixed[k].word, name)) {
      if (what) *what = fixed[k].what;
      return fixed[k].word;
    }
  return NULL;
}
