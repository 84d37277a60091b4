/* The gnuplot plumbing of the figures: a figure's script written to a file
 * in its output folder (fig_plot_open, fig_plot_close), gnuplot started on
 * it with posix_spawn and an argument vector (no shell), the figure checked
 * whole and renamed into place; a run's figures drawn side by side, one
 * gnuplot per processor (fig_batch_begin, fig_batch_end); text escaped for
 * gnuplot's single-quoted strings. */
/* _GNU_SOURCE (meson.build): posix_spawn_file_actions_addchdir_np (glibc 2.29) */
#include "figures_internal.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

extern char **environ;

#include "outdir.h"

/* figures one batch (a run) may hold */
#define FB_FIGURE_BATCH 64

const char *fig_ext(fb_figure_format f) { return f == FB_FIGURE_PNG ? "png" : "svg"; }

/* Text for the inside of a gnuplot single-quoted string: a single quote is
 * doubled (the only escape gnuplot knows there) and every control character
 * (a newline would end the command) becomes '?'; gnuplot does no backquote or
 * macro substitution inside single quotes, so the result is inert data. With
 * enhanced = 1 the enhanced-text markup characters _ ^ @ & ~ { } \ are
 * backslash-escaped too. Truncates to size (never inside an escape). */
const char *fig_gp_text(const char *in, int enhanced, char *out, size_t size) {
  size_t k = 0;
  for (const unsigned char *c = (const unsigned char *)in; *c && k + 3 < size; c++) {
    if (*c < 0x20 || *c == 0x7f) {
      out[k++] = '?';
    } else if (*c == '\'') {
      out[k++] = '\'';
      out[k++] = '\'';
    } else {
      if (enhanced && strchr("_^@&~{}\\", *c)) out[k++] = '\\';
      out[k++] = (char)*c;
    }
  }
  out[k] = '\0';
  return out;
}

/* text for gnuplot's enhanced mode: underscores would become subscripts */
const char *fig_esc(const char *in, char *out, size_t size) { return fig_gp_text(in, 1, out, size); }

/* Opens a figure: its gnuplot script is written to a file in dir
 * (.figure.tmp.<pid>.<n>.gp), and fig_plot_close hands it to gnuplot as a file
 * argument. gnuplot reads a script on its standard input one byte per read
 * (246,849 read calls for a 20,000-point figure, 1.1 s against 0.2 s from a
 * file). The script never names a path from the user: gnuplot runs in dir
 * and writes the temporary name below, relative to it. */
fb_status fig_plot_open(plot *pl, const char *dir, const char *name, fb_figure_format fmt,
                        int width, int height, fb_diag *diag) {
  static unsigned serial;
  memset(pl, 0, sizeof *pl);
  pl->columns = width;
  snprintf(pl->dir, sizeof pl->dir, "%s", dir);
  snprintf(pl->path, sizeof pl->path, "%s/%s.%s", dir, name, fig_ext(fmt));
  const unsigned n = serial++;
  char tmpname[96];
  snprintf(tmpname, sizeof tmpname, ".figure.tmp.%ld.%u.%s", (long)getpid(), n, fig_ext(fmt));
  snprintf(pl->tmp, sizeof pl->tmp, "%s/%s", dir, tmpname);
  snprintf(pl->script, sizeof pl->script, "%s/.figure.tmp.%ld.%u.gp", dir, (long)getpid(), n);
  snprintf(pl->log, sizeof pl->log, "%s/.gnuplot.log", dir);
  const int fd = open(pl->script, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0 || !(pl->p = fdopen(fd, "w"))) {
    if (fd >= 0) close(fd);
    return fb_diag_set(diag, FB_ERR_IO, "%s: cannot write its gnuplot script: %s", pl->path,
                       strerror(errno));
  }
  /* one gnuplot may draw several figures' scripts in turn: each starts anew */
  fprintf(pl->p, "reset session\n");
  if (fmt == FB_FIGURE_PNG)
    fprintf(pl->p, "set terminal pngcairo size %d,%d enhanced font 'sans,10'\n", width, height);
  else
    fprintf(pl->p, "set terminal svg size %d,%d enhanced font 'sans,11' background '#ffffff'\n",
            width, height);
  fprintf(pl->p, "set output '%s'\nset grid lc rgb '#dddddd'\nset key outside right top box\n",
          tmpname);
  return FB_OK;
}

