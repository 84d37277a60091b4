/* fourbar sweep and fourbar merge: parsing, processes and files. The points
 * themselves are computed by study.c. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <fcntl.h>
#include <getopt.h>
#include <jansson.h>
#include <limits.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>
#include <dirent.h>

#include "casefile.h"
#include "cli.h"
#include "textsafe.h"
#include "clock.h"
#include "figures.h"
#include "fileio.h"
#include "outdir.h"
#include "worker.h"

#ifndef FB_VERSION
#define FB_VERSION "unknown"
#endif
#include "report.h"
#include "study.h"

static const char sweep_help[] =
    "usage: fourbar sweep STUDY [--jobs J] [--shard I/N] [--out DIR]\n"
    "       fourbar sweep STUDY --list N [--out DIR]\n"
    "\n"
    "Runs every point of a study's grid (cases/studies/*.ini): one row per point in\n"
    "DIR/points.jsonl (appended as points finish) and DIR/points.csv (written at the\n"
    "end, sorted). A rerun skips the points already in the JSON lines, so a killed\n"
    "sweep resumes without recomputing. Rows are resumed only when computed from the\n"
    "same study, case files and fourbar version (recorded in\n"
    "DIR/points.provenance.json); otherwise the sweep refuses and says what changed.\n"
    "A progress bar with ETA is drawn on a terminal.\n"
    "\n"
    "  --jobs J     J worker processes on this machine (default 1)\n"
    "  --shard I/N  only points with index % N == I (0 <= I < N), into\n"
    "               DIR/points.shard-I-of-N.jsonl: for Slurm job arrays\n"
    "               (--shard $SLURM_ARRAY_TASK_ID/N) or GNU parallel\n"
    "  --list N     print the N shard commands, one per line, for GNU parallel\n"
    "  --restart    discard the rows already in DIR (of this shard) and start fresh\n"
    "  --out DIR    default results/studies/<study name>\n"
    "Then: fourbar merge DIR... joins shard outputs, checking no point is missing\n"
    "or duplicated.\n"
    "Exit status: 0 ok, 1 failed, 2 bad input.\n";

static const char merge_help[] =
    "usage: fourbar merge DIR... [--out DIR] [--study STUDY]\n"
    "\n"
    "Joins the points*.jsonl files of the given folders into OUT/points.jsonl and\n"
    "OUT/points.csv (default OUT: the first DIR), after checking that they belong to\n"
    "one study and that every point 0..N-1 is present exactly once. With --study\n"
    "it also draws OUT/study.svg.\n"
    "Exit status: 0 ok, 1 failed, 2 bad input.\n";

typedef struct {
  char **rows;
  size_t n, cap;
} rowset;

static int rows_add(rowset *r, const char *line) {
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

static void rows_free(rowset *r) {
  for (size_t k = 0; k < r->n; k++) free(r->rows[k]);
  free(r->rows);
  memset(r, 0, sizeof *r);
}

/* reads the rows of a JSON-lines file, each checked field by field
 * (fb_study_row_parse). With repair (a sweep resuming its own file) a broken
 * or partial line (a killed writer) is dropped, to be computed again, and the
 * file rewritten without it; without repair (merge) the first one is an error
 * naming file, line and rule in err. */
