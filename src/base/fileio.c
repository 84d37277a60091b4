/* _GNU_SOURCE (meson.build): renameat2 */
#include "fileio.h"

#include "manifest.h"
#include "outdir.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* the kind of node sb describes, in words */
static const char *node_kind(const struct stat *sb) {
  if (S_ISFIFO(sb->st_mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(sb->st_mode)) return "a character device";
  if (S_ISBLK(sb->st_mode)) return "a block device";
  if (S_ISSOCK(sb->st_mode)) return "a socket";
  return "not a regular file";
}

fb_status fb_outpath_check(const char *path, const fb_outpath_rule *rule, int *exists,
                           fb_diag *diag) {
  const char *flag = rule && rule->flag ? rule->flag : "--out";
  if (exists) *exists = 0;
  if (!path[0])
    return fb_diag_set(diag, FB_ERR_ARG, "%s '': an empty path names no file: give a file name",
                       flag);
  struct stat sb;
  if (lstat(path, &sb) != 0) {
    if (errno == ENOENT) return FB_OK;
    return fb_diag_set(diag, FB_ERR_ARG, "%s %s: cannot be examined: %s", flag, path,
                       strerror(errno));
  }
  if (exists) *exists = 1;
  if (S_ISLNK(sb.st_mode)) {
    char to[PATH_MAX];
    const ssize_t n = readlink(path, to, sizeof to - 1);
    to[n > 0 ? n : 0] = '\0';
    return fb_diag_set(diag, FB_ERR_ARG, "%s %s: a symbolic link (to '%s'): fourbar never writes "
                       "through a link nor replaces one, even with --overwrite: give the path of "
                       "a regular file", flag, path, to);
  }
  if (S_ISDIR(sb.st_mode))
    return fb_diag_set(diag, FB_ERR_ARG, "%s %s: a folder: %s names the file to write, and "
                       "fourbar never replaces a folder with a file: give a file's path", flag,
                       path, flag);
  if (!S_ISREG(sb.st_mode))
    return fb_diag_set(diag, FB_ERR_ARG, "%s %s: %s: fourbar writes regular files only (whole, "
                       "then renamed into place, which would replace this node), even with "
                       "--overwrite: give a regular file's path", flag, path, node_kind(&sb));
  struct stat in;
  if (rule && rule->input && stat(rule->input, &in) == 0 && in.st_dev == sb.st_dev &&
      in.st_ino == sb.st_ino)
    return fb_diag_set(diag, FB_ERR_ARG, "%s %s: the file this command reads (%s): fourbar never "
                       "replaces its input, even with --overwrite: give another path", flag, path,
                       rule->input);
  if (rule && rule->overwrite) return FB_OK;
  if (rule && rule->writer) {
    /* the same command's earlier file, by the folder's manifest */
    char dir[4096];
    const char *slash = strrchr(path, '/');
    if (slash) snprintf(dir, sizeof dir, "%.*s", slash == path ? 1 : (int)(slash - path), path);
    else snprintf(dir, sizeof dir, ".");
    fb_manifest m;
    const char *owner = NULL;
    if (fb_manifest_read(&m, dir) == 0) owner = fb_manifest_owner(&m, slash ? slash + 1 : path);
    const int mine = owner && strcmp(owner, rule->writer) == 0;
    fb_manifest_free(&m);
    if (mine) return FB_OK;
    return fb_diag_set(diag, FB_ERR_ARG, "%s %s: %s exists and no fourbar %s wrote it (the "
                       "folder's %s does not list it as one): fourbar replaces a file it did not "
                       "write only with --overwrite: give --overwrite, or another %s", flag, dir,
                       path, rule->writer, FB_MANIFEST_NAME, flag);
  }
  return fb_diag_set(diag, FB_ERR_ARG, "%s %s: the file exists: fourbar replaces an existing "
                     "file only with --overwrite: give --overwrite, or another %s", flag, path,
                     flag);
}

fb_status fb_outfile_open_checked(fb_outfile *o, const char *path, const fb_outpath_rule *rule,
                                  fb_diag *diag) {
  int exists = 0;
  fb_status st = fb_outpath_check(path, rule, &exists, diag);
  if (st != FB_OK) {
    memset(o, 0, sizeof *o);
    o->cleanup = -1;
    return st;
  }
  st = fb_outfile_open(o, path, diag);
  if (st == FB_OK) o->noreplace = !exists;
  return st;
}

/* renames tmp to path, or with noreplace links it there only when nothing
 * is at path (an atomic test: RENAME_NOREPLACE, else link(2)) */
static int put_in_place(const char *tmp, const char *path, int noreplace) {
  if (!noreplace) return rename(tmp, path);
  if (renameat2(AT_FDCWD, tmp, AT_FDCWD, path, RENAME_NOREPLACE) == 0) return 0;
  if (errno != EINVAL && errno != ENOSYS) return -1;
  if (link(tmp, path) != 0) return -1; /* a file system without the flag */
  unlink(tmp);
  return 0;
}

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
  if (bad || chmod(o->tmp, 0644) != 0 || put_in_place(o->tmp, o->path, o->noreplace) != 0) {
    int e = errno;
    unlink(o->tmp);
    fb_cleanup_forget(o->cleanup);
    if (e == EEXIST && o->noreplace)
      return fb_diag_set(diag, FB_ERR_IO, "%s: another program created this file while fourbar "
                         "wrote it: nothing replaced, nothing of this output written", o->path);
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

fb_status fb_outfiles_begin(fb_outfiles *f, const char *dir, const char *writer,
                            const char *const *names, int n, const fb_outpath_rule *rule,
                            fb_diag *diag) {
  f->writer = writer;
  f->names = names;
  f->n = n;
  fb_status st = fb_outdir_lock(&f->dir, dir, 0, NULL, diag);
  if (st != FB_OK) return st;
  st = fb_outfiles_check(dir, writer, names, n, rule, diag);
  if (st != FB_OK) fb_outdir_release(&f->dir);
  return st;
}

fb_status fb_outfiles_check(const char *dir, const char *writer, const char *const *names, int n,
                            const fb_outpath_rule *rule, fb_diag *diag) {
  fb_outpath_rule r = *rule;
  r.writer = writer;
  fb_status st = FB_OK;
  for (int k = 0; k < n && st == FB_OK; k++) {
    char path[FB_OUTDIR_PATH + 320];
    snprintf(path, sizeof path, "%s/%s", dir, names[k]);
    st = fb_outpath_check(path, &r, NULL, diag);
  }
  return st;
}

fb_status fb_outfiles_end(fb_outfiles *f, fb_diag *diag) {
  const char *have[64 + 1];
  int m = 0;
  for (int k = 0; k < f->n && m < 64; k++) {
    char path[FB_OUTDIR_PATH + 320];
    snprintf(path, sizeof path, "%s/%s", f->dir.target, f->names[k]);
    struct stat sb;
    if (lstat(path, &sb) == 0 && S_ISREG(sb.st_mode)) have[m++] = f->names[k];
  }
  char log[FB_OUTDIR_PATH + 16];
  snprintf(log, sizeof log, "%s/.gnuplot.log", f->dir.target);
  struct stat sb;
  if (lstat(log, &sb) == 0 && S_ISREG(sb.st_mode)) have[m++] = ".gnuplot.log";
  const fb_status st = m ? fb_manifest_record(f->dir.target, f->writer, have, m, diag) : FB_OK;
  fb_outdir_release(&f->dir);
  return st;
}
