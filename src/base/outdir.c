/* _GNU_SOURCE (meson.build): renameat2, syscall */
#include "outdir.h"

#include "manifest.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

/* ---- signal-time cleanup ------------------------------------------------------ */

#define CLEANUP_SLOTS 64

typedef struct {
  volatile sig_atomic_t used;
  int is_dir;
  pid_t owner; /* a forked worker inherits the table: only the owner cleans */
  char path[FB_OUTDIR_PATH];
} cleanup_slot;

static cleanup_slot slots[CLEANUP_SLOTS];

/* The mark of a folder this program made beside an output folder (its
 * staging folder, or the old set it moves aside before removing it): a file
 * .fourbar-own.<pid> inside it, <pid> the maker's. Only a folder holding
 * the mark of the process it is removed for loses its files: a name proves
 * nothing (a user's folder, or a symbolic link to one, may be called
 * .<out>.staging.<pid>). */
#define OWN_MARK ".fourbar-own."

/* the mark's name for pid into buf (32 bytes), with system-call-free code
 * only (it runs in a signal handler) */
static void mark_name(char buf[32], long pid) {
  char num[24];
  int k = (int)sizeof num - 1;
  num[k] = '\0';
  do num[--k] = (char)('0' + pid % 10), pid /= 10; while (pid > 0 && k > 0);
  const size_t l = sizeof OWN_MARK - 1;
  memcpy(buf, OWN_MARK, l);
  memcpy(buf + l, num + k, sizeof num - (size_t)k);
}

/* Puts this process's mark into the folder dir (never through a link).
 * Returns 0, or -1 with errno set. */
