/* fourbar bench on a planar case (planar_bench.h): the grid, each row's
 * error against its yardstick and its cost, then the files and the table. */
#include "planar_bench.h"

#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "clock.h"
#include "engine.h"
#include "fileio.h"
#include "impact.h"
#include "model_table.h"
#include "numfmt.h"
#include "pilot.h"
#include "planar_run.h"
#include "work.h"

static const char *kinds[2] = {"ideal", "clearance-impact"};
static const double targets[FB_BENCH_TARGETS] = {1e-2, 1e-3, 1e-4};

/* one row's run: its case (one model) and what the writers add to its
 * fb_bench_row */
typedef struct {
  fb_case k;                     /* the point's case, k.models[0] the row's model */
  int kind;                      /* 0 ideal, 1 clearance */
  char yardstick[FB_NAME_SIZE];  /* "analytic" or the reference of its law */
  char status[256];              /* "ok" or why it stopped or could not run */
  double by_body[FB_PLANAR_BENCH_BODIES]; /* the error's part of each body (index b - 1; NaN:
                                             left out) [-] */
  char worst_body[FB_PLANAR_NAME_SIZE]; /* the body of the largest of them */
  double walls[FB_BENCH_ROUNDS], setups[FB_BENCH_ROUNDS]; /* [s] */
  int rounds;
  double revs;                   /* revolutions simulated [-] */
  double first_force, first_pen; /* a clearance row: its first impact's peak force and
                                    penetration against the reference's, fourbar run's verdict
                                    measure (planar_run.h fb_planar_first_impact) [-]; NaN:
                                    unpaired or not a clearance row */
} planar_point;

typedef struct {
  const fb_bench_opts *o;
  fb_case base;                  /* the case at 2 revolutions and a fixed h */
  fb_planar_run yard;            /* the yardsticks: analytic and the references */
  fb_bench_row rows[FB_PLANAR_BENCH_MAX_ROWS];
  planar_point pt[FB_PLANAR_BENCH_MAX_ROWS];
  int n;
  const fb_model *models[2][FB_ENGINE_COUNT]; /* each engine's models by kind, NULL: none */
  int ne;
  char left_out[160];            /* engines that step a world without a kit binding in this build */
  double wall;                   /* the bench's wall time [s] */
  unsigned char eligible[FB_PLANAR_BENCH_MAX_ROWS]; /* 1: a row the cheapest lines may name
                                                       (within_run_bound) */
} planar_bench;

/* 1 when row pt reads no error in fourbar run on its first impact: an
 * ideal row, or a clearance row whose first impact pairs with the
 * reference's within FB_FAITHFUL_PENETRATION_TOL in peak force and
 * penetration (planar_verdict.c's first test) */
static int within_run_bound(const planar_point *pt) {
  return !pt->kind || (fabs(pt->first_force) <= FB_FAITHFUL_PENETRATION_TOL &&
                       fabs(pt->first_pen) <= FB_FAITHFUL_PENETRATION_TOL);
}

/* the first model of engine e's table of kind q (0 ideal nominal, 1
 * clearance with the impact law and a reference) that the kit builds on a
 * planar case; NULL: none */
static const fb_model *planar_model(fb_engine_id e, int q) {
  for (int i = 0; i < fb_model_count; i++) {
    const fb_model *m = &fb_models[i];
    if (m->engine != e || !fb_planar_kit_of(m->name)) continue;
    if (q == 0 && m->joints == FB_JOINTS_IDEAL && m->lengths == FB_LENGTHS_NOMINAL) return m;
    if (q == 1 && m->joints == FB_JOINTS_CLEARANCE && m->law == FB_MODEL_LAW_IMPACT &&
        fb_model_reference_of(m))
      return m;
  }
  return NULL;
}

