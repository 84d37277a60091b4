/* _GNU_SOURCE (meson.build): posix_spawn_file_actions_addchdir_np (glibc 2.29) */
#include "figures.h"

#include <errno.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

extern char **environ;

#include "bench.h"
#include "decimate.h"
#include "fileio.h"
#include "outdir.h"
#include "start.h"
#include "study.h"
#include "casefile.h"
#include "linkage.h"
#include "units.h"
#include "report.h"

/* figures one batch (a run) may hold */
#define FB_FIGURE_BATCH 64

typedef struct {
  FILE *p;         /* the figure's gnuplot script, written to a file in dir */
  int columns;     /* the figure's width [px]: the buckets of min/max decimation */
  char dir[4096];  /* output folder; gnuplot runs in it */
  char path[4400]; /* final name */
  char tmp[4400];  /* written by gnuplot (a fixed-form name in dir), renamed on success */
  char script[4400]; /* the script (a fixed-form name in dir), removed when drawn */
  char log[4400];
} plot;

static const char *ext(fb_figure_format f) { return f == FB_FIGURE_PNG ? "png" : "svg"; }

/* Text for the inside of a gnuplot single-quoted string: a single quote is
 * doubled (the only escape gnuplot knows there) and every control character
 * (a newline would end the command) becomes '?'; gnuplot does no backquote or
 * macro substitution inside single quotes, so the result is inert data. With
 * enhanced = 1 the enhanced-text markup characters _ ^ @ & ~ { } \ are
 * backslash-escaped too. Truncates to size (never inside an escape). */
