/* The study figure's CSV reader: a sweep's points.csv (as
 * fb_study_write_csv writes it: quotes only around status) read into text
 * cells, and a cell as a number. */
#include "figures_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void fig_csv_free(study_csv *t) {
  for (size_t r = 0; r < t->nrow; r++) {
    for (int c = 0; c < t->ncol; c++) free(t->cell[r][c]);
    free(t->cell[r]);
  }
  for (int c = 0; c < t->ncol; c++) free(t->head[c]);
  free(t->cell);
  free(t->head);
  memset(t, 0, sizeof *t);
}

/* splits one CSV line of fb_study_write_csv (quotes only around status) */
static int csv_split(const char *line, char **out, int max) {
  int n = 0;
  const char *p = line;
  while (n < max) {
    char buf[2048];
    size_t k = 0;
    if (*p == '"') {
      for (p++; *p && !(*p == '"' && p[1] != '"'); p++) {
        if (*p == '"') p++;
        if (k + 1 < sizeof buf) buf[k++] = *p;
      }
      if (*p == '"') p++;
    } else {
      for (; *p && *p != ',' && *p != '\n' && *p != '\r'; p++)
        if (k + 1 < sizeof buf) buf[k++] = *p;
    }
    buf[k] = '\0';
    out[n++] = strdup(buf);
    if (*p != ',') break;
    p++;
  }
  return n;
}

#define STUDY_FIG_MAX_COLS 256
#define STUDY_FIG_MAX_ROWS 200000 /* a larger grid draws its first rows */

int fig_csv_read(study_csv *t, const char *path) {
  memset(t, 0, sizeof *t);
  t->status_col = -1;
  FILE *f = fopen(path, "r");
  if (!f) return 0;
  static char line[1 << 16];
  char *cells[STUDY_FIG_MAX_COLS];
  if (fgets(line, sizeof line, f)) {
    t->ncol = csv_split(line, cells, STUDY_FIG_MAX_COLS);
    t->head = malloc((size_t)t->ncol * sizeof *t->head);
    for (int c = 0; c < t->ncol; c++) {
      t->head[c] = cells[c];
      if (strcmp(cells[c], "status") == 0) t->status_col = c;
    }
  }
  size_t cap = 0;
  while (t->ncol && t->nrow < STUDY_FIG_MAX_ROWS && fgets(line, sizeof line, f)) {
    int n = csv_split(line, cells, STUDY_FIG_MAX_COLS);
    if (t->nrow == cap) {
      cap = cap ? 2 * cap : 64;
      t->cell = realloc(t->cell, cap * sizeof *t->cell);
    }
    char **row = calloc((size_t)t->ncol, sizeof *row);
    for (int c = 0; c < t->ncol; c++) row[c] = c < n ? cells[c] : strdup("");
    for (int c = t->ncol; c < n; c++) free(cells[c]);
    t->cell[t->nrow++] = row;
  }
  fclose(f);
  return t->ncol > 0 && t->status_col >= 0;
}

int fig_csv_col(const study_csv *t, const char *name) {
  for (int c = 0; c < t->ncol; c++)
    if (strcmp(t->head[c], name) == 0) return c;
  return -1;
}

double fig_cell_num(const char *text) {
  char *end;
  double v = strtod(text, &end);
  return end != text && *end == '\0' && isfinite(v) ? v : NAN;
}