/* appends the row of model m (kind q) of engine e at case k */
static fb_status add_row(planar_bench *pb, fb_engine_id e, int q, const fb_case *k,
                         const fb_bench_point *p, fb_diag *diag) {
  if (pb->n == FB_PLANAR_BENCH_MAX_ROWS)
    return fb_diag_set(diag, FB_ERR_NOMEM, "bench: more than %d rows (FB_PLANAR_BENCH_MAX_ROWS)",
                       FB_PLANAR_BENCH_MAX_ROWS);
  const fb_model *m = pb->models[q][pb->ne];
  fb_bench_row *b = &pb->rows[pb->n];
  planar_point *pt = &pb->pt[pb->n++];
  memset(b, 0, sizeof *b);
  memset(pt, 0, sizeof *pt);
  pt->k = *k;
  pt->k.model_count = 1;
  snprintf(pt->k.models[0], FB_NAME_SIZE, "%s", m->name);
  pt->kind = q;
  const fb_model *ref = q ? fb_model_reference_of(m) : NULL;
  snprintf(pt->yardstick, sizeof pt->yardstick, "%s", ref ? ref->name : "analytic");
  b->row = m;
  snprintf(b->model, sizeof b->model, "%s", m->name);
  snprintf(b->engine, sizeof b->engine, "%s", fb_engine_name(e));
  snprintf(b->stepper, sizeof b->stepper, "%s", p->stepper[0] ? p->stepper : "case");
  b->h = k->solver.h;
  b->mapping = q ? p->mapping : -1;
  b->world_erp = b->world_cfm = NAN;
  snprintf(b->collider, sizeof b->collider, "%s", q ? fb_collider_name(m->collider) : "-");
  b->error = b->halving = b->ecc_direction_rms = b->us_per_step = NAN;
  b->stepping_per_rev = b->sampling_per_rev = b->cost_vs_exact = NAN;
  for (int i = 0; i < FB_BENCH_PARTS; i++) b->part[i] = b->halving_part[i] = NAN;
  return FB_OK;
}

/* 1 when engine e's rows already hold a point at k's h with stepper s */
static int repeats_point(const planar_bench *pb, int first, const fb_case *k, const char *s) {
  for (int i = first; i < pb->n; i++)
    if (pb->rows[i].h == k->solver.h && strcmp(pb->rows[i].stepper, s[0] ? s : "case") == 0)
      return 1;
  return 0;
}

/* engine e's points (planar_bench.h): its default grid's fixed-step points,
 * each at h and h/2, or the case's h and h/2 */
static fb_status engine_rows(planar_bench *pb, fb_engine_id e, const fb_engine *eng,
                             fb_diag *diag) {
  const int first = pb->n;
  fb_status st = FB_OK;
  int configs = 0;
  for (int i = 0; st == FB_OK && configs < FB_PLANAR_BENCH_POINTS; i++) {
    fb_case k = pb->base;
    fb_bench_point p = {.mapping = (int)pb->base.clearance.mapping};
    if (eng->bench && eng->bench->point) {
      if (!eng->bench->point(FB_BENCH_SET_DEFAULT, i, &pb->base, &k, &p)) break;
      if (k.solver.h_mode != FB_STEP_FIXED) continue; /* auto, adaptive: not the kit's */
    } else if (i > 0) {
      break;
    }
    /* the engine's first point also at h/2 (its order shows there) */
    const int halves = pb->n == first ? 2 : 1;
    for (int half = 0; half < halves && st == FB_OK && configs < FB_PLANAR_BENCH_POINTS; half++) {
      if (half) k.solver.h *= 0.5;
      if (repeats_point(pb, first, &k, p.stepper)) continue;
      configs++;
      for (int q = 0; q < 2 && st == FB_OK; q++)
        if (pb->models[q][pb->ne] && !(q == 0 && p.no_ideal_row))
          st = add_row(pb, e, q, &k, &p, diag);
    }
  }
  return st;
}

/* the grid's rows, engine by engine */
static fb_status grid(planar_bench *pb, fb_diag *diag) {
  const int with_clearance = pb->base.clearance.mask != 0;
  for (int e = 0; e < FB_ENGINE_COUNT; e++) {
    if (!fb_engine_steps_world((fb_engine_id)e)) continue;
    const fb_engine *eng = fb_engine_get((fb_engine_id)e, NULL);
    pb->models[0][pb->ne] = eng && eng->kit ? planar_model((fb_engine_id)e, 0) : NULL;
    pb->models[1][pb->ne] = eng && eng->kit && with_clearance ? planar_model((fb_engine_id)e, 1) : NULL;
    if (!pb->models[0][pb->ne] && !pb->models[1][pb->ne]) {
      const size_t l = strlen(pb->left_out);
      snprintf(pb->left_out + l, sizeof pb->left_out - l, "%s%s", l ? ", " : "",
               fb_engine_name((fb_engine_id)e));
      continue;
    }
    fb_status st = engine_rows(pb, (fb_engine_id)e, eng, diag);
    if (st != FB_OK) return st;
    pb->ne++;
  }
  return FB_OK;
}

