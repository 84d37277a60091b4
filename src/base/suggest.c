#include "suggest.h"

#include <string.h>

int fb_edit_distance(const char *a, const char *b) {
  const size_t la = strlen(a), lb = strlen(b);
  if (la > FB_SUGGEST_MAX_LEN || lb > FB_SUGGEST_MAX_LEN) return FB_SUGGEST_FAR;
  int d[FB_SUGGEST_MAX_LEN + 1][FB_SUGGEST_MAX_LEN + 1];
  for (size_t i = 0; i <= la; i++) d[i][0] = (int)i;
  for (size_t j = 0; j <= lb; j++) d[0][j] = (int)j;
  for (size_t i = 1; i <= la; i++)
    for (size_t j = 1; j <= lb; j++) {
      const int sub = d[i - 1][j - 1] + (a[i - 1] != b[j - 1]);
      const int del = d[i - 1][j] + 1, ins = d[i][j - 1] + 1;
      int best = sub < del ? (sub < ins ? sub : ins) : (del < ins ? del : ins);
      /* two adjacent characters swapped ("lenght") count as one error */
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] &&
          d[i - 2][j - 2] + 1 < best)
        best = d[i - 2][j - 2] + 1;
      d[i][j] = best;
    }
  return d[la][lb];
}

int fb_suggest_bound(const char *word) {
  const int n = (int)strlen(word);
  return n <= 4 ? 1 : n <= 8 ? 2 : 2 + (n - 5) / 4;
}

const char *fb_suggest(const char *word, const char *const *names, int n) {
  const char *best = NULL;
  int bd = fb_suggest_bound(word) + 1;
  for (int i = 0; i < n; i++) {
    const int d = fb_edit_distance(word, names[i]);
    if (d < bd) bd = d, best = names[i];
  }
  return best;
}
