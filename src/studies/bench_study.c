/* fourbar bench's study (bench_study.h): the grid and the peers run, then
 * bench.csv, bench.json and bench.svg written and the tables printed. */
#include "bench_study.h"

#include "numfmt.h"

#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "clock.h"
#include "contact.h"
#include "engine.h"
#include "fileio.h"
#include "outcome_text.h"
#include "scaling.h"
#include "textsafe.h"
#include "work.h"

/* models by kind (ideal, clearance impact) and engine (each engine that steps
 * a world, in the order of their ids: ode, mujoco, bullet, simbody) */
enum { NE = FB_ENGINE_COUNT };

/* a bench's results */
typedef struct {
  const fb_bench_opts *o;
  const fb_bench_row *rows;
  int n;
  const fb_peer_row *peers;
  int npeers;
  const fb_scaling_row *scaling; /* --grid scaling's rows (scaling.h) */
  int nscaling;
  double wall;                /* [s] */
  const fb_model *models[2][NE];
  int ne;                     /* engines in models */
  char left_out[160];         /* the engines whose models build no case's mechanism, comma-separated
                                 ("" : none; fb_bench_builds) */
} bench_result;

static const char *kinds[2] = {"ideal", "clearance-impact"};
static const double targets[FB_BENCH_TARGETS] = {1e-2, 1e-3, 1e-4};

static json_t *finite_or_null(double x) { return isfinite(x) ? json_real(x) : json_null(); }

static const char *mapping_name(int m) { return m < 0 ? "-" : fb_mapping_name((fb_mapping)m); }

/* 1 when a row of model ran (MuJoCo's rows exist only in builds with it) */
static int has_model(const fb_bench_row *rows, int n, const fb_model *model) {
  for (int i = 0; i < n; i++)
    if (rows[i].row == model) return 1;
  return 0;
}

/* 1 when the cheapest lines list model kind q of engine e: the first
 * engine (ODE, which every build has) always, another when a row of its
 * model ran (not every build or grid has it) */
static int listed(const bench_result *br, int q, int e) {
  const fb_model *m = br->models[q][e];
  return m && (e == 0 || has_model(br->rows, br->n, m));
}

static void print_config(const char *model, double target, const fb_bench_row *b) {
  /* the mapping is a contact setting: an ideal model has none */
  char mapping[32] = "";
  if (b->mapping >= 0) snprintf(mapping, sizeof mapping, "%s, ", mapping_name(b->mapping));
  const fb_engine *e = b->row ? fb_engine_get(b->row->engine, NULL) : NULL;
  if (e && e->bench && e->bench->names_world_erp)
    printf("  %-24s error <= %.0e: %s, h = %g s%s, %sERP %g, CFM %g: %.3e at %.3e s/rev\n", model,
           target, b->stepper, b->h, b->h_auto ? " (auto)" : "", mapping, b->world_erp,
           b->world_cfm, b->error, b->wall_per_rev);
  else
    printf("  %-24s error <= %.0e: %s, h = %g s: %.3e at %.3e s/rev\n", model, target, b->stepper,
           b->h, b->error, b->wall_per_rev);
}

/* the bench's progress: the one progress line of long work (work.h) */
static void progress(double f, void *user) { fb_progress_draw(user, "bench", f); }
static void peers_progress(double f, void *user) { fb_progress_draw(user, "bench: peers", f); }

int fb_bench_work(const fb_bench_opts *o, double cpu_s, double pilot_s, const char *instead) {
  char what[160], basis[160], est[48];
  snprintf(what, sizeof what, "--grid %s on %s", o->grid_name, o->c->name);
  fb_diag d;
  /* one process, one run after the other: its wall time is its CPU time */
  if (fb_work_bound(cpu_s, o->c->max_wall_s, what,
                    instead ? instead : "its runs have no shorter form", &d) != FB_OK)
    return fb_study_fail("bench", 2, "%s", d.msg);
  snprintf(basis, sizeof basis, "from two short runs of each of this case's runs, which took %s",
           fb_work_duration(est, sizeof est, pilot_s));
  fb_work_note("bench", what, cpu_s, basis, "", 0);
  return 0;
}

