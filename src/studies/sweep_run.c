/* A sweep: resume, compute on this process or on workers, write the table
 * (sweep_run.h). */
#define _POSIX_C_SOURCE 200809L
#include "sweep_run.h"

#include <errno.h>
#include <fcntl.h>
#include <jansson.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "casefile.h"
#include "clock.h"
#include "fileio.h"
#include "manifest.h"
#include "outdir.h"
#include "sweep_rows.h"
#include "textsafe.h"
#include "worker.h"

/* the points of this run of a sweep */
typedef struct {
  const fb_study *s;
  const fb_sweep_opts *o;
  char rows_path[4200];
  size_t *todo, ntodo, mine; /* points still to compute; points of this shard */
  size_t finished;           /* computed now */
  int fd;                    /* the rows file, appended */
  int tty;
  double t0;
} sweep_state;

/* rows kept, for the note a signal prints (fb_cleanup_note) */
static volatile long kept;

void fb_sweep_note_variants(const fb_study *s) {
  /* a point runs its case alone: said when the case has variants */
  static fb_case probe;
  fb_diag pd;
  if (fb_casefile_load_planar(&probe, s->case_path, NULL, 0, &pd) == FB_OK && probe.variant_count)
    fprintf(stderr, "fourbar sweep: note: %s has %d [variant.*] section%s; a sweep runs each "
            "point's case alone, without them (fourbar run runs them)\n", s->case_path,
            probe.variant_count, probe.variant_count > 1 ? "s" : "");
}

/* 1 when the provenance stored at path differs from now (or is missing), with
 * what differs in what */
static int provenance_differs(const char *path, const json_t *now, char *what, size_t size) {
  json_t *old = json_load_file(path, 0, NULL);
  if (!old) {
    snprintf(what, size, "%s is missing, so what they were computed from is unknown", path);
    return 1;
  }
  char why[3000];
  const int differs = fb_study_provenance_differs(old, now, why, sizeof why);
  if (differs) snprintf(what, size, "they and this sweep differ: %s", why);
  json_decref(old);
  return differs;
}

static void progress(size_t done, size_t total, double t0, int tty) {
  if (!tty) return;
  const int width = 30;
  const double frac = total ? (double)done / (double)total : 1.0;
  const double el = fb_clock_s() - t0;
  const double eta = done ? el * (double)(total - done) / (double)done : 0.0;
  char bar[64];
  int filled = (int)(frac * width);
  for (int k = 0; k < width; k++) bar[k] = k < filled ? '#' : '.';
  bar[width] = '\0';
  fputc('\r', fb_text_raw_stderr()); /* ours: never escaped */
  fprintf(stderr, "  [%s] %zu/%zu points, %.0f s elapsed, ETA %.0f s   ", bar, done, total, el, eta);
  if (done == total) fputc('\n', stderr);
  fflush(stderr);
}

/* What the rows file already holds (checked against this sweep's
 * provenance, which is then written beside it) and the points left:
 * st->todo, st->ntodo, st->mine. Returns the exit status. */
