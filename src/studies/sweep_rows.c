/* The rows files of a sweep: reading, repair, appending (sweep_rows.h). */
#define _POSIX_C_SOURCE 200809L
#include "sweep_rows.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fileio.h"
#include "study.h"

int fb_sweep_rows_add(fb_sweep_rowset *r, const char *line) {
  if (r->n == r->cap) {
    size_t cap = r->cap ? 2 * r->cap : 64;
    char **p = realloc(r->rows, cap * sizeof *p);
    if (!p) return 0;
    r->rows = p;
    r->cap = cap;
  }
  r->rows[r->n] = strdup(line);
  return r->rows[r->n++] != NULL;
}

void fb_sweep_rows_free(fb_sweep_rowset *r) {
  for (size_t k = 0; k < r->n; k++) free(r->rows[k]);
  free(r->rows);
  memset(r, 0, sizeof *r);
}

int fb_sweep_rows_read(const char *path, fb_sweep_rowset *r, int repair, char *err,
                       size_t err_size) {
  int not_regular;
  FILE *f = fb_fopen_regular(path, &not_regular); /* a FIFO never blocks (fileio.h) */
  if (!f) {
    const int e = errno;
    snprintf(err, err_size, "%s: cannot read: %s", path,
             not_regular ? "not a regular file" : strerror(e));
    return !not_regular && e == ENOENT ? 0 : -1;
  }
  char *line = NULL;
  size_t cap = 0;
  ssize_t len;
  int bad = 0, lineno = 0;
  while ((len = getline(&line, &cap, f)) > 0) {
    lineno++;
    long ix;
    size_t of;
    char why[128] = "the line does not end (a writer was killed mid-row)";
    if (memchr(line, '\0', (size_t)len)) snprintf(why, sizeof why, "a NUL byte in the line");
    else if (line[len - 1] == '\n' && fb_study_row_parse(line, &ix, &of, why, sizeof why)) {
      if (!fb_sweep_rows_add(r, line)) {
        snprintf(err, err_size, "%s: out of memory for %zu rows", path, r->n);
        free(line);
        fclose(f);
        return -1;
      }
      continue;
    }
    if (!repair) {
      snprintf(err, err_size, "%s:%d: not a row of a study: %s", path, lineno, why);
      free(line);
      fclose(f);
      return -1;
    }
    bad = 1;
  }
  free(line);
  fclose(f);
  if (bad && repair) {
    fb_outfile o;
    fb_diag d;
    if (fb_outfile_open(&o, path, &d) != FB_OK) return -1;
    for (size_t k = 0; k < r->n; k++) fputs(r->rows[k], o.f);
    if (fb_outfile_commit(&o, &d) != FB_OK) return -1;
    fprintf(stderr, "fourbar sweep: %s: dropped a broken or incomplete row (an interrupted run); "
            "it is computed again\n", path);
  }
  return 0;
}

int fb_sweep_rows_append(int fd, const char *line) {
  size_t l = strlen(line), off = 0;
  while (off < l) {
    ssize_t w = write(fd, line + off, l - off);
    if (w < 0) {
      if (errno == EINTR) continue;
      return -1;
    }
    off += (size_t)w;
  }
  return fsync(fd);
}

void fb_sweep_rows_beside(char *out, size_t size, const char *rows_path, const char *suffix) {
  snprintf(out, size, "%.*s%s", (int)(strlen(rows_path) - 6), rows_path, suffix);
}