/* the four-bar's bench said and bounded before it starts: 0 or the exit status */
static int study_work(const fb_bench_opts *o) {
  double cpu = 0.0, pilot = 0.0, x, px;
  fb_diag d;
  fb_status st = fb_bench_estimate(&x, &px, o->c, o->grids & ~(FB_BENCH_PEERS | FB_BENCH_SCALING), &d);
  cpu += x, pilot += px;
  if (st == FB_OK && (o->grids & FB_BENCH_PEERS) &&
      (st = fb_peers_estimate(&x, &px, o->c, NULL, &d)) == FB_OK)
    cpu += x, pilot += px;
  if (st == FB_OK && (o->grids & FB_BENCH_SCALING) &&
      (st = fb_scaling_estimate(&x, &px, o->c, &fb_scaling_default, &d)) == FB_OK)
    cpu += x, pilot += px;
  if (st != FB_OK) return fb_study_fail("bench", 1, "%s", d.msg);
  const int smaller = o->grids != (FB_BENCH_DEFAULT | FB_BENCH_PEERS) && o->grids != FB_BENCH_PEERS;
  return fb_bench_work(o, cpu, pilot, smaller ? "run a smaller --grid (default, peers, frontier)"
                                              : NULL);
}

/* bench.csv: one line per row; returns the exit status */
static int write_csv(const char *dir, const fb_bench_row *rows, int n) {
  char path[4200];
  fb_diag d;
  snprintf(path, sizeof path, "%s/bench.csv", dir);
  fb_outfile f;
  if (fb_outfile_open(&f, path, &d) != FB_OK) return fb_study_fail("bench", 1, "%s", d.msg);
  fprintf(f.f, "model,engine,stepper,h_s,h_auto,mapping,world_erp,world_cfm,status,error,wall_per_rev_s,"
               "repeats,pareto,setup_s,"
               "collider,segments,us_per_step,force_vs_exact_rel,penetration_vs_exact_rel,"
               "alpha_coupler_vs_exact_rel,impacts,impacts_exact,cost_vs_exact,"
               "force_rel,penetration_rel,alpha_spike_coupler_rel,alpha_spike_follower_rel,"
               "halving_rel,halving_force_rel,halving_penetration_rel,"
               "halving_alpha_spike_coupler_rel,halving_alpha_spike_follower_rel,h_adaptive,steps_taken,"
               "stepping_per_rev_s,sampling_per_rev_s,samples_per_rev,ecc_direction_rms_rad\n");
  for (int i = 0; i < n; i++) {
    const fb_bench_row *b = &rows[i];
    char stop[256];
    char erp[32] = "", cfm[32] = "";
    if (isfinite(b->world_erp)) snprintf(erp, sizeof erp, "%g", b->world_erp);
    if (isfinite(b->world_cfm)) snprintf(cfm, sizeof cfm, "%g", b->world_cfm);
    /* a value a row could not measure: an empty field (numfmt.h), never nan */
#define CSV(x) FB_NUM_CELL("%.6g", (x), FB_NUM_NONE_CSV)
    fprintf(f.f, "%s,%s,%s,%s,%d,%s,%s,%s,\"%s\",%s,%s,%d,%d,%s,%s,%d,%s,%s,%s,%s,%d,%d,%s",
            b->model, b->engine, b->stepper, FB_NUM_CELL("%g", b->h, FB_NUM_NONE_CSV), b->h_auto,
            mapping_name(b->mapping), erp, cfm, fb_stop_text(stop, sizeof stop, &b->stop),
            CSV(b->error), CSV(b->wall_per_rev), b->repeats, b->pareto, CSV(b->setup_s), b->collider,
            b->segments, CSV(b->us_per_step), CSV(b->force_vs_exact), CSV(b->pen_vs_exact),
            CSV(b->alpha_vs_exact), b->impacts, b->impacts_exact, CSV(b->cost_vs_exact));
    for (int p = 0; p < FB_BENCH_PARTS; p++) fprintf(f.f, ",%s", CSV(b->part[p]));
    fprintf(f.f, ",%s", CSV(b->halving));
    for (int p = 0; p < FB_BENCH_PARTS; p++) fprintf(f.f, ",%s", CSV(b->halving_part[p]));
    fprintf(f.f, ",%d,%s,%s,%s,%s,%s\n", b->h_adaptive, FB_NUM_CELL("%.0f", b->steps_taken, FB_NUM_NONE_CSV),
            CSV(b->stepping_per_rev), CSV(b->sampling_per_rev), CSV(b->samples_per_rev),
            CSV(b->ecc_direction_rms));
#undef CSV
  }
  if (fb_outfile_commit(&f, &d) != FB_OK) return fb_study_fail("bench", 1, "%s", d.msg);
  return 0;
}