static int resume(sweep_state *st) {
  const fb_sweep_opts *o = st->o;
  const fb_study *s = st->s;
  fb_diag d;
  /* what the rows are computed from, beside them */
  char prov_path[4300];
  fb_sweep_rows_beside(prov_path, sizeof prov_path, st->rows_path, ".provenance.json");
  if (o->restart) {
    char csv_path[4300];
    fb_sweep_rows_beside(csv_path, sizeof csv_path, st->rows_path, ".csv");
    unlink(st->rows_path);
    unlink(csv_path);
    unlink(prov_path);
  }
  /* resume: what this file already holds */
  fb_sweep_rowset done = {0};
  char err[4400] = "";
  if (fb_sweep_rows_read(st->rows_path, &done, 1, err, sizeof err) != 0)
    return fb_study_fail("sweep", 1, "%s", err);
  json_t *prov = fb_study_provenance(s);
  json_object_set_new(prov, "fourbar_version", json_string(o->version));
  if (done.n) {
    /* resume only rows computed from the same study, case files and program */
    char what[4400];
    if (provenance_differs(prov_path, prov, what, sizeof what)) {
      json_decref(prov);
      fb_sweep_rows_free(&done);
      return fb_study_fail("sweep", 2, "%s holds %zu rows computed from other inputs: %s; start "
                           "fresh with --restart (discards them) or choose another --out",
                           st->rows_path, done.n, what);
    }
  }
  fb_status pst = o->write_json(prov_path, prov, &d);
  json_decref(prov);
  if (pst != FB_OK) {
    fb_sweep_rows_free(&done);
    return fb_study_fail("sweep", 1, "%s", d.msg);
  }
  char *have = calloc(s->points, 1);
  if (!have) {
    fb_sweep_rows_free(&done);
    return fb_study_fail("sweep", 1, "out of memory");
  }
  for (size_t k = 0; k < done.n; k++) {
    size_t of = 0;
    long i = fb_study_row_index(done.rows[k], &of);
    if (of != s->points) {
      free(have);
      fb_sweep_rows_free(&done);
      return fb_study_fail("sweep", 2, "%s holds rows of a %zu-point grid, this study has %zu "
                           "points: use another --out", st->rows_path, of, s->points);
    }
    if (i >= 0 && (size_t)i < s->points) have[i] = 1;
  }
  fb_sweep_rows_free(&done);
  st->todo = malloc(s->points * sizeof *st->todo);
  if (!st->todo) {
    free(have);
    return fb_study_fail("sweep", 1, "out of memory for %zu points", s->points);
  }
  st->ntodo = st->mine = 0;
  for (size_t i = 0; i < s->points; i++) {
    if ((long)(i % (size_t)o->shard_n) != o->shard_i) continue;
    st->mine++;
    if (!have[i]) st->todo[st->ntodo++] = i;
  }
  free(have);
  return 0;
}

/* the points computed here, one after the other; returns the exit status */
static int compute_here(sweep_state *st) {
  int rc = 0;
  fb_diag d;
  for (size_t k = 0; k < st->ntodo && rc == 0; k++) {
    char *line;
    if (fb_study_point(st->s, st->todo[k], &line, &d) != FB_OK) {
      rc = fb_study_fail("sweep", 1, "%s", d.msg);
      break;
    }
    if (fb_sweep_rows_append(st->fd, line) != 0)
      rc = fb_study_fail("sweep", 1, "%s: write failed", st->rows_path);
    else kept++;
    free(line);
    progress(++st->finished, st->ntodo, st->t0, st->tty);
  }
  return rc;
}

/* the whole lines in a worker's buffer b (*len bytes) appended to the rows
 * file; returns 1 when an append failed */
static int take_lines(sweep_state *st, char *b, size_t *len) {
  int bad = 0;
  char *nl;
  while ((nl = memchr(b, '\n', *len))) {
    size_t l = (size_t)(nl - b) + 1;
    char save = b[l];
    b[l] = '\0';
    if (fb_sweep_rows_append(st->fd, b) != 0) bad = 1;
    else kept++;
    b[l] = save;
    memmove(b, b + l, *len - l + 1);
    *len -= l;
    progress(++st->finished, st->ntodo, st->t0, st->tty);
  }
  return bad;
}

/* worker w of nw: computes todo[k] for k % nw == w, each row through fd */
static void worker(const sweep_state *st, int w, int nw, int fd) {
  fb_diag d;
  for (size_t k = (size_t)w; k < st->ntodo; k += (size_t)nw) {
    char *line;
    if (fb_study_point(st->s, st->todo[k], &line, &d) != FB_OK) _exit(3);
    if (fb_sweep_rows_append(fd, line) != 0 && errno != EINVAL) _exit(4);
    free(line);
  }
  _exit(0);
}

/* the points computed by worker processes: worker w computes todo[k] for
 * k % jobs == w and sends rows through its pipe; this process alone writes
 * the file. Returns the exit status. */