static const fb_planar_model *find(const fb_planar_run *r, const char *name) {
  for (int i = 0; i < r->n; i++)
    if (strcmp(r->model[i].name, name) == 0) return &r->model[i];
  return NULL;
}

static double spike(const fb_body_peaks *k) { return fmax(fabs(k->alpha_max), fabs(k->alpha_min)); }

/* the ideal row's error (planar_bench.h): omega window peaks of p against
 * the analytic extremes a, each body's part in by_body */
static double ideal_error(planar_point *pt, const fb_planar *m, const fb_planar_model *a,
                          const fb_planar_model *p) {
  double largest = 0.0, worst = 0.0;
  for (int b = 1; b < m->nbodies; b++)
    largest = fmax(largest, fmax(fabs(a->peaks[b].omega_max), fabs(a->peaks[b].omega_min)));
  for (int b = 1; b < m->nbodies; b++) {
    const fb_body_peaks *x = &a->peaks[b], *y = &p->peaks[b];
    const double scale = fmax(fabs(x->omega_max), fabs(x->omega_min));
    double e = NAN;
    if (scale >= FB_PLANAR_PEAK_FLOOR_REL * largest)
      e = fmax(fabs(y->omega_max - x->omega_max), fabs(y->omega_min - x->omega_min)) / scale;
    if (b <= FB_PLANAR_BENCH_BODIES) pt->by_body[b - 1] = e;
    if (isnan(e) && scale >= FB_PLANAR_PEAK_FLOOR_REL * largest) return NAN;
    if (isfinite(e) && e >= worst) {
      worst = e;
      snprintf(pt->worst_body, sizeof pt->worst_body, "%s", m->body[b].name);
    }
  }
  return worst;
}

static double rel(double a, double b) { return b != 0.0 ? (a - b) / fabs(b) : NAN; }

/* the clearance row's error (planar_bench.h): force, penetration and every
 * body's alpha spike of p against reference y; the parts in b->part
 * (force, penetration, the worst body's spike) and by_body */
static double clearance_error(planar_point *pt, fb_bench_row *b, const fb_planar *m,
                              const fb_planar_model *y, const fb_planar_model *p) {
  b->part[FB_BENCH_PART_FORCE] = rel(p->ref.force_max, y->ref.force_max);
  b->part[FB_BENCH_PART_PENETRATION] = rel(p->ref.penetration_max, y->ref.penetration_max);
  double worst = fmax(fabs(b->part[0]), fabs(b->part[1])), largest = 0.0, body = 0.0;
  if (!isfinite(worst)) return NAN;
  for (int k = 1; k < m->nbodies; k++) largest = fmax(largest, spike(&y->peaks[k]));
  for (int k = 1; k < m->nbodies; k++) {
    const double s = spike(&y->peaks[k]);
    const double e = s >= FB_PLANAR_PEAK_FLOOR_REL * largest ? rel(spike(&p->peaks[k]), s) : NAN;
    if (k <= FB_PLANAR_BENCH_BODIES) pt->by_body[k - 1] = e;
    if (isnan(e) && s >= FB_PLANAR_PEAK_FLOOR_REL * largest) return NAN;
    if (isfinite(e) && fabs(e) >= fabs(body)) {
      body = e;
      snprintf(pt->worst_body, sizeof pt->worst_body, "%s", m->body[k].name);
    }
  }
  b->part[FB_BENCH_PART_ALPHA_COUPLER] = body; /* the worst body's, named in worst_body */
  return fmax(worst, fabs(body));
}

/* row i's first run: its error against the yardsticks and its first round */
static void first_run(planar_bench *pb, int i) {
  fb_bench_row *b = &pb->rows[i];
  planar_point *pt = &pb->pt[i];
  for (int k = 0; k < FB_PLANAR_BENCH_BODIES; k++) pt->by_body[k] = NAN;
  pt->first_force = pt->first_pen = NAN;
  static fb_planar_run r;
  fb_diag d;
  if (fb_planar_run_case(&r, &pt->k, &d) != FB_OK) { /* not built (a prismatic clearance) */
    snprintf(pt->status, sizeof pt->status, "not run: %.230s", d.msg);
    return;
  }
  const fb_planar_model *p = &r.model[0], *y = find(&pb->yard, pt->yardstick);
  if (p->ref.failed) snprintf(pt->status, sizeof pt->status, "stopped: %.230s", p->ref.stop);
  else snprintf(pt->status, sizeof pt->status, "ok");
  if (!p->ref.failed && y)
    b->error = pt->kind ? clearance_error(pt, b, r.m, y, p) : ideal_error(pt, r.m, y, p);
  if (!p->ref.failed && y && pt->kind) /* what fourbar run's verdict rests on first */
    fb_planar_first_impact(&pt->first_force, &pt->first_pen, &r, p, y);
  pt->revs = r.duration * fabs(r.omega) / (2.0 * M_PI);
  pt->walls[0] = p->wall_s - p->setup_s;
  pt->setups[0] = p->setup_s;
  pt->rounds = 1;
  b->steps_taken = (double)(p->n - 1);
  b->samples_per_rev = pt->revs > 0.0 ? (double)p->n / pt->revs : NAN;
  fb_planar_run_free(&r);
}

