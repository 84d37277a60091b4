#define _POSIX_C_SOURCE 200809L
#include "fileio.h"

#include "outdir.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

fb_status fb_outfile_open(fb_outfile *o, const char *path, fb_diag *diag) {
  memset(o, 0, sizeof *o);
  o->cleanup = -1;
  if (snprintf(o->path, sizeof o->path, "%s", path) >= (int)sizeof o->path ||
      snprintf(o->tmp, sizeof o->tmp, "%s.tmp.%ld.XXXXXX", path, (long)getpid()) >=
          (int)sizeof o->tmp)
    return fb_diag_set(diag, FB_ERR_IO, "%s: path too long", path);
  int fd = mkstemp(o->tmp);
  if (fd < 0) return fb_diag_set(diag, FB_ERR_IO, "%s: cannot create: %s", path, strerror(errno));
  o->cleanup = fb_cleanup_add(o->tmp, 0);
  o->f = fdopen(fd, "w");
  if (!o->f) {
    fb_cleanup_forget(o->cleanup);
    close(fd);
    unlink(o->tmp);
    return fb_diag_set(diag, FB_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
  }
  return FB_OK;
}

fb_status fb_outfile_commit(fb_outfile *o, fb_diag *diag) {
  int bad = ferror(o->f);
  bad |= fflush(o->f) != 0;
  bad |= fsync(fileno(o->f)) != 0 && errno != EINVAL;
  bad |= fclose(o->f) != 0;
  o->f = NULL;
  if (bad || chmod(o->tmp, 0644) != 0 || rename(o->tmp, o->path) != 0) {
    int e = errno;
    unlink(o->tmp);
    fb_cleanup_forget(o->cleanup);
    return fb_diag_set(diag, FB_ERR_IO, "%s: write failed: %s", o->path, strerror(e));
  }
  fb_cleanup_forget(o->cleanup);
  return FB_OK;
}

void fb_outfile_abort(fb_outfile *o) {
  if (o->f) fclose(o->f);
  o->f = NULL;
  if (o->tmp[0]) unlink(o->tmp);
  fb_cleanup_forget(o->cleanup);
}

FILE *fb_fopen_regular(const char *path, int *not_regular) {
  struct stat sb;
  *not_regular = 0;
  if (stat(path, &sb) != 0) return NULL;
  if (!S_ISREG(sb.st_mode)) {
    *not_regular = 1;
    return NULL;
  }
  int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) return NULL;
  /* swapped between the stat and the open: check what was opened */
  if (fstat(fd, &sb) != 0 || !S_ISREG(sb.st_mode)) {
    close(fd);
    *not_regular = 1;
    return NULL;
  }
  fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  FILE *f = fdopen(fd, "r");
  if (!f) close(fd);
  return f;
}

fb_status fb_outdir_prepare(const char *dir, fb_diag *diag) {
  char buf[4096];
  if (snprintf(buf, sizeof buf, "%s", dir) >= (int)sizeof buf)
    return fb_diag_set(diag, FB_ERR_IO, "%s: path too long", dir);
  for (char *p = buf + 1; *p; p++) {
    if (*p != '/') continue;
    *p = '\0';
    if (mkdir(buf, 0755) != 0 && errno != EEXIST)
      return fb_diag_set(diag, FB_ERR_IO, "%s: cannot create output folder: %s", buf,
                         strerror(errno));
    *p = '/';
  }
  if (mkdir(buf, 0755) != 0 && errno != EEXIST)
    return fb_diag_set(diag, FB_ERR_IO, "%s: cannot create output folder: %s", dir,
                       strerror(errno));
  char probe[4200];
  snprintf(probe, sizeof probe, "%s/.fourbar-probe.XXXXXX", dir);
  int fd = mkstemp(probe);
  if (fd < 0)
    return fb_diag_set(diag, FB_ERR_IO, "%s: output folder is not writable: %s", dir,
                       strerror(errno));
  close(fd);
  unlink(probe);
  return FB_OK;
}