static int compute_workers(sweep_state *st) {
  int nw = (int)(st->o->jobs < (long)st->ntodo ? st->o->jobs : (long)st->ntodo);
  pid_t pid[256];
  int rfd[256], rc = 0;
  char *buf[256];
  size_t blen[256], bcap[256];
  fflush(NULL);
  for (int w = 0; w < nw; w++) {
    int p[2];
    if (pipe(p) != 0) return fb_study_fail("sweep", 1, "pipe: %s", strerror(errno));
    const pid_t parent = getpid();
    pid[w] = fork();
    if (pid[w] == 0) {
      /* a worker dies with its parent (a killed sweep leaves no orphan)
       * and holds none of its locks (worker.h) */
      if (fb_worker_tie_to_parent(parent, p[1]) != 0) _exit(5);
      worker(st, w, nw, p[1]);
    }
    close(p[1]);
    rfd[w] = p[0];
    buf[w] = NULL;
    blen[w] = bcap[w] = 0;
  }
  int open_pipes = nw;
  while (open_pipes > 0) {
    struct pollfd pf[256];
    for (int w = 0; w < nw; w++) {
      pf[w].fd = rfd[w];
      pf[w].events = POLLIN;
      pf[w].revents = 0;
    }
    if (poll(pf, (nfds_t)nw, -1) < 0 && errno != EINTR) break;
    for (int w = 0; w < nw; w++) {
      if (rfd[w] < 0 || !(pf[w].revents & (POLLIN | POLLHUP))) continue;
      char chunk[65536];
      ssize_t got = read(rfd[w], chunk, sizeof chunk);
      if (got <= 0) {
        close(rfd[w]);
        rfd[w] = -1;
        open_pipes--;
        continue;
      }
      if (blen[w] + (size_t)got + 1 > bcap[w]) {
        bcap[w] = 2 * (blen[w] + (size_t)got + 1);
        buf[w] = realloc(buf[w], bcap[w]);
      }
      memcpy(buf[w] + blen[w], chunk, (size_t)got);
      blen[w] += (size_t)got;
      buf[w][blen[w]] = '\0';
      if (take_lines(st, buf[w], &blen[w])) rc = 1;
    }
  }
  for (int w = 0; w < nw; w++) {
    int status;
    waitpid(pid[w], &status, 0);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) rc = 1;
    free(buf[w]);
  }
  if (rc) fb_study_fail("sweep", 1, "a worker failed; rerun to finish the remaining points");
  return rc;
}

/* the CSV of everything the rows file holds, and what it holds on stdout;
 * returns the exit status */
static int finish(const sweep_state *st, double wall) {
  const fb_study *s = st->s;
  fb_sweep_rowset all = {0};
  char err[4400] = "";
  fb_diag d;
  int rc = 0;
  if (fb_sweep_rows_read(st->rows_path, &all, 0, err, sizeof err) != 0) {
    fb_sweep_rows_free(&all);
    return fb_study_fail("sweep", 1, "%s", err);
  }
  char csv[4300];
  fb_sweep_rows_beside(csv, sizeof csv, st->rows_path, ".csv");
  if (fb_study_write_csv(csv, all.rows, all.n, &d) != FB_OK) rc = fb_study_fail("sweep", 1, "%s", d.msg);
  printf("%s: %zu rows (%zu computed now in %.1f s) in %s and %s\n", s->name, all.n, st->finished,
         wall, st->rows_path, csv);
  size_t stopped, warned;
  fb_study_tally(all.rows, all.n, &stopped, &warned);
  if (stopped || warned)
    printf("%zu of them stopped (column status), %zu carry warnings (column warnings)\n", stopped,
           warned);
  /* the study figure, once the whole grid is in this folder's points.csv */
  if (!rc && st->o->shard_n == 1 && all.n == s->points) {
    if (st->o->draw(s, st->o->dir, &d) != FB_OK) fprintf(stderr, "fourbar sweep: warning: %s\n", d.msg);
    else printf("drew %s/study.svg\n", st->o->dir);
  }
  fb_sweep_rows_free(&all);
  return rc;
}