/* a further round of row i: its run timed again */
static void retime(planar_bench *pb, int i) {
  planar_point *pt = &pb->pt[i];
  static fb_planar_run r;
  fb_diag d;
  if (fb_planar_run_case(&r, &pt->k, &d) != FB_OK) return;
  pt->walls[pt->rounds] = r.model[0].wall_s - r.model[0].setup_s;
  pt->setups[pt->rounds++] = r.model[0].setup_s;
  fb_planar_run_free(&r);
}

static int cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* row i's cost: the median of its rounds per revolution, its set-up's median */
static void cost(planar_bench *pb, int i) {
  fb_bench_row *b = &pb->rows[i];
  planar_point *pt = &pb->pt[i];
  b->repeats = pt->rounds;
  b->wall_per_rev = b->setup_s = NAN;
  if (!pt->rounds || strncmp(pt->status, "ok", 2) != 0 || !(pt->revs > 0.0)) return;
  qsort(pt->walls, (size_t)pt->rounds, sizeof(double), cmp_double);
  qsort(pt->setups, (size_t)pt->rounds, sizeof(double), cmp_double);
  b->wall_per_rev = pt->walls[pt->rounds / 2] / pt->revs;
  b->setup_s = pt->setups[pt->rounds / 2];
  b->us_per_step = b->steps_taken > 0.0 ? 1e6 * pt->walls[pt->rounds / 2] / b->steps_taken : NAN;
}

/* the yardsticks' case: the analytic model and the references the rows name */
static void yardstick_case(fb_case *k, const planar_bench *pb) {
  *k = pb->base;
  k->model_count = 0;
  for (int i = -1; i < pb->n; i++) {
    const char *name = i < 0 ? "analytic" : pb->pt[i].yardstick;
    int have = 0;
    for (int q = 0; q < k->model_count; q++) have |= strcmp(k->models[q], name) == 0;
    if (!have && k->model_count < FB_MAX_MODELS)
      snprintf(k->models[k->model_count++], FB_NAME_SIZE, "%s", name);
  }
}

static fb_status yardsticks(planar_bench *pb, fb_diag *diag) {
  static fb_case k;
  yardstick_case(&k, pb);
  return fb_planar_run_case(&pb->yard, &k, diag);
}

/* a row's first run is timed again in the later rounds (planar_bench.h) */
static int repeats(double wall, double setup) { return wall + setup <= fb_bench_repeat_below_s(); }

/* the bench said and bounded before it starts (bench_study.h): the
 * yardsticks' case and each row's by their pilots (pilot.h), each row's
 * later rounds by the same rule as the runs; 0 or the exit status. Each
 * row's repeats are counted into *steps, for the progress */
static int work(planar_bench *pb, int *steps) {
  static fb_case k;
  yardstick_case(&k, pb);
  fb_pilot p;
  fb_diag d;
  if (fb_pilot_case(&p, &k, &d) != FB_OK) return fb_study_fail("bench", 1, "%s", d.msg);
  double cpu = p.cpu_s, pilot = p.pilot_cpu_s;
  *steps = pb->n;
  for (int i = 0; i < pb->n; i++) {
    /* a row that does not run (a prismatic clearance) is a row, not an error */
    if (fb_pilot_case(&p, &pb->pt[i].k, &d) != FB_OK) continue;
    const int later = repeats(p.model_s[0], p.setup_s[0]) ? FB_BENCH_ROUNDS - 1 : 0;
    cpu += (1 + later) * p.cpu_s;
    pilot += p.pilot_cpu_s;
    *steps += later;
  }
  return fb_bench_work(pb->o, cpu, pilot, NULL);
}

/* the base case: 2 revolutions (the case's [run] revolutions when fewer)
 * at a fixed step (the case's h_s; the step auto chose from the contacts,
 * planar_resolution.h; a revolution / 6000 where the case asks adaptive,
 * or auto without clearance joints) */
