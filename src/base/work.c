/* Long work said, bounded and drawn (work.h). */
#include "work.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "clock.h"
#include "textsafe.h"

double fb_work_cpu_s(void) {
  struct timespec ts;
  if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts) != 0) return fb_clock_cpu_s();
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* one window of the probe: eval until FB_WORK_PROBE_S of CPU (bounds of
 * work.h); its mean into *each, its calls added to *calls, its time to *spent */
static fb_status window(double *each, int *calls, double *spent, fb_work_eval eval, void *ctx,
                        fb_diag *diag) {
  const double t0 = fb_work_cpu_s();
  int n = 0;
  double w = 0.0;
  while (n < FB_WORK_PROBE_MIN || (w < FB_WORK_PROBE_S && n < FB_WORK_PROBE_MAX)) {
    const fb_status st = eval(ctx, diag);
    if (st != FB_OK) return st;
    n++;
    w = fb_work_cpu_s() - t0;
  }
  *each = w / n;
  *calls += n;
  *spent += w;
  return FB_OK;
}

fb_status fb_work_probe(double *s_per_eval, int *evals, double units, fb_work_eval eval,
                        void *ctx, fb_diag *diag) {
  int calls = 0;
  double spent = 0.0, best;
  fb_status st = window(&best, &calls, &spent, eval, ctx, diag);
  if (st != FB_OK) return st;
  if (units > 0.0 && units * best > FB_WORK_NOTE_S) {
    const double budget = fmin(FB_WORK_PROBE_SHARE * units * best, FB_WORK_PROBE_LONG_S);
    while (spent < budget && calls < FB_WORK_PROBE_MAX) {
      double each;
      if ((st = window(&each, &calls, &spent, eval, ctx, diag)) != FB_OK) return st;
      best = fmin(best, each);
    }
  }
  *s_per_eval = best;
  if (evals) *evals = calls;
  return FB_OK;
}

const char *fb_work_duration(char *buf, size_t size, double s) {
  if (!isfinite(s)) snprintf(buf, size, "an unbounded time");
  else if (s < 10.0) snprintf(buf, size, "%.2g s", s);
  else if (s < 120.0) snprintf(buf, size, "%.0f s", s);
  else if (s < 7200.0) snprintf(buf, size, "%.0f min", s / 60.0);
  else if (s < 2.0 * 86400.0) snprintf(buf, size, "%.2g h", s / 3600.0);
  else if (s < 365.25 * 86400.0) snprintf(buf, size, "%.3g days", s / 86400.0);
  else snprintf(buf, size, "%.3g years", s / (365.25 * 86400.0));
  return buf;
}

const char *fb_work_each(char *buf, size_t size, double each_s) {
  char each[48];
  if (each_s < 1e-3) snprintf(each, sizeof each, "%.3g us", each_s * 1e6);
  else if (each_s < 1.0) snprintf(each, sizeof each, "%.3g ms", each_s * 1e3);
  else fb_work_duration(each, sizeof each, each_s);
  snprintf(buf, size, "%s each, measured on this case", each);
  return buf;
}

void fb_work_note(const char *command, const char *what, double cpu_s, const char *basis,
                  const char *after, int force) {
  if (!force && !(cpu_s > FB_WORK_NOTE_S)) return;
  char total[48];
  fprintf(stderr, "fourbar %s: %s: an estimated %s of CPU (%s)%s\n", command, what,
          fb_work_duration(total, sizeof total, cpu_s), basis, after ? after : "");
}

fb_status fb_work_bound(double wall_s, double max_wall_s, const char *what, const char *instead,
                        fb_diag *diag) {
  if (wall_s <= max_wall_s) return FB_OK;
  if (!isfinite(wall_s)) /* no limit runs it */
    return fb_diag_set(diag, FB_ERR_RANGE, "%s: more than any [run] max_wall_s: %s", what, instead);
  /* the limit that would run it: the estimate, rounded up to two digits */
  double need = 1.0;
  if (wall_s > 1.0) {
    const double scale = pow(10.0, floor(log10(wall_s)) - 1.0);
    need = ceil(wall_s / scale) * scale;
  }
  char est[48], secs[48] = "";
  fb_work_duration(est, sizeof est, wall_s);
  if (wall_s >= 120.0) snprintf(secs, sizeof secs, " (%.3g s)", wall_s);
  return fb_diag_set(diag, FB_ERR_RANGE, "%s: an estimated %s%s, more than [run] max_wall_s = "
                     "%g s: %s, or raise the limit (--set run.max_wall_s=%.15g)",
                     what, est, secs, max_wall_s, instead, need);
}

void fb_progress_init(fb_progress *p, int json) {
  memset(p, 0, sizeof *p);
  p->on = isatty(2) && !json;
}

void fb_progress_draw(fb_progress *p, const char *label, double fraction) {
  if (!p->on) return;
  const double now = fb_clock_s();
  if (strncmp(p->label, label, sizeof p->label - 1) != 0) {
    snprintf(p->label, sizeof p->label, "%s", label);
    p->t0 = now;
    p->last = 0.0;
  }
  if (fraction < 1.0 && now - p->last < FB_WORK_REDRAW_S) return;
  p->last = now;
  const double el = now - p->t0;
  fputc('\r', fb_text_raw_stderr()); /* ours: never escaped */
  fprintf(stderr, "  %-22s %3.0f %%  %.*f s", p->label, 100.0 * fraction, el < 100.0, el);
  if (fraction > 0.0 && fraction < 1.0) fprintf(stderr, ", about %.0f s left   ", el * (1.0 - fraction) / fraction);
  else fputs("                    ", stderr);
  if (fraction >= 1.0) {
    fputc('\n', stderr);
    p->label[0] = '\0'; /* the next draw of it starts anew */
  }
  fflush(stderr);
}