/* a row as bench.json holds it */
static json_t *row_json(const fb_bench_row *b) {
  char stop[256];
  json_t *o = json_object();
  json_object_set_new(o, "model", json_string(b->model));
  json_object_set_new(o, "engine", json_string(b->engine));
  json_object_set_new(o, "stepper", json_string(b->stepper));
  json_object_set_new(o, "h_s", json_real(b->h));
  json_object_set_new(o, "h_auto", json_boolean(b->h_auto));
  json_object_set_new(o, "mapping", json_string(mapping_name(b->mapping)));
  json_object_set_new(o, "world_erp", isfinite(b->world_erp) ? json_real(b->world_erp) : json_null());
  json_object_set_new(o, "world_cfm", isfinite(b->world_cfm) ? json_real(b->world_cfm) : json_null());
  json_object_set_new(o, "status", json_string(fb_stop_text(stop, sizeof stop, &b->stop)));
  json_object_set_new(o, "error", isfinite(b->error) ? json_real(b->error) : json_null());
  json_object_set_new(o, "wall_per_rev_s", isfinite(b->wall_per_rev) ? json_real(b->wall_per_rev) : json_null());
  json_object_set_new(o, "pareto", json_boolean(b->pareto));
  json_object_set_new(o, "collider", json_string(b->collider));
  json_object_set_new(o, "segments", b->segments > 0 ? json_integer(b->segments) : json_null());
  json_object_set_new(o, "us_per_step", finite_or_null(b->us_per_step));
  json_object_set_new(o, "collider_axis", json_boolean(b->collider_axis));
  if (b->has_vs_exact)
    json_object_set_new(o, "vs_exact",
                        json_pack("{s:o,s:o,s:o,s:i,s:i,s:o}", "force_max_rel",
                                  finite_or_null(b->force_vs_exact), "penetration_max_rel",
                                  finite_or_null(b->pen_vs_exact), "alpha_peak_ratio_coupler_rel",
                                  finite_or_null(b->alpha_vs_exact), "impacts", b->impacts,
                                  "impacts_exact", b->impacts_exact, "cost_rel",
                                  finite_or_null(b->cost_vs_exact)));
  else
    json_object_set_new(o, "vs_exact", json_null());
  json_object_set_new(o, "setup_s", json_real(b->setup_s));
  /* the parts of a clearance row's error, and the step-halving figure */
  static const char *part_keys[FB_BENCH_PARTS] = {"force_max_rel", "penetration_max_rel",
                                                  "alpha_spike_coupler_rel",
                                                  "alpha_spike_follower_rel"};
  json_t *parts = json_null(), *hparts = json_null();
  if (isfinite(b->part[0])) {
    parts = json_object();
    for (int p = 0; p < FB_BENCH_PARTS; p++)
      json_object_set_new(parts, part_keys[p], finite_or_null(b->part[p]));
  }
  if (isfinite(b->halving_part[0])) {
    hparts = json_object();
    for (int p = 0; p < FB_BENCH_PARTS; p++)
      json_object_set_new(hparts, part_keys[p], finite_or_null(b->halving_part[p]));
  }
  json_object_set_new(o, "error_parts", parts);
  json_object_set_new(o, "halving_rel", finite_or_null(b->halving));
  json_object_set_new(o, "halving_parts", hparts);
  json_object_set_new(o, "h_adaptive", json_boolean(b->h_adaptive));
  json_object_set_new(o, "steps_taken", json_real(b->steps_taken));
  json_object_set_new(o, "stepping_per_rev_s", finite_or_null(b->stepping_per_rev));
  json_object_set_new(o, "sampling_per_rev_s", finite_or_null(b->sampling_per_rev));
  json_object_set_new(o, "samples_per_rev", finite_or_null(b->samples_per_rev));
  json_object_set_new(o, "ecc_direction_rms_rad", finite_or_null(b->ecc_direction_rms));
  return o;
}