static const char *gp_text(const char *in, int enhanced, char *out, size_t size) {
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
static const char *esc(const char *in, char *out, size_t size) { return gp_text(in, 1, out, size); }

/* Opens a figure: its gnuplot script is written to a file in dir
 * (.figure.tmp.<pid>.<n>.gp), and plot_close hands it to gnuplot as a file
 * argument. gnuplot reads a script on its standard input one byte per read
 * (246,849 read calls for a 20,000-point figure, 1.1 s against 0.2 s from a
 * file). The script never names a path from the user: gnuplot runs in dir
 * and writes the temporary name below, relative to it. */
static fb_status plot_open(plot *pl, const char *dir, const char *name, fb_figure_format fmt,
                           int width, int height, fb_diag *diag) {
  static unsigned serial;
  memset(pl, 0, sizeof *pl);
  pl->columns = width;
  snprintf(pl->dir, sizeof pl->dir, "%s", dir);
  snprintf(pl->path, sizeof pl->path, "%s/%s.%s", dir, name, ext(fmt));
  const unsigned n = serial++;
  char tmpname[96];
  snprintf(tmpname, sizeof tmpname, ".figure.tmp.%ld.%u.%s", (long)getpid(), n, ext(fmt));
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
  int logfd = open(pl[0].log, O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (logfd < 0)
    return fb_diag_set(diag, FB_ERR_IO, "%s: cannot start gnuplot: %s", pl[0].path, strerror(errno));
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
  int rc = posix_spawnp(pid, "gnuplot", &fa, NULL, argv, environ);
  posix_spawn_file_actions_destroy(&fa);
  close(logfd);
  if (rc != 0)
    return fb_diag_set(diag, FB_ERR_IO, "%s: cannot start gnuplot: %s (apt-get install "
                       "gnuplot-nox, or pass --no-figures)", pl[0].path, strerror(rc));
  fb_cleanup_child_add(*pid); /* at most FB_CLEANUP_CHILDREN run at once */
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

/* A run's figures: while a batch is open (fb_figures_run), plot_close only
 * keeps the figure's script; batch_end hands the scripts to one gnuplot per
 * processor (at most FB_CLEANUP_CHILDREN), each drawing its share in turn,
 * side by side, and puts every figure into place. One gnuplot for many
 * figures saves its start-up per figure (0.05 s of processor time each). */
static struct {
  int open;
  int n;
  plot pl[FB_FIGURE_BATCH];
} batch;

static void batch_begin(void) {
  memset(&batch, 0, sizeof batch);
  batch.open = 1;
}

/* the size of a figure's script [bytes]: what its drawing costs, nearly */
static long script_size(const plot *pl) {
  struct stat sb;
  return stat(pl->script, &sb) == 0 ? (long)sb.st_size : 0;
}

static fb_status batch_end(fb_diag *diag) {
  batch.open = 0;
  const int n = batch.n;
  if (n == 0) return FB_OK;
  const long cpus = sysconf(_SC_NPROCESSORS_ONLN);
  int groups = cpus < 1 ? 1 : cpus > FB_CLEANUP_CHILDREN ? FB_CLEANUP_CHILDREN : (int)cpus;
  if (groups > n) groups = n;
  /* contiguous shares of about equal script size, in the figures' order */
  long total = 0;
  for (int k = 0; k < n; k++) total += script_size(&batch.pl[k]);
  int first[FB_CLEANUP_CHILDREN + 1], g = 0;
  long acc = 0;
  first[0] = 0;
  for (int k = 0; k < n && g + 1 < groups; k++) {
    acc += script_size(&batch.pl[k]);
    if (acc * groups >= total * (g + 1) && k + 1 < n) first[++g] = k + 1;
  }
  groups = g + 1;
  first[groups] = n;
  pid_t pid[FB_CLEANUP_CHILDREN];
  int rc[FB_CLEANUP_CHILDREN];
  fb_status st = FB_OK;
  for (g = 0; g < groups; g++) {
    pid[g] = -1;
    rc[g] = 127;
    fb_diag d;
    const fb_status sg = gnuplot_start(&batch.pl[first[g]], first[g + 1] - first[g], &pid[g], &d);
    if (sg != FB_OK && st == FB_OK) {
      st = sg;
      *diag = d;
    }
  }
  for (g = 0; g < groups; g++)
    if (pid[g] > 0) rc[g] = gnuplot_wait(pid[g]);
  for (g = 0; g < groups; g++)
    for (int k = first[g]; k < first[g + 1]; k++) {
      fb_diag d;
      const fb_status sf = plot_finish(&batch.pl[k], rc[g], &d);
      if (sf != FB_OK && st == FB_OK) {
        st = sf;
        *diag = d;
      }
    }
  drop_empty_log(batch.pl[0].log);
  return st;
}

static fb_status plot_close(plot *pl, fb_diag *diag) {
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

fb_status fb_figures_check_gnuplot(fb_diag *diag) {
  const char *path = getenv("PATH");
  char buf[4096];
  snprintf(buf, sizeof buf, "%s", path && *path ? path : "/usr/bin:/bin");
  char *save = NULL;
  for (char *d = strtok_r(buf, ":", &save); d; d = strtok_r(NULL, ":", &save)) {
    char exe[4200];
    snprintf(exe, sizeof exe, "%s/gnuplot", *d ? d : ".");
    if (access(exe, X_OK) == 0) return FB_OK;
  }
  return fb_diag_set(diag, FB_ERR_IO, "gnuplot is not on PATH, and the figures need it: apt-get "
                     "install gnuplot-nox, or pass --no-figures");
}

/* crank angle in degrees in [0, 360) */
static double crank_deg(double th) {
  double d = fmod(th * 180.0 / M_PI, 360.0);
  return d < 0.0 ? d + 360.0 : d;
}

/* writes a datablock of (crank deg, y) over the window, min/max-decimated
 * per pixel column of the figure (decimate.h); a blank line where the crank
 * angle wraps; returns the points written and the extremes of what was
 * plotted (equal to the window's: min/max decimation) */
static int datablock_x(const plot *pl, const char *name, const fb_series *s, const double *y,
                       double t0, double t1, int x_time, double *ymin, double *ymax);

static int datablock(const plot *pl, const char *name, const fb_series *s, const double *y,
                     double t0, double t1, double *ymin, double *ymax) {
  return datablock_x(pl, name, s, y, t0, t1, 0, ymin, ymax);
}

/* as datablock, x either the crank angle [deg] (x_time = 0) or the time [ms]
 * (x_time = 1: no wrap, pixel columns equally wide in log t from t0 > 0, as
 * the log axis draws them, so the first microseconds keep their samples) */
static int datablock_x(const plot *pl, const char *name, const fb_series *s, const double *y,
                       double t0, double t1, int x_time, double *ymin, double *ymax) {
  FILE *p = pl->p;
  size_t i0 = 0, i1 = 0;
  while (i0 < s->n && s->t[i0] < t0) i0++;
  i1 = i0;
  while (i1 < s->n && s->t[i1] <= t1) i1++;
  const size_t count = i1 > i0 ? i1 - i0 : 0;
  /* the abscissa the figure draws, and the samples each pixel column keeps */
  const int logt = x_time && t0 > 0.0 && t1 > t0;
  double *ax = malloc((count ? count : 1) * sizeof *ax);
  size_t *keep = malloc((count ? count : 1) * sizeof *keep);
  size_t m = 0;
  if (ax && keep) {
    for (size_t k = 0; k < count; k++)
      ax[k] = logt ? log(s->t[i0 + k]) : x_time ? s->t[i0 + k] : crank_deg(s->crank_angle[i0 + k]);
    const double a0 = logt ? log(t0) : x_time ? t0 : 0.0, a1 = logt ? log(t1) : x_time ? t1 : 360.0;
    m = fb_decimate_minmax(ax, y + i0, count, a0, a1 > a0 ? a1 : a0 + 1.0, pl->columns, keep);
  } else { /* no memory for the decimation: every sample */
    for (size_t k = 0; keep && k < count; k++) keep[m++] = k;
  }
  fprintf(p, "$%s << EOD\n", name);
  int pts = 0;
  double last = -1.0;
  for (size_t q = 0; q < m || (!keep && q < count); q++) {
    const size_t i = i0 + (keep ? keep[q] : q);
    if (isnan(y[i])) continue;
    double x = x_time ? s->t[i] * 1e3 : crank_deg(s->crank_angle[i]);
    if (!x_time && last >= 0.0 && fabs(x - last) > 180.0) fprintf(p, "\n");
    fprintf(p, x_time ? "%.9g %.17g\n" : "%.6f %.17g\n", x, y[i]);
    if (pts == 0 || y[i] < *ymin) *ymin = y[i];
    if (pts == 0 || y[i] > *ymax) *ymax = y[i];
    last = x;
    pts++;
  }
  fprintf(p, "EOD\n");
  free(ax);
  free(keep);
  return pts;
}

static void manifest_add(json_t *figs, const char *file, const char *title, json_t *curves) {
  json_t *o = json_object();
  json_object_set_new(o, "file", json_string(file));
  json_object_set_new(o, "title", json_string(title));
  json_object_set_new(o, "curves", curves);
  json_array_append_new(figs, o);
}

static json_t *curve(const char *model, const char *column, const char *csv, int points,
                     double ymin, double ymax, double t0, double t1) {
  json_t *o = json_pack("{s:s,s:s,s:s,s:i}", "model", model, "column", column, "csv", csv,
                        "points", points);
  if (isfinite(ymin)) {
    json_object_set_new(o, "y_min", json_real(ymin));
    json_object_set_new(o, "y_max", json_real(ymax));
    json_object_set_new(o, "time_from_s", json_real(t0));
    json_object_set_new(o, "time_to_s", json_real(t1));
  }
  return o;
}

/* ---- one style per model, the same in every figure ------------------------ */

typedef struct {
  const char *name;  /* model name */
  const char *color; /* '#rrggbb' */
  int dash;          /* gnuplot dash type: 1 solid, 2 dashed, 3 dotted, 4 dash-dot */
  double width;      /* line width */
} model_style;


/* models without a style in the table: a colour from this list chosen by a hash of the
 * name, so it is the same in every figure of every run */
static const char *const fallback_colors[] = {"#17becf", "#e377c2", "#8c564b", "#bcbd22",
                                              "#393b79", "#637939", "#843c39", "#7b4173"};

/* Colour families: every model of one simulation engine is drawn in shades
 * of that engine's hue (ODE blues, MuJoCo oranges; greens and purples kept
 * for Simbody and Bullet), so that two engines are told apart at a glance
 * in every figure; the yardsticks (analytic, reference) keep the model
 * table's black and grey. The shade is the row's rank among the rows of
 * its engine in the model table, the dash and width the table's. */
typedef struct {
  const char *engine;       /* fb_engine_name of the engine */
  const char *shade[8];     /* dark to light, in an order that keeps neighbours apart */
} color_family;

static const color_family families[] = {
    {"ode", {"#08519c", "#3182bd", "#6baed6", "#2171b5", "#4292c6", "#9ecae1", "#084594", "#5a8fc4"}},
    {"mujoco", {"#a63603", "#e6550d", "#fd8d3c", "#d94801", "#f16913", "#fdae6b", "#7f2704", "#c8640a"}},
    {"simbody", {"#006d2c", "#31a354", "#74c476", "#238b45", "#41ab5d", "#a1d99b", "#00441b", "#4f9a5f"}},
    {"bullet", {"#54278f", "#756bb1", "#9e9ac8", "#6a51a3", "#807dba", "#bcbddc", "#3f007d", "#8a6fb3"}},
};

/* the colour of row m from its engine's family, or NULL (a yardstick or an
 * engine without a family) */
static const char *family_color(const fb_model *m) {
  const char *engine = fb_engine_name(m->engine);
  for (size_t f = 0; f < sizeof families / sizeof families[0]; f++) {
    if (strcmp(families[f].engine, engine) != 0) continue;
    int rank = 0;
    for (int k = 0; k < fb_model_count && &fb_models[k] != m; k++) rank += fb_models[k].engine == m->engine;
    return families[f].shade[rank % 8];
  }
  return NULL;
}

/* the model's style: its engine's colour family (or the model table's
 * colour for a yardstick) with the table's dash and width (model_table.c;
 * docs/figures.md), else one derived from the name */
static model_style style_of(const char *name) {
  const fb_model *m = fb_model_find(name);
  if (m && (m->style.color || family_color(m))) {
    const char *color = family_color(m);
    const model_style st = {m->name, color ? color : m->style.color, m->style.dash,
                            m->style.width};
    return st;
  }
  unsigned long h = 2166136261ul; /* FNV-1a */
  for (const unsigned char *c = (const unsigned char *)name; *c; c++) h = (h ^ *c) * 16777619ul;
  const size_t nf = sizeof fallback_colors / sizeof fallback_colors[0];
  model_style st = {name, fallback_colors[h % nf], 1 + (int)((h / nf) % 2) * 4, 1.3};
  return st;
}

/* "lc rgb '#rrggbb' dt N lw W" of a model */
static const char *style_spec(const char *model, char *out, size_t size) {
  const model_style st = style_of(model);
  snprintf(out, size, "lc rgb '%s' dt %d lw %.1f", st.color, st.dash, st.width);
  return out;
}

/* records a curve's style in the manifest */
static void curve_style(json_t *c, const char *model) {
  const model_style st = style_of(model);
  json_object_set_new(c, "color", json_string(st.color));
  json_object_set_new(c, "dash", json_integer(st.dash));
}

/* yardsticks (analytic, reference) are drawn first, underneath the simulated models */
static int draw_order(const fb_run *r, int order[]) {
  int n = 0;
  for (int pass = 0; pass < 2; pass++)
    for (int i = 0; i < r->n; i++)
      if (!fb_engine_steps_world(r->model[i].run.model->engine) == (pass == 0)) order[n++] = i;
  return n;
}

/* the symlog transform of alpha.svg: linear within +-C, logarithmic beyond */
#define SYMLOG_C 1000.0

/* the decade at or above |y| * headroom, at least SYMLOG_C */
static double decade_above(double y, double headroom) {
  const double a = fabs(y) * headroom;
  return a <= SYMLOG_C ? SYMLOG_C : pow(10.0, ceil(log10(a) - 1e-12));
}

/* residual of model i against the analytic solution of its own lengths at
 * the same instants: resid[k] = y[k] - exact(t[k]) (body 0 coupler, 1
 * follower) for the samples in [t0, t1], the figure's window (NaN outside
 * it, and where the linkage cannot be solved) */
static void residual(const fb_run *r, int i, int body, double t0, double t1, double *resid) {
  const fb_series *s = &r->model[i].run.series;
  const double w = r->c.direction * r->c.crank_speed;
  for (size_t k = 0; k < s->n; k++) {
    fb_linkage_state x;
    if (s->t[k] < t0 || s->t[k] > t1) {
      resid[k] = NAN;
      continue;
    }
    const double y = body ? s->follower_omega[k] : s->coupler_omega[k];
    if (fb_linkage_solve(&x, &r->model[i].run.lengths, r->c.branch, r->c.crank_angle0 + w * s->t[k], w,
                         0.0, NULL) != FB_OK)
      resid[k] = NAN;
    else
      resid[k] = y - (body ? x.follower_omega : x.coupler_omega);
  }
}

/* the ODE model of the run that model i is compared with: the same
 * lengths, joints and law run by ODE, when model i is another simulation
 * engine's; -1 when there is none */
static int engine_partner(const fb_run *r, int i) {
  const fb_model *m = r->model[i].run.model;
  if (m->engine == FB_ENGINE_ODE || !fb_engine_steps_world(m->engine)) return -1;
  for (int j = 0; j < r->n; j++) {
    const fb_model *o = r->model[j].run.model;
    if (o->engine == FB_ENGINE_ODE && o->lengths == m->lengths && o->joints == m->joints &&
        o->law == m->law && r->model[j].run.series.n > 1)
      return j;
  }
  return -1;
}

/* diff[k] = omega of model i at its sample k minus model j's at the same
 * instant (linear interpolation between j's samples; NaN outside them) */
static void engine_difference(const fb_run *r, int i, int j, int body, double *diff) {
  const fb_series *a = &r->model[i].run.series, *b = &r->model[j].run.series;
  const double *ya = body ? a->follower_omega : a->coupler_omega;
  const double *yb = body ? b->follower_omega : b->coupler_omega;
  size_t q = 0;
  for (size_t k = 0; k < a->n; k++) {
    const double t = a->t[k];
    while (q + 2 < b->n && b->t[q + 1] < t) q++;
    if (b->n < 2 || t < b->t[0] || t > b->t[b->n - 1]) {
      diff[k] = NAN;
      continue;
    }
    const double dt = b->t[q + 1] - b->t[q];
    const double w = dt > 0.0 ? (t - b->t[q]) / dt : 0.0;
    diff[k] = ya[k] - (yb[q] + w * (yb[q + 1] - yb[q]));
  }
}

/* omega.svg: coupler and follower omega (top) and each ODE model's residual
 * against the analytic solution of its lengths (bottom); alpha.svg: coupler
 * and follower alpha on a symlog axis */
static fb_status kin_figure(const fb_run *r, const char *dir, fb_figure_format fmt, int alpha,
                            json_t *figs, fb_diag *diag) {
  const char *name = alpha ? "alpha" : "omega";
  plot pl;
  /* omega.svg's rows: values, residuals, engine differences (450 px each) */
  int nrows = 1;
  if (!alpha) {
    int res = 0, dif = 0;
    for (int i = 0; i < r->n; i++) {
      res |= fb_engine_steps_world(r->model[i].run.model->engine) && r->model[i].run.series.n > 0;
      dif |= engine_partner(r, i) >= 0;
    }
    nrows += res + dif;
  }
  fb_status st = plot_open(&pl, dir, name, fmt, alpha ? 1100 : 1400, alpha ? 850 : 450 * nrows, diag);
  if (st != FB_OK) return st;
  if (!alpha) pl.columns /= 2; /* omega.svg: coupler and follower side by side */
  const double period = 2.0 * M_PI / r->c.crank_speed;
  const double t0 = r->t_window, t1 = r->t_window + period;
  json_t *curves = json_array();
  int order[FB_MAX_MODELS];
  const int nm = draw_order(r, order);
  double amax = 0.0, amin = 0.0;
  int has_resid[FB_MAX_MODELS] = {0};
  for (int q = 0; q < nm; q++) {
    const int i = order[q];
    const fb_series *s = &r->model[i].run.series;
    for (int b = 0; b < 2; b++) {
      char dname[32];
      snprintf(dname, sizeof dname, "m%d_%d", i, b);
      const double *y = alpha ? (b ? s->follower_alpha : s->coupler_alpha)
                              : (b ? s->follower_omega : s->coupler_omega);
      double lo = NAN, hi = NAN;
      /* a stepping engine's acceleration at t = 0 is its first step's start
       * artefact (ODE: the velocity-level step has no drift to correct yet
       * and applies almost none), not the mechanism's: drawn from the first
       * step on */
      const double ta = alpha && fb_engine_steps_world(r->model[i].run.model->engine)
                            ? fmax(t0, 0.5 * r->model[i].run.h)
                            : t0;
      const int pts = datablock(&pl, dname, s, y, ta, t1, &lo, &hi);
      if (pts > 0) {
        amax = fmax(amax, hi);
        amin = fmin(amin, lo);
      }
      char csv[96], col[48];
      snprintf(csv, sizeof csv, "%s.csv", r->model[i].run.name);
      snprintf(col, sizeof col, "%s_%s", b ? "follower" : "coupler", alpha ? "alpha_rad_s2" : "omega_rad_s");
      json_t *c = curve(r->model[i].run.name, col, csv, pts, lo, hi, t0, t1);
      json_object_set_new(c, "panel", json_string(b ? "follower" : "coupler"));
      curve_style(c, r->model[i].run.name);
      json_array_append_new(curves, c);
    }
  }
  /* residual panels: ODE models only (the analytic ones are the yardstick) */
  if (!alpha)
    for (int q = 0; q < nm; q++) {
      const int i = order[q];
      const fb_series *s = &r->model[i].run.series;
      if (!fb_engine_steps_world(r->model[i].run.model->engine) || s->n == 0) continue;
      double *res = malloc(s->n * sizeof *res);
      if (!res) continue;
      has_resid[i] = 1;
      for (int b = 0; b < 2; b++) {
        residual(r, i, b, t0, t1, res);
        char dname[32], col[64], csv[96];
        snprintf(dname, sizeof dname, "r%d_%d", i, b);
        double lo = NAN, hi = NAN;
        const int pts = datablock(&pl, dname, s, res, t0, t1, &lo, &hi);
        snprintf(col, sizeof col, "%s_omega_residual_rad_s", b ? "follower" : "coupler");
        snprintf(csv, sizeof csv, "%s.csv", r->model[i].run.name);
        json_t *c = curve(r->model[i].run.name, col, csv, pts, lo, hi, t0, t1);
        json_object_set_new(c, "panel", json_string(b ? "follower residual" : "coupler residual"));
        json_object_set_new(c, "derived", json_string("model minus the analytic solution of its own "
                                                      "lengths at the same instants"));
        curve_style(c, r->model[i].run.name);
        json_array_append_new(curves, c);
      }
      free(res);
    }
  /* engine difference panels: another engine's model minus ODE's of the
   * same kind, at the same instants */
  int partner[FB_MAX_MODELS];
  int any_resid = 0, any_diff = 0;
  for (int i = 0; i < r->n; i++) {
    any_resid |= has_resid[i];
    partner[i] = alpha ? -1 : engine_partner(r, i);
    if (partner[i] < 0) continue;
    const fb_series *s = &r->model[i].run.series;
    double *d = malloc((s->n ? s->n : 1) * sizeof *d);
    if (!d) {
      partner[i] = -1;
      continue;
    }
    any_diff = 1;
    for (int b = 0; b < 2; b++) {
      engine_difference(r, i, partner[i], b, d);
      char dname[32], col[64], csv[96];
      snprintf(dname, sizeof dname, "d%d_%d", i, b);
      double lo = NAN, hi = NAN;
      const int pts = datablock(&pl, dname, s, d, t0, t1, &lo, &hi);
      snprintf(col, sizeof col, "%s_omega_engine_difference_rad_s", b ? "follower" : "coupler");
      snprintf(csv, sizeof csv, "%s.csv", r->model[i].run.name);
      json_t *c = curve(r->model[i].run.name, col, csv, pts, lo, hi, t0, t1);
      json_object_set_new(c, "panel", json_string(b ? "follower engine difference" : "coupler engine difference"));
      char what[256];
      snprintf(what, sizeof what, "%s minus %s at the same instants", r->model[i].run.name,
               r->model[partner[i]].run.name);
      json_object_set_new(c, "derived", json_string(what));
      curve_style(c, r->model[i].run.name);
      json_array_append_new(curves, c);
    }
    free(d);
  }
  const int rows = 1 + any_resid + any_diff;
  char en[160];
  const double rpm = r->c.crank_speed * 60.0 / (2.0 * M_PI);
  /* a clockwise drive decreases the crank angle: its motion runs right to left */
  const char *dirnote = r->c.direction > 0 ? "ccw drive: motion runs left to right"
                                           : "cw drive: crank angle decreases, motion runs right to left";
  fprintf(pl.p, "set multiplot layout %d,%d title '%s: %s against crank angle (revolution %d, %.0f rpm; %s)'\n",
          alpha ? 2 : rows, alpha ? 1 : 2, esc(r->c.name, en, sizeof en),
          alpha ? "angular acceleration" : "angular velocity", r->c.peaks == FB_PEAKS_ALL ? 1 : 2,
          rpm, dirnote);
  fprintf(pl.p, "set xrange [0:360]\nset xtics 30\nset xlabel 'crank angle [deg] (counter-clockwise from +x)'\n");
  json_t *axis = json_object();
  if (alpha) {
    /* symlog: linear within +-C, logarithmic beyond; every decade that holds
     * data labelled; 15 % headroom beyond the largest spike */
    const double top = decade_above(amax, 1.15), bottom = -decade_above(amin, 1.15);
    fprintf(pl.p, "C = %.1f\nset nonlinear y via sgn(y)*log10(1+abs(y)/C) inverse "
                  "sgn(y)*C*(10**abs(y)-1)\nset yrange [%.6g:%.6g]\nset ytics (",
            SYMLOG_C, bottom, top);
    json_t *tics = json_array();
    int first = 1;
    for (double d = -bottom; d >= SYMLOG_C * 0.999; d /= 10.0) {
      fprintf(pl.p, "%s'-1e%d' %.6g", first ? "" : ", ", (int)lround(log10(d)), -d);
      json_array_append_new(tics, json_real(-d));
      first = 0;
    }
    fprintf(pl.p, ", '0' 0");
    json_array_append_new(tics, json_real(0.0));
    for (double d = SYMLOG_C; d <= top * 1.001; d *= 10.0) {
      fprintf(pl.p, ", '1e%d' %.6g", (int)lround(log10(d)), d);
      json_array_append_new(tics, json_real(d));
    }
    fprintf(pl.p, ")\n");
    json_object_set_new(axis, "y_min", json_real(bottom));
    json_object_set_new(axis, "y_max", json_real(top));
    json_object_set_new(axis, "y_tics", tics);
    json_object_set_new(axis, "scale", json_string("symlog, linear within +-1000 rad/s^2"));
  }
  json_object_set_new(axis, "direction", json_string(r->c.direction > 0 ? "ccw" : "cw"));
  json_object_set_new(axis, "note", json_string(dirnote));
  for (int b = 0; b < (alpha ? 2 : 2 * rows); b++) {
    const int body = b % 2;
    /* rows: values, then residuals (when an ODE-like model ran), then the
     * engine differences (when two engines ran the same kind of model) */
    const int row = b / 2;
    const int resid = row == 1 && any_resid;
    const int diffrow = row >= 1 && !resid;
    if (diffrow) {
      /* the legend inside the panel: its long entries would squeeze the plot beside it */
      fprintf(pl.p, "set title '%s: engine difference (minus the ODE model of the same kind, same instants)'\n"
                    "set ylabel '%s omega difference [rad/s]'\nset autoscale y\n"
                    "set key inside bottom left opaque box font ',8'\n",
              body ? "follower" : "coupler", body ? "follower" : "coupler");
      fprintf(pl.p, "plot ");
      int anyd = 0;
      for (int q = 0; q < nm; q++) {
        const int i = order[q];
        if (partner[i] < 0) continue;
        char mn[160], pn[160], sp[96];
        fprintf(pl.p, "%s$d%d_%d using 1:2 with lines %s title '%s - %s'", anyd ? ", " : "", i, body,
                style_spec(r->model[i].run.name, sp, sizeof sp), esc(r->model[i].run.name, mn, sizeof mn),
                esc(r->model[partner[i]].run.name, pn, sizeof pn));
        anyd = 1;
      }
      fprintf(pl.p, "\n");
      continue;
    }
    if (resid) {
      fprintf(pl.p, "set title '%s: model minus analytic (same link lengths, same instants)'\n"
                    "set ylabel '%s omega residual [rad/s]'\nset autoscale y\n",
              body ? "follower" : "coupler", body ? "follower" : "coupler");
    } else {
      fprintf(pl.p, "set title '%s'\nset ylabel '%s %s [%s]'\n", body ? "follower" : "coupler",
              body ? "follower" : "coupler", alpha ? "alpha" : "omega",
              alpha ? "rad/s^2 (symlog)" : "rad/s");
    }
    fprintf(pl.p, "plot ");
    int any = 0;
    for (int q = 0; q < nm; q++) {
      const int i = order[q];
      if (resid && !has_resid[i]) continue;
      char mn[160], sp[96];
      fprintf(pl.p, "%s$%c%d_%d using 1:2 with lines %s title '%s'", any ? ", " : "", resid ? 'r' : 'm', i,
              body, style_spec(r->model[i].run.name, sp, sizeof sp), esc(r->model[i].run.name, mn, sizeof mn));
      any = 1;
    }
    if (!any) fprintf(pl.p, "0 with lines lc rgb '#888888' title 'no ODE model in this run'");
    fprintf(pl.p, "\n");
  }
  fprintf(pl.p, "unset multiplot\n");
  st = plot_close(&pl, diag);
  char file[128];
  snprintf(file, sizeof file, "%s.%s", name, ext(fmt));
  if (st == FB_OK) {
    manifest_add(figs, file, alpha ? "angular acceleration against crank angle"
                                   : "angular velocity against crank angle, and residuals", curves);
    json_object_set_new(json_array_get(figs, json_array_size(figs) - 1), "axis", axis);
  } else {
    json_decref(curves);
    json_decref(axis);
  }
  return st;
}

/* state colours of the orbit (as gnuplot rgb integers and as text) */
static const unsigned state_rgb[3] = {0x2a9d8f, 0xe63946, 0x1d3557};
static const char *const state_name[3] = {"free flight", "impact", "continuous contact"};

/* pin orbit and contact force of one clearance joint of one model */
static fb_status contact_figure(const fb_run *r, int mi, int j, const char *dir,
                                fb_figure_format fmt, json_t *figs, char *file, size_t fsize,
                                int startup, fb_diag *diag) {
  const fb_model_result *m = &r->model[mi];
  const fb_series *s = &m->run.series;
  char joint[32], name[100];
  snprintf(joint, sizeof joint, "%s", fb_joint_name(j));
  for (char *p = joint; *p; p++)
    if (*p == '-') *p = '_';
  snprintf(name, sizeof name, "%scontact_%s_%s", startup ? "startup_" : "", m->run.name, joint);
  plot pl;
  fb_status st = plot_open(&pl, dir, name, fmt, 1300, 600, diag);
  if (st != FB_OK) return st;
  pl.columns /= 2; /* the orbit and the force side by side */
  const double period = 2.0 * M_PI / r->c.crank_speed;
  /* the peak window's first revolution, or revolution 1 (the start-up); the
   * start-up's force against log time from the first step */
  const double t0 = startup ? 0.0 : r->t_window;
  const double t1 = startup ? r->t_startup_end : r->t_window + period;
  const double tf0 = startup ? 0.5 * r->c.solver.h : t0;
  const int rev = startup || r->c.peaks == FB_PEAKS_ALL ? 1 : 2;
  /* the orbit as one path in um, each segment coloured by the state at its
   * start, decimated to the pixels it crosses (decimate.h: a sample is kept
   * where the path enters another pixel of the panel, and at every change
   * of state, so no impact is under-drawn) */
  size_t i0 = 0;
  while (i0 < s->n && s->t[i0] < t0) i0++;
  size_t i1 = i0;
  while (i1 < s->n && s->t[i1] <= t1) i1++;
  const double *ex = s->contact[j][FB_C_EX], *ey = s->contact[j][FB_C_EY], *state = s->contact[j][FB_C_STATE];
  const double c_um = r->c.radial_clearance * 1e6;
  /* the clearance circle with a margin, or the whole path when the pin sinks
   * deeper (a start-up beyond the penalty model's validity) */
  double e_um = 0.0;
  for (size_t i = i0; i < i1; i++) e_um = fmax(e_um, 1e6 * hypot(ex[i], ey[i]));
  const double span = fmax(1.35 * c_um, 1.05 * e_um);
  /* the panel's pixel: the square plot spans 2 span over at most its width */
  const double cell_um = 2.0 * span / (double)pl.columns;
  const size_t count = i1 - i0;
  double *ox = malloc((count ? count : 1) * sizeof *ox), *oy = malloc((count ? count : 1) * sizeof *oy);
  size_t *keep = malloc((count ? count : 1) * sizeof *keep);
  size_t kept = 0;
  if (ox && oy && keep) {
    for (size_t k = 0; k < count; k++) {
      ox[k] = ex[i0 + k] * 1e6;
      oy[k] = ey[i0 + k] * 1e6;
    }
    kept = fb_decimate_path(ox, oy, state + i0, count, cell_um, keep);
  } else {
    for (size_t k = 0; keep && k < count; k++) keep[kept++] = k;
  }
  int orbit_pts = 0, impacts = 0;
  fprintf(pl.p, "$orbit << EOD\n");
  for (size_t q = 0; q < kept; q++) {
    const size_t i = i0 + keep[q];
    const int k = (int)state[i] >= 0 && (int)state[i] < 3 ? (int)state[i] : 0;
    fprintf(pl.p, "%.6f %.6f %u\n", ex[i] * 1e6, ey[i] * 1e6, state_rgb[k]);
    orbit_pts++;
  }
  free(ox);
  free(oy);
  free(keep);
  fprintf(pl.p, "EOD\n$impacts << EOD\n");
  /* an impact: the state turns to 1 from anything else (or starts the window at 1) */
  for (size_t i = i0; i < i1; i++)
    if ((int)state[i] == FB_STATE_IMPACT && (i == i0 || (int)state[i - 1] != FB_STATE_IMPACT)) {
      fprintf(pl.p, "%.6f %.6f\n", ex[i] * 1e6, ey[i] * 1e6);
      impacts++;
    }
  if (!impacts) fprintf(pl.p, "NaN NaN\n");
  fprintf(pl.p, "EOD\n");
  double flo = NAN, fhi = NAN;
  const int force_pts =
      datablock_x(&pl, "force", s, s->contact[j][FB_C_FORCE], tf0, t1, startup, &flo, &fhi);
  /* the reference dynamics of the same law, when the run has it, overlaid */
  int ri = -1;
  if (m->has_ref_error)
    for (int k = 0; k < r->n; k++)
      if (r->model[k].run.model == fb_model_reference_of(m->run.model) &&
          (r->model[k].run.series.contact_mask & (1 << j)))
        ri = k;
  double rlo = NAN, rhi = NAN;
  int ref_pts = 0;
  if (ri >= 0)
    ref_pts = datablock_x(&pl, "rforce", &r->model[ri].run.series,
                          r->model[ri].run.series.contact[j][FB_C_FORCE], tf0, t1, startup, &rlo, &rhi);
  char mn[160], rn[160], sp[96];
  fprintf(pl.p, "set multiplot layout 1,2 title '%s, %s joint: pin in hole (revolution %d%s)'\n",
          esc(m->run.name, mn, sizeof mn), fb_joint_name(j), rev,
          startup ? ", the start-up" : ""); /* joint names have no underscore */
  fprintf(pl.p, "set size ratio -1\nset title 'pin centre relative to hole centre (path)'\n"
                "set xlabel 'eccentricity x [um]'\nset ylabel 'eccentricity y [um]'\n"
                "set object 1 circle at 0,0 size %.6f fs empty border lc rgb '#888888' lw 1.5\n"
                "set xrange [%.4f:%.4f]\nset yrange [%.4f:%.4f]\nset key bottom right box\n",
          c_um, -span, span, -span, span);
  fprintf(pl.p, "plot $orbit using 1:2:3 with lines lw 1.2 lc rgb variable notitle, "
                "$impacts using 1:2 with points pt 2 ps 1.4 lw 1.5 lc rgb 'black' title 'impact start (%d)'",
          impacts);
  for (int k = 0; k < 3; k++)
    fprintf(pl.p, ", NaN with lines lw 2 lc rgb '#%06x' title '%s'", state_rgb[k], state_name[k]);
  fprintf(pl.p, ", NaN with lines lc rgb '#888888' title 'clearance circle'\n");
  fprintf(pl.p, "unset object 1\nset size noratio\nset autoscale\nset key top right box\n"
                "set title 'contact force'\n");
  if (startup)
    fprintf(pl.p, "set logscale x\nset format x '10^{%%L}'\nset xrange [%.9g:%.9g]\n"
                  "set xlabel 'time [ms]'\n",
            tf0 * 1e3, t1 * 1e3);
  else
    fprintf(pl.p, "set xrange [0:360]\nset xtics 60\nset xlabel 'crank angle [deg]'\n");
  fprintf(pl.p, "set ylabel 'contact force on the pin [N]'\n"
                "plot $force using 1:2 with lines %s title '%s'",
          style_spec(m->run.name, sp, sizeof sp), mn);
  if (ri >= 0) {
    char sr[96];
    fprintf(pl.p, ", $rforce using 1:2 with lines %s title '%s: reference dynamics'",
            style_spec(r->model[ri].run.name, sr, sizeof sr), esc(r->model[ri].run.name, rn, sizeof rn));
  }
  fprintf(pl.p, "\nunset multiplot\n");
  st = plot_close(&pl, diag);
  snprintf(file, fsize, "%s.%s", name, ext(fmt));
  if (st == FB_OK) {
    char csv[96], col[96];
    snprintf(csv, sizeof csv, "%s.csv", m->run.name);
    json_t *curves = json_array();
    snprintf(col, sizeof col, "%s_ecc_x_m,%s_ecc_y_m", joint, joint);
    json_t *c = curve(m->run.name, col, csv, orbit_pts, NAN, NAN, t0, t1);
    json_object_set_new(c, "impacts", json_integer(impacts));
    json_object_set_new(c, "pixel_um", json_real(cell_um));
    json_object_set_new(c, "time_from_s", json_real(t0));
    json_object_set_new(c, "time_to_s", json_real(t1));
    json_array_append_new(curves, c);
    snprintf(col, sizeof col, "%s_force_n", joint);
    c = curve(m->run.name, col, csv, force_pts, flo, fhi, tf0, t1);
    curve_style(c, m->run.name);
    json_array_append_new(curves, c);
    if (ri >= 0) {
      snprintf(csv, sizeof csv, "%s.csv", r->model[ri].run.name);
      c = curve(r->model[ri].run.name, col, csv, ref_pts, rlo, rhi, tf0, t1);
      curve_style(c, r->model[ri].run.name);
      json_array_append_new(curves, c);
    }
    manifest_add(figs, file,
                 startup ? "pin orbit and contact force, revolution 1 (start-up)"
                         : "pin orbit and contact force",
                 curves);
  }
  return st;
}

/* startup.<ext>: omega and alpha of coupler and follower against time over
 * revolution 1 on a logarithmic time axis (from the first step), every model
 * in its own style: the first impacts of a rest start sit in the first
 * microseconds, the run-in's decay over the milliseconds after */
static fb_status startup_figure(const fb_run *r, const char *dir, fb_figure_format fmt,
                                json_t *figs, fb_diag *diag) {
  plot pl;
  fb_status st = plot_open(&pl, dir, "startup", fmt, 1300, 950, diag);
  if (st != FB_OK) return st;
  pl.columns /= 2; /* two panels across */
  const double t0 = 0.5 * r->c.solver.h, t1 = r->t_startup_end; /* a log axis has no t = 0 */
  json_t *curves = json_array();
  int order[FB_MAX_MODELS];
  const int nm = draw_order(r, order);
  double amax = 0.0, amin = 0.0;
  for (int p = 0; p < 4; p++) { /* coupler omega, follower omega, coupler alpha, follower alpha */
    const int b = p & 1, alpha = p >> 1;
    for (int q = 0; q < nm; q++) {
      const int i = order[q];
      const fb_series *s = &r->model[i].run.series;
      const double *y = alpha ? (b ? s->follower_alpha : s->coupler_alpha)
                              : (b ? s->follower_omega : s->coupler_omega);
      char dname[32], csv[96], col[48];
      snprintf(dname, sizeof dname, "s%d_%d", p, i);
      double lo = NAN, hi = NAN;
      const int pts = datablock_x(&pl, dname, s, y, t0, t1, 1, &lo, &hi);
      if (alpha && pts) amax = fmax(amax, hi), amin = fmin(amin, lo);
      snprintf(csv, sizeof csv, "%s.csv", r->model[i].run.name);
      snprintf(col, sizeof col, "%s_%s", b ? "follower" : "coupler",
               alpha ? "alpha_rad_s2" : "omega_rad_s");
      json_t *c = curve(r->model[i].run.name, col, csv, pts, lo, hi, t0, t1);
      json_object_set_new(c, "panel", json_string(p == 0   ? "coupler omega"
                                                  : p == 1 ? "follower omega"
                                                  : p == 2 ? "coupler alpha"
                                                           : "follower alpha"));
      curve_style(c, r->model[i].run.name);
      json_array_append_new(curves, c);
    }
  }
  char en[160];
  fprintf(pl.p,
          "set multiplot layout 2,2 title '%s: the start-up, revolution 1 (start = %s, pin %s; "
          "log time)'\n",
          esc(r->c.name, en, sizeof en), fb_start_name(r->c.start),
          fb_pin_start_name(r->c.pin_start));
  fprintf(pl.p, "set logscale x\nset format x '10^{%%L}'\nset xlabel 'time [ms]'\n"
                "set xrange [%.9g:%.9g]\nset key inside top left box opaque font ',8'\n",
          t0 * 1e3, t1 * 1e3);
  for (int p = 0; p < 4; p++) {
    const int b = p & 1, alpha = p >> 1;
    if (p == 1) fprintf(pl.p, "unset key\n"); /* one legend, in the first panel */
    if (p == 2) {
      /* symlog as alpha.svg, the range to the decade above the spikes */
      const double top = decade_above(amax, 1.15), bottom = -decade_above(amin, 1.15);
      fprintf(pl.p, "C = %.1f\nset nonlinear y via sgn(y)*log10(1+abs(y)/C) inverse "
                    "sgn(y)*C*(10**abs(y)-1)\nset yrange [%.6g:%.6g]\nset ytics (",
              SYMLOG_C, bottom, top);
      int first = 1;
      for (double d = -bottom; d >= SYMLOG_C * 0.999; d /= 10.0, first = 0)
        fprintf(pl.p, "%s'-1e%d' %.6g", first ? "" : ", ", (int)lround(log10(d)), -d);
      fprintf(pl.p, ", '0' 0");
      for (double d = SYMLOG_C; d <= top * 1.001; d *= 10.0)
        fprintf(pl.p, ", '1e%d' %.6g", (int)lround(log10(d)), d);
      fprintf(pl.p, ")\n");
    }
    fprintf(pl.p, "set title '%s %s'\nset ylabel '%s [%s]'\nplot ", b ? "follower" : "coupler",
            alpha ? "angular acceleration" : "angular velocity", alpha ? "alpha" : "omega",
            alpha ? "rad/s^2 (symlog)" : "rad/s");
    for (int q = 0; q < nm; q++) {
      const int i = order[q];
      char mn[160], sp[96];
      fprintf(pl.p, "%s$s%d_%d using 1:2 with lines %s title '%s'", q ? ", " : "", p, i,
              style_spec(r->model[i].run.name, sp, sizeof sp),
              esc(r->model[i].run.name, mn, sizeof mn));
    }
    fprintf(pl.p, "\n");
  }
  fprintf(pl.p, "unset multiplot\n");
  st = plot_close(&pl, diag);
  char file[128];
  snprintf(file, sizeof file, "startup.%s", ext(fmt));
  if (st == FB_OK)
    manifest_add(figs, file, "start-up: angular velocity and acceleration against log time", curves);
  else
    json_decref(curves);
  return st;
}

/* spikes.svg: the window around one spike is the impact episode it lies in
 * (or the FB_SPIKE_MIN_SAMPLES samples around it), widened by one episode
 * length before and two after, so the approach, the rebound and the next
 * impact show; the paper case's episodes last 5-60 us (12 steps) */
#define FB_SPIKE_MIN_SAMPLES 10
/* an impact up to this many samples before the spike is its episode: the
 * rebound's alpha peaks a step or two after the force peak */
#define FB_SPIKE_LOOKBACK 50

/* the index of the largest |y| over t >= t_from, or n when none */
static size_t spike_index(const fb_series *s, const double *y, double t_from) {
  size_t k = s->n;
  for (size_t i = 0; i < s->n; i++)
    if (s->t[i] >= t_from && (k == s->n || fabs(y[i]) > fabs(y[k]))) k = i;
  return k;
}

/* the sample window [*i0, *i1] around spike k and the clearance joint of
 * its contact (-1: none near): the contact episode (state impact or
 * continuous contact) holding k or ending up to FB_SPIKE_LOOKBACK samples
 * before it, clipped to FB_SPIKE_LOOKBACK samples either side of k */
static int spike_window(const fb_series *s, int mask, size_t k, size_t *i0, size_t *i1) {
  size_t a = k, b = k;
  int joint = -1;
  for (int j = 0; j < 4 && joint < 0; j++) {
    if (!(mask & s->contact_mask & (1 << j))) continue;
    const double *st = s->contact[j][FB_C_STATE];
    for (size_t back = 0; back <= FB_SPIKE_LOOKBACK && back <= k; back++)
      if ((int)st[k - back] != FB_STATE_FREE) {
        joint = j;
        b = k - back;
        break;
      }
    if (joint < 0) continue;
    a = b;
    while (a > 0 && k - a < FB_SPIKE_LOOKBACK && (int)st[a - 1] != FB_STATE_FREE) a--;
    while (b + 1 < s->n && b - k < FB_SPIKE_LOOKBACK && (int)st[b + 1] != FB_STATE_FREE) b++;
  }
  size_t len = b - a + 1;
  if (len < FB_SPIKE_MIN_SAMPLES) len = FB_SPIKE_MIN_SAMPLES;
  *i0 = a > len ? a - len : 0;
  *i1 = b + 2 * len < s->n ? b + 2 * len : s->n - 1;
  return joint;
}

/* a datablock of (t - ts [us], y) over [i0, i1] at every sample; returns the
 * points and the extremes */
static int spike_block(FILE *p, const char *name, const fb_series *s, const double *y, size_t i0,
                       size_t i1, double ts, double *lo, double *hi) {
  fprintf(p, "$%s << EOD\n", name);
  int pts = 0;
  for (size_t i = i0; i <= i1 && i < s->n; i++) {
    fprintf(p, "%.9g %.17g\n", (s->t[i] - ts) * 1e6, y[i]);
    if (pts == 0 || y[i] < *lo) *lo = y[i];
    if (pts == 0 || y[i] > *hi) *hi = y[i];
    pts++;
  }
  if (!pts) fprintf(p, "NaN NaN\n");
  fprintf(p, "EOD\n");
  return pts;
}

/* the model of the run that is row want, or -1 */
static int run_index(const fb_run *r, const fb_model *want) {
  for (int k = 0; want && k < r->n; k++)
    if (r->model[k].run.model == want) return k;
  return -1;
}

/* spikes.<ext>: for each clearance model (the ODE and MuJoCo ones, else the
 * reference), its largest coupler and follower alpha spike over the peak
 * window on a microsecond axis around the spike, the reference of its law
 * and its ideal model overlaid at the same instants, the contact force
 * below. Nothing is drawn (and *drawn = 0) for a run without clearance
 * model. */
static fb_status spikes_figure(const fb_run *r, const char *dir, fb_figure_format fmt, json_t *figs,
                               int *drawn, fb_diag *diag) {
  int list[FB_MAX_MODELS], nc = 0;
  for (int pass = 0; pass < 2 && nc == 0; pass++)
    for (int i = 0; i < r->n; i++)
      if (r->model[i].has_spikes && r->model[i].run.series.n > 0 &&
          (r->model[i].run.model->engine == FB_ENGINE_REFERENCE) == (pass == 1))
        list[nc++] = i;
  *drawn = 0;
  if (nc == 0) return FB_OK;
  plot pl;
  fb_status st = plot_open(&pl, dir, "spikes", fmt, 1300, 430 * nc + 60, diag);
  if (st != FB_OK) return st;
  json_t *curves = json_array();
  char en[160];
  fprintf(pl.p, "set multiplot layout %d,2 title '%s: the largest alpha spike of each clearance model "
                "(peak window), reference and ideal model at the same instants'\n",
          2 * nc, esc(r->c.name, en, sizeof en));
  fprintf(pl.p, "set key outside right top box font ',8'\nset xlabel 'time from the spike [us]'\n");
  for (int q = 0; q < nc; q++) {
    const int mi = list[q];
    const fb_model_result *m = &r->model[mi];
    const fb_series *s = &m->run.series;
    const int ri = run_index(r, fb_model_reference_of(m->run.model));
    const int ii = run_index(r, fb_model_ideal_of(m->run.model));
    int others[3] = {mi, ri >= 0 && r->model[ri].run.series.n == s->n ? ri : -1,
                     ii >= 0 && r->model[ii].run.series.n == s->n ? ii : -1};
    const char *role[3] = {"model", "reference", "ideal"};
    size_t w0[2], w1[2];
    int joint[2];
    double ts[2];
    for (int b = 0; b < 2; b++) {
      const double *y = b ? s->follower_alpha : s->coupler_alpha;
      const size_t k = spike_index(s, y, r->t_window);
      joint[b] = spike_window(s, m->run.clearance_mask, k, &w0[b], &w1[b]);
      ts[b] = s->t[k];
      for (int o = 0; o < 3; o++) {
        if (others[o] < 0) continue;
        const fb_series *so = &r->model[others[o]].run.series;
        char dname[32], csv[96], col[48], panel[160];
        snprintf(dname, sizeof dname, "a%d_%d_%d", q, b, o);
        double lo = NAN, hi = NAN;
        const int pts = spike_block(pl.p, dname, so, b ? so->follower_alpha : so->coupler_alpha, w0[b],
                                    w1[b], ts[b], &lo, &hi);
        snprintf(csv, sizeof csv, "%s.csv", r->model[others[o]].run.name);
        snprintf(col, sizeof col, "%s_alpha_rad_s2", b ? "follower" : "coupler");
        json_t *c = curve(r->model[others[o]].run.name, col, csv, pts, lo, hi, s->t[w0[b]], s->t[w1[b]]);
        snprintf(panel, sizeof panel, "%s %s spike", m->run.name, b ? "follower" : "coupler");
        json_object_set_new(c, "panel", json_string(panel));
        json_object_set_new(c, "role", json_string(role[o]));
        json_object_set_new(c, "spike_time_s", json_real(ts[b]));
        curve_style(c, r->model[others[o]].run.name);
        json_array_append_new(curves, c);
        /* the contact force of the spike's joint, model and reference */
        const int fj = joint[b] >= 0 ? joint[b] : -1;
        if (o == 2 || fj < 0 || !(so->contact_mask & (1 << fj))) continue;
        snprintf(dname, sizeof dname, "f%d_%d_%d", q, b, o);
        lo = hi = NAN;
        const int fp = spike_block(pl.p, dname, so, so->contact[fj][FB_C_FORCE], w0[b], w1[b], ts[b],
                                   &lo, &hi);
        char jn[32];
        snprintf(jn, sizeof jn, "%s", fb_joint_name(fj));
        for (char *x = jn; *x; x++)
          if (*x == '-') *x = '_';
        snprintf(col, sizeof col, "%s_force_n", jn);
        c = curve(r->model[others[o]].run.name, col, csv, fp, lo, hi, s->t[w0[b]], s->t[w1[b]]);
        snprintf(panel, sizeof panel, "%s %s spike force", m->run.name, b ? "follower" : "coupler");
        json_object_set_new(c, "panel", json_string(panel));
        json_object_set_new(c, "role", json_string(role[o]));
        json_object_set_new(c, "spike_time_s", json_real(ts[b]));
        curve_style(c, r->model[others[o]].run.name);
        json_array_append_new(curves, c);
      }
    }
    /* row 1: alpha of coupler and follower; row 2: the force below each */
    for (int row = 0; row < 2; row++)
      for (int b = 0; b < 2; b++) {
        char mn[160];
        const double deg = crank_deg(s->crank_angle[0] + (ts[b] - s->t[0]) * r->c.direction * r->c.crank_speed);
        if (row == 0)
          fprintf(pl.p, "set title '%s: %s alpha spike at t = %.6f ms (crank %.1f deg)'\n"
                        "set ylabel '%s alpha [rad/s^2]'\nplot ",
                  esc(m->run.name, mn, sizeof mn), b ? "follower" : "coupler", ts[b] * 1e3, deg,
                  b ? "follower" : "coupler");
        else
          fprintf(pl.p, "set title '%s: contact force at the %s joint'\nset ylabel 'force [N]'\nplot ",
                  esc(m->run.name, mn, sizeof mn), joint[b] >= 0 ? fb_joint_name(joint[b]) : "(no impact)");
        int any = 0;
        for (int o = 2; o >= 0; o--) { /* yardsticks under the model */
          if (others[o] < 0 || (row == 1 && (o == 2 || joint[b] < 0 ||
                                             !(r->model[others[o]].run.series.contact_mask & (1 << joint[b])))))
            continue;
          char on[160], sp[96];
          fprintf(pl.p, "%s$%c%d_%d_%d using 1:2 with linespoints pt 7 ps 0.35 %s title '%s%s'",
                  any ? ", " : "", row ? 'f' : 'a', q, b, o,
                  style_spec(r->model[others[o]].run.name, sp, sizeof sp),
                  esc(r->model[others[o]].run.name, on, sizeof on),
                  o == 1 ? " (reference)" : o == 2 ? " (ideal)" : "");
          any = 1;
        }
        if (!any) fprintf(pl.p, "0 with lines lc rgb '#888888' title 'no impact near this spike'");
        fprintf(pl.p, "\n");
      }
  }
  fprintf(pl.p, "unset multiplot\n");
  st = plot_close(&pl, diag);
  char file[128];
  snprintf(file, sizeof file, "spikes.%s", ext(fmt));
  if (st == FB_OK) {
    manifest_add(figs, file, "largest alpha spikes on a microsecond axis, reference and ideal overlaid, "
                             "contact force below", curves);
    *drawn = 1;
  } else {
    json_decref(curves);
  }
  return st;
}

/* contact_figure for every clearance joint of every model that has the
 * window's metrics (startup 0: the steady window, spikes measured; 1: the
 * start-up of a clearance model), each file name appended to names */
static fb_status contact_figures(const fb_run *r, const char *dir, fb_figure_format fmt,
                                 int startup, json_t *figs, char names[][128], int max, int *n,
                                 fb_diag *diag) {
  fb_status st = FB_OK;
  for (int i = 0; i < r->n && st == FB_OK; i++) {
    const fb_model_result *m = &r->model[i];
    if (startup ? !(m->has_startup && m->run.clearance_mask) : !m->has_spikes) continue;
    for (int j = 0; j < 4 && st == FB_OK; j++) {
      if (!(m->run.series.contact_mask & (1 << j))) continue;
      char file[128];
      st = contact_figure(r, i, j, dir, fmt, figs, file, sizeof file, startup, diag);
      if (st == FB_OK && *n < max) snprintf(names[(*n)++], 128, "%s", file);
    }
  }
  return st;
}

fb_status fb_figures_run(const fb_run *r, const char *dir, fb_figure_format fmt, char names[][128],
                         int max, int *n, fb_diag *diag) {
  *n = 0;
  json_t *figs = json_array();
  fb_status st = FB_OK;
  batch_begin(); /* the figures drawn side by side */
  for (int alpha = 0; alpha < 2 && st == FB_OK; alpha++) {
    st = kin_figure(r, dir, fmt, alpha, figs, diag);
    if (st == FB_OK && *n < max) snprintf(names[(*n)++], 128, "%s.%s", alpha ? "alpha" : "omega", ext(fmt));
  }
  if (st == FB_OK) st = contact_figures(r, dir, fmt, 0, figs, names, max, n, diag);
  if (st == FB_OK) {
    int drawn = 0;
    st = spikes_figure(r, dir, fmt, figs, &drawn, diag);
    if (st == FB_OK && drawn && *n < max) snprintf(names[(*n)++], 128, "spikes.%s", ext(fmt));
  }
  /* the start-up: revolution 1 against log time, and each clearance model's
   * pin path and force over it */
  if (st == FB_OK) {
    st = startup_figure(r, dir, fmt, figs, diag);
    if (st == FB_OK && *n < max) snprintf(names[(*n)++], 128, "startup.%s", ext(fmt));
  }
  if (st == FB_OK) st = contact_figures(r, dir, fmt, 1, figs, names, max, n, diag);
  fb_diag drawn;
  const fb_status sb = batch_end(&drawn); /* every figure started is waited for */
  if (st == FB_OK && sb != FB_OK) {
    st = sb;
    *diag = drawn;
  }
  if (st == FB_OK) {
    char path[4096];
    snprintf(path, sizeof path, "%s/figures.json", dir);
    json_t *o = json_pack("{s:o}", "figures", figs);
    st = fb_report_write_json(path, o, diag);
    json_decref(o);
  } else {
    json_decref(figs);
  }
  return st;
}

/* "dir/name.ext" -> dir, name (no extension); "name.ext" -> ".", name */
static void split_path(const char *path, char *dir, size_t dsize, char *name, size_t nsize) {
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

fb_status fb_figures_penalty(const char *path, fb_figure_format fmt, const char *mode, int n,
                             const double *rpm, const double *force[2], const double *stiffness[2],
                             const double *penalty[2], const double *approach_um[2],
                             fb_diag *diag) {
  char dir[4096], name[256];
  split_path(path, dir, sizeof dir, name, sizeof name);
  plot pl;
  fb_status st = plot_open(&pl, dir, name, fmt, 1100, 850, diag);
  if (st != FB_OK) return st;
  const double **cols[4] = {force, stiffness, penalty, approach_um};
  /* P = Kc C^1.5: the paper's Table II unit in paper mode, SI otherwise */
  const char *labels[4] = {"force [N]", "contact stiffness Kc [N/m]",
                           strcmp(mode, "paper") == 0 ? "penalty P [N mm^{0.5}]" : "penalty P [N m^{0.5}]",
                           "approach [um]"};
  for (int q = 0; q < 4; q++)
    for (int j = 0; j < 2; j++) {
      fprintf(pl.p, "$d%d_%d << EOD\n", q, j);
      for (int i = 0; i < n; i++) fprintf(pl.p, "%.6g %.9g\n", rpm[i], cols[q][j][i]);
      fprintf(pl.p, "EOD\n");
    }
  char en[160];
  fprintf(pl.p, "set multiplot layout 2,2 title 'penalty estimate against crank speed (%s mode)'\n",
          esc(mode, en, sizeof en));
  /* inside the panel, where the rising curves leave room (outside, the
   * legends of the right column sat on the left column's plots) */
  fprintf(pl.p, "set xlabel 'crank speed [rpm]'\nset key inside top left box opaque\n");
  for (int q = 0; q < 4; q++)
    fprintf(pl.p, "set title '%s'\nset ylabel '%s'\nplot $d%d_0 using 1:2 with linespoints pt 7 "
                  "title 'crank-coupler', $d%d_1 using 1:2 with linespoints pt 5 title "
                  "'coupler-follower'\n",
            labels[q], labels[q], q, q);
  fprintf(pl.p, "unset multiplot\n");
  return plot_close(&pl, diag);
}

fb_status fb_figures_mapping(const char *path, fb_figure_format fmt, const char *title, int nk,
                             const double *k, int nh, const double *h, const double *erp,
                             const double *h_omega, fb_diag *diag) {
  char dir[4096], name[256];
  split_path(path, dir, sizeof dir, name, sizeof name);
  plot pl;
  char en[512];
  fb_status st = plot_open(&pl, dir, name, fmt, 1000, 760, diag);
  if (st != FB_OK) return st;
  fprintf(pl.p, "$map << EOD\n");
  for (int i = 0; i < nk; i++) {
    for (int j = 0; j < nh; j++)
      fprintf(pl.p, "%.6f %.6f %.9g %.9g\n", log10(k[i]), log10(h[j]), erp[i * nh + j],
              log10(h_omega[i * nh + j]));
    fprintf(pl.p, "\n");
  }
  fprintf(pl.p, "EOD\n");
  /* contours first (tabulated without pm3d), then the map */
  fprintf(pl.p, "set view map\nset contour base\nunset surface\nset cntrparam levels discrete 0\n"
                "set table $hw\nsplot $map using 1:2:4\nunset table\n"
                "set cntrparam levels discrete 0.1, 0.99\nset table $erpc\n"
                "splot $map using 1:2:3\nunset table\nunset contour\nset surface\n");
  fprintf(pl.p, "set title '%s' noenhanced\nset xlabel 'log10 stiffness k [N/m]'\n"
                "set ylabel 'log10 step size h [s]'\nset cblabel 'ERP'\nset cbrange [0:1]\n"
                "set pm3d map interpolate 4,4\nset palette rgb 33,13,10\n"
                "set key outside top center horizontal\n"
                "splot $map using 1:2:3 with pm3d notitle, "
                "$hw using 1:2:(1) with lines lw 3 lc rgb 'white' title 'h omega = 1 (above: under-resolved)', "
                "$erpc using 1:2:(1) with lines lw 2 dt 2 lc rgb 'black' title 'ERP = 0.1 and 0.99'\n",
          gp_text(title, 0, en, sizeof en));
  return plot_close(&pl, diag);
}

static int by_wall(const void *a, const void *b) {
  const fb_bench_row *x = *(const fb_bench_row *const *)a, *y = *(const fb_bench_row *const *)b;
  return (x->wall_per_rev > y->wall_per_rev) - (x->wall_per_rev < y->wall_per_rev);
}

fb_status fb_figures_bench(const char *path, fb_figure_format fmt, const char *case_name,
                           const void *rows_, int n, fb_diag *diag) {
  const fb_bench_row *rows = rows_;
  char dir[4096], name[256];
  split_path(path, dir, sizeof dir, name, sizeof name);
  plot pl;
  fb_status st = plot_open(&pl, dir, name, fmt, 1000, 700, diag);
  if (st != FB_OK) return st;
  /* the models of the grid, in order of first appearance */
  const char *models[8];
  const fb_model *model_rows[8];
  int nm = 0;
  for (int i = 0; i < n; i++) {
    int seen = 0;
    for (int q = 0; q < nm; q++) seen |= model_rows[q] == rows[i].row;
    if (!seen && nm < 8) {
      model_rows[nm] = rows[i].row;
      models[nm++] = rows[i].model;
    }
  }
  /* only measured rows are drawn: a run that stopped (NaN error) or whose
   * cost is not a number has no place on the chart (no placeholder point) */
  json_t *curves = json_array();
  int drawn[8] = {0}, fronts[8] = {0};
  for (int q = 0; q < nm; q++) {
    const fb_bench_row *front[FB_BENCH_MAX_ROWS];
    int nf = 0;
    double x0 = NAN, x1 = NAN, y0 = NAN, y1 = NAN;
    fprintf(pl.p, "$all%d << EOD\n", q);
    for (int i = 0; i < n; i++) {
      const fb_bench_row *b = &rows[i];
      if (b->row != model_rows[q] || !isfinite(b->error) || !(b->wall_per_rev > 0.0) ||
          !isfinite(b->wall_per_rev))
        continue;
      /* an exact result (error 0) sits at the axis floor of 1e-12 */
      const double y = fmax(b->error, 1e-12);
      fprintf(pl.p, "%.9g %.9g\n", b->wall_per_rev, y);
      x0 = drawn[q] ? fmin(x0, b->wall_per_rev) : b->wall_per_rev;
      x1 = drawn[q] ? fmax(x1, b->wall_per_rev) : b->wall_per_rev;
      y0 = drawn[q] ? fmin(y0, y) : y;
      y1 = drawn[q] ? fmax(y1, y) : y;
      drawn[q]++;
      if (b->pareto && nf < FB_BENCH_MAX_ROWS) front[nf++] = b;
    }
    fprintf(pl.p, "EOD\n$front%d << EOD\n", q);
    qsort(front, (size_t)nf, sizeof front[0], by_wall);
    for (int i = 0; i < nf; i++)
      fprintf(pl.p, "%.9g %.9g\n", front[i]->wall_per_rev, fmax(front[i]->error, 1e-12));
    fprintf(pl.p, "EOD\n");
    fronts[q] = nf;
    json_t *c = json_pack("{s:s,s:i,s:i}", "model", models[q], "points", drawn[q], "pareto_points", nf);
    if (drawn[q]) {
      json_object_set_new(c, "x_min", json_real(x0));
      json_object_set_new(c, "x_max", json_real(x1));
      json_object_set_new(c, "y_min", json_real(y0));
      json_object_set_new(c, "y_max", json_real(y1));
    }
    curve_style(c, models[q]);
    json_array_append_new(curves, c);
  }
  char en[160];
  fprintf(pl.p, "set title '%s: error against cost, both engines (fourbar bench)'\nset logscale xy\n"
                "set format x '10^{%%L}'\nset format y '10^{%%L}'\n"
                "set xlabel 'wall time per simulated revolution [s]'\n"
                "set ylabel 'error against the exact yardstick [-]'\nset key outside right top box\n"
                "set offsets graph 0.03, graph 0.03, graph 0.05, graph 0.05\n",
          esc(case_name, en, sizeof en));
  int any = 0;
  fprintf(pl.p, "plot ");
  for (int q = 0; q < nm; q++) {
    if (!drawn[q]) continue;
    const model_style ms = style_of(models[q]);
    const char *what = model_rows[q] && !fb_model_has_clearance(model_rows[q])
                           ? "omega peaks vs analytic"
                           : "force, penetration vs reference";
    char mn[160];
    esc(models[q], mn, sizeof mn);
    fprintf(pl.p, "%s$all%d using 1:2 with points pt 7 ps 0.8 lc rgb '%s' title '%s (%s)'", any ? ", " : "", q,
            ms.color, mn, what);
    if (fronts[q])
      fprintf(pl.p, ", $front%d using 1:2 with linespoints pt 7 lw 2 dt %d lc rgb '%s' title '%s: Pareto front'",
              q, ms.dash, ms.color, mn);
    any = 1;
  }
  if (!any) fprintf(pl.p, "1 with lines lc rgb '#888888' title 'no configuration finished'");
  fprintf(pl.p, "\n");
  st = plot_close(&pl, diag);
  if (st == FB_OK) {
    /* the manifest beside it: what was drawn, for the tests and the reader */
    char mpath[4400], file[300];
    snprintf(mpath, sizeof mpath, "%s/%s.figure.json", dir, name);
    snprintf(file, sizeof file, "%s.%s", name, ext(fmt));
    json_t *figs = json_array();
    manifest_add(figs, file, "error against cost", curves);
    json_t *o = json_pack("{s:o}", "figures", figs);
    st = fb_report_write_json(mpath, o, diag);
    json_decref(o);
  } else {
    json_decref(curves);
  }
  return st;
}

/* ---- study.svg ------------------------------------------------------------- */

/* points.csv as text cells: header names, then rows (status unquoted) */
typedef struct {
  int ncol;
  char **head;     /* (ncol) */
  size_t nrow;
  char ***cell;    /* (nrow x ncol) */
  int status_col;  /* index of "status" */
} study_csv;

static void csv_free(study_csv *t) {
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

static int csv_read(study_csv *t, const char *path) {
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

static int csv_col(const study_csv *t, const char *name) {
  for (int c = 0; c < t->ncol; c++)
    if (strcmp(t->head[c], name) == 0) return c;
  return -1;
}

static double cell_num(const char *text) {
  char *end;
  double v = strtod(text, &end);
  return end != text && *end == '\0' && isfinite(v) ? v : NAN;
}

/* a readable label with its unit for a case key (section.key) or a metric
 * (model.group.name): "crank speed [rpm]", "force max [N] (ode-clearance-impact)" */
static const char *readable(const char *key, char *out, size_t size) {
  static const struct { const char *key, *label; } known[] = {
      {"drive.speed_rpm", "crank speed [rpm]"},
      {"solver.h_s", "step size h [s]"},
      {"clearance.stiffness_scale", "contact stiffness scale [-]"},
      {"clearance.mapping", "ERP/CFM mapping"},
      {"clearance.penalty", "penalty source"},
      {"clearance.restitution", "coefficient of restitution [-]"},
      {"pin.radial_clearance_um", "radial clearance [um]"},
      {"solver.stepper", "stepper"},
  };
  for (size_t k = 0; k < sizeof known / sizeof known[0]; k++)
    if (strcmp(known[k].key, key) == 0) return snprintf(out, size, "%s", known[k].label), out;
  static const struct { const char *suffix, *unit; } units[] = {
      {"_rad_s2", "rad/s^2"}, {"_rad_s", "rad/s"}, {"_rpm", "rpm"}, {"_mm", "mm"}, {"_um", "um"},
      {"_n_m1_5", "N/m^1.5"}, {"_n_s_m", "N s/m"}, {"_n_m", "N/m"}, {"_n", "N"}, {"_m", "m"},
      {"_s", "s"}, {"_deg", "deg"}, {"_kg", "kg"}, {"_rad", "rad"}, {"_m_s2", "m/s^2"}};
  const char *last = strrchr(key, '.');
  char word[128];
  snprintf(word, sizeof word, "%s", last ? last + 1 : key);
  const char *unit = NULL;
  size_t lw = strlen(word);
  for (size_t k = 0; k < sizeof units / sizeof units[0] && !unit; k++) {
    size_t ls = strlen(units[k].suffix);
    if (lw > ls && strcmp(word + lw - ls, units[k].suffix) == 0) {
      unit = units[k].unit;
      word[lw - ls] = '\0';
    }
  }
  for (char *p = word; *p; p++)
    if (*p == '_') *p = ' ';
  /* a metric: model.group.name -> "[group ]name [unit] (model)"; spikes
   * names already say what they are */
  const char *dot = strchr(key, '.');
  char owner[128] = "", group[64] = "";
  if (dot && last && dot != last) {
    snprintf(owner, sizeof owner, " (%.*s)", (int)(dot - key), key);
    if (strncmp(dot + 1, "spikes.", 7) != 0) snprintf(group, sizeof group, "%.*s ", (int)(last - dot - 1), dot + 1);
  }
  snprintf(out, size, "%s%s%s%s%s%s", group, word, unit ? " [" : "", unit ? unit : "", unit ? "]" : "", owner);
  return out;
}

/* values of an axis are log-spaced: all positive, a constant ratio other
 * than 1 (two values: a ratio of 10 or more) */
static int log_spaced(const fb_axis *a) {
  double v[FB_STUDY_MAX_VALUES];
  for (int k = 0; k < a->n; k++) {
    v[k] = cell_num(a->value[k]);
    if (!(v[k] > 0.0)) return 0;
  }
  if (a->n < 2) return 0;
  if (a->n == 2) return fmax(v[0], v[1]) / fmin(v[0], v[1]) >= 10.0;
  const double ratio = v[1] / v[0];
  if (fabs(ratio - 1.0) < 1e-9) return 0;
  for (int k = 2; k < a->n; k++)
    if (fabs(v[k] / v[k - 1] - ratio) > 1e-6 * fabs(ratio)) return 0;
  return 1;
}

static int numeric_axis(const fb_axis *a) {
  if (a->montecarlo) return 0;
  for (int k = 0; k < a->n; k++)
    if (isnan(cell_num(a->value[k]))) return 0;
  return 1;
}

/* index of text among the axis's values, -1 if none */
static int axis_index(const fb_axis *a, const char *text) {
  for (int k = 0; k < a->n; k++)
    if (strcmp(a->value[k], text) == 0) return k;
  return -1;
}

static int by_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

fb_status fb_figures_study(const fb_study *s, const char *dir, fb_diag *diag) {
  char csvpath[4200];
  snprintf(csvpath, sizeof csvpath, "%s/points.csv", dir);
  study_csv t;
  if (!csv_read(&t, csvpath)) {
    csv_free(&t);
    return FB_OK; /* nothing to draw */
  }
  char names[8][128];
  int n = 0;
  if (s->nplot) {
    for (int k = 0; k < s->nplot; k++) snprintf(names[n++], 128, "%s", s->plot[k]);
  } else {
    /* the spike metrics first (the distribution a clearance study exists
     * for), then the others in column order, up to four */
    for (int pass = 0; pass < 2; pass++)
      for (int c = t.status_col + 1; c < t.ncol && n < 4; c++)
        if (strcmp(t.head[c], "warnings") != 0 && (strstr(t.head[c], ".spikes.") != NULL) == (pass == 0))
          snprintf(names[n++], 128, "%s", t.head[c]);
  }
  if (n == 0) {
    csv_free(&t);
    return FB_OK;
  }
  const fb_axis *x = &s->axis[0];
  const int mc = x->montecarlo;
  /* Monte Carlo: per metric, its empirical CDF and a scatter against the
   * sampled lengths (deviation from nominal); grids: one panel per metric */
  const int cols = mc ? 2 : (n > 1 ? 2 : 1), rows = mc ? n : (n + 1) / 2;
  plot pl;
  fb_status st = plot_open(&pl, dir, "study", FB_FIGURE_SVG, mc ? 1300 : 1400, 440 * rows, diag);
  if (st != FB_OK) {
    csv_free(&t);
    return st;
  }
  double nominal_mm[FB_LINK_COUNT] = {0};
  int lcol[FB_LINK_COUNT];
  if (mc) {
    fb_case base;
    const char *fixed[FB_STUDY_MAX_SETS];
    for (int k = 0; k < s->nsets; k++) fixed[k] = s->sets[k];
    const int loaded = fb_casefile_load(&base, s->case_path, fixed, s->nsets, NULL) == FB_OK;
    for (int k = 0; k < FB_LINK_COUNT; k++) {
      char key[64];
      snprintf(key, sizeof key, "linkage.%s_mm", fb_link_name(k));
      lcol[k] = csv_col(&t, key);
      nominal_mm[k] = loaded ? base.nominal.length[k] / FB_M_PER_MM : NAN;
    }
  }
  json_t *panels = json_array();
  char en[160], ep[600], lab[300], lab2[300], tmp[600];
  fprintf(pl.p, "set key noenhanced outside right top vertical box\n"
                "set multiplot layout %d,%d title 'study %s (%s)' noenhanced\n",
          rows, cols, gp_text(s->name, 0, en, sizeof en), gp_text(s->path, 0, ep, sizeof ep));
  for (int m = 0; m < n; m++) {
    const int mcol = csv_col(&t, names[m]);
    gp_text(readable(names[m], tmp, sizeof tmp), 0, lab, sizeof lab);
    json_t *panel = json_pack("{s:s,s:s}", "metric", names[m], "ylabel", tmp);
    int stopped = 0;
    if (mc) {
      /* empirical CDF of the finished samples */
      double *v = malloc((t.nrow + 1) * sizeof *v);
      size_t nv = 0;
      for (size_t r = 0; r < t.nrow; r++) {
        const double y = mcol >= 0 ? cell_num(t.cell[r][mcol]) : NAN;
        if (strcmp(t.cell[r][t.status_col], "ok") != 0) stopped++;
        else if (isfinite(y)) v[nv++] = y;
      }
      qsort(v, nv, sizeof *v, by_double);
      fprintf(pl.p, "$cdf%d << EOD\n", m);
      for (size_t k = 0; k < nv; k++) fprintf(pl.p, "%.17g %.17g\n", v[k], (double)(k + 1) / (double)nv);
      if (!nv) fprintf(pl.p, "NaN NaN\n");
      fprintf(pl.p, "EOD\n");
      free(v);
      fprintf(pl.p, "unset logscale\nset title 'distribution over %zu samples%s' noenhanced\n"
                    "set xlabel '%s' noenhanced\nset ylabel 'fraction of samples at or below [-]'\n"
                    "set yrange [0:1.05]\nplot $cdf%d using 1:2 with steps lw 2 lc rgb '#d62728' "
                    "title 'empirical CDF', $cdf%d using 1:2 with points pt 7 ps 0.5 lc rgb '#d62728' notitle\n"
                    "set autoscale y\n",
              nv, stopped ? " (stopped samples left out)" : "", lab, m, m);
      /* scatter against each sampled length's deviation from nominal */
      static const char *const link_color[FB_LINK_COUNT] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd"};
      int nl = 0;
      for (int k = 0; k < FB_LINK_COUNT; k++) {
        fprintf(pl.p, "$sc%d_%d << EOD\n", m, k);
        int np = 0;
        for (size_t r = 0; r < t.nrow && lcol[k] >= 0 && mcol >= 0; r++) {
          const double l = cell_num(t.cell[r][lcol[k]]), y = cell_num(t.cell[r][mcol]);
          if (isfinite(l) && isfinite(y) && isfinite(nominal_mm[k])) {
            fprintf(pl.p, "%.17g %.17g\n", l - nominal_mm[k], y);
            np++;
          }
        }
        if (!np) fprintf(pl.p, "NaN NaN\n");
        fprintf(pl.p, "EOD\n");
        nl += np > 0;
      }
      fprintf(pl.p, "set title 'against the sampled link lengths' noenhanced\n"
                    "set xlabel 'sampled length minus nominal [mm]'\nset ylabel '%s' noenhanced\nplot ",
              lab);
      for (int k = 0; k < FB_LINK_COUNT; k++)
        fprintf(pl.p, "%s$sc%d_%d using 1:2 with points pt %d ps 0.9 lc rgb '%s' title '%s'", k ? ", " : "",
                m, k, 5 + 2 * k, link_color[k], fb_link_name(k));
      fprintf(pl.p, "\n");
      json_object_set_new(panel, "kind", json_string("montecarlo: empirical CDF and scatter against "
                                                     "sampled lengths"));
      json_object_set_new(panel, "samples", json_integer((json_int_t)nv));
      json_object_set_new(panel, "lengths_plotted", json_integer(nl));
    } else if (s->heatmap) {
      /* cells over the first two axes (their value order), each labelled;
       * further axes at their first value */
      const fb_axis *y = &s->axis[1];
      const int xc = csv_col(&t, x->key), yc = csv_col(&t, y->key);
      fprintf(pl.p, "$hm%d << EOD\n", m);
      int cells = 0;
      for (size_t r = 0; r < t.nrow && xc >= 0 && yc >= 0 && mcol >= 0; r++) {
        int first = 1;
        for (int a = 2; a < s->naxes; a++) {
          const int ac = csv_col(&t, s->axis[a].key);
          first &= ac >= 0 && strcmp(t.cell[r][ac], s->axis[a].value[0]) == 0;
        }
        const int ix = axis_index(x, t.cell[r][xc]), iy = axis_index(y, t.cell[r][yc]);
        const double z = cell_num(t.cell[r][mcol]);
        const int ok = strcmp(t.cell[r][t.status_col], "ok") == 0;
        if (!first || ix < 0 || iy < 0) continue;
        if (!ok) stopped++;
        fprintf(pl.p, "%d %d %.17g %s\n", ix, iy, z, ok ? "ok" : "stopped");
        cells++;
      }
      if (!cells) fprintf(pl.p, "0 0 NaN ok\n");
      fprintf(pl.p, "EOD\n");
      fprintf(pl.p, "unset logscale\nunset key\nset title '%s' noenhanced\nset xlabel '%s' noenhanced\nset ylabel '%s' noenhanced\n"
                    "set cblabel '%s' noenhanced\nset palette rgb 33,13,10\nset xrange [-0.5:%d.5]\n"
                    "set yrange [-0.5:%d.5]\nset xtics (",
              lab, gp_text(readable(x->key, tmp, sizeof tmp), 0, lab2, sizeof lab2),
              gp_text(readable(y->key, ep, sizeof ep), 0, en, sizeof en), lab, x->n - 1, y->n - 1);
      for (int k = 0; k < x->n; k++) fprintf(pl.p, "%s'%s' %d", k ? ", " : "", gp_text(x->value[k], 0, tmp, sizeof tmp), k);
      fprintf(pl.p, ")\nset ytics (");
      for (int k = 0; k < y->n; k++) fprintf(pl.p, "%s'%s' %d", k ? ", " : "", gp_text(y->value[k], 0, tmp, sizeof tmp), k);
      fprintf(pl.p, ")\nplot $hm%d using 1:2:3 with image notitle, "
                    "$hm%d using 1:2:(strcol(4) eq 'ok' ? sprintf('%%.3g', $3) : sprintf('%%.3g (stopped)', $3)) "
                    "with labels font ',10' notitle\n"
                    "unset xtics\nunset ytics\nset xtics\nset ytics\nset autoscale\nset key noenhanced outside right top vertical box\n",
              m, m);
      json_object_set_new(panel, "kind", json_string("heatmap"));
      json_object_set_new(panel, "cells", json_integer(cells));
      json_object_set_new(panel, "xlabel", json_string(readable(x->key, tmp, sizeof tmp)));
    } else {
      /* the metric against the first axis, one series per combination of the
       * other axes; written per series, so every line is drawn */
      const int xnum = numeric_axis(x), xlog = xnum && log_spaced(x);
      const int xc = csv_col(&t, x->key);
      int combos = 1;
      for (int a = 1; a < s->naxes; a++) combos *= s->axis[a].n;
      if (combos > 12) combos = 12;
      json_t *series = json_array();
      fprintf(pl.p, "$stop%d << EOD\n", m);
      double ylo = INFINITY;
      for (size_t r = 0; r < t.nrow && mcol >= 0; r++) {
        const double y = cell_num(t.cell[r][mcol]);
        if (isfinite(y)) ylo = fmin(ylo, y);
      }
      for (size_t r = 0; r < t.nrow && xc >= 0; r++)
        if (strcmp(t.cell[r][t.status_col], "ok") != 0) {
          /* a stopped point: at its value if it has one, else at the lowest value drawn */
          const double xv = xnum ? cell_num(t.cell[r][xc]) : axis_index(x, t.cell[r][xc]);
          double y = mcol >= 0 ? cell_num(t.cell[r][mcol]) : NAN;
          if (!isfinite(y)) y = isfinite(ylo) ? ylo : 0.0;
          fprintf(pl.p, "%.17g %.17g\n", xv, y);
          stopped++;
        }
      if (!stopped) fprintf(pl.p, "NaN NaN\n");
      fprintf(pl.p, "EOD\n");
      for (int k = 0; k < combos; k++) {
        char title[1024] = "";
        size_t lt = 0;
        int rest = k, want[FB_STUDY_MAX_AXES], acol[FB_STUDY_MAX_AXES];
        for (int a = s->naxes - 1; a >= 1; a--) {
          const fb_axis *ax = &s->axis[a];
          want[a] = rest % ax->n;
          rest /= ax->n;
          acol[a] = csv_col(&t, ax->key);
        }
        for (int a = 1; a < s->naxes; a++)
          lt += (size_t)snprintf(title + lt, lt < sizeof title ? sizeof title - lt : 0, "%s%s = %s",
                                 lt ? ", " : "", readable(s->axis[a].key, tmp, sizeof tmp),
                                 s->axis[a].value[want[a]]);
        fprintf(pl.p, "$s%d_%d << EOD\n", m, k);
        int np = 0;
        for (size_t r = 0; r < t.nrow && xc >= 0 && mcol >= 0; r++) {
          int match = 1;
          for (int a = 1; a < s->naxes; a++)
            match &= acol[a] >= 0 && strcmp(t.cell[r][acol[a]], s->axis[a].value[want[a]]) == 0;
          const double y = cell_num(t.cell[r][mcol]);
          const double xv = xnum ? cell_num(t.cell[r][xc]) : axis_index(x, t.cell[r][xc]);
          if (!match || !isfinite(y) || !isfinite(xv)) continue;
          fprintf(pl.p, "%.17g %.17g\n", xv, y);
          np++;
        }
        if (!np) fprintf(pl.p, "NaN NaN\n");
        fprintf(pl.p, "EOD\n");
        json_array_append_new(series, json_pack("{s:s,s:i}", "title", s->naxes > 1 ? title : names[m],
                                                "points", np));
      }
      fprintf(pl.p, "set title '%s' noenhanced\nset xlabel '%s' noenhanced\nset ylabel '%s' noenhanced\n%s\n",
              lab, gp_text(readable(x->key, tmp, sizeof tmp), 0, lab2, sizeof lab2), lab,
              xlog ? "set logscale x\nset format x '%g'" : "unset logscale x\nset format x '% h'");
      if (!xnum) {
        fprintf(pl.p, "set xrange [-0.5:%d.5]\nset xtics (", x->n - 1);
        for (int k = 0; k < x->n; k++)
          fprintf(pl.p, "%s'%s' %d", k ? ", " : "", gp_text(x->value[k], 0, tmp, sizeof tmp), k);
        fprintf(pl.p, ")\n");
      } else {
        fprintf(pl.p, "set autoscale x\nset xtics\nset offsets graph 0.03, graph 0.03, graph 0.05, graph 0.05\n");
      }
      fprintf(pl.p, "plot ");
      for (int k = 0; k < combos; k++) {
        const char *title = json_string_value(json_object_get(json_array_get(series, (size_t)k), "title"));
        fprintf(pl.p, "%s$s%d_%d using 1:2 with linespoints pt 7 lw 1.5 title '%s'", k ? ", " : "", m, k,
                gp_text(title, 0, tmp, sizeof tmp));
      }
      if (stopped)
        fprintf(pl.p, ", $stop%d using 1:2 with points pt 4 ps 2 lw 2 lc rgb '#d62728' title 'stopped (%d "
                      "points, status not ok; drawn at their value or the panel floor)'", m, stopped);
      fprintf(pl.p, "\n");
      fprintf(pl.p, "set offsets 0, 0, 0, 0\nunset logscale x\n");
      json_object_set_new(panel, "kind", json_string("curves"));
      json_object_set_new(panel, "xlabel", json_string(readable(x->key, tmp, sizeof tmp)));
      json_object_set_new(panel, "xlog", json_boolean(xlog));
      json_object_set_new(panel, "series", series);
    }
    json_object_set_new(panel, "stopped", json_integer(stopped));
    json_array_append_new(panels, panel);
  }
  fprintf(pl.p, "unset multiplot\n");
  st = plot_close(&pl, diag);
  csv_free(&t);
  if (st == FB_OK) {
    char mpath[4400];
    snprintf(mpath, sizeof mpath, "%s/study.figure.json", dir);
    json_t *o = json_pack("{s:s,s:o}", "file", "study.svg", "panels", panels);
    st = fb_report_write_json(mpath, o, diag);
    json_decref(o);
  } else {
    json_decref(panels);
  }
  return st;
}
