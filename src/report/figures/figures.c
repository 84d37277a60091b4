/* The figures' entry points (figures.h): a run's figures, drawn as one
 * batch (fig_batch_begin .. fig_batch_end, side by side; fb_figures_start
 * and fb_figures_finish around the caller's other work) with figures.json
 * beside them, and the check that gnuplot is there. One file per figure
 * family draws them (figures_omega_alpha.c, figures_contact.c,
 * figures_spikes.c, figures_startup.c, figures_verdict.c; figures_penalty.c, figures_mapping.c,
 * figures_bench.c, figures_study.c for the other commands' figures) over one
 * gnuplot module (figures_gnuplot.c). */
#include "figures_internal.h"

#include <jansson.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "report.h"

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

/* between fb_figures_start and fb_figures_finish: the figures' entries for
 * figures.json, the folder, and a failure met before the gnuplots started */
static struct {
  json_t *figs;
  char dir[4096];
  fb_status st;
  fb_diag diag;
} pending;

/* keeps a started batch's figures.json entries, folder and failure for
 * fb_figures_finish */
static void hold(fb_status st, json_t *figs, const char *dir, const fb_diag *diag) {
  pending.figs = figs;
  pending.st = st;
  if (st != FB_OK) pending.diag = *diag;
  snprintf(pending.dir, sizeof pending.dir, "%s", dir);
}

fb_status fb_figures_start(const fb_run *r, const char *dir, fb_figure_format fmt, char names[][128],
                           int max, int *n, fb_diag *diag) {
  *n = 0;
  json_t *figs = json_array();
  fb_status st = FB_OK;
  fig_batch_begin(); /* the figures drawn side by side */
  for (int alpha = 0; alpha < 2 && st == FB_OK; alpha++) {
    st = fig_omega_alpha(r, dir, fmt, alpha, figs, diag);
    if (st == FB_OK && *n < max) snprintf(names[(*n)++], 128, "%s.%s", alpha ? "alpha" : "omega", fig_ext(fmt));
  }
  if (st == FB_OK) st = fig_contact_figures(r, dir, fmt, 0, figs, names, max, n, diag);
  if (st == FB_OK) {
    int drawn = 0;
    st = fig_spikes(r, dir, fmt, figs, &drawn, diag);
    if (st == FB_OK && drawn && *n < max) snprintf(names[(*n)++], 128, "spikes.%s", fig_ext(fmt));
  }
  /* the start-up: revolution 1 against log time, and each clearance model's
   * pin path and force over it */
  if (st == FB_OK) {
    st = fig_startup(r, dir, fmt, figs, diag);
    if (st == FB_OK && *n < max) snprintf(names[(*n)++], 128, "startup.%s", fig_ext(fmt));
  }
  if (st == FB_OK) st = fig_contact_figures(r, dir, fmt, 1, figs, names, max, n, diag);
  /* each verdict on statistics: what it rests on */
  if (st == FB_OK) st = fig_verdicts(r, dir, fmt, figs, names, max, n, diag);
  fig_batch_start(); /* the gnuplots draw while the caller goes on */
  hold(st, figs, dir, diag);
  return st;
}

fb_status fb_figures_finish(fb_diag *diag) {
  fb_status st = pending.st;
  if (st != FB_OK) *diag = pending.diag;
  fb_diag drawn;
  const fb_status sb = fig_batch_end(&drawn); /* every figure started is waited for */
  if (st == FB_OK && sb != FB_OK) {
    st = sb;
    *diag = drawn;
  }
  json_t *figs = pending.figs;
  pending.figs = NULL;
  if (st == FB_OK) {
    char path[4400];
    snprintf(path, sizeof path, "%s/figures.json", pending.dir);
    json_t *o = json_pack("{s:o}", "figures", figs);
    st = fb_report_write_json(path, o, diag);
    json_decref(o);
  } else {
    json_decref(figs);
  }
  return st;
}

fb_status fb_figures_run(const fb_run *r, const char *dir, fb_figure_format fmt, char names[][128],
                         int max, int *n, fb_diag *diag) {
  fb_figures_start(r, dir, fmt, names, max, n, diag);
  return fb_figures_finish(diag);
}

fb_status fig_batch_finish(fb_status st, json_t *figs, const char *dir, fb_diag *diag) {
  hold(st, figs, dir, diag);
  return fb_figures_finish(diag);
}