/* the row of the cheapest configuration of kind q meeting target t across
 * the listed engines (-1: none) */
static int cheapest_across(const bench_result *br, int q, int t) {
  int best = -1;
  for (int e = 0; e < br->ne; e++) {
    if (!listed(br, q, e)) continue; /* not in this build or grid */
    const int i = fb_bench_cheapest(br->rows, br->n, br->models[q][e], targets[t]);
    if (i >= 0 && (best < 0 || br->rows[i].wall_per_rev < br->rows[best].wall_per_rev)) best = i;
  }
  return best;
}

/* bench.json's "cheapest" (per engine) and "cheapest_across_engines" */
static void cheapest_json(const bench_result *br, json_t *cheap, json_t *across) {
  for (int q = 0; q < 2; q++)
    for (int t = 0; t < FB_BENCH_TARGETS; t++) {
      for (int e = 0; e < br->ne; e++) {
        if (!listed(br, q, e)) continue; /* not in this build or grid */
        int i = fb_bench_cheapest(br->rows, br->n, br->models[q][e], targets[t]);
        json_array_append_new(cheap, json_pack("{s:s,s:f,s:o}", "model", br->models[q][e]->name, "target",
                                               targets[t], "row", i >= 0 ? json_integer(i) : json_null()));
      }
      const int best = cheapest_across(br, q, t);
      json_array_append_new(across, json_pack("{s:s,s:f,s:o}", "kind", kinds[q], "target", targets[t],
                                              "row", best >= 0 ? json_integer(best) : json_null()));
    }
}

/* bench.json's "peers" */
static json_t *peers_json(const fb_peer_row *peers, int npeers) {
  json_t *pj = json_array();
  for (int i = 0; i < npeers; i++) {
    const fb_peer_row *p = &peers[i];
    json_t *hs = json_array(), *bs = json_array();
    for (int q = 0; q < p->rounds; q++) {
      json_array_append_new(hs, json_real(p->harness_s[q]));
      json_array_append_new(bs, json_real(p->bare_s[q]));
    }
    json_t *po = json_object();
    json_object_set_new(po, "engine", json_string(p->engine));
    json_object_set_new(po, "model", json_string(p->model ? p->model->name : ""));
    json_object_set_new(po, "peer", json_string(p->peer));
    json_object_set_new(po, "ran", json_boolean(p->ran));
    json_object_set_new(po, "status", json_string(p->status));
    json_object_set_new(po, "h_s", finite_or_null(p->h));
    json_object_set_new(po, "samples", json_integer(p->samples));
    json_object_set_new(po, "peer_steps", json_integer(p->peer_steps));
    json_object_set_new(po, "rounds", json_integer(p->rounds));
    json_object_set_new(po, "harness_s", hs);
    json_object_set_new(po, "bare_s", bs);
    json_object_set_new(po, "harness_per_rev_s", finite_or_null(p->harness_per_rev));
    json_object_set_new(po, "bare_per_rev_s", finite_or_null(p->bare_per_rev));
    json_object_set_new(po, "harness_over_bare", finite_or_null(p->harness_over_bare));
    json_object_set_new(po, "omega_peak_rel", finite_or_null(p->peak_rel));
    json_array_append_new(pj, po);
  }
  return pj;
}