/* Starts one gnuplot on the scripts of plots pl[0..n) (one folder), in
 * turn, with posix_spawn and an argument vector (no shell) in their folder,
 * its standard input /dev/null, its output and errors appended to
 * dir/.gnuplot.log; *pid receives it. */
static fb_status gnuplot_start(const plot *pl, int n, pid_t *pid, fb_diag *diag) {
  /* the log is appended to: never through a link, never a FIFO's reader wait */
  int logfd = open(pl[0].log, O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK, 0644);
  struct stat lb;
  if (logfd >= 0 && (fstat(logfd, &lb) != 0 || !S_ISREG(lb.st_mode))) {
    close(logfd);
    logfd = -1;
    errno = EINVAL;
  }
  if (logfd < 0)
    return fb_diag_set(diag, FB_ERR_IO, "%s: cannot start gnuplot: %s: %s", pl[0].path, pl[0].log,
                       errno == ELOOP || errno == EINVAL ? "not a regular file" : strerror(errno));
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&fa, logfd, 1);
  posix_spawn_file_actions_adddup2(&fa, logfd, 2);
  posix_spawn_file_actions_addchdir_np(&fa, pl[0].dir);
  char *argv[FB_FIGURE_BATCH + 2];
  argv[0] = "gnuplot";
  for (int k = 0; k < n; k++) {
    const char *slash = strrchr(pl[k].script, '/');
    argv[k + 1] = (char *)(slash ? slash + 1 : pl[k].script);
  }
  argv[n + 1] = NULL;
  /* SIGINT, SIGTERM and SIGHUP wait until the child is registered for the
   * clean-up (outdir.h), which kills it before the folder is removed: one
   * arriving between the spawn and the registration would otherwise leave
   * a gnuplot writing into a removed folder; the child starts with the
   * caller's own mask */
  sigset_t block, old_mask;
  sigemptyset(&block);
  sigaddset(&block, SIGINT);
  sigaddset(&block, SIGTERM);
  sigaddset(&block, SIGHUP);
  sigprocmask(SIG_BLOCK, &block, &old_mask);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  posix_spawnattr_setsigmask(&attr, &old_mask);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK);
  int rc = posix_spawnp(pid, "gnuplot", &fa, &attr, argv, environ);
  posix_spawnattr_destroy(&attr);
  posix_spawn_file_actions_destroy(&fa);
  if (rc == 0) fb_cleanup_child_add(*pid); /* at most FB_CLEANUP_CHILDREN run at once */
  sigprocmask(SIG_SETMASK, &old_mask, NULL);
  close(logfd);
  if (rc != 0)
    return fb_diag_set(diag, FB_ERR_IO, "%s: cannot start gnuplot: %s (apt-get install "
                       "gnuplot-nox, or pass --no-figures)", pl[0].path, strerror(rc));
  return FB_OK;
}

