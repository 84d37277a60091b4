/* timing.json and the run's last line (report_timing.h). */
#include "report_timing.h"

#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "clock.h"

static json_t *num(double x) { return isfinite(x) ? json_real(x) : json_null(); }

/* appends part name = s (a name of at most FB_NAME_SIZE + 15 characters) */
static int part(fb_time_part *out, int n, int max, const char *model, const char *name, double s) {
  if (n >= max) return n;
  snprintf(out[n].name, sizeof out[n].name, "%s%s%s", model ? model : "", model ? "." : "", name);
  out[n].s = s;
  return n + 1;
}

int fb_report_time_parts(fb_time_part *out, int max, const fb_run *r, const fb_write_costs *w,
                         double run_wall_s) {
  const fb_write_costs none = {0};
  if (!w) w = &none;
  const double start = r->t_run_start > 0.0 ? r->t_run_start - fb_clock_process_start_s() : 0.0;
  int n = 0;
  n = part(out, n, max, NULL, "start", start);
  n = part(out, n, max, NULL, "scene", r->scene_s);
  for (int i = 0; i < r->n; i++) {
    const fb_model_run *m = &r->model[i].run;
    n = part(out, n, max, m->name, "setup", m->setup_s);
    n = part(out, n, max, m->name, "stepping", m->stepping_s);
    n = part(out, n, max, m->name, "sampling", m->wall_s - m->setup_s - m->stepping_s);
    n = part(out, n, max, m->name, "check", r->model[i].check_s);
  }
  n = part(out, n, max, NULL, "metrics", r->metrics_s);
  n = part(out, n, max, NULL, "h_auto_redo", r->redo_s);
  n = part(out, n, max, NULL, "ensemble", r->ensemble_wall_s);
  n = part(out, n, max, NULL, "variants", r->variants_s);
  n = part(out, n, max, NULL, "series", w->series_async ? w->series_part_s : w->series_s);
  n = part(out, n, max, NULL, "figures", w->figures_s);
  n = part(out, n, max, NULL, "report", w->summary_s + w->report_s);
  double named = 0.0;
  for (int k = 0; k < n; k++) named += out[k].s;
  return part(out, n, max, NULL, "other", run_wall_s - named);
}

json_t *fb_report_timing_json(const fb_run *r, const fb_write_costs *w, double run_wall_s) {
  json_t *models_json = json_array();
  for (int i = 0; i < r->n; i++) {
    const fb_model_run *run = &r->model[i].run;
    json_t *m = json_pack("{s:s,s:I,s:o,s:o,s:o,s:o}", "name", run->name, "steps",
                          (json_int_t)run->steps, "wall_s", num(run->wall_s), "setup_s",
                          num(run->setup_s), "time_per_step_us",
                          run->steps ? num(1e6 * run->wall_s / (double)run->steps) : json_null(),
                          "stepping_s", num(run->stepping_s));
    json_object_set_new(m, "samples", json_integer((json_int_t)run->series.n));
    json_object_set_new(m, "cpu_s", num(run->cpu_s));
    json_object_set_new(m, "check_cpu_s", num(r->model[i].check_cpu_s));
    json_array_append_new(models_json, m);
  }
  /* the ensemble's members beyond the first (docs/chaos.md): its cost */
  json_t *ens = json_pack("{s:i,s:s,s:o,s:o,s:o}", "members",
                          r->ensemble_auto > 1 ? r->ensemble_auto : r->c.ensemble > 1 ? r->c.ensemble : 1,
                          "source", r->ensemble_auto > 1 ? "run" : r->c.ensemble > 1 ? "case" : "none",
                          "wall_s", num(r->ensemble_wall_s), "models_wall_s", num(r->models_wall_s),
                          "estimate_s", r->ensemble_auto > 1 || r->ensemble_auto_skipped
                                            ? num(r->ensemble_estimate_s)
                                            : json_null());
  fb_time_part p[FB_TIME_PARTS_MAX];
  const int np = fb_report_time_parts(p, FB_TIME_PARTS_MAX, r, w, run_wall_s);
  json_t *parts = json_object();
  for (int k = 0; k < np; k++) json_object_set_new(parts, p[k].name, num(p[k].s));
  /* the up-front estimate (run.h fb_run_estimate) beside what it stands for */
  double wall, cpu;
  fb_run_estimated_work(r, &wall, &cpu);
  struct rusage ru;
  const double rss = getrusage(RUSAGE_SELF, &ru) == 0 ? 1024.0 * (double)ru.ru_maxrss : NAN;
  json_t *est = json_pack("{s:o,s:o,s:o,s:o,s:o}", "wall_s", num(r->estimate_s), "models_wall_s",
                          num(wall), "models_cpu_s", num(cpu), "bytes", num(r->estimate_bytes),
                          "max_rss_bytes", num(rss));
  json_t *o = json_pack("{s:s,s:o,s:o,s:o,s:o,s:o}", "case", r->c.name, "run_wall_s",
                        num(run_wall_s), "parts", parts, "models", models_json, "ensemble", ens,
                        "estimate", est);
  const fb_write_costs none = {0};
  if (!w) w = &none;
  json_object_set_new(o, "series_write_s", num(w->series_s));
  json_object_set_new(o, "series_write_cpu_s", num(w->series_cpu_s));
  json_object_set_new(o, "series_bytes", json_integer((json_int_t)w->series_bytes));
  return o;
}

static int by_time(const void *a, const void *b) {
  const double x = ((const fb_time_part *)a)->s, y = ((const fb_time_part *)b)->s;
  return (x < y) - (x > y);
}

/* parts the last line names, at most, and its width (the run's table's) */
#define TIMING_LINE_PARTS 5
#define TIMING_LINE_COLUMNS 120

void fb_report_timing_line(char *buf, size_t size, const fb_run *r, const fb_write_costs *w,
                           double run_wall_s) {
  fb_time_part p[FB_TIME_PARTS_MAX];
  const int np = fb_report_time_parts(p, FB_TIME_PARTS_MAX, r, w, run_wall_s);
  qsort(p, (size_t)np, sizeof p[0], by_time);
  static const char tail[] = " (every part: timing.json)";
  char line[TIMING_LINE_COLUMNS + 1];
  int used = snprintf(line, sizeof line, "time %.2f s:", run_wall_s);
  for (int k = 0; k < np && k < TIMING_LINE_PARTS; k++) {
    char item[sizeof p[k].name + 32];
    const int len = snprintf(item, sizeof item, "%s %s %.2f s", k ? "," : "", p[k].name, p[k].s);
    if (used + len + (int)sizeof tail - 1 > TIMING_LINE_COLUMNS) break;
    memcpy(line + used, item, (size_t)len + 1);
    used += len;
  }
  snprintf(buf, size, "%s%s", line, tail);
}
