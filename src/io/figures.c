/* _GNU_SOURCE (meson.build): posix_spawn_file_actions_addchdir_np, pipe2 (glibc 2.29) */
#include "figures.h"

#include <errno.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

extern char **environ;

#include "bench.h"
#include "fileio.h"
#include "study.h"
#include "report.h"

typedef struct {
  FILE *p;         /* gnuplot's standard input */
  pid_t pid;       /* gnuplot */
  char dir[4096];  /* output folder; gnuplot runs in it */
  char path[4400]; /* final name */
  char tmp[4400];  /* written by gnuplot (a fixed-form name in dir), renamed on success */
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

/* Starts gnuplot with posix_spawn and an argument vector (no shell) in dir,
 * its standard input a pipe, its output and errors appended to
 * dir/.gnuplot.log. The script never names a path from the user: gnuplot
 * writes the temporary name below, relative to dir. */
static fb_status plot_open(plot *pl, const char *dir, const char *name, fb_figure_format fmt,
                           int width, int height, fb_diag *diag) {
  static unsigned serial;
  memset(pl, 0, sizeof *pl);
  pl->pid = -1;
  snprintf(pl->dir, sizeof pl->dir, "%s", dir);
  snprintf(pl->path, sizeof pl->path, "%s/%s.%s", dir, name, ext(fmt));
  char tmpname[96];
  snprintf(tmpname, sizeof tmpname, ".figure.tmp.%ld.%u.%s", (long)getpid(), serial++, ext(fmt));
  snprintf(pl->tmp, sizeof pl->tmp, "%s/%s", dir, tmpname);
  snprintf(pl->log, sizeof pl->log, "%s/.gnuplot.log", dir);
  int logfd = open(pl->log, O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  int fds[2] = {-1, -1};
  if (logfd < 0 || pipe2(fds, O_CLOEXEC) != 0) {
    if (logfd >= 0) close(logfd);
    return fb_diag_set(diag, FB_ERR_IO, "%s: cannot start gnuplot: %s", pl->path, strerror(errno));
  }
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_adddup2(&fa, fds[0], 0);
  posix_spawn_file_actions_adddup2(&fa, logfd, 1);
  posix_spawn_file_actions_adddup2(&fa, logfd, 2);
  posix_spawn_file_actions_addchdir_np(&fa, dir);
  char *argv[] = {"gnuplot", NULL};
  int rc = posix_spawnp(&pl->pid, "gnuplot", &fa, NULL, argv, environ);
  posix_spawn_file_actions_destroy(&fa);
  close(fds[0]);
  close(logfd);
  if (rc != 0 || !(pl->p = fdopen(fds[1], "w"))) {
    close(fds[1]);
    if (rc == 0) waitpid(pl->pid, NULL, 0);
    return fb_diag_set(diag, FB_ERR_IO, "%s: cannot start gnuplot: %s (apt-get install "
                       "gnuplot-nox, or pass --no-figures)", pl->path, strerror(rc ? rc : errno));
  }
  if (fmt == FB_FIGURE_PNG)
    fprintf(pl->p, "set terminal pngcairo size %d,%d enhanced font 'sans,10'\n", width, height);
  else
    fprintf(pl->p, "set terminal svg size %d,%d enhanced font 'sans,11' background '#ffffff'\n",
            width, height);
  fprintf(pl->p, "set output '%s'\nset grid lc rgb '#dddddd'\nset key outside right top box\n",
          tmpname);
  return FB_OK;
}

static fb_status plot_close(plot *pl, fb_diag *diag) {
  fprintf(pl->p, "unset output\nexit\n");
  int bad = fclose(pl->p) != 0; /* EPIPE when gnuplot stopped early (SIGPIPE is ignored) */
  pl->p = NULL;
  int status = 0;
  while (waitpid(pl->pid, &status, 0) < 0 && errno == EINTR) {
  }
  const int rc = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  if (bad || rc != 0 || access(pl->tmp, F_OK) != 0) {
    unlink(pl->tmp);
    return fb_diag_set(diag, FB_ERR_IO, "%s: gnuplot failed (exit %d); see %s", pl->path, rc, pl->log);
  }
  if (rename(pl->tmp, pl->path) != 0) {
    unlink(pl->tmp);
    return fb_diag_set(diag, FB_ERR_IO, "%s: cannot rename into place", pl->path);
  }
  return FB_OK;
}

/* crank angle in degrees in [0, 360) */
static double crank_deg(double th) {
  double d = fmod(th * 180.0 / M_PI, 360.0);
  return d < 0.0 ? d + 360.0 : d;
}

/* writes a datablock of (crank deg, y) over the window, min/max-decimated;
 * a blank line where the crank angle wraps; returns the points written and
 * the extremes of what was plotted (equal to the window's: min/max decimation) */
static int datablock(FILE *p, const char *name, const fb_series *s, const double *y, double t0,
                     double t1, double *ymin, double *ymax) {
  size_t i0 = 0, i1 = 0;
  while (i0 < s->n && s->t[i0] < t0) i0++;
  i1 = i0;
  while (i1 < s->n && s->t[i1] <= t1) i1++;
  const size_t count = i1 > i0 ? i1 - i0 : 0;
  const size_t buckets = FB_FIGURE_MAX_POINTS / 2;
  const size_t per = count > 2 * buckets ? (count + buckets - 1) / buckets : 1;
  fprintf(p, "$%s << EOD\n", name);
  int pts = 0;
  double last = -1.0;
  for (size_t b = i0; b < i1; b += per) {
    size_t e = b + per < i1 ? b + per : i1;
    size_t lo = b, hi = b;
    for (size_t k = b; k < e; k++) {
      if (y[k] < y[lo]) lo = k;
      if (y[k] > y[hi]) hi = k;
    }
    size_t idx[2] = {lo < hi ? lo : hi, lo < hi ? hi : lo};
    int m = per == 1 || lo == hi ? 1 : 2;
    for (int q = 0; q < m; q++) {
      double x = crank_deg(s->crank_angle[idx[q]]);
      if (last >= 0.0 && fabs(x - last) > 180.0) fprintf(p, "\n");
      fprintf(p, "%.6f %.17g\n", x, y[idx[q]]);
      if (pts == 0 || y[idx[q]] < *ymin) *ymin = y[idx[q]];
      if (pts == 0 || y[idx[q]] > *ymax) *ymax = y[idx[q]];
      last = x;
      pts++;
    }
  }
  fprintf(p, "EOD\n");
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

/* one figure with coupler (top) and follower (bottom) panels of omega or alpha */
static fb_status kin_figure(const fb_run *r, const char *dir, fb_figure_format fmt, int alpha,
                            json_t *figs, fb_diag *diag) {
  const char *name = alpha ? "alpha" : "omega";
  plot pl;
  fb_status st = plot_open(&pl, dir, name, fmt, 1100, 850, diag);
  if (st != FB_OK) return st;
  const double period = 2.0 * M_PI / r->c.crank_speed;
  const double t0 = r->t_window, t1 = r->t_window + period;
  json_t *curves = json_array();
  int pts[FB_MAX_MODELS][2];
  for (int i = 0; i < r->n; i++) {
    const fb_series *s = &r->model[i].run.series;
    for (int b = 0; b < 2; b++) {
      char dname[32];
      snprintf(dname, sizeof dname, "m%d_%d", i, b);
      const double *y = alpha ? (b ? s->follower_alpha : s->coupler_alpha)
                              : (b ? s->follower_omega : s->coupler_omega);
      double lo = NAN, hi = NAN;
      pts[i][b] = datablock(pl.p, dname, s, y, t0, t1, &lo, &hi);
      char csv[96], col[48];
      snprintf(csv, sizeof csv, "%s.csv", r->model[i].run.name);
      snprintf(col, sizeof col, "%s_%s", b ? "follower" : "coupler", alpha ? "alpha_rad_s2" : "omega_rad_s");
      json_array_append_new(curves, curve(r->model[i].run.name, col, csv, pts[i][b], lo, hi, t0, t1));
    }
  }
  char en[160];
  fprintf(pl.p, "set multiplot layout 2,1 title '%s: %s against crank angle (revolution 2, %.0f rpm %s)'\n",
          esc(r->c.name, en, sizeof en), alpha ? "angular acceleration" : "angular velocity",
          r->c.crank_speed * 60.0 / (2.0 * M_PI), r->c.direction > 0 ? "ccw" : "cw");
  fprintf(pl.p, "set xrange [0:360]\nset xtics 30\nset xlabel 'crank angle [deg]'\n");
  if (alpha) {
    /* symlog: linear within +-1000 rad/s^2, logarithmic beyond */
    fprintf(pl.p, "C = 1000.0\nset nonlinear y via sgn(y)*log10(1+abs(y)/C) inverse "
                  "sgn(y)*C*(10**abs(y)-1)\n"
                  "set ytics ('-1e5' -1e5, '-3e4' -3e4, '-1e4' -1e4, '-3e3' -3e3, '-1e3' -1e3, "
                  "'0' 0, '1e3' 1e3, '3e3' 3e3, '1e4' 1e4, '3e4' 3e4, '1e5' 1e5)\n");
  }
  for (int b = 0; b < 2; b++) {
    fprintf(pl.p, "set title '%s'\nset ylabel '%s %s [%s]'\n", b ? "follower" : "coupler",
            b ? "follower" : "coupler", alpha ? "alpha" : "omega", alpha ? "rad/s^2 (symlog)" : "rad/s");
    fprintf(pl.p, "plot ");
    for (int i = 0; i < r->n; i++) {
      const int an = r->model[i].run.kind == FB_KIND_ANALYTIC;
      char mn[160];
      fprintf(pl.p, "%s$m%d_%d using 1:2 with lines lw %s %s title '%s'", i ? ", " : "", i, b,
              an ? "2.5" : "1.2", an ? "lc rgb 'black' dt 2" : "",
              esc(r->model[i].run.name, mn, sizeof mn));
    }
    fprintf(pl.p, "\n");
  }
  fprintf(pl.p, "unset multiplot\n");
  st = plot_close(&pl, diag);
  char file[128];
  snprintf(file, sizeof file, "%s.%s", name, ext(fmt));
  if (st == FB_OK)
    manifest_add(figs, file, alpha ? "angular acceleration against crank angle"
                                   : "angular velocity against crank angle", curves);
  else
    json_decref(curves);
  return st;
}

/* pin orbit and contact force of one clearance joint of one model */
static fb_status contact_figure(const fb_run *r, int mi, int j, const char *dir,
                                fb_figure_format fmt, json_t *figs, char *file, size_t fsize,
                                fb_diag *diag) {
  const fb_model_result *m = &r->model[mi];
  const fb_series *s = &m->run.series;
  char joint[32], name[100];
  snprintf(joint, sizeof joint, "%s", fb_joint_name(j));
  for (char *p = joint; *p; p++)
    if (*p == '-') *p = '_';
  snprintf(name, sizeof name, "contact_%s_%s", m->run.name, joint);
  plot pl;
  fb_status st = plot_open(&pl, dir, name, fmt, 1200, 560, diag);
  if (st != FB_OK) return st;
  const double period = 2.0 * M_PI / r->c.crank_speed;
  const double t0 = r->t_window, t1 = r->t_window + period;
  /* orbit in um, one block per contact state, decimated by stride */
  size_t i0 = 0;
  while (i0 < s->n && s->t[i0] < t0) i0++;
  size_t i1 = i0;
  while (i1 < s->n && s->t[i1] <= t1) i1++;
  const size_t stride = (i1 - i0) / FB_FIGURE_MAX_POINTS + 1;
  int orbit_pts = 0, in_state[3] = {0, 0, 0};
  for (int state = 0; state < 3; state++) {
    fprintf(pl.p, "$orbit%d << EOD\n", state);
    for (size_t i = i0; i < i1; i += stride)
      if ((int)s->contact[j][FB_C_STATE][i] == state) {
        fprintf(pl.p, "%.6f %.6f\n", s->contact[j][FB_C_EX][i] * 1e6, s->contact[j][FB_C_EY][i] * 1e6);
        orbit_pts++;
        in_state[state]++;
      }
    /* an empty block would draw nothing and warn: one point off the axes */
    if (!in_state[state]) fprintf(pl.p, "1e9 1e9\n");
    fprintf(pl.p, "EOD\n");
  }
  double flo = NAN, fhi = NAN;
  const int force_pts = datablock(pl.p, "force", s, s->contact[j][FB_C_FORCE], t0, t1, &flo, &fhi);
  const double c_um = r->c.radial_clearance * 1e6;
  char mn[160];
  fprintf(pl.p, "set multiplot layout 1,2 title '%s, %s joint: pin in hole (revolution 2)'\n",
          esc(m->run.name, mn, sizeof mn), fb_joint_name(j)); /* joint names have no underscore */
  fprintf(pl.p, "set size ratio -1\nset title 'pin centre relative to hole centre'\n"
                "set xlabel 'eccentricity x [um]'\nset ylabel 'eccentricity y [um]'\n"
                "set object 1 circle at 0,0 size %.6f fs empty border lc rgb '#888888' lw 1.5\n"
                "set xrange [%.4f:%.4f]\nset yrange [%.4f:%.4f]\nset key bottom right box\n",
          c_um, -1.35 * c_um, 1.35 * c_um, -1.35 * c_um, 1.35 * c_um);
  fprintf(pl.p, "plot $orbit0 using 1:2 with points pt 7 ps 0.3 lc rgb '#2a9d8f' title 'free flight', "
                "$orbit1 using 1:2 with points pt 7 ps 0.4 lc rgb '#e63946' title 'impact', "
                "$orbit2 using 1:2 with points pt 7 ps 0.3 lc rgb '#1d3557' title 'continuous contact', "
                "NaN with lines lc rgb '#888888' title 'clearance circle'\n");
  fprintf(pl.p, "unset object 1\nset size noratio\nset autoscale\nset key top right box\n"
                "set title 'contact force'\nset xrange [0:360]\nset xtics 60\n"
                "set xlabel 'crank angle [deg]'\nset ylabel 'contact force [N]'\n"
                "plot $force using 1:2 with lines lc rgb '#e63946' title 'force on the pin'\n");
  fprintf(pl.p, "unset multiplot\n");
  st = plot_close(&pl, diag);
  snprintf(file, fsize, "%s.%s", name, ext(fmt));
  if (st == FB_OK) {
    char csv[96], col[96];
    snprintf(csv, sizeof csv, "%s.csv", m->run.name);
    json_t *curves = json_array();
    snprintf(col, sizeof col, "%s_ecc_x_m,%s_ecc_y_m", joint, joint);
    json_array_append_new(curves, curve(m->run.name, col, csv, orbit_pts, NAN, NAN, t0, t1));
    snprintf(col, sizeof col, "%s_force_n", joint);
    json_array_append_new(curves, curve(m->run.name, col, csv, force_pts, flo, fhi, t0, t1));
    manifest_add(figs, file, "pin orbit and contact force", curves);
  }
  return st;
}

fb_status fb_figures_run(const fb_run *r, const char *dir, fb_figure_format fmt, char names[][128],
                         int max, int *n, fb_diag *diag) {
  *n = 0;
  json_t *figs = json_array();
  fb_status st = FB_OK;
  for (int alpha = 0; alpha < 2 && st == FB_OK; alpha++) {
    st = kin_figure(r, dir, fmt, alpha, figs, diag);
    if (st == FB_OK && *n < max) snprintf(names[(*n)++], 128, "%s.%s", alpha ? "alpha" : "omega", ext(fmt));
  }
  for (int i = 0; i < r->n && st == FB_OK; i++) {
    if (!r->model[i].has_spikes) continue;
    for (int j = 0; j < 4 && st == FB_OK; j++) {
      if (!(r->model[i].run.series.contact_mask & (1 << j))) continue;
      char file[128];
      st = contact_figure(r, i, j, dir, fmt, figs, file, sizeof file, diag);
      if (st == FB_OK && *n < max) snprintf(names[(*n)++], 128, "%s", file);
    }
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
  const char *labels[4] = {"force [N]", "contact stiffness Kc [N/m]", "penalty P", "approach [um]"};
  for (int q = 0; q < 4; q++)
    for (int j = 0; j < 2; j++) {
      fprintf(pl.p, "$d%d_%d << EOD\n", q, j);
      for (int i = 0; i < n; i++) fprintf(pl.p, "%.6g %.9g\n", rpm[i], cols[q][j][i]);
      fprintf(pl.p, "EOD\n");
    }
  char en[160];
  fprintf(pl.p, "set multiplot layout 2,2 title 'penalty estimate against crank speed (%s mode)'\n",
          esc(mode, en, sizeof en));
  fprintf(pl.p, "set xlabel 'crank speed [rpm]'\nset key top left box\n");
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
  const char *models[2] = {"ode-ideal-stackup", "ode-clearance-impact"};
  for (int q = 0; q < 2; q++) {
    const fb_bench_row *front[256];
    int nf = 0;
    fprintf(pl.p, "$all%d << EOD\n", q);
    for (int i = 0; i < n; i++)
      if (strcmp(rows[i].model, models[q]) == 0 && isfinite(rows[i].error)) {
        fprintf(pl.p, "%.9g %.9g\n", rows[i].wall_per_rev, fmax(rows[i].error, 1e-12));
        if (rows[i].pareto && nf < 256) front[nf++] = &rows[i];
      }
    fprintf(pl.p, "1e9 1e9\nEOD\n$front%d << EOD\n", q);
    qsort(front, (size_t)nf, sizeof front[0], by_wall);
    for (int i = 0; i < nf; i++)
      fprintf(pl.p, "%.9g %.9g\n", front[i]->wall_per_rev, fmax(front[i]->error, 1e-12));
    fprintf(pl.p, "1e9 1e9\nEOD\n");
  }
  char en[160];
  fprintf(pl.p, "set title '%s: error against cost (fourbar bench)'\nset logscale xy\n"
                "set format x '10^{%%L}'\nset format y '10^{%%L}'\n"
                "set xlabel 'wall time per simulated revolution [s]'\n"
                "set ylabel 'error against the exact yardstick [-]'\nset key top right box\n"
                "set xrange [*:*] noextend\nset yrange [*:*] noextend\n"
                "plot $all0 using 1:2 with points pt 7 ps 0.8 lc rgb '#1d3557' title 'ideal stack-up "
                "(omega peaks vs analytic)', $front0 using 1:2 with linespoints pt 7 lw 2 lc rgb "
                "'#1d3557' title 'its Pareto front', $all1 using 1:2 with points pt 5 ps 0.8 lc rgb "
                "'#e63946' title 'clearance impact (force, penetration vs reference)', $front1 using "
                "1:2 with linespoints pt 5 lw 2 lc rgb '#e63946' title 'its Pareto front'\n",
          esc(case_name, en, sizeof en));
  return plot_close(&pl, diag);
}

/* the metric columns of a study CSV header, after index, axes and status */
static int csv_metrics(const char *csv, int naxes, char names[][128], int max) {
  FILE *f = fopen(csv, "r");
  if (!f) return 0;
  static char line[1 << 16];
  int n = 0;
  if (fgets(line, sizeof line, f)) {
    line[strcspn(line, "\r\n")] = '\0';
    int col = 0;
    char *save = NULL;
    for (char *t = strtok_r(line, ",", &save); t && n < max; t = strtok_r(NULL, ",", &save), col++)
      if (col >= naxes + 2) snprintf(names[n++], 128, "%s", t);
  }
  fclose(f);
  return n;
}

static int numeric_axis(const fb_axis *a) {
  if (a->montecarlo) return 0;
  for (int k = 0; k < a->n; k++) {
    char *end;
    strtod(a->value[k], &end);
    if (*end) return 0;
  }
  return 1;
}

fb_status fb_figures_study(const fb_study *s, const char *dir, fb_diag *diag) {
  char csv[4200];
  snprintf(csv, sizeof csv, "%s/points.csv", dir);
  char names[8][128];
  int n = 0;
  if (s->nplot) {
    for (int k = 0; k < s->nplot; k++) snprintf(names[n++], 128, "%s", s->plot[k]);
  } else {
    n = csv_metrics(csv, s->naxes, names, 4);
  }
  if (n == 0) return FB_OK; /* nothing to draw */
  plot pl;
  const int rows = (n + 1) / 2;
  fb_status st = plot_open(&pl, dir, "study", FB_FIGURE_SVG, 1200, 420 * rows, diag);
  if (st != FB_OK) return st;
  const fb_axis *x = &s->axis[0];
  const int xnum = numeric_axis(x);
  /* every text below comes from the study file: escaped, never pasted */
  char en[160], ep[600], xk[300], yk[300], nm[300];
  gp_text(x->key, 0, xk, sizeof xk);
  gp_text(s->naxes > 1 ? s->axis[1].key : "", 0, yk, sizeof yk);
  fprintf(pl.p, "set datafile separator ','\nset datafile columnheaders\nset key noenhanced inside top right box\n"
                "set multiplot layout %d,%d title 'study %s (%s)' noenhanced\n",
          rows, n > 1 ? 2 : 1, gp_text(s->name, 0, en, sizeof en), gp_text(s->path, 0, ep, sizeof ep));
  for (int m = 0; m < n; m++) {
    gp_text(names[m], 0, nm, sizeof nm);
    fprintf(pl.p, "set title '%s' noenhanced\nunset logscale\n", nm);
    if (s->heatmap) {
      fprintf(pl.p, "set view map\nset xlabel '%s' noenhanced\nset ylabel '%s' noenhanced\n"
                    "splot 'points.csv' using (column('%s')):(column('%s')):(column('%s')) with points pt 5 "
                    "ps 3 palette notitle\n",
              xk, yk, xk, yk, nm);
      continue;
    }
    fprintf(pl.p, "set xlabel '%s' noenhanced\nset ylabel '%s' noenhanced\n",
            xnum ? xk : "point index", nm);
    /* one series per combination of the other axes' values */
    int combos = 1;
    for (int a = 1; a < s->naxes; a++) combos *= s->axis[a].n;
    if (combos > 12) combos = 12;
    fprintf(pl.p, "plot ");
    for (int k = 0; k < combos; k++) {
      /* bounded: at most 7 axes of (escaped key <= 256, escaped value <= 64) */
      char cond[8192] = "1", title[8192] = "";
      size_t lc = 1, lt = 0;
      int rest = k;
      for (int a = s->naxes - 1; a >= 1; a--) {
        const fb_axis *ax = &s->axis[a];
        char ek[300], ev[80];
        gp_text(ax->key, 0, ek, sizeof ek);
        gp_text(ax->value[rest % ax->n], 0, ev, sizeof ev);
        rest /= ax->n;
        lc += (size_t)snprintf(cond + lc, sizeof cond - lc, " && strcol('%s') eq '%s'", ek, ev);
        lt += (size_t)snprintf(title + lt, sizeof title - lt, "%s%s=%s", lt ? ", " : "", ek, ev);
      }
      fprintf(pl.p, "%s'points.csv' using (column('%s')):((%s) ? column('%s') : NaN) with linespoints "
              "pt 7 title '%s'", k ? ", " : "", xnum ? xk : "index", cond, nm,
              s->naxes > 1 ? title : nm);
    }
    fprintf(pl.p, "\n");
  }
  fprintf(pl.p, "unset multiplot\n");
  return plot_close(&pl, diag);
}