static int mark_put(const char *dir) {
  char name[32];
  mark_name(name, (long)getpid());
  const int dfd = open(dir, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (dfd < 0) return -1;
  const int fd = openat(dfd, name, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  const int e = errno;
  close(dfd);
  if (fd < 0 && e != EEXIST) {
    errno = e;
    return -1;
  }
  if (fd >= 0) close(fd);
  return 0;
}

/* Removes pid's mark from dir (once dir is the result folder again). */
static void mark_drop(const char *dir, long pid) {
  char name[32];
  mark_name(name, pid);
  const int dfd = open(dir, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (dfd < 0) return;
  unlinkat(dfd, name, 0);
  close(dfd);
}

/* 1 when the open folder dfd is one pid made: a real folder owned by this
 * user holding pid's mark, a regular file owned by this user */
static int made_by(int dfd, long pid) {
  struct stat sb;
  if (fstat(dfd, &sb) != 0 || !S_ISDIR(sb.st_mode) || sb.st_uid != geteuid()) return 0;
  char name[32];
  mark_name(name, pid);
  return fstatat(dfd, name, &sb, AT_SYMLINK_NOFOLLOW) == 0 && S_ISREG(sb.st_mode) &&
         sb.st_uid == geteuid();
}

/* Removes the files of a flat folder pid made (made_by), then the folder,
 * with system calls only (safe in a signal handler). The folder is opened
 * without following a link, and its entries are unlinked through that open
 * folder, so nothing outside it is touched; a link inside loses the link
 * only. A folder without pid's mark keeps its files: it is removed only
 * when it is empty (a writer killed between the staging folder's mkdir and
 * its mark, fb_outdir_stage, leaves one; rmdir takes nothing else, and a
 * link put in its place fails it). Subfolders are left (the rmdir then
 * fails). */
static void remove_flat(const char *dir, long pid) {
  const int fd = open(dir, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return;
  if (!made_by(fd, pid)) {
    struct stat sb;
    const int mine = fstat(fd, &sb) == 0 && S_ISDIR(sb.st_mode) && sb.st_uid == geteuid();
    close(fd);
    if (mine) rmdir(dir); /* ENOTEMPTY: a folder with anything in it stays whole */
    return;
  }
  char buf[8192], mark[32];
  mark_name(mark, pid);
  long n;
  while ((n = syscall(SYS_getdents64, fd, buf, sizeof buf)) > 0) {
    for (long off = 0; off < n;) {
      /* struct linux_dirent64: ino (8), off (8), reclen (2), type (1), name */
      unsigned short reclen;
      memcpy(&reclen, buf + off + 16, sizeof reclen);
      const char *name = buf + off + 19;
      /* the mark last: a folder interrupted here is still recognised as ours */
      if (!(name[0] == '.' && (name[1] == '\0' || (name[1] == '.' && name[2] == '\0'))) &&
          strcmp(name, mark) != 0)
        unlinkat(fd, name, 0);
      off += reclen;
    }
  }
  unlinkat(fd, mark, 0);
  close(fd);
  rmdir(dir); /* a link put in its place meanwhile: ENOTDIR, nothing removed */
}

/* the children (gnuplot, drawing figures side by side) writing into a
 * registered folder: ended first */
static volatile pid_t child_pid[FB_CLEANUP_CHILDREN];

void fb_cleanup_child(pid_t pid) {
  for (int k = 0; k < FB_CLEANUP_CHILDREN; k++) child_pid[k] = 0;
  child_pid[0] = pid;
}

int fb_cleanup_child_add(pid_t pid) {
  for (int k = 0; k < FB_CLEANUP_CHILDREN; k++)
    if (child_pid[k] == 0) {
      child_pid[k] = pid;
      return 0;
    }
  return -1;
}

void fb_cleanup_child_forget(pid_t pid) {
  for (int k = 0; k < FB_CLEANUP_CHILDREN; k++)
    if (child_pid[k] == pid) child_pid[k] = 0;
}

/* the note written on a signal (fb_cleanup_note) */
static const char *volatile note_head;
static const char *note_text, *note_tail;
static const volatile long *note_count;
static pid_t note_owner; /* a forked worker inherits the note: only the owner writes it */

static void write_str(const char *s) {
  size_t n = strlen(s);
  while (n) {
    const ssize_t w = write(2, s, n);
    if (w <= 0) return;
    s += w, n -= (size_t)w;
  }
}

static void write_note(int sig) {
  if (!note_head) return;
  char num[24];
  int k = (int)sizeof num - 1;
  num[k] = '\0';
  long v = note_count ? *note_count : 0;
  if (v < 0) v = 0;
  do num[--k] = (char)('0' + v % 10), v /= 10; while (v && k > 0);
  write_str("\n");
  write_str(note_head);
  write_str(sig == SIGINT ? " by SIGINT: " : sig == SIGTERM ? " by SIGTERM: " : " by SIGHUP: ");
  write_str(note_text ? note_text : "");
  if (note_count) write_str(num + k);
  write_str(note_tail ? note_tail : "");
  write_str("\n");
}

static void on_signal(int sig) {
  const pid_t me = getpid();
  for (int k = 0; k < FB_CLEANUP_CHILDREN; k++) {
    const pid_t child = child_pid[k];
    if (child > 0) { /* it could otherwise write into the folder after it is removed */
      kill(child, SIGKILL);
      waitpid(child, NULL, 0);
    }
  }
  for (int k = 0; k < CLEANUP_SLOTS; k++) {
    if (!slots[k].used || slots[k].owner != me) continue;
    if (slots[k].is_dir) remove_flat(slots[k].path, (long)me);
    else unlink(slots[k].path);
  }
  if (note_owner == me) write_note(sig);
  signal(sig, SIG_DFL);
  raise(sig);
}

static void install_handlers(void) {
  static int done;
  if (done) return;
  done = 1;
  const int sigs[3] = {SIGINT, SIGTERM, SIGHUP};
  for (int k = 0; k < 3; k++) {
    struct sigaction old, sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    if (sigaction(sigs[k], NULL, &old) == 0 && old.sa_handler == SIG_IGN) continue; /* nohup */
    sigaction(sigs[k], &sa, NULL);
  }
}

int fb_cleanup_add(const char *path, int is_dir) {
  install_handlers();
  for (int k = 0; k < CLEANUP_SLOTS; k++) {
    if (slots[k].used && slots[k].owner == getpid()) continue;
    slots[k].used = 0;
    snprintf(slots[k].path, sizeof slots[k].path, "%s", path);
    slots[k].is_dir = is_dir;
    slots[k].owner = getpid();
    slots[k].used = 1; /* last: the handler sees a complete slot or none */
    return k;
  }
  return -1;
}

void fb_cleanup_note(const char *head, const char *text, const volatile long *count,
                     const char *tail) {
  install_handlers();
  note_head = NULL; /* the handler sees a whole note or none */
  note_text = text;
  note_count = count;
  note_tail = tail;
  note_owner = getpid();
  note_head = head;
}

void fb_cleanup_forget(int slot) {
  if (slot >= 0 && slot < CLEANUP_SLOTS) slots[slot].used = 0;
}

/* ---- locking and staging ------------------------------------------------------- */

static fb_status mkdir_p(const char *dir, fb_diag *diag) {
  char buf[FB_OUTDIR_PATH];
  if (snprintf(buf, sizeof buf, "%s", dir) >= (int)sizeof buf)
    return fb_diag_set(diag, FB_ERR_IO, "%s: path too long", dir);
  for (char *p = buf + 1;; p++) {
    if (*p != '/' && *p != '\0') continue;
    const char c = *p;
    *p = '\0';
    if (mkdir(buf, 0755) != 0 && errno != EEXIST)
      return fb_diag_set(diag, FB_ERR_IO, "%s: cannot create output folder: %s", buf, strerror(errno));
    *p = c;
    if (!c) break;
  }
  return FB_OK;
}

/* absolute path of dir (whose parent is created), split at its last '/' */
static fb_status resolve(const char *dir, char *abs, char *parent, char *base, fb_diag *diag) {
  char buf[FB_OUTDIR_PATH];
  if (!dir[0] || snprintf(buf, sizeof buf, "%s", dir) >= (int)sizeof buf)
    return fb_diag_set(diag, FB_ERR_ARG, "--out '%s': not a usable output folder name (empty, or "
                       "too long): give a folder's path", dir);
  size_t l = strlen(buf);
  while (l > 1 && buf[l - 1] == '/') buf[--l] = '\0';
  char rp[PATH_MAX];
  if (realpath(buf, rp)) {
    snprintf(abs, FB_OUTDIR_PATH, "%s", rp);
  } else {
    char *slash = strrchr(buf, '/');
    const char *name = slash ? slash + 1 : buf;
    if (strcmp(name, ".") == 0 || strcmp(name, "..") == 0)
      return fb_diag_set(diag, FB_ERR_ARG, "--out %s: not a usable output folder name ('.' or "
                         "'..' of a folder that is not there): give a folder's path", dir);
    char par[FB_OUTDIR_PATH];
    if (slash == buf) snprintf(par, sizeof par, "/");
    else if (slash) snprintf(par, sizeof par, "%.*s", (int)(slash - buf), buf);
    else snprintf(par, sizeof par, ".");
    fb_status st = mkdir_p(par, diag);
    if (st != FB_OK) return st;
    if (!realpath(par, rp))
      return fb_diag_set(diag, FB_ERR_IO, "%s: cannot resolve: %s", par, strerror(errno));
    if (snprintf(abs, FB_OUTDIR_PATH, "%s/%s", strcmp(rp, "/") ? rp : "", name) >= FB_OUTDIR_PATH)
      return fb_diag_set(diag, FB_ERR_IO, "%s: path too long", dir);
  }
  char *slash = strrchr(abs, '/');
  if (!slash || !slash[1])
    return fb_diag_set(diag, FB_ERR_ARG, "--out %s: the root folder cannot be an output folder", dir);
  snprintf(parent, FB_OUTDIR_PATH, "%.*s", slash == abs ? 1 : (int)(slash - abs), abs);
  snprintf(base, NAME_MAX + 1, "%s", slash + 1);
  return FB_OK;
}

/* the extensions of the files fourbar writes: only to recognise a
 * temporary file of this program by its name (fb_outdir_temp_pid), never to
 * decide that a file is a run's (the folder's manifest does, manifest.h) */
static int result_like(const char *name) {
  if (strcmp(name, FB_MANIFEST_NAME) == 0) return 1;
  if (name[0] == '.') return 0;
  const char *dot = strrchr(name, '.');
  const char *known[] = {".csv", ".h5", ".json", ".jsonl", ".svg", ".png", ".md", ".log",
                         ".html", ".js", ".css", NULL};
  for (int k = 0; dot && known[k]; k++)
    if (strcmp(dot, known[k]) == 0) return 1;
  return 0;
}

/* the number text[0..n) is, when it is a decimal number > 0 without a leading
 * zero (a PID as fourbar writes it), else 0 */
static long pid_in(const char *text, size_t n) {
  if (n == 0 || n > 9 || text[0] == '0') return 0;
  long v = 0;
  for (size_t k = 0; k < n; k++) {
    if (text[k] < '0' || text[k] > '9') return 0;
    v = v * 10 + (text[k] - '0');
  }
  return v;
}

static int pid_gone(long pid) { return pid > 0 && kill((pid_t)pid, 0) != 0 && errno == ESRCH; }

/* The PID in a temporary file's name when the name has exactly a form this
 * program writes, else 0:
 *   <result file>.tmp.<pid>.XXXXXX  (fileio.c: mkstemp's six characters)
 *   .figure.tmp.<pid>.<serial>.svg|png  (figures.c: gnuplot's output)
 *   .fourbar-own.<pid>  (the mark of a folder this program made, OWN_MARK:
 *                        left in a result folder by a writer killed within
 *                        its commit)
 * A user's file that merely contains ".tmp.<number>." is none of these. */
long fb_outdir_temp_pid(const char *name) {
  const size_t n = strlen(name);
  if (strncmp(name, OWN_MARK, sizeof OWN_MARK - 1) == 0)
    return pid_in(name + sizeof OWN_MARK - 1, n - (sizeof OWN_MARK - 1));
  if (strncmp(name, ".figure.tmp.", 12) == 0) {
    const char *p = name + 12, *d1 = strchr(p, '.');
    const char *d2 = d1 ? strchr(d1 + 1, '.') : NULL;
    if (!d2 || (strcmp(d2, ".svg") != 0 && strcmp(d2, ".png") != 0)) return 0;
    const size_t serial = (size_t)(d2 - d1 - 1); /* figures.c's counter, from 0 */
    if (serial == 0 || strspn(d1 + 1, "0123456789") != serial) return 0;
    return pid_in(p, (size_t)(d1 - p));
  }
  if (n < 7 || name[n - 7] != '.') return 0; /* ".XXXXXX" */
  for (size_t k = n - 6; k < n; k++)
    if (!((name[k] >= '0' && name[k] <= '9') || (name[k] >= 'a' && name[k] <= 'z') ||
          (name[k] >= 'A' && name[k] <= 'Z')))
      return 0;
  /* back over the PID to ".tmp." */
  size_t e = n - 7, b = e;
  while (b > 0 && name[b - 1] >= '0' && name[b - 1] <= '9') b--;
  if (b < 5 || strncmp(name + b - 5, ".tmp.", 5) != 0) return 0;
  char result[NAME_MAX + 1];
  snprintf(result, sizeof result, "%.*s", (int)(b - 5), name);
  if (!result[0] || !result_like(result)) return 0;
  return pid_in(name + b, e - b);
}

/* 1 when name is .<base>.<kind>.<pid> exactly (a staging or old folder of
 * this output folder), with *pid set */
static int beside_name(const char *name, const char *base, const char *kind, long *pid) {
  char prefix[NAME_MAX + 32];
  snprintf(prefix, sizeof prefix, ".%s.%s.", base, kind);
  const size_t l = strlen(prefix);
  if (strncmp(name, prefix, l) != 0) return 0;
  *pid = pid_in(name + l, strlen(name + l));
  return *pid > 0;
}

/* What a killed writer (its PID gone) left beside the folder. With
 * restore = 1: an old set it had moved aside (.<base>.old.<pid>) is moved
 * back when the folder is not there (the writer died between the two
 * renames of fb_outdir_commit), so a user's files in it are not lost. With
 * restore = 0: its staging and old folders are removed. Either only for a
 * folder holding its maker's mark (made_by): a link, or a folder fourbar did
 * not make, is left as it is whatever its name. */
static void leftovers(const char *parent, const char *base, const char *target, int restore) {
  DIR *d = opendir(parent);
  if (!d) return;
  struct dirent *e;
  while ((e = readdir(d))) {
    long pid = 0;
    const int old = beside_name(e->d_name, base, "old", &pid);
    if (!old && (restore || !beside_name(e->d_name, base, "staging", &pid))) continue;
    if (!pid_gone(pid)) continue; /* a live writer's (it holds the lock: never ours to take) */
    char path[FB_OUTDIR_PATH + NAME_MAX + 2];
    snprintf(path, sizeof path, "%s/%s", parent, e->d_name);
    if (!restore) {
      remove_flat(path, pid);
      continue;
    }
    struct stat sb;
    if (lstat(target, &sb) == 0 || errno != ENOENT) continue;
    const int fd = open(path, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0) continue;
    if (made_by(fd, pid) && rename(path, target) == 0) mark_drop(target, pid);
    close(fd);
  }
  closedir(d);
}

/* Checks the target may be used (replaced, with replace = 1), then removes
 * what a killed writer left: staging and old folders beside the target and
 * temporary files in it, each only when its name has this program's exact
 * form and the process named in it is gone. Nothing is removed from a folder
 * that is refused. */
static fb_status clean_and_check(const fb_outdir *o, const char *parent, const char *base,
                                 int replace, fb_diag *diag) {
  DIR *d = opendir(o->target);
  if (!d && errno != ENOENT)
    return fb_diag_set(diag, errno == ENOTDIR ? FB_ERR_ARG : FB_ERR_IO,
                       "--out %s: cannot use as an output folder: %s", o->target,
                       errno == ENOTDIR ? "not a folder" : strerror(errno));
  if (d) {
    /* a result folder has a manifest (manifest.h), or summary.json when an
     * older fourbar wrote it; a run keeps every file of it that no run
     * wrote (fb_outdir_commit), and it can keep regular files only */
    char mpath[FB_OUTDIR_PATH + NAME_MAX + 2];
    snprintf(mpath, sizeof mpath, "%s/%s", o->target, FB_MANIFEST_NAME);
    struct stat mb;
    const int manifest = lstat(mpath, &mb) == 0 && S_ISREG(mb.st_mode);
    int summary = 0, other = 0;
    char other_name[NAME_MAX + 1] = "", odd_name[NAME_MAX + 1] = "";
    const char *odd = NULL;
    struct dirent *e;
    while ((e = readdir(d))) {
      if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) continue;
      if (fb_outdir_temp_pid(e->d_name)) continue; /* ours, removed below if its writer is gone */
      if (strcmp(e->d_name, FB_MANIFEST_NAME) == 0) continue;
      char path[FB_OUTDIR_PATH + NAME_MAX + 2];
      snprintf(path, sizeof path, "%s/%s", o->target, e->d_name);
      struct stat sb;
      if (strcmp(e->d_name, "summary.json") == 0) summary = 1;
      if (lstat(path, &sb) != 0 || !S_ISREG(sb.st_mode)) {
        if (!odd) {
          odd = lstat(path, &sb) != 0 ? "gone while read"
                : S_ISDIR(sb.st_mode) ? "a folder" : S_ISLNK(sb.st_mode) ? "a symbolic link"
                                                                           : "not a regular file";
          snprintf(odd_name, sizeof odd_name, "%s", e->d_name);
        }
      } else if (strcmp(e->d_name, ".gnuplot.log") != 0 && !other++) {
        snprintf(other_name, sizeof other_name, "%s", e->d_name);
      }
    }
    if (replace && odd) {
      closedir(d);
      return fb_diag_set(diag, FB_ERR_ARG, "--out %s: holds '%s', %s: a run keeps every file of its "
                         "folder that no run wrote, and can keep regular files only, so it will "
                         "not be replaced; move it, or choose another --out", o->target, odd_name,
                         odd);
    }
    if (replace && other && !manifest && !summary) {
      closedir(d);
      return fb_diag_set(diag, FB_ERR_ARG, "--out %s: holds '%s' but neither %s nor summary.json: not a "
                         "fourbar run's result folder, so it will not be replaced; choose another "
                         "--out", o->target, other_name, FB_MANIFEST_NAME);
    }
    rewinddir(d);
    while ((e = readdir(d))) {
      const long pid = fb_outdir_temp_pid(e->d_name);
      if (!pid_gone(pid)) continue;
      char path[FB_OUTDIR_PATH + NAME_MAX + 2];
      snprintf(path, sizeof path, "%s/%s", o->target, e->d_name);
      struct stat sb;
      if (lstat(path, &sb) == 0 && S_ISREG(sb.st_mode)) unlink(path);
    }
    closedir(d);
  }
  leftovers(parent, base, o->target, 0);
  return FB_OK;
}

/* Refuses, before any work, an output folder that cannot be committed: a
 * symbolic link to nothing, a mount point or the current folder (or one
 * above it) for a writer that replaces the folder whole. */
static fb_status check_target(const char *dir, const char *target, const char *parent, int replace,
                              fb_diag *diag) {
  struct stat sb, pb;
  char given[FB_OUTDIR_PATH];
  snprintf(given, sizeof given, "%s", dir);
  size_t l = strlen(given);
  while (l > 1 && given[l - 1] == '/') given[--l] = '\0';
  if (lstat(given, &sb) == 0 && S_ISLNK(sb.st_mode) && stat(given, &pb) != 0) {
    char to[PATH_MAX];
    const ssize_t n = readlink(given, to, sizeof to - 1);
    to[n > 0 ? n : 0] = '\0';
    return fb_diag_set(diag, FB_ERR_ARG, "--out %s: a symbolic link to '%s', which does not exist; "
                       "create that folder or choose another --out", dir, to);
  }
  if (stat(target, &sb) != 0) return FB_OK;
  if (!S_ISDIR(sb.st_mode)) {
    struct stat lb;
    const int link = lstat(given, &lb) == 0 && S_ISLNK(lb.st_mode);
    return fb_diag_set(diag, FB_ERR_ARG, "--out %s: %s, not a folder: --out names the folder the "
                       "results go to, and fourbar never replaces a file, a link, a FIFO or a "
                       "device with a folder: choose another --out", dir,
                       link ? "a symbolic link to a file" : S_ISREG(sb.st_mode) ? "a file"
                       : S_ISFIFO(sb.st_mode) ? "a FIFO" : S_ISCHR(sb.st_mode) || S_ISBLK(sb.st_mode)
                       ? "a device" : "not a regular file");
  }
  if (!replace) return FB_OK;
  if (stat(parent, &pb) == 0 && pb.st_dev != sb.st_dev)
    return fb_diag_set(diag, FB_ERR_ARG, "--out %s: a mount point; a run replaces its output folder whole, "
                       "which cannot be done to a mount point: give a folder inside it, e.g. "
                       "--out %s/run", dir, dir);
  char cwd[PATH_MAX];
  if (getcwd(cwd, sizeof cwd)) {
    const size_t t = strlen(target);
    if (strncmp(cwd, target, t) == 0 && (cwd[t] == '\0' || cwd[t] == '/'))
      return fb_diag_set(diag, FB_ERR_ARG, "--out %s: the current folder%s; a run replaces its output "
                         "folder whole, which would leave this shell in a removed folder: give a "
                         "new folder, e.g. --out %s/run", dir, cwd[t] ? " is inside it" : "",
                         strcmp(dir, ".") == 0 ? "." : dir);
  }
  return FB_OK;
}

static fb_status take_lock_of(const char *path, const char *dir, const char *what,
                              const char *fix, int exclusive, int *out_fd, fb_diag *diag);

/* takes an advisory lock on path (exclusive or shared), writing this PID */
static fb_status take_lock(const char *path, const char *dir, int exclusive, int *out_fd,
                           fb_diag *diag) {
  return take_lock_of(path, dir, "this output folder", " or choose another --out", exclusive,
                      out_fd, diag);
}

fb_status fb_lock_take(const char *lock_path, const char *name, const char *what, int *fd,
                       fb_diag *diag) {
  return take_lock_of(lock_path, name, what, "", 1, fd, diag);
}

/* take_lock for a lock guarding what (of dir), fix said after "wait for it to finish" */
static fb_status take_lock_of(const char *path, const char *dir, const char *what,
                              const char *fix, int exclusive, int *out_fd, fb_diag *diag) {
  /* the lock file is truncated to hold this PID: never through a link, never
   * a FIFO or a device */
  int fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK, 0644);
  struct stat sb;
  if (fd >= 0 && (fstat(fd, &sb) != 0 || !S_ISREG(sb.st_mode))) {
    close(fd);
    fd = -1;
    errno = EINVAL;
  }
  if (fd < 0)
    return fb_diag_set(diag, FB_ERR_IO, "%s: cannot create the lock %s: %s", dir, path,
                       errno == ELOOP || errno == EINVAL ? "not a regular file (a link, a FIFO "
                       "or a device): fourbar writes its lock only into a file of its own"
                                                         : strerror(errno));
  if (flock(fd, (exclusive ? LOCK_EX : LOCK_SH) | LOCK_NB) != 0) {
    const int e = errno;
    char pid[32] = "";
    ssize_t n = pread(fd, pid, sizeof pid - 1, 0);
    pid[n > 0 ? n : 0] = '\0';
    pid[strcspn(pid, "\n")] = '\0';
    close(fd);
    if (e == EWOULDBLOCK)
      return fb_diag_set(diag, FB_ERR_IO, "%s: another fourbar process (PID %s) is writing %s; "
                         "wait for it to finish%s", dir, pid[0] ? pid : "unknown", what, fix);
    return fb_diag_set(diag, FB_ERR_IO, "%s: cannot lock %s: %s", dir, path, strerror(e));
  }
  char pid[32];
  const int n = snprintf(pid, sizeof pid, "%ld\n", (long)getpid());
  if (ftruncate(fd, 0) != 0 || pwrite(fd, pid, (size_t)n, 0) != n) {
    /* the lock holds; only the PID in the message of a second writer is lost */
  }
  *out_fd = fd;
  return FB_OK;
}

fb_status fb_outdir_lock(fb_outdir *o, const char *dir, int replace, const char *tag,
                         fb_diag *diag) {
  memset(o, 0, sizeof *o);
  o->lock_fd = -1;
  o->tag_fd = -1;
  char parent[FB_OUTDIR_PATH], base[NAME_MAX + 1];
  fb_status st = resolve(dir, o->target, parent, base, diag);
  if (st != FB_OK) return st;
  st = check_target(dir, o->target, parent, replace, diag);
  if (st != FB_OK) return st;
  /* every writer of the folder takes .<name>.lock: a whole-folder writer
   * (run, sweep, merge) exclusively, a writer of one part (a sweep shard)
   * shared, plus .<name>.<tag>.lock exclusively for its part; so a run and
   * a shard sweep never write one folder at the same time */
  if (snprintf(o->lock, sizeof o->lock, "%s/.%s.lock", parent, base) >= (int)sizeof o->lock)
    return fb_diag_set(diag, FB_ERR_IO, "%s: path too long", dir);
  st = take_lock(o->lock, dir, tag == NULL, &o->lock_fd, diag);
  if (st != FB_OK) return st;
  if (tag) {
    char tag_lock[FB_OUTDIR_PATH + NAME_MAX + 16];
    snprintf(tag_lock, sizeof tag_lock, "%s/.%s.%s.lock", parent, base, tag);
    st = take_lock(tag_lock, dir, 1, &o->tag_fd, diag);
    if (st != FB_OK) {
      fb_outdir_release(o);
      return st;
    }
  }
  leftovers(parent, base, o->target, 1);
  st = clean_and_check(o, parent, base, replace, diag);
  if (st == FB_OK && !replace) st = mkdir_p(o->target, diag);
  if (st != FB_OK) fb_outdir_release(o);
  return st;
}

static int stage_slot = -1;

fb_status fb_outdir_stage(fb_outdir *o, fb_diag *diag) {
  char *slash = strrchr(o->target, '/');
  if (snprintf(o->stage, sizeof o->stage, "%.*s/.%s.staging.%ld", (int)(slash - o->target),
               o->target, slash + 1, (long)getpid()) >= (int)sizeof o->stage)
    return fb_diag_set(diag, FB_ERR_IO, "%s: path too long", o->target);
  if (mkdir(o->stage, 0755) != 0) {
    const int e = errno;
    o->stage[0] = '\0';
    return fb_diag_set(diag, FB_ERR_IO, "%s: cannot create the staging folder beside it: %s",
                       o->target, strerror(e));
  }
  if (mark_put(o->stage) != 0) {
    const int e = errno;
    rmdir(o->stage);
    o->stage[0] = '\0';
    return fb_diag_set(diag, FB_ERR_IO, "%s: cannot mark the staging folder beside it as "
                       "fourbar's: %s", o->target, strerror(e));
  }
  stage_slot = fb_cleanup_add(o->stage, 1);
  return FB_OK;
}

/* 1 when dir holds an entry called name */
static int holds(const char *dir, const char *name) {
  char path[FB_OUTDIR_PATH + NAME_MAX + 2];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  struct stat sb;
  return lstat(path, &sb) == 0;
}

/* adds name to o's note of kept files */
static void note_kept(fb_outdir *o, const char *name) {
  const size_t l = strlen(o->kept);
  if (o->kept_n++ < 8)
    snprintf(o->kept + l, sizeof o->kept - l, "%s%s", l ? ", " : "", name);
  else if (o->kept_n == 9)
    snprintf(o->kept + l, sizeof o->kept - l, ", ...");
}

/* The staging folder's files are this run's: the new manifest lists them as
 * the run's. Every regular file of the old folder that its manifest does not
 * list as a run's is kept: hard-linked into the staging folder (the same
 * file, not a copy), with its manifest line when another command wrote it.
 * A folder without a manifest (an older fourbar's) proves nothing: its files
 * are kept too, but one that this run writes again by name (summary.json,
 * a model's CSV) is taken for the older run's and replaced. A file no run
 * wrote that this run would write by the same name stops the commit: the
 * folder is left as it was. With no old folder, only the manifest is
 * written. */
static fb_status carry_over(fb_outdir *o, fb_diag *diag) {
  fb_manifest old, now;
  memset(&now, 0, sizeof now);
  if (fb_manifest_read(&old, o->target) != 0)
    return fb_diag_set(diag, FB_ERR_NOMEM, "%s: out of memory for its manifest", o->target);
  o->legacy = !old.present && holds(o->target, "summary.json");
  fb_status st = FB_OK;
  DIR *d = opendir(o->stage);
  struct dirent *e;
  while (d && st == FB_OK && (e = readdir(d)))
    if (e->d_name[0] != '.' || strcmp(e->d_name, ".gnuplot.log") == 0)
      if (!fb_outdir_temp_pid(e->d_name) && fb_manifest_set(&now, "run", e->d_name) != 0)
        st = fb_diag_set(diag, FB_ERR_NOMEM, "%s: out of memory for its manifest", o->target);
  if (d) closedir(d);
  d = opendir(o->target);
  while (d && st == FB_OK && (e = readdir(d))) {
    const char *name = e->d_name;
    if (strcmp(name, ".") == 0 || strcmp(name, "..") == 0 || strcmp(name, FB_MANIFEST_NAME) == 0 ||
        fb_outdir_temp_pid(name))
      continue;
    const char *owner = fb_manifest_owner(&old, name);
    if (owner && strcmp(owner, "run") == 0) continue; /* an earlier run's: replaced */
    char from[FB_OUTDIR_PATH + NAME_MAX + 2], to[FB_OUTDIR_PATH + NAME_MAX + 2];
    snprintf(from, sizeof from, "%s/%s", o->target, name);
    snprintf(to, sizeof to, "%s/%s", o->stage, name);
    struct stat sb;
    if (lstat(from, &sb) != 0) continue;
    if (holds(o->stage, name)) {
      if (o->legacy && !owner && S_ISREG(sb.st_mode)) continue; /* the older run's, by its name */
      if (owner && strcmp(name, ".gnuplot.log") == 0) continue; /* one log, any figure's */
      st = fb_diag_set(diag, FB_ERR_IO, "%s: holds '%s', which %s, and this run writes a file of "
                       "that name: nothing of the folder replaced; move '%s' and run again, or "
                       "choose another --out", o->target, name,
                       owner ? "another fourbar command wrote" : "no fourbar run wrote", name);
    } else if (!S_ISREG(sb.st_mode)) {
      st = fb_diag_set(diag, FB_ERR_IO, "%s: '%s' appeared while the run ran and is not a regular "
                       "file: nothing of the folder replaced", o->target, name);
    } else if (link(from, to) != 0) {
      st = fb_diag_set(diag, FB_ERR_IO, "%s: cannot keep '%s' (which no run wrote) beside the new "
                       "results: %s; nothing of the folder replaced", o->target, name,
                       strerror(errno));
    } else if (owner) {
      if (fb_manifest_set(&now, owner, name) != 0)
        st = fb_diag_set(diag, FB_ERR_NOMEM, "%s: out of memory for its manifest", o->target);
    } else if (strcmp(name, ".gnuplot.log") != 0) {
      note_kept(o, name);
    }
  }
  if (d) closedir(d);
  if (st == FB_OK) st = fb_manifest_write(&now, o->stage, diag);
  fb_manifest_free(&old);
  fb_manifest_free(&now);
  return st;
}

fb_status fb_outdir_commit(fb_outdir *o, fb_diag *diag) {
  struct stat sb;
  o->kept[0] = '\0';
  o->kept_n = 0;
  o->legacy = 0;
  const fb_status cst = carry_over(o, diag); /* also into a folder that is not there yet */
  if (cst != FB_OK) return cst;
  const long me = (long)getpid();
  if (stat(o->target, &sb) != 0) {
    if (rename(o->stage, o->target) != 0)
      return fb_diag_set(diag, FB_ERR_IO, "%s: cannot move the results into place: %s", o->target,
                         strerror(errno));
  } else {
    /* the old set is marked as this process's before it leaves the folder's
     * name, so that it is removed (here, on a signal, or after a kill by the
     * next writer) as a folder this program made, and nothing else is */
    if (mark_put(o->target) != 0)
      return fb_diag_set(diag, FB_ERR_IO, "%s: cannot replace: %s", o->target, strerror(errno));
    if (renameat2(AT_FDCWD, o->stage, AT_FDCWD, o->target, RENAME_EXCHANGE) != 0) {
      /* a file system without the exchange: the old set leaves, then the new arrives */
      char old[FB_OUTDIR_PATH + 32];
      char *slash = strrchr(o->target, '/');
      snprintf(old, sizeof old, "%.*s/.%s.old.%ld", (int)(slash - o->target), o->target,
               slash + 1, me);
      if (rename(o->target, old) != 0) {
        const int e = errno;
        mark_drop(o->target, me);
        return fb_diag_set(diag, FB_ERR_IO, "%s: cannot replace: %s", o->target, strerror(e));
      }
      if (rename(o->stage, o->target) != 0) {
        const int e = errno;
        rename(old, o->target);
        mark_drop(o->target, me);
        return fb_diag_set(diag, FB_ERR_IO, "%s: cannot replace: %s", o->target, strerror(e));
      }
      mark_drop(o->target, me); /* the new set's: it is the result folder now */
      remove_flat(old, me);
      fb_cleanup_forget(stage_slot);
      o->stage[0] = '\0';
      return FB_OK;
    }
  }
  mark_drop(o->target, me);
  /* after an exchange the staging name holds the old set */
  remove_flat(o->stage, me);
  fb_cleanup_forget(stage_slot);
  o->stage[0] = '\0';
  return FB_OK;
}

void fb_outdir_release(fb_outdir *o) {
  if (o->stage[0]) {
    remove_flat(o->stage, (long)getpid());
    fb_cleanup_forget(stage_slot);
    o->stage[0] = '\0';
  }
  if (o->tag_fd >= 0) {
    flock(o->tag_fd, LOCK_UN);
    close(o->tag_fd);
    o->tag_fd = -1;
  }
  if (o->lock_fd >= 0) {
    flock(o->lock_fd, LOCK_UN);
    close(o->lock_fd);
    o->lock_fd = -1;
  }
}