/* waits for gnuplot pid; its exit status (128 + signal when killed) */
static int gnuplot_wait(pid_t pid) {
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  fb_cleanup_child_forget(pid);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/* 1 when the figure file at path is whole: flushed to the disk without error,
 * not empty, and ending as its format ends (an SVG's closing </svg> tag, a
 * PNG's IEND chunk); else 0 with the reason in why */
static int figure_whole(const char *path, char *why, size_t size) {
  int fd = open(path, O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    snprintf(why, size, "cannot open it: %s", strerror(errno));
    return 0;
  }
  struct stat sb;
  unsigned char tail[64];
  ssize_t n = 0;
  int ok = fstat(fd, &sb) == 0;
  if (!ok) snprintf(why, size, "cannot stat it: %s", strerror(errno));
  else if (fsync(fd) != 0 && errno != EINVAL) {
    snprintf(why, size, "cannot flush it: %s", strerror(errno));
    ok = 0;
  } else if (sb.st_size == 0) {
    snprintf(why, size, "it is empty");
    ok = 0;
  } else {
    const off_t from = sb.st_size > (off_t)sizeof tail ? sb.st_size - (off_t)sizeof tail : 0;
    n = pread(fd, tail, sizeof tail, from);
  }
  close(fd);
  if (!ok) return 0;
  const size_t l = strlen(path);
  if (l > 4 && strcmp(path + l - 4, ".png") == 0) {
    static const unsigned char iend[8] = {'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82};
    if (n >= 8 && memcmp(tail + n - 8, iend, 8) == 0) return 1;
    snprintf(why, size, "%lld bytes without the PNG end chunk", (long long)sb.st_size);
    return 0;
  }
  while (n > 0 && (tail[n - 1] == '\n' || tail[n - 1] == ' ' || tail[n - 1] == '\r')) n--;
  if (n >= 6 && memcmp(tail + n - 6, "</svg>", 6) == 0) return 1;
  snprintf(why, size, "%lld bytes without the closing </svg>", (long long)sb.st_size);
  return 0;
}

/* Puts a drawn figure into place, rc its gnuplot's exit status: a whole
 * file renamed to its name, else an error naming it; the script and the
 * temporary output are removed either way. */
static fb_status plot_finish(plot *pl, int rc, fb_diag *diag) {
  unlink(pl->script);
  char why[160];
  const int drawn = access(pl->tmp, F_OK) == 0;
  /* gnuplot exits 0 when its output could not be written (a full disk):
   * the file itself must be whole before it is renamed into place; a
   * figure drawn whole before a later script of the same gnuplot failed
   * is kept */
  if (drawn && figure_whole(pl->tmp, why, sizeof why)) {
    if (rename(pl->tmp, pl->path) == 0) return FB_OK;
    unlink(pl->tmp);
    return fb_diag_set(diag, FB_ERR_IO, "%s: cannot rename into place", pl->path);
  }
  unlink(pl->tmp);
  if (!drawn || rc != 0)
    return fb_diag_set(diag, FB_ERR_IO, "%s: gnuplot failed (exit %d); see %s", pl->path, rc, pl->log);
  const char *slash = strrchr(pl->path, '/');
  return fb_diag_set(diag, FB_ERR_IO, "%s: gnuplot wrote a damaged figure (%s; a full disk?)",
                     slash ? slash + 1 : pl->path, why);
}

/* an empty log says nothing: no hidden empty file in the result folder */
static void drop_empty_log(const char *log) {
  struct stat lst;
  if (stat(log, &lst) == 0 && lst.st_size == 0) unlink(log);
}

/* A run's figures: while a batch is open (fb_figures_run), fig_plot_close only
 * keeps the figure's script; fig_batch_end hands the scripts to one gnuplot per
 * processor (at most FB_CLEANUP_CHILDREN), each drawing its share in turn,
 * side by side, and puts every figure into place. One gnuplot for many
 * figures saves its start-up per figure (0.05 s of processor time each). */
static struct {
  int open;
  int n;
  plot pl[FB_FIGURE_BATCH];
  int started, groups;                /* fig_batch_start ran; its gnuplots */
  int first[FB_CLEANUP_CHILDREN + 1]; /* group g draws pl[first[g] .. first[g + 1]) */
  pid_t pid[FB_CLEANUP_CHILDREN];
  fb_status st; /* the first failure to start, its message in diag */
  fb_diag diag;
} batch;

void fig_batch_begin(void) {
  memset(&batch, 0, sizeof batch);
  batch.open = 1;
}

/* the size of a figure's script [bytes]: what its drawing costs, nearly */
static long script_size(const plot *pl) {
  struct stat sb;
  return stat(pl->script, &sb) == 0 ? (long)sb.st_size : 0;
}

void fig_batch_start(void) {
  batch.open = 0;
  if (batch.started) return;
  batch.started = 1;
  batch.st = FB_OK;
  const int n = batch.n;
  if (n == 0) return;
  const long cpus = sysconf(_SC_NPROCESSORS_ONLN);
  int groups = cpus < 1 ? 1 : cpus > FB_CLEANUP_CHILDREN ? FB_CLEANUP_CHILDREN : (int)cpus;
  if (groups > n) groups = n;
  /* contiguous shares of about equal script size, in the figures' order */
  long total = 0;
  for (int k = 0; k < n; k++) total += script_size(&batch.pl[k]);
  int *first = batch.first, g = 0;
  long acc = 0;
  first[0] = 0;
  for (int k = 0; k < n && g + 1 < groups; k++) {
    acc += script_size(&batch.pl[k]);
    if (acc * groups >= total * (g + 1) && k + 1 < n) first[++g] = k + 1;
  }
  groups = batch.groups = g + 1;
  first[groups] = n;
  for (g = 0; g < groups; g++) {
    batch.pid[g] = -1;
    fb_diag d;
    const fb_status sg = gnuplot_start(&batch.pl[first[g]], first[g + 1] - first[g], &batch.pid[g], &d);
    if (sg != FB_OK && batch.st == FB_OK) {
      batch.st = sg;
      batch.diag = d;
    }
  }
}

fb_status fig_batch_end(fb_diag *diag) {
  fig_batch_start();
  const int n = batch.n, groups = batch.groups;
  if (n == 0) return FB_OK;
  fb_status st = batch.st;
  if (st != FB_OK) *diag = batch.diag;
  int rc[FB_CLEANUP_CHILDREN];
  for (int g = 0; g < groups; g++) rc[g] = batch.pid[g] > 0 ? gnuplot_wait(batch.pid[g]) : 127;
  for (int g = 0; g < groups; g++)
    for (int k = batch.first[g]; k < batch.first[g + 1]; k++) {
      fb_diag d;
      const fb_status sf = plot_finish(&batch.pl[k], rc[g], &d);
      if (sf != FB_OK && st == FB_OK) {
        st = sf;
        *diag = d;
      }
    }
  drop_empty_log(batch.pl[0].log);
  batch.n = 0;
  return st;
}

fb_status fig_plot_close(plot *pl, fb_diag *diag) {
  fprintf(pl->p, "unset output\n");
  const int bad = fflush(pl->p) != 0 || ferror(pl->p);
  if (fclose(pl->p) != 0 || bad) {
    pl->p = NULL;
    unlink(pl->script);
    return fb_diag_set(diag, FB_ERR_IO, "%s: cannot write its gnuplot script: %s", pl->path,
                       strerror(errno));
  }
  pl->p = NULL;
  if (batch.open && batch.n < FB_FIGURE_BATCH) {
    batch.pl[batch.n++] = *pl;
    return FB_OK;
  }
  pid_t pid;
  fb_status st = gnuplot_start(pl, 1, &pid, diag);
  if (st != FB_OK) {
    unlink(pl->script);
    return st;
  }
  st = plot_finish(pl, gnuplot_wait(pid), diag);
  drop_empty_log(pl->log);
  return st;
}

/* "dir/name.ext" -> dir, name (no extension); "name.ext" -> ".", name */
void fig_split_path(const char *path, char *dir, size_t dsize, char *name, size_t nsize) {
  snprintf(dir, dsize, "%s", path);
  char *slash = strrchr(dir, '/');
  if (slash) {
    snprintf(name, nsize, "%s", slash + 1);
    *slash = '\0';
  } else {
    snprintf(name, nsize, "%s", path);
    snprintf(dir, dsize, ".");
  }
  char *dot = strrchr(name, '.');
  if (dot) *dot = '\0';
}
