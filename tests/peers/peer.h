/* What every bare peer program shares (tests/peers/peer_*.c, .cpp): reading
 * its settings, the samples it keeps, its clock and its one line of JSON.
 * Engine-free and harness-free: a peer uses its engine's API and this
 * header only. `fourbar bench --grid peers` (src/studies/peers.c) starts a
 * peer with the ideal four-bar of the case and the settings the harness's
 * model runs with, and compares its cost with the harness's.
 *
 * Arguments, each key=value, SI units:
 *   h steps window      step [s], steps to take, peaks taken over t >= window [s]
 *   a b c g             crank, coupler, follower, ground lengths [m]
 *   mK iK ilK itK fK    link K (0 crank, 1 coupler, 2 follower): mass [kg], moment
 *                       about the hinge axis through the centre of mass, about the
 *                       link's long axis, about the transverse axis [kg m^2], centre of
 *                       mass as a fraction of the link from its first joint
 *   gravity omega2      [m/s^2] along -y, signed crank speed [rad/s]
 *   th2 th3 th4 w3 w4   start: crank, coupler, follower angles [rad], coupler and
 *                       follower angular velocities [rad/s]
 *   engine settings     erp cfm fmax (ODE); integrator loop_k loop_b loop_imp armature
 *                       (MuJoCo); solver iterations erp fmax (Bullet); integrator
 *                       accuracy (Simbody); erp fmax pgs_sweeps pgs_dx pgs_rel_dx
 *                       (DART)
 *
 * Output, one line: {"engine", "samples", "steps", "setup_s", "loop_s",
 * "peaks": {"coupler_omega_max", "coupler_omega_min", "follower_omega_max",
 * "follower_omega_min"}}: loop_s is the stepping and sampling loop alone,
 * setup_s the world's creation and the samples' memory. */
#ifndef FB_PEER_H
#define FB_PEER_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define PEER_MAX_ARGS 64

typedef struct {
  int n;
  const char *key[PEER_MAX_ARGS];
  const char *value[PEER_MAX_ARGS];
} peer_args;

static inline void peer_parse(peer_args *a, int argc, char **argv) {
  a->n = 0;
  for (int i = 1; i < argc && a->n < PEER_MAX_ARGS; i++) {
    char *eq = strchr(argv[i], '=');
    if (!eq) {
      fprintf(stderr, "peer: argument '%s' is not key=value\n", argv[i]);
      exit(2);
    }
    *eq = '\0';
    a->key[a->n] = argv[i];
    a->value[a->n++] = eq + 1;
  }
}

static inline const char *peer_str(const peer_args *a, const char *key) {
  for (int i = 0; i < a->n; i++)
    if (strcmp(a->key[i], key) == 0) return a->value[i];
  fprintf(stderr, "peer: missing argument %s=\n", key);
  exit(2);
}

static inline double peer_num(const peer_args *a, const char *key) {
  const char *v = peer_str(a, key);
  char *end;
  const double x = strtod(v, &end);
  if (end == v || *end || !isfinite(x)) {
    fprintf(stderr, "peer: %s=%s is not a number\n", key, v);
    exit(2);
  }
  return x;
}

/* the four-bar of the case */
typedef struct {
  double h, window;
  long steps;
  double len[4];               /* crank, coupler, follower, ground [m] */
  double mass[3], inertia[3], inertia_long[3], inertia_transverse[3], com[3];
  double gravity, omega2;
  double th2, th3, th4, w3, w4; /* start */
} peer_fourbar;

static inline void peer_fourbar_read(peer_fourbar *f, const peer_args *a) {
  f->h = peer_num(a, "h");
  f->steps = (long)peer_num(a, "steps");
  f->window = peer_num(a, "window");
  const char *ln[4] = {"a", "b", "c", "g"};
  for (int i = 0; i < 4; i++) f->len[i] = peer_num(a, ln[i]);
  for (int k = 0; k < 3; k++) {
    char key[8];
    snprintf(key, sizeof key, "m%d", k);
    f->mass[k] = peer_num(a, key);
    snprintf(key, sizeof key, "i%d", k);
    f->inertia[k] = peer_num(a, key);
    snprintf(key, sizeof key, "il%d", k);
    f->inertia_long[k] = peer_num(a, key);
    snprintf(key, sizeof key, "it%d", k);
    f->inertia_transverse[k] = peer_num(a, key);
    snprintf(key, sizeof key, "f%d", k);
    f->com[k] = peer_num(a, key);
  }
  f->gravity = peer_num(a, "gravity");
  f->omega2 = peer_num(a, "omega2");
  f->th2 = peer_num(a, "th2");
  f->th3 = peer_num(a, "th3");
  f->th4 = peer_num(a, "th4");
  f->w3 = peer_num(a, "w3");
  f->w4 = peer_num(a, "w4");
}