static void base_case(fb_case *k, const fb_case *c) {
  *k = *c;
  k->revolutions = fmin(c->revolutions, 2.0);
  k->duration_s = 0.0; /* by revolutions */
  const int from_contacts = fb_planar_run_step_auto(c) && c->clearance.mask;
  if (!from_contacts && (k->solver.h_mode != FB_STEP_FIXED || !(k->solver.h > 0.0)))
    k->solver.h = 2.0 * M_PI / c->crank_speed / FB_H_AUTO_STEPS_PER_REV;
  k->solver.h_mode = FB_STEP_FIXED;
}

/* the runs: yardsticks, the first pass, the further rounds, said and
 * bounded before they start, drawn on a terminal */
static int run_grid(planar_bench *pb) {
  fb_diag d;
  const double t0 = fb_clock_s();
  base_case(&pb->base, pb->o->c);
  if (grid(pb, &d) != FB_OK) return fb_study_fail("bench", 1, "%s", d.msg);
  int steps = 1, done = 0;
  const int rc = work(pb, &steps);
  if (rc) return rc;
  static fb_progress bar;
  fb_progress_init(&bar, pb->o->json);
  fb_progress_draw(&bar, "bench: yardsticks", 0.0);
  if (yardsticks(pb, &d) != FB_OK) return fb_study_fail("bench", 1, "%s", d.msg);
  fb_progress_draw(&bar, "bench: yardsticks", 1.0);
  for (int i = 0; i < pb->n; i++) {
    first_run(pb, i);
    fb_progress_draw(&bar, "bench", (double)++done / steps);
  }
  for (int round = 1; round < FB_BENCH_ROUNDS; round++)
    for (int i = 0; i < pb->n; i++)
      if (pb->pt[i].rounds == round && repeats(pb->pt[i].walls[0], pb->pt[i].setups[0])) {
        retime(pb, i);
        fb_progress_draw(&bar, "bench", fmin((double)++done / steps, 0.999));
      }
  fb_progress_draw(&bar, "bench", 1.0);
  for (int i = 0; i < pb->n; i++) cost(pb, i);
  fb_bench_mark_pareto(pb->rows, pb->n);
  for (int i = 0; i < pb->n; i++) pb->eligible[i] = (unsigned char)within_run_bound(&pb->pt[i]);
  pb->wall = fb_clock_s() - t0;
  return 0;
}

/* the cheapest row of kind q meeting target t across engines (-1: none) */
static int cheapest_across(const planar_bench *pb, int q, int t) {
  int best = -1;
  for (int e = 0; e < pb->ne; e++) {
    if (!pb->models[q][e]) continue;
    const int i = fb_bench_cheapest_of(pb->rows, pb->n, pb->models[q][e], targets[t], pb->eligible);
    if (i >= 0 && (best < 0 || pb->rows[i].wall_per_rev < pb->rows[best].wall_per_rev)) best = i;
  }
  return best;
}

/* bench.csv: one line per row; returns the exit status */
static int write_csv(const planar_bench *pb) {
  char path[4200];
  fb_diag d;
  snprintf(path, sizeof path, "%s/bench.csv", pb->o->dir);
  fb_outfile f;
  if (fb_outfile_open(&f, path, &d) != FB_OK) return fb_study_fail("bench", 1, "%s", d.msg);
  fprintf(f.f, "model,engine,kind,yardstick,stepper,h_s,status,error,force_rel,penetration_rel,"
               "alpha_spike_rel,worst_body,wall_per_rev_s,setup_s,repeats,pareto,steps_taken,"
               "us_per_step,first_impact_force_rel,first_impact_penetration_rel\n");
#define CSV(x) FB_NUM_CELL("%.6g", (x), FB_NUM_NONE_CSV)
  for (int i = 0; i < pb->n; i++) {
    const fb_bench_row *b = &pb->rows[i];
    const planar_point *pt = &pb->pt[i];
    fprintf(f.f, "%s,%s,%s,%s,%s,%g,\"%s\",%s,%s,%s,", b->model, b->engine, kinds[pt->kind],
            pt->yardstick, b->stepper, b->h, pt->status, CSV(b->error),
            CSV(b->part[FB_BENCH_PART_FORCE]), CSV(b->part[FB_BENCH_PART_PENETRATION]));
    fprintf(f.f, "%s,%s,%s,%s,%d,%d,%.0f,%s,", CSV(b->part[FB_BENCH_PART_ALPHA_COUPLER]),
            pt->worst_body, CSV(b->wall_per_rev), CSV(b->setup_s), b->repeats, b->pareto,
            b->steps_taken, CSV(b->us_per_step));
    fprintf(f.f, "%s,%s\n", CSV(pt->first_force), CSV(pt->first_pen));
  }
#undef CSV
  if (fb_outfile_commit(&f, &d) != FB_OK) return fb_study_fail("bench", 1, "%s", d.msg);
  return 0;
}