/* the table of every row on stdout */
static void print_rows(const bench_result *br) {
  const fb_bench_row *rows = br->rows;
  const int n = br->n;
  printf("bench of %s: %d configurations in %.1f s ('P': Pareto front of its engine and model; "
         "h_s 'a': auto, 'ad': adaptive on that output grid; error of a clearance row: the largest of its force, penetration and "
         "coupler and follower alpha spike errors; h/2: the step-halving change; s/rev split into "
         "the engine's stepping and the harness's sampling of samples/rev output samples)\n\n"
         "%-24s %-9s %8s %-8s %5s %7s %12s %9s %9s %9s %9s %9s %12s  %9s %9s %8s %s\n",
         br->o->c->name, n, br->wall, "model", "stepper", "h_s", "mapping", "ERP", "CFM", "error", "force",
         "pen", "alpha_c", "alpha_f", "h/2", "s/rev", "stepping", "sampling", "samp/rev", "status");
  for (int i = 0; i < n; i++) {
    const fb_bench_row *b = &rows[i];
    char stop[256];
    char erp[16] = "-", cfm[16] = "-";
    if (isfinite(b->world_erp)) snprintf(erp, sizeof erp, "%5.1f", b->world_erp);
    if (isfinite(b->world_cfm)) snprintf(cfm, sizeof cfm, "%7.0e", b->world_cfm);
    /* a run that stopped before a whole step has no cost per revolution */
    char cost[32];
    if (isfinite(b->wall_per_rev)) snprintf(cost, sizeof cost, "%12.3e", b->wall_per_rev);
    else snprintf(cost, sizeof cost, "%12s", "-");
    char hs[24];
    snprintf(hs, sizeof hs, b->h_auto ? "a%.2g" : b->h_adaptive ? "ad%.0e" : "%.2g", b->h);
    char parts[FB_BENCH_PARTS][16], half[16];
    for (int p = 0; p < FB_BENCH_PARTS; p++) {
      if (isfinite(b->part[p])) snprintf(parts[p], sizeof parts[p], "%+9.1e", b->part[p]);
      else snprintf(parts[p], sizeof parts[p], "%9s", "-");
    }
    if (isfinite(b->halving)) snprintf(half, sizeof half, "%9.1e", b->halving);
    else snprintf(half, sizeof half, "%9s", "-");
    char split[64] = "        -         -        -";
    if (isfinite(b->stepping_per_rev) && isfinite(b->sampling_per_rev))
      snprintf(split, sizeof split, "%9.2e %9.2e %8.0f", b->stepping_per_rev, b->sampling_per_rev,
               b->samples_per_rev);
    printf("%-24s %-9s %8s %-8s %5s %7s %12.3e %s %s %s %s %s %s %c %s %.40s\n", b->model,
           b->stepper, hs, mapping_name(b->mapping), erp, cfm, b->error, parts[0], parts[1],
           parts[2], parts[3], half, cost, b->pareto ? 'P' : ' ', split,
           fb_stop_text(stop, sizeof stop, &b->stop));
  }
}