int fb_sweep_run(const fb_study *s, const fb_sweep_opts *o) {
  /* one writer per folder (outdir.h); released when this process ends */
  static fb_outdir od;
  fb_diag d;
  char tag[64];
  snprintf(tag, sizeof tag, "shard-%ld-of-%ld", o->shard_i, o->shard_n);
  const fb_status lst = fb_outdir_lock(&od, o->dir, 0, o->shard_n > 1 ? tag : NULL, &d);
  if (lst != FB_OK) return fb_study_fail("sweep", lst == FB_ERR_ARG ? 2 : 1, "%s", d.msg);
  static sweep_state st;
  st = (sweep_state){.s = s, .o = o, .fd = -1};
  if (o->shard_n > 1)
    snprintf(st.rows_path, sizeof st.rows_path, "%s/points.shard-%ld-of-%ld.jsonl", o->dir,
             o->shard_i, o->shard_n);
  else
    snprintf(st.rows_path, sizeof st.rows_path, "%s/points.jsonl", o->dir);
  /* its files: replaced only when a sweep wrote them (the folder's
   * manifest), or asked (--overwrite, --restart); recorded before any is
   * written, so that a killed sweep's rows are its own when it resumes */
  char base[4300], names[5][4400];
  snprintf(base, sizeof base, "%s", strrchr(st.rows_path, '/') + 1);
  snprintf(names[0], sizeof names[0], "%s", base);
  fb_sweep_rows_beside(names[1], sizeof names[1], base, ".provenance.json");
  fb_sweep_rows_beside(names[2], sizeof names[2], base, ".csv");
  snprintf(names[3], sizeof names[3], "study.svg");
  snprintf(names[4], sizeof names[4], "study.figure.json");
  const char *const name_list[5] = {names[0], names[1], names[2], names[3], names[4]};
  const int nnames = o->shard_n > 1 ? 3 : 5;
  const fb_outpath_rule rule = {.flag = "--out", .overwrite = o->overwrite || o->restart};
  if (fb_outfiles_check(o->dir, "sweep", name_list, nnames, &rule, &d) != FB_OK)
    return fb_study_fail("sweep", 2, "%s", d.msg);
  if (fb_manifest_record(od.target, "sweep", name_list, nnames, &d) != FB_OK)
    return fb_study_fail("sweep", 1, "%s", d.msg);
  int rc = resume(&st);
  if (rc) return rc;
  fprintf(stderr, "study %s: %zu points, %zu in this %s, %zu already done, computing %zu with %ld job%s\n",
          s->name, s->points, st.mine, o->shard_n > 1 ? "shard" : "run", st.mine - st.ntodo,
          st.ntodo, o->jobs, o->jobs > 1 ? "s" : "");
  /* never through a link, never blocking on a FIFO (checked above; again here) */
  st.fd = open(st.rows_path, O_WRONLY | O_CREAT | O_APPEND | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0644);
  struct stat sb;
  if (st.fd >= 0 && (fstat(st.fd, &sb) != 0 || !S_ISREG(sb.st_mode))) {
    close(st.fd);
    st.fd = -1;
    errno = EINVAL;
  }
  if (st.fd < 0) {
    free(st.todo);
    return fb_study_fail("sweep", 1, "%s: %s", st.rows_path, strerror(errno));
  }
  st.tty = isatty(2);
  st.t0 = fb_clock_s();
  /* stopped by a signal: the rows kept and the command that resumes */
  static char note_tail[4 * 4300 + 8192 + 128], esc_rows[4 * 4300];
  kept = (long)(st.mine - st.ntodo);
  snprintf(note_tail, sizeof note_tail, " of %zu points of this %s kept in %s; resume with: %s",
           st.mine, o->shard_n > 1 ? "shard" : "study",
           fb_text_escape(esc_rows, sizeof esc_rows, st.rows_path), o->again);
  fb_cleanup_note("fourbar sweep: stopped", "", &kept, note_tail);
  if (o->jobs == 1 || st.ntodo <= 1) rc = compute_here(&st);
  else rc = compute_workers(&st);
  close(st.fd);
  free(st.todo);
  const double wall = fb_clock_s() - st.t0;
  if (rc) return rc;
  return finish(&st, wall);
}
