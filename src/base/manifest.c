/* _GNU_SOURCE (meson.build): flock */
#include "manifest.h"

#include <errno.h>
#include <fcntl.h>
#include <sys/file.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

void fb_manifest_free(fb_manifest *m) {
  free(m->entry);
  m->entry = NULL;
  m->n = m->cap = 0;
}

int fb_manifest_set(fb_manifest *m, const char *writer, const char *name) {
  for (int i = 0; i < m->n; i++)
    if (strcmp(m->entry[i].name, name) == 0) {
      snprintf(m->entry[i].writer, sizeof m->entry[i].writer, "%s", writer);
      return 0;
    }
  if (m->n == m->cap) {
    const int cap = m->cap ? 2 * m->cap : 64;
    fb_manifest_entry *e = realloc(m->entry, (size_t)cap * sizeof *e);
    if (!e) return -1;
    m->entry = e;
    m->cap = cap;
  }
  snprintf(m->entry[m->n].writer, sizeof m->entry[m->n].writer, "%s", writer);
  snprintf(m->entry[m->n].name, sizeof m->entry[m->n].name, "%s", name);
  m->n++;
  return 0;
}

const char *fb_manifest_owner(const fb_manifest *m, const char *name) {
  for (int i = 0; i < m->n; i++)
    if (strcmp(m->entry[i].name, name) == 0) return m->entry[i].writer;
  return NULL;
}

int fb_manifest_read(fb_manifest *m, const char *dir) {
  memset(m, 0, sizeof *m);
  char path[4096 + sizeof FB_MANIFEST_NAME + 1];
  snprintf(path, sizeof path, "%s/%s", dir, FB_MANIFEST_NAME);
  struct stat sb;
  if (lstat(path, &sb) != 0 || !S_ISREG(sb.st_mode)) return 0;
  FILE *f = fopen(path, "r");
  if (!f) return 0;
  m->present = 1;
  char line[FB_MANIFEST_WRITER + FB_MANIFEST_FILE + 8];
  while (fgets(line, sizeof line, f)) {
    line[strcspn(line, "\n")] = '\0';
    const size_t w = strcspn(line, " ");
    if (line[0] == '#' || w == 0 || w >= FB_MANIFEST_WRITER || line[w] != ' ' || !line[w + 1])
      continue;
    line[w] = '\0';
    const char *name = line + w + 1;
    if (strchr(name, '/') || strcmp(name, ".") == 0 || strcmp(name, "..") == 0) continue;
    if (fb_manifest_set(m, line, name) != 0) {
      fclose(f);
      fb_manifest_free(m);
      return -1;
    }
  }
  fclose(f);
  return 0;
}

fb_status fb_manifest_write(const fb_manifest *m, const char *dir, fb_diag *diag) {
  char path[4096 + sizeof FB_MANIFEST_NAME + 1], tmp[sizeof path + 48];
  snprintf(path, sizeof path, "%s/%s", dir, FB_MANIFEST_NAME);
  /* the temporary name has the form outdir.c cleans when its writer is gone */
  snprintf(tmp, sizeof tmp, "%s.tmp.%ld.XXXXXX", path, (long)getpid());
  const int fd = mkstemp(tmp);
  if (fd < 0) return fb_diag_set(diag, FB_ERR_IO, "%s: cannot create: %s", path, strerror(errno));
  FILE *f = fdopen(fd, "w");
  if (!f) {
    close(fd);
    unlink(tmp);
    return fb_diag_set(diag, FB_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
  }
  fputs("# fourbar: the files fourbar wrote into this folder, one per line: <command> <file>.\n"
        "# A run replaces only the files listed as a run's and keeps every other file here.\n",
        f);
  for (int i = 0; i < m->n; i++) fprintf(f, "%s %s\n", m->entry[i].writer, m->entry[i].name);
  int bad = ferror(f);
  bad |= fflush(f) != 0;
  bad |= fclose(f) != 0;
  if (bad || chmod(tmp, 0644) != 0 || rename(tmp, path) != 0) {
    const int e = errno;
    unlink(tmp);
    return fb_diag_set(diag, FB_ERR_IO, "%s: write failed: %s", path, strerror(e));
  }
  return FB_OK;
}

fb_status fb_manifest_record(const char *dir, const char *writer, const char *const *names, int n,
                             fb_diag *diag) {
  /* writers of parts of one folder (sweep shards) share its lock: the
   * read-modify-write of the manifest is one at a time (flock on the folder) */
  const int dfd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) flock(dfd, LOCK_EX);
  fb_manifest m;
  fb_status st = FB_OK;
  if (fb_manifest_read(&m, dir) != 0)
    st = fb_diag_set(diag, FB_ERR_NOMEM, "%s: out of memory for its manifest", dir);
  for (int i = 0; i < n && st == FB_OK; i++)
    if (fb_manifest_set(&m, writer, names[i]) != 0)
      st = fb_diag_set(diag, FB_ERR_NOMEM, "%s: out of memory for its manifest", dir);
  if (st == FB_OK) st = fb_manifest_write(&m, dir, diag);
  fb_manifest_free(&m);
  if (dfd >= 0) close(dfd); /* and its lock */
  return st;
}