/* the collider axis' rows on stdout */
static void print_colliders(const fb_bench_row *rows, int n) {
  int ncol = 0;
  for (int i = 0; i < n; i++) ncol += rows[i].collider_axis;
  if (ncol) {
    printf("\ncollider axis (impact law, dWorldStep): differences from the exact collider of the "
           "same run\n%-22s %-8s %5s %7s %9s %9s %9s %8s %10s %9s %9s\n", "model", "collider", "N",
           "h_s", "force", "pen", "alpha_c", "impacts", "us/step", "cost", "error");
    for (int i = 0; i < n; i++) {
      const fb_bench_row *b = &rows[i];
      char stop[256];
      if (!b->collider_axis) continue;
      char ring[16] = "-";
      if (b->segments > 0) snprintf(ring, sizeof ring, "%d", b->segments);
      if (!b->has_vs_exact) {
        printf("%-22s %-8s %5s %7.0e %.60s\n", b->model, b->collider, ring, b->h,
               fb_stop_text(stop, sizeof stop, &b->stop));
        continue;
      }
      char imp[32];
      snprintf(imp, sizeof imp, "%d/%d", b->impacts, b->impacts_exact);
      printf("%-22s %-8s %5s %7.0e %+8.2f%% %+8.2f%% %+8.2f%% %8s %10.2f %8.2fx %9.2e\n", b->model,
             b->collider, ring, b->h, 100 * b->force_vs_exact, 100 * b->pen_vs_exact,
             100 * b->alpha_vs_exact, imp, b->us_per_step, b->cost_vs_exact, b->error);
    }
  }
}

/* bench.json's "scaling" */
static json_t *scaling_json(const fb_scaling_row *rows, int n) {
  json_t *a = json_array();
  for (int i = 0; i < n; i++) {
    const fb_scaling_row *r = &rows[i];
    json_t *o = json_object();
    json_object_set_new(o, "vary", json_string(r->vary));
    json_object_set_new(o, "value", json_real(r->value));
    json_object_set_new(o, "jobs", json_integer(r->jobs));
    json_object_set_new(o, "ran", json_boolean(r->ran));
    json_object_set_new(o, "status", json_string(r->status));
    json_object_set_new(o, "cpu_s", finite_or_null(r->cpu_s));
    json_object_set_new(o, "wall_s", finite_or_null(r->wall_s));
    json_object_set_new(o, "estimate_s", finite_or_null(r->estimate_s));
    json_object_set_new(o, "reference_steps_per_rev", finite_or_null(r->reference_steps_per_rev));
    json_object_set_new(o, "check_steps_per_rev", finite_or_null(r->check_steps_per_rev));
    json_array_append_new(a, o);
  }
  return a;
}

/* --grid scaling's rows on stdout */
static void print_scaling(const fb_scaling_row *rows, int n) {
  if (!n) return;
  printf("\nscaling: the case at each value of one setting (revolutions: the reference alone; "
         "CPU time the measure, wall time grows with the machine's load; estimate: the up-front "
         "one)\n%-20s %10s %4s %9s %9s %11s %13s %15s  %s\n",
         "vary", "value", "jobs", "CPU s", "wall s", "estimate s", "ref steps/rev",
         "check steps/rev", "status");
  for (int i = 0; i < n; i++) {
    const fb_scaling_row *r = &rows[i];
    char steps[2][24]; /* "-": none */
    const double v[2] = {r->reference_steps_per_rev, r->check_steps_per_rev};
    for (int k = 0; k < 2; k++) snprintf(steps[k], sizeof steps[k], isfinite(v[k]) ? "%.0f" : "-", v[k]);
    printf("%-20s %10g %4d %9.3f %9.3f %11.3g %13s %15s  %.200s\n", r->vary, r->value, r->jobs,
           r->cpu_s, r->wall_s, r->estimate_s, steps[0], steps[1], r->status);
  }
}