static int read_rows(const char *path, rowset *r, int repair, char *err, size_t err_size) {
  FILE *f = fopen(path, "r");
  if (!f) {
    snprintf(err, err_size, "%s: cannot read: %s", path, strerror(errno));
    return errno == ENOENT ? 0 : -1;
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
      if (!rows_add(r, line)) {
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

static int append_row(int fd, const char *line) {
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

int fb_cmd_sweep(int argc, char **argv) {
  static const struct option opts[] = {{"jobs", required_argument, 0, 'j'},
                                       {"shard", required_argument, 0, 's'},
                                       {"out", required_argument, 0, 'o'},
                                       {"list", required_argument, 0, 'l'},
                                       {"restart", no_argument, 0, 'r'},
                                       {"help", no_argument, 0, 'h'},
                                       {0, 0, 0, 0}};
  long jobs = 1, shard_i = 0, shard_n = 1, list = 0;
  int restart = 0;
  const char *out = NULL;
  int ch;
  optind = 1;
  while ((ch = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
    char *end;
    switch (ch) {
      case 'j':
        jobs = strtol(optarg, &end, 10);
        if (*end || jobs < 1 || jobs > 256) return fb_cli_fail("sweep", 2, "--jobs '%s': 1 to 256", optarg);
        break;
      case 's':
        {
          int used = -1; /* the whole value: "0/2junk" is not a shard */
          if (sscanf(optarg, "%ld/%ld%n", &shard_i, &shard_n, &used) != 2 ||
              used != (int)strlen(optarg) || strspn(optarg, "0123456789/") != strlen(optarg))
            shard_n = 0;
        }
        if (shard_n < 1 || shard_n > 100000 || shard_i < 0 || shard_i >= shard_n)
          return fb_cli_fail("sweep", 2, "--shard '%s': expected I/N, decimal integers with 0 <= I < N <= 100000", optarg);
        break;
      case 'o': out = optarg; break;
      case 'r': restart = 1; break;
      case 'l':
        list = strtol(optarg, &end, 10);
        if (*end || list < 1 || list > 100000) return fb_cli_fail("sweep", 2, "--list '%s': 1 to 100000", optarg);
        break;
      case 'h': fputs(sweep_help, stdout); return 0;
      default: return fb_cli_bad_option(argv, "h");
    }
  }
  if (argc - optind != 1) return fb_cli_fail("sweep", 2, "one STUDY file is required; see --help");
  const char *study_path = argv[optind];
  static fb_study s;
  fb_diag d;
  if (fb_study_load_with_cases(&s, study_path, fb_cli_cases_dir(), &d) != FB_OK)
    return fb_cli_fail("sweep", 2, "%s", d.msg);
  {
    /* a point runs its case alone: said when the case has variants */
    static fb_case probe;
    fb_diag pd;
    if (!list && fb_casefile_load(&probe, s.case_path, NULL, 0, &pd) == FB_OK && probe.variant_count)
      fprintf(stderr, "fourbar sweep: note: %s has %d [variant.*] section%s; a sweep runs each "
              "point's case alone, without them (fourbar run runs them)\n", s.case_path,
              probe.variant_count, probe.variant_count > 1 ? "s" : "");
  }
  char dir[4096];
  if (out) snprintf(dir, sizeof dir, "%s", out);
  else snprintf(dir, sizeof dir, "results/studies/%s", s.name);

  if (list) {
    char exe[PATH_MAX];
    ssize_t l = readlink("/proc/self/exe", exe, sizeof exe - 1);
    exe[l > 0 ? l : 0] = '\0';
    char study_abs[PATH_MAX], dir_abs[PATH_MAX];
    if (!realpath(study_path, study_abs)) snprintf(study_abs, sizeof study_abs, "%s", study_path);
    if (fb_outdir_prepare(dir, &d) != FB_OK) return fb_cli_fail("sweep", 1, "%s", d.msg);
    if (!realpath(dir, dir_abs)) snprintf(dir_abs, sizeof dir_abs, "%s", dir);
    for (long k = 0; k < list; k++) {
      static char line[12 * PATH_MAX + 64]; /* a quote takes 4 characters */
      line[0] = '\0';
      int fits = fb_cli_shell_word(line, sizeof line, l > 0 ? exe : "fourbar");
      strcat(line, " sweep ");
      fits = fits && fb_cli_shell_word(line, sizeof line, study_abs);
      snprintf(line + strlen(line), sizeof line - strlen(line), " --shard %ld/%ld --out ", k, list);
      if (!fits || !fb_cli_shell_word(line, sizeof line, dir_abs))
        return fb_cli_fail("sweep", 2, "%s: path too long for a command line", dir_abs);
      puts(line);
    }
    return 0;
  }
  /* one writer per folder (outdir.h); released when this process ends */
  static fb_outdir od;
  char tag[64];
  snprintf(tag, sizeof tag, "shard-%ld-of-%ld", shard_i, shard_n);
  if (fb_outdir_lock(&od, dir, 0, shard_n > 1 ? tag : NULL, &d) != FB_OK)
    return fb_cli_fail("sweep", 1, "%s", d.msg);
  char rows_path[4200];
  if (shard_n > 1)
    snprintf(rows_path, sizeof rows_path, "%s/points.shard-%ld-of-%ld.jsonl", dir, shard_i, shard_n);
  else
    snprintf(rows_path, sizeof rows_path, "%s/points.jsonl", dir);

  /* what the rows are computed from, beside them */
  char prov_path[4300];
  snprintf(prov_path, sizeof prov_path, "%.*s.provenance.json", (int)(strlen(rows_path) - 6), rows_path);
  if (restart) {
    char csv_path[4300];
    snprintf(csv_path, sizeof csv_path, "%.*s.csv", (int)(strlen(rows_path) - 6), rows_path);
    unlink(rows_path);
    unlink(csv_path);
    unlink(prov_path);
  }
  /* resume: what this file already holds */
  rowset done = {0};
  char err[4400] = "";
  if (read_rows(rows_path, &done, 1, err, sizeof err) != 0) return fb_cli_fail("sweep", 1, "%s", err);
  json_t *prov = fb_study_provenance(&s);
  json_object_set_new(prov, "fourbar_version", json_string(FB_VERSION));
  if (done.n) {
    /* resume only rows computed from the same study, case files and program */
    char what[4400];
    if (provenance_differs(prov_path, prov, what, sizeof what)) {
      json_decref(prov);
      rows_free(&done);
      return fb_cli_fail("sweep", 2, "%s holds %zu rows computed from other inputs: %s; start "
                         "fresh with --restart (discards them) or choose another --out",
                         rows_path, done.n, what);
    }
  }
  fb_status pst = fb_report_write_json(prov_path, prov, &d);
  json_decref(prov);
  if (pst != FB_OK) {
    rows_free(&done);
    return fb_cli_fail("sweep", 1, "%s", d.msg);
  }
  char *have = calloc(s.points, 1);
  if (!have) return fb_cli_fail("sweep", 1, "out of memory");
  for (size_t k = 0; k < done.n; k++) {
    size_t of = 0;
    long i = fb_study_row_index(done.rows[k], &of);
    if (of != s.points) {
      free(have);
      rows_free(&done);
      return fb_cli_fail("sweep", 2, "%s holds rows of a %zu-point grid, this study has %zu points: "
                         "use another --out", rows_path, of, s.points);
    }
    if (i >= 0 && (size_t)i < s.points) have[i] = 1;
  }
  size_t *todo = malloc(s.points * sizeof *todo);
  if (!todo) {
    rows_free(&done);
    return fb_cli_fail("sweep", 1, "out of memory for %zu points", s.points);
  }
  size_t ntodo = 0, mine = 0;
  for (size_t i = 0; i < s.points; i++) {
    if ((long)(i % (size_t)shard_n) != shard_i) continue;
    mine++;
    if (!have[i]) todo[ntodo++] = i;
  }
  free(have);
  fprintf(stderr, "study %s: %zu points, %zu in this %s, %zu already done, computing %zu with %ld job%s\n",
          s.name, s.points, mine, shard_n > 1 ? "shard" : "run", mine - ntodo, ntodo, jobs,
          jobs > 1 ? "s" : "");
  int fd = open(rows_path, O_WRONLY | O_CREAT | O_APPEND, 0644);
  if (fd < 0) {
    free(todo);
    rows_free(&done);
    return fb_cli_fail("sweep", 1, "%s: %s", rows_path, strerror(errno));
  }
  const int tty = isatty(2);
  const double t0 = fb_clock_s();
  size_t finished = 0;
  int rc = 0;
  /* stopped by a signal: the rows kept and the command that resumes */
  static volatile long kept;
  static char note_tail[4 * 4300 + 8192 + 128], esc_rows[4 * 4300], again[8192];
  kept = (long)(mine - ntodo);
  fb_cli_command_line(again, sizeof again, argc, argv, "--restart");
  snprintf(note_tail, sizeof note_tail, " of %zu points of this %s kept in %s; resume with: %s",
           mine, shard_n > 1 ? "shard" : "study", fb_text_escape(esc_rows, sizeof esc_rows, rows_path),
           again);
  fb_cleanup_note("fourbar sweep: stopped", "", &kept, note_tail);
  if (jobs == 1 || ntodo <= 1) {
    for (size_t k = 0; k < ntodo && rc == 0; k++) {
      char *line;
      if (fb_study_point(&s, todo[k], &line, &d) != FB_OK) {
        rc = fb_cli_fail("sweep", 1, "%s", d.msg);
        break;
      }
      if (append_row(fd, line) != 0) rc = fb_cli_fail("sweep", 1, "%s: write failed", rows_path);
      else kept++;
      free(line);
      progress(++finished, ntodo, t0, tty);
    }
  } else {
    /* workers: worker w computes todo[k] for k % jobs == w and sends rows
     * through its pipe; the parent alone writes the file */
    int nw = (int)(jobs < (long)ntodo ? jobs : (long)ntodo);
    pid_t pid[256];
    int rfd[256];
    char *buf[256];
    size_t blen[256], bcap[256];
    fflush(NULL);
    for (int w = 0; w < nw; w++) {
      int p[2];
      if (pipe(p) != 0) return fb_cli_fail("sweep", 1, "pipe: %s", strerror(errno));
      const pid_t parent = getpid();
      pid[w] = fork();
      if (pid[w] == 0) {
        /* a worker dies with its parent (a killed sweep leaves no orphan)
         * and holds none of its locks (worker.h) */
        if (fb_worker_tie_to_parent(parent, p[1]) != 0) _exit(5);
        for (size_t k = (size_t)w; k < ntodo; k += (size_t)nw) {
          char *line;
          if (fb_study_point(&s, todo[k], &line, &d) != FB_OK) _exit(3);
          if (append_row(p[1], line) != 0 && errno != EINVAL) _exit(4);
          free(line);
        }
        _exit(0);
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
        char *nl;
        while ((nl = memchr(buf[w], '\n', blen[w]))) {
          size_t l = (size_t)(nl - buf[w]) + 1;
          char save = buf[w][l];
          buf[w][l] = '\0';
          if (append_row(fd, buf[w]) != 0) rc = 1;
          else kept++;
          buf[w][l] = save;
          memmove(buf[w], buf[w] + l, blen[w] - l + 1);
          blen[w] -= l;
          progress(++finished, ntodo, t0, tty);
        }
      }
    }
    for (int w = 0; w < nw; w++) {
      int status;
      waitpid(pid[w], &status, 0);
      if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) rc = 1;
      free(buf[w]);
    }
    if (rc) fb_cli_fail("sweep", 1, "a worker failed; rerun to finish the remaining points");
  }
  close(fd);
  free(todo);
  rows_free(&done);
  const double wall = fb_clock_s() - t0;
  if (rc) return rc;
  /* the CSV of everything this file holds */
  rowset all = {0};
  if (read_rows(rows_path, &all, 0, err, sizeof err) != 0) {
    rows_free(&all);
    return fb_cli_fail("sweep", 1, "%s", err);
  }
  char csv[4300];
  snprintf(csv, sizeof csv, "%.*s.csv", (int)(strlen(rows_path) - 6), rows_path);
  if (fb_study_write_csv(csv, all.rows, all.n, &d) != FB_OK) rc = fb_cli_fail("sweep", 1, "%s", d.msg);
  printf("%s: %zu rows (%zu computed now in %.1f s) in %s and %s\n", s.name, all.n, finished, wall,
         rows_path, csv);
  size_t stopped, warned;
  fb_study_tally(all.rows, all.n, &stopped, &warned);
  if (stopped || warned)
    printf("%zu of them stopped (column status), %zu carry warnings (column warnings)\n", stopped,
           warned);
  /* the study figure, once the whole grid is in this folder's points.csv */
  if (!rc && shard_n == 1 && all.n == s.points) {
    if (fb_figures_study(&s, dir, &d) != FB_OK) fprintf(stderr, "fourbar sweep: warning: %s\n", d.msg);
    else printf("drew %s/study.svg\n", dir);
  }
  rows_free(&all);
  return rc;
}

/* the provenance file beside a rows file: points[.X].jsonl -> points[.X].provenance.json */
static void provenance_path(char *out, size_t size, const char *rows_path) {
  snprintf(out, size, "%.*s.provenance.json", (int)(strlen(rows_path) - 6), rows_path);
}

/* 1 when the folder's points.jsonl is a merge's output (its provenance says so) */
static int merged_output(const char *dir) {
  char path[4300];
  snprintf(path, sizeof path, "%s/points.provenance.json", dir);
  json_t *p = json_load_file(path, 0, NULL);
  const int merged = json_is_true(json_object_get(p, "merged"));
  json_decref(p);
  return merged;
}

int fb_cmd_merge(int argc, char **argv) {
  static const struct option opts[] = {{"out", required_argument, 0, 'o'},
                                       {"study", required_argument, 0, 's'},
                                       {"help", no_argument, 0, 'h'},
                                       {0, 0, 0, 0}};
  const char *out = NULL, *study_path = NULL;
  int ch;
  optind = 1;
  while ((ch = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
    if (ch == 'o') out = optarg;
    else if (ch == 's') study_path = optarg;
    else if (ch == 'h') { fputs(merge_help, stdout); return 0; }
    else { return fb_cli_bad_option(argv, "h"); }
  }
  if (optind >= argc) return fb_cli_fail("merge", 2, "at least one DIR is required; see --help");
  if (!out) out = argv[optind];
  /* the output folder, locked before anything is read: no shard may be
   * writing it; compared by its real path, not its spelling (D and D/) */
  static fb_outdir od;
  fb_diag d;
  if (fb_outdir_lock(&od, out, 0, NULL, &d) != FB_OK) return fb_cli_fail("merge", 1, "%s", d.msg);
  char out_real[PATH_MAX];
  if (!realpath(out, out_real)) snprintf(out_real, sizeof out_real, "%s", od.target);
  /* a study given to draw with must be the shards' study: loaded first */
  static fb_study st;
  json_t *study_prov = NULL;
  if (study_path) {
    if (fb_study_load_with_cases(&st, study_path, fb_cli_cases_dir(), &d) != FB_OK)
      return fb_cli_fail("merge", 2, "--study: %s", d.msg);
    study_prov = fb_study_provenance(&st);
    json_object_set_new(study_prov, "fourbar_version", json_string(FB_VERSION));
  }
  rowset all = {0};
  json_t *prov = NULL; /* the shards' common provenance */
  char prov_from[8300] = "";
  static char prov_problem[20000];
  prov_problem[0] = '\0';
  int rc = 0;
  for (int a = optind; a < argc && !rc; a++) {
    DIR *dd = opendir(argv[a]);
    if (!dd) {
      rc = fb_cli_fail("merge", 2, "%s: %s", argv[a], strerror(errno));
      break;
    }
    char real[PATH_MAX];
    const int is_out = realpath(argv[a], real) && strcmp(real, out_real) == 0;
    struct dirent *e;
    while (!rc && (e = readdir(dd))) {
      size_t l = strlen(e->d_name);
      if (strncmp(e->d_name, "points", 6) != 0 || l < 6 || strcmp(e->d_name + l - 6, ".jsonl") != 0) continue;
      char path[8192];
      snprintf(path, sizeof path, "%s/%s", argv[a], e->d_name);
      if (strcmp(e->d_name, "points.jsonl") == 0 && merged_output(argv[a]))
        continue; /* a previous merge's output: merged again from the shards */
      if (strcmp(e->d_name, "points.jsonl") == 0 && is_out) {
        rc = fb_cli_fail("merge", 2, "%s holds a sweep's own rows (not a merge's output), which "
                         "merging into %s would replace: give another --out", path, out);
        break;
      }
      char err[9000];
      if (read_rows(path, &all, 0, err, sizeof err) != 0) {
        rc = fb_cli_fail("merge", 2, "%s", err);
        break;
      }
      /* each file's provenance, all equal: rows of two studies, builds or
       * environments are never mixed */
      char pp[8300];
      provenance_path(pp, sizeof pp, path);
      json_t *p = json_load_file(pp, 0, NULL);
      char what[3000];
      if (prov_problem[0]) {
        /* the first problem is reported, after the rows' own checks */
      } else if (!p) {
        snprintf(prov_problem, sizeof prov_problem, "%s: its provenance %s is missing or "
                 "unreadable, so which study its rows belong to is unknown: run that shard again "
                 "(with --restart)", path, pp);
      } else if (!prov) {
        prov = p;
        snprintf(prov_from, sizeof prov_from, "%s", pp);
        p = NULL;
      } else if (fb_study_provenance_differs(prov, p, what, sizeof what)) {
        snprintf(prov_problem, sizeof prov_problem, "%s and %s: not one study's shards: %s",
                 prov_from, pp, what);
      }
      json_decref(p);
    }
    closedir(dd);
  }
  if (!rc && all.n == 0) rc = fb_cli_fail("merge", 2, "no points*.jsonl rows in the given folders");
  size_t of = 0;
  unsigned char *count = NULL;
  if (!rc) {
    fb_study_row_index(all.rows[0], &of); /* every row read was checked: 1 <= of <= 1e7 */
    count = calloc(of, 1);
    if (!count) rc = fb_cli_fail("merge", 1, "out of memory for %zu points", of);
  }
  if (!rc) {
    json_t *row0 = json_loads(all.rows[0], 0, NULL);
    char study0[256];
    snprintf(study0, sizeof study0, "%s", json_string_value(json_object_get(row0, "study")));
    json_decref(row0);
    for (size_t k = 0; k < all.n && !rc; k++) {
      size_t o2 = 0;
      long i = fb_study_row_index(all.rows[k], &o2);
      json_t *row = json_loads(all.rows[k], 0, NULL); /* checked when read: "study" is a string */
      char study[256];
      snprintf(study, sizeof study, "%s", json_string_value(json_object_get(row, "study")));
      json_decref(row);
      if (strcmp(study, study0) != 0)
        rc = fb_cli_fail("merge", 2, "rows of studies '%s' and '%s': not one study", study0, study);
      else if (o2 != of) rc = fb_cli_fail("merge", 2, "rows of a %zu-point and a %zu-point grid: not one study", of, o2);
      else if (i < 0 || (size_t)i >= of) rc = fb_cli_fail("merge", 2, "row index %ld outside 0..%zu", i, of - 1);
      else if (count[i]++) rc = fb_cli_fail("merge", 2, "point %ld appears more than once", i);
    }
  }
  if (!rc) {
    size_t missing = 0, first = 0;
    for (size_t i = 0; i < of; i++)
      if (!count[i] && missing++ == 0) first = i;
    if (missing) rc = fb_cli_fail("merge", 2, "%zu of %zu points missing (first: %zu): run the missing "
                                  "shards, then merge again", missing, of, first);
  }
  free(count);
  if (!rc && prov_problem[0]) rc = fb_cli_fail("merge", 2, "%s", prov_problem);
  char what[3000];
  if (!rc && study_prov && fb_study_provenance_differs(prov, study_prov, what, sizeof what))
    rc = fb_cli_fail("merge", 2, "--study %s is not the study of these shards (%s): give the study "
                     "file they were computed from", study_path, what);
  if (!rc) {
    /* rows, their provenance (marked as a merge's), then the table */
    char path[4200];
    snprintf(path, sizeof path, "%s/points.jsonl", out);
    fb_outfile o;
    if (fb_outfile_open(&o, path, &d) != FB_OK) {
      rc = fb_cli_fail("merge", 1, "%s", d.msg);
    } else {
      for (size_t k = 0; k < all.n; k++) fputs(all.rows[k], o.f);
      if (fb_outfile_commit(&o, &d) != FB_OK) rc = fb_cli_fail("merge", 1, "%s", d.msg);
    }
    json_object_set_new(prov, "merged", json_true());
    snprintf(path, sizeof path, "%s/points.provenance.json", out);
    if (!rc && fb_report_write_json(path, prov, &d) != FB_OK) rc = fb_cli_fail("merge", 1, "%s", d.msg);
    snprintf(path, sizeof path, "%s/points.csv", out);
    if (!rc && fb_study_write_csv(path, all.rows, all.n, &d) != FB_OK) rc = fb_cli_fail("merge", 1, "%s", d.msg);
    if (!rc) printf("merged %zu points into %s/points.jsonl and points.csv\n", all.n, out);
    if (!rc && study_path) {
      if (fb_figures_study(&st, out, &d) != FB_OK) rc = fb_cli_fail("merge", 1, "%s", d.msg);
      else printf("drew %s/study.svg\n", out);
    }
  }
  json_decref(prov);
  json_decref(study_prov);
  rows_free(&all);
  fb_outdir_release(&od);
  return rc;
}