static json_t *num(double x) { return isfinite(x) ? json_real(x) : json_null(); }

/* a row as bench.json holds it: the four-bar's keys where they apply */
static json_t *row_json(const planar_bench *pb, int i) {
  const fb_bench_row *b = &pb->rows[i];
  const planar_point *pt = &pb->pt[i];
  json_t *o = json_object();
  json_object_set_new(o, "model", json_string(b->model));
  json_object_set_new(o, "engine", json_string(b->engine));
  json_object_set_new(o, "kind", json_string(kinds[pt->kind]));
  json_object_set_new(o, "yardstick", json_string(pt->yardstick));
  json_object_set_new(o, "stepper", json_string(b->stepper));
  json_object_set_new(o, "h_s", json_real(b->h));
  json_object_set_new(o, "h_auto", json_false());
  json_object_set_new(o, "h_adaptive", json_false());
  json_object_set_new(o, "mapping", json_string(b->mapping >= 0 ? fb_mapping_name((fb_mapping)b->mapping) : "-"));
  json_object_set_new(o, "collider", json_string(b->collider));
  json_object_set_new(o, "status", json_string(pt->status));
  json_object_set_new(o, "error", num(b->error));
  json_object_set_new(o, "wall_per_rev_s", num(b->wall_per_rev));
  json_object_set_new(o, "setup_s", num(b->setup_s));
  json_object_set_new(o, "repeats", json_integer(b->repeats));
  json_object_set_new(o, "pareto", json_boolean(b->pareto));
  json_object_set_new(o, "steps_taken", json_real(b->steps_taken));
  json_object_set_new(o, "samples_per_rev", num(b->samples_per_rev));
  json_object_set_new(o, "us_per_step", num(b->us_per_step));
  json_t *parts = json_null(), *bodies = json_object();
  if (pt->kind)
    parts = json_pack("{s:o,s:o,s:o,s:s}", "force_max_rel", num(b->part[FB_BENCH_PART_FORCE]),
                      "penetration_max_rel", num(b->part[FB_BENCH_PART_PENETRATION]),
                      "alpha_spike_rel", num(b->part[FB_BENCH_PART_ALPHA_COUPLER]),
                      "alpha_spike_body", pt->worst_body);
  const fb_planar *m = pb->yard.m;
  for (int k = 1; k < m->nbodies && k <= FB_PLANAR_BENCH_BODIES; k++)
    if (!isnan(pt->by_body[k - 1]))
      json_object_set_new(bodies, m->body[k].name, json_real(pt->by_body[k - 1]));
  json_object_set_new(o, "error_parts", parts);
  json_object_set_new(o, "error_by_body", bodies);
  json_object_set_new(o, "worst_body", json_string(pt->worst_body));
  /* fourbar run's measure beside bench's: a clearance model's verdict rests
   * first on its first impact within FB_FAITHFUL_PENETRATION_TOL */
  const int paired = isfinite(pt->first_force) && isfinite(pt->first_pen);
  json_object_set_new(o, "first_impact",
                      pt->kind ? json_pack("{s:o,s:o,s:f,s:o}", "force_rel", num(pt->first_force),
                                           "penetration_rel", num(pt->first_pen), "verdict_bound",
                                           FB_FAITHFUL_PENETRATION_TOL, "within_verdict_bound",
                                           paired ? json_boolean(within_run_bound(pt)) : json_null())
                               : json_null());
  return o;
}