/* the peers on stdout */
static void print_peers(const fb_peer_row *peers, int npeers) {
  if (npeers) {
    printf("\npeers: each engine's bare program (tests/peers) beside the harness's ideal nominal "
           "model, the same four-bar, settings and output grid; %d alternating rounds, medians "
           "(harness: the model's wall time without its set-up; peer: its loop)\n"
           "%-8s %-22s %10s %8s %12s %12s %10s %12s  %s\n",
           FB_PEER_ROUNDS, "engine", "model", "h_s", "samples", "harness s/rev", "bare s/rev",
           "harness/bare", "omega peaks", "status");
    for (int i = 0; i < npeers; i++) {
      const fb_peer_row *p = &peers[i];
      if (!p->ran) {
        printf("%-8s %-22s %.200s\n", p->engine, p->model ? p->model->name : "-", p->status);
        continue;
      }
      printf("%-8s %-22s %10.3g %8ld %12.4f %12.4f %10.2f   %10.1e  %s\n", p->engine,
             p->model->name, p->h, p->samples, p->harness_per_rev, p->bare_per_rev,
             p->harness_over_bare, p->peak_rel, p->status);
    }
  }
}

/* the cheapest configuration of each engine and across engines on stdout */
static void print_cheapest(const bench_result *br) {
  const fb_bench_row *rows = br->rows;
  const int n = br->n;
  printf("\ncheapest configuration meeting each error target (per engine, then across engines):\n");
  for (int q = 0; q < 2; q++)
    for (int t = 0; t < FB_BENCH_TARGETS; t++) {
      for (int e = 0; e < br->ne; e++) {
        if (!listed(br, q, e)) continue;
        int i = fb_bench_cheapest(rows, n, br->models[q][e], targets[t]);
        if (i < 0) {
          printf("  %-24s error <= %.0e: none in the grid\n", br->models[q][e]->name, targets[t]);
          continue;
        }
        print_config(br->models[q][e]->name, targets[t], &rows[i]);
      }
      const int best = cheapest_across(br, q, t);
      if (best >= 0) printf("  -> %s error <= %.0e: cheapest on %s\n", kinds[q], targets[t],
                            rows[best].engine);
    }
}

/* bench.csv, bench.json and bench.svg; *j receives bench.json's object.
 * Returns the exit status. */
static int write_files(const bench_result *br, json_t **j) {
  const fb_bench_opts *o = br->o;
  int rc = write_csv(o->dir, br->rows, br->n);
  if (rc) return rc;
  json_t *arr = json_array();
  for (int i = 0; i < br->n; i++) json_array_append_new(arr, row_json(&br->rows[i]));
  json_t *cheap = json_array(), *across = json_array();
  cheapest_json(br, cheap, across);
  json_t *pj = peers_json(br->peers, br->npeers);
  *j = json_pack("{s:s,s:s,s:f,s:o,s:o,s:o,s:o,s:o}", "case", o->c->name, "grid", o->grid_name,
                 "wall_s", br->wall, "rows", arr, "cheapest", cheap,
                 "cheapest_across_engines", across, "peers", pj, "scaling",
                 scaling_json(br->scaling, br->nscaling));
  /* a mechanism not every model builds (fb_mech_desc.every_model_builds): the engines
     left out */
  if (!fb_case_mech(o->c)->every_model_builds) {
    json_t *lo = json_array();
    char names[sizeof br->left_out];
    snprintf(names, sizeof names, "%s", br->left_out);
    for (char *save = NULL, *t = strtok_r(names, ", ", &save); t; t = strtok_r(NULL, ", ", &save))
      json_array_append_new(lo, json_string(t));
    json_object_set_new(*j, "engines_left_out", lo);
  }
  fb_bench_marks marks = {.peers = br->peers, .npeers = br->npeers};
  for (int t = 0; t < FB_BENCH_TARGETS; t++) {
    marks.target[t] = targets[t];
    for (int q = 0; q < 2; q++) marks.cheapest[q][t] = cheapest_across(br, q, t);
  }
  return fb_bench_write_json_svg(o, *j, br->rows, br->n, &marks);
}