/* a peer's start: its arguments into a, the four-bar among them into f */
static inline void peer_start(peer_args *a, peer_fourbar *f, int argc, char **argv) {
  peer_parse(a, argc, argv);
  peer_fourbar_read(f, a);
}

/* the samples a peer keeps, one per output step: what the harness keeps of
 * an ideal model (angles, angular velocities and accelerations, the drive
 * torque and the four joint reactions) */
enum { P_T, P_CRANK, P_COUPLER, P_COUPLER_W, P_COUPLER_A, P_FOLLOWER, P_FOLLOWER_W,
       P_FOLLOWER_A, P_TORQUE, P_RX, P_COLS = P_RX + 8 };

typedef struct {
  long n, cap;
  double *col[P_COLS];
} peer_series;

/* allocates and touches the columns (set-up, as the harness's series) */
static inline void peer_series_init(peer_series *s, long cap) {
  s->n = 0;
  s->cap = cap;
  for (int c = 0; c < P_COLS; c++) {
    s->col[c] = (double *)malloc((size_t)cap * sizeof(double));
    if (!s->col[c]) {
      fprintf(stderr, "peer: out of memory for %ld samples\n", cap);
      exit(1);
    }
    memset(s->col[c], 0, (size_t)cap * sizeof(double));
  }
}

/* frees the columns (after the report; a sanitizer build checks for leaks) */
static inline void peer_series_free(peer_series *s) {
  for (int c = 0; c < P_COLS; c++) free(s->col[c]);
}

/* the kinematic columns of the sample at t from the bodies' (crank, coupler,
 * follower) angles, angular velocities and accelerations (al NULL: none yet) */
static inline void peer_bodies(double v[P_COLS], double t, const double ang[3], const double w[3],
                               const double al[3]) {
  v[P_T] = t;
  v[P_CRANK] = ang[0];
  v[P_COUPLER] = ang[1];
  v[P_COUPLER_W] = w[1];
  v[P_COUPLER_A] = al ? al[1] : 0.0;
  v[P_FOLLOWER] = ang[2];
  v[P_FOLLOWER_W] = w[2];
  v[P_FOLLOWER_A] = al ? al[2] : 0.0;
}

/* a body after a step of h: its angle unwrapped from the one before, its
 * angular velocity, and the acceleration the step applied (the change of
 * angular velocity over h) */
static inline void peer_body_step(double *ang, double *w, double *al, double angle_now,
                                  double w_now, double h) {
  *al = (w_now - *w) / h;
  *w = w_now;
  *ang += remainder(angle_now - *ang, 2.0 * M_PI);
}

/* keeps one sample (its columns in P_ order) */
static inline void peer_push(peer_series *s, const double v[P_COLS]) {
  if (s->n == s->cap) return;
  for (int c = 0; c < P_COLS; c++) s->col[c][s->n] = v[c];
  s->n++;
}

static inline double peer_clock(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* the one line of output */
static inline void peer_report(const char *engine, const peer_series *s, long steps,
                               double setup_s, double loop_s, double window) {
  double wmax[2] = {-INFINITY, -INFINITY}, wmin[2] = {INFINITY, INFINITY};
  const int col[2] = {P_COUPLER_W, P_FOLLOWER_W};
  for (long i = 0; i < s->n; i++) {
    if (s->col[P_T][i] < window) continue;
    for (int b = 0; b < 2; b++) {
      wmax[b] = fmax(wmax[b], s->col[col[b]][i]);
      wmin[b] = fmin(wmin[b], s->col[col[b]][i]);
    }
  }
  printf("{\"engine\": \"%s\", \"samples\": %ld, \"steps\": %ld, \"setup_s\": %.9g, "
         "\"loop_s\": %.9g, \"peaks\": {\"coupler_omega_max\": %.17g, \"coupler_omega_min\": "
         "%.17g, \"follower_omega_max\": %.17g, \"follower_omega_min\": %.17g}}\n",
         engine, s->n, steps, setup_s, loop_s, wmax[0], wmin[0], wmax[1], wmin[1]);
}

#endif