/* bench.json's "cheapest" (per engine and model) and "cheapest_across_engines" */
static void cheapest_json(const planar_bench *pb, json_t *cheap, json_t *across) {
  for (int q = 0; q < 2; q++)
    for (int t = 0; t < FB_BENCH_TARGETS; t++) {
      for (int e = 0; e < pb->ne; e++) {
        if (!pb->models[q][e]) continue;
        const int i = fb_bench_cheapest_of(pb->rows, pb->n, pb->models[q][e], targets[t],
                                           pb->eligible);
        const int by_error = fb_bench_cheapest(pb->rows, pb->n, pb->models[q][e], targets[t]);
        json_array_append_new(cheap, json_pack("{s:s,s:f,s:o,s:o}", "model", pb->models[q][e]->name,
                                               "target", targets[t], "row",
                                               i >= 0 ? json_integer(i) : json_null(),
                                               "row_by_error_alone",
                                               by_error >= 0 ? json_integer(by_error)
                                                             : json_null()));
      }
      const int best = cheapest_across(pb, q, t);
      json_array_append_new(across, json_pack("{s:s,s:f,s:o}", "kind", kinds[q], "target", targets[t],
                                              "row", best >= 0 ? json_integer(best) : json_null()));
    }
}

/* bench.json's "yardsticks": each yardstick model's run */
static json_t *yardsticks_json(const planar_bench *pb) {
  json_t *y = json_object();
  for (int i = 0; i < pb->yard.n; i++) {
    const fb_planar_model *p = &pb->yard.model[i];
    json_t *o = json_pack("{s:f,s:f}", "h_s", p->h, "wall_s", p->wall_s);
    if (p->reference)
      json_object_update_new(o, json_pack("{s:o,s:o,s:o,s:b,s:b}", "force_max_n",
                                          num(p->ref.force_max), "penetration_max_m",
                                          num(p->ref.penetration_max), "check_rel",
                                          num(p->ref.check_rel), "converged", p->ref.converged,
                                          "failed", p->ref.failed));
    json_object_set_new(y, p->name, o);
  }
  return y;
}

/* bench.csv, bench.json and bench.svg; *j receives bench.json's object */
static int write_files(const planar_bench *pb, json_t **j) {
  const fb_bench_opts *o = pb->o;
  int rc = write_csv(pb);
  if (rc) return rc;
  json_t *arr = json_array(), *cheap = json_array(), *across = json_array(), *lo = json_array();
  for (int i = 0; i < pb->n; i++) json_array_append_new(arr, row_json(pb, i));
  cheapest_json(pb, cheap, across);
  char names[sizeof pb->left_out];
  snprintf(names, sizeof names, "%s", pb->left_out);
  for (char *save = NULL, *t = strtok_r(names, ", ", &save); t; t = strtok_r(NULL, ", ", &save))
    json_array_append_new(lo, json_string(t));
  *j = json_pack("{s:s,s:s,s:s,s:f,s:f,s:o,s:o,s:o,s:o,s:o,s:o,s:o}", "case", o->c->name, "grid",
                 o->grid_name, "mechanism", "planar", "wall_s", pb->wall, "revolutions",
                 pb->base.revolutions, "rows", arr, "cheapest", cheap, "cheapest_across_engines",
                 across, "peers", json_array(), "scaling", json_array(), "yardsticks",
                 yardsticks_json(pb), "engines_left_out", lo);
  fb_bench_marks marks = {.npeers = 0}; /* no peers on a planar case */
  for (int t = 0; t < FB_BENCH_TARGETS; t++) {
    marks.target[t] = targets[t];
    for (int q = 0; q < 2; q++) marks.cheapest[q][t] = cheapest_across(pb, q, t);
  }
  return fb_bench_write_json_svg(o, *j, pb->rows, pb->n, &marks);
}

/* the table of every row on stdout */
static void print_rows(const planar_bench *pb) {
  printf("bench of %s (planar): %d rows in %.1f s, %g revolution%s each, peaks %s "
         "('P': Pareto front of its engine's model; error of an ideal row: omega peaks against "
         "the analytic; of a clearance row: the largest of its force, penetration and alpha "
         "spike errors against the reference of its law, body: the worst part's)\n\n"
         "%-26s %-16s %9s %11s %10s %10s %10s %-10s %11s %10s %10s %10s  %s\n",
         pb->o->c->name, pb->n, pb->wall, pb->base.revolutions,
         pb->base.revolutions == 1.0 ? "" : "s",
         pb->base.peaks == FB_PEAKS_ALL ? "over all of it" : "after the first", "model", "stepper", "h_s", "error", "force", "pen",
         "alpha", "body", "s/rev", "setup s", "1st force", "1st pen", "status");
  for (int i = 0; i < pb->n; i++) {
    const fb_bench_row *b = &pb->rows[i];
    const planar_point *pt = &pb->pt[i];
    char cell[5][16];
    const double v[5] = {b->error, b->part[0], b->part[1], b->part[2], b->wall_per_rev};
    for (int k = 0; k < 5; k++) snprintf(cell[k], sizeof cell[k], isfinite(v[k]) ? "%.3e" : "-", v[k]);
    printf("%-26s %-16s %9.3g %11s %10s %10s %10s %-10s %11s %c %8s %10s %10s  %.60s\n",
           b->model, b->stepper, b->h, cell[0], cell[1], cell[2], cell[3], pt->worst_body, cell[4],
           b->pareto ? 'P' : ' ', FB_NUM_CELL("%.2e", b->setup_s, "-"),
           FB_NUM_CELL("%+.2e", pt->first_force, "-"), FB_NUM_CELL("%+.2e", pt->first_pen, "-"),
           pt->status);
  }
}