int fb_bench_write_json_svg(const fb_bench_opts *o, json_t *j, const fb_bench_row *rows, int n,
                            const fb_bench_marks *marks) {
  char path[4200];
  fb_diag d;
  snprintf(path, sizeof path, "%s/bench.json", o->dir);
  if (o->write_json(path, j, &d) != FB_OK) {
    json_decref(j);
    return fb_study_fail("bench", 1, "%s", d.msg);
  }
  snprintf(path, sizeof path, "%s/bench.svg", o->dir);
  if (n > 0 && o->draw(path, o->c->name, rows, n, marks, &d) != FB_OK)
    fprintf(stderr, "fourbar bench: warning: %s\n", d.msg);
  return 0;
}

int fb_bench_study(const fb_bench_opts *o) {
  fb_diag d;
  if (fb_outdir_prepare(o->dir, &d) != FB_OK) return fb_study_fail("bench", 1, "%s", d.msg);
  int rc = study_work(o);
  if (rc) return rc;
  static fb_bench_row rows[FB_BENCH_MAX_ROWS];
  int n;
  const double t0 = fb_clock_s();
  static fb_progress bp;
  fb_progress_init(&bp, o->json);
  if (fb_bench_run(rows, &n, o->c, o->grids & ~(FB_BENCH_PEERS | FB_BENCH_SCALING), progress, &bp,
                   &d) != FB_OK)
    return fb_study_fail("bench", 1, "%s", d.msg);
  /* the peers: each engine's bare program beside the harness (peers.h) */
  fb_peer_row peers[FB_PEERS_MAX];
  int npeers = 0;
  if ((o->grids & FB_BENCH_PEERS) &&
      fb_peers_run(peers, &npeers, o->c, NULL, peers_progress, &bp, &d) != FB_OK)
    return fb_study_fail("bench", 1, "%s", d.msg);
  /* how the cost grows (scaling.h) */
  static fb_scaling_row scaling[FB_SCALING_MAX_ROWS];
  int nscaling = 0;
  if ((o->grids & FB_BENCH_SCALING) &&
      fb_scaling_run(scaling, &nscaling, o->c, &fb_scaling_default, &d) != FB_OK)
    return fb_study_fail("bench", 1, "%s", d.msg);
  bench_result br = {.o = o, .rows = rows, .n = n, .peers = peers, .npeers = npeers,
                     .scaling = scaling, .nscaling = nscaling, .wall = fb_clock_s() - t0};
  for (int e = 0; e < FB_ENGINE_COUNT; e++)
    if (fb_engine_steps_world((fb_engine_id)e)) {
      if (!fb_bench_builds((fb_engine_id)e, o->c)) { /* its rows are left out */
        const size_t l = strlen(br.left_out);
        snprintf(br.left_out + l, sizeof br.left_out - l, "%s%s", l ? ", " : "",
                 fb_engine_name((fb_engine_id)e));
        continue;
      }
      fb_bench_models((fb_engine_id)e, &br.models[0][br.ne], &br.models[1][br.ne]);
      br.ne++;
    }
  json_t *j;
  rc = write_files(&br, &j);
  if (rc) return rc;
  if (o->json) {
    json_dumpf(j, stdout, JSON_INDENT(2) | JSON_REAL_PRECISION(10));
    fputc('\n', stdout);
    json_decref(j);
    return 0;
  }
  json_decref(j);
  if (br.left_out[0])
    printf("left out: %s (their models build no %s; fourbar models lists what each builds)\n",
           br.left_out, fb_case_mech(o->c)->type);
  print_rows(&br);
  print_colliders(rows, n);
  print_peers(peers, npeers);
  print_scaling(scaling, nscaling);
  if (n == 0) {
    printf("\nwrote %s/bench.csv and bench.json\n", o->dir);
    return 0;
  }
  print_cheapest(&br);
  printf("\nwrote %s/bench.csv, bench.json and bench.svg\n", o->dir);
  return 0;
}