/* the cheapest row of each model and across engines on stdout: among the
 * rows fourbar run reads without error on their first impact; a cheaper
 * row that meets the target on bench's error alone is named beside it */
static void print_cheapest(const planar_bench *pb) {
  printf("\ncheapest configuration meeting each error target and, for a clearance model, "
         "fourbar run's first-impact bound %g (per engine, then across engines):\n",
         FB_FAITHFUL_PENETRATION_TOL);
  for (int q = 0; q < 2; q++)
    for (int t = 0; t < FB_BENCH_TARGETS; t++) {
      for (int e = 0; e < pb->ne; e++) {
        const fb_model *m = pb->models[q][e];
        if (!m) continue;
        const int i = fb_bench_cheapest_of(pb->rows, pb->n, m, targets[t], pb->eligible);
        const int by_error = fb_bench_cheapest(pb->rows, pb->n, m, targets[t]);
        if (i < 0) printf("  %-26s error <= %.0e: none in the grid", m->name, targets[t]);
        else {
          printf("  %-26s error <= %.0e: %s, h = %g s: %.3e at %.3e s/rev", m->name,
                 targets[t], pb->rows[i].stepper, pb->rows[i].h, pb->rows[i].error,
                 pb->rows[i].wall_per_rev);
          if (q == 1)
            printf("; first impact %+.2g force, %+.2g penetration", pb->pt[i].first_force,
                   pb->pt[i].first_pen);
        }
        if (by_error >= 0 && by_error != i) {
          const planar_point *pt = &pb->pt[by_error];
          if (isfinite(pt->first_force) && isfinite(pt->first_pen))
            printf(" (h = %g s meets it on error alone, but its first impact is %+.2g force, "
                   "%+.2g penetration: fourbar run reads error there)",
                   pb->rows[by_error].h, pt->first_force, pt->first_pen);
          else
            printf(" (h = %g s meets it on error alone, but its first impact has no partner: "
                   "fourbar run reads error there)",
                   pb->rows[by_error].h);
        }
        printf("\n");
      }
      const int best = cheapest_across(pb, q, t);
      if (best >= 0)
        printf("  -> %s error <= %.0e: cheapest on %s\n", kinds[q], targets[t], pb->rows[best].engine);
    }
}

/* the files, then bench.json or the tables on stdout */
static int write_and_print(const planar_bench *pb) {
  json_t *j;
  int rc = write_files(pb, &j);
  if (rc) return rc;
  if (pb->o->json) {
    json_dumpf(j, stdout, JSON_INDENT(2) | JSON_REAL_PRECISION(10));
    fputc('\n', stdout);
    json_decref(j);
    return 0;
  }
  json_decref(j);
  if (pb->left_out[0])
    printf("left out: %s (no binding of the engine kit in this build: fourbar models lists what "
           "each builds)\n", pb->left_out);
  print_rows(pb);
  print_cheapest(pb);
  printf("\nwrote %s/bench.csv, bench.json and bench.svg\n", pb->o->dir);
  return 0;
}

int fb_bench_planar(const fb_bench_opts *o) {
  if (o->c->planar.undriven)
    return fb_study_fail("bench", 2, "case '%s' is undriven ([drive] joint = none): the bench "
                         "measures engine models, which follow the drive; give the case a "
                         "[drive] joint", o->c->name);
  fb_diag d;
  if (fb_outdir_prepare(o->dir, &d) != FB_OK) return fb_study_fail("bench", 1, "%s", d.msg);
  planar_bench *pb = calloc(1, sizeof *pb);
  if (!pb) return fb_study_fail("bench", 1, "out of memory");
  pb->o = o;
  int rc = run_grid(pb);
  if (!rc) rc = write_and_print(pb);
  if (pb->yard.m) fb_planar_run_free(&pb->yard);
  free(pb);
  return rc;
}
