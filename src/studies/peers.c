/* _GNU_SOURCE (meson.build): pipe2 */
#include "peers.h"

#include "pilot.h"

#include <errno.h>
#include <fcntl.h>
#include <jansson.h>
#include <math.h>
#include <signal.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "engine.h"
#include "run.h"
#include "scene.h"
#include "start.h"

extern char **environ;

#ifndef FB_PEERS_DIR
#define FB_PEERS_DIR "tests"
#endif

/* what a peer prints, at most (its one JSON line, or its error) */
#define PEER_OUTPUT_MAX 65536
#define PEER_ARGS_MAX 48

static int cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double median(const double *v, int n) {
  double s[FB_PEER_ROUNDS];
  memcpy(s, v, (size_t)n * sizeof *s);
  qsort(s, (size_t)n, sizeof *s, cmp_double);
  return n % 2 ? s[n / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
}

typedef struct {
  int n;
  char text[PEER_ARGS_MAX][80];
} arglist;

static void arg(arglist *a, const char *key, double v) {
  if (a->n < PEER_ARGS_MAX) snprintf(a->text[a->n++], sizeof a->text[0], "%s=%.17g", key, v);
}

static void arg_s(arglist *a, const char *key, const char *v) {
  if (a->n < PEER_ARGS_MAX) snprintf(a->text[a->n++], sizeof a->text[0], "%s=%s", key, v);
}

static void put_arg(void *a, const char *key, const char *value) { arg_s(a, key, value); }

/* the four-bar of model view sm and the engine's settings, as peer.h reads them */
static fb_status peer_args(arglist *a, const fb_model_scene *sm, double window, fb_diag *diag) {
  fb_start_state st;
  fb_status rc = fb_model_scene_start(&st, sm, diag);
  if (rc != FB_OK) return rc;
  a->n = 0;
  const double h = sm->solver.h;
  arg(a, "h", h);
  arg(a, "steps", (double)sm->def->steps);
  arg(a, "window", window);
  const char *ln[4] = {"a", "b", "c", "g"};
  const int li[4] = {FB_CRANK, FB_COUPLER, FB_FOLLOWER, FB_GROUND};
  for (int i = 0; i < 4; i++) arg(a, ln[i], sm->lengths.length[li[i]]);
  for (int k = 0; k < 3; k++) {
    char key[8];
    const fb_link_mass *m = &sm->link[k];
    snprintf(key, sizeof key, "m%d", k);
    arg(a, key, m->mass);
    snprintf(key, sizeof key, "i%d", k);
    arg(a, key, m->inertia);
    snprintf(key, sizeof key, "il%d", k);
    arg(a, key, m->inertia_long);
    snprintf(key, sizeof key, "it%d", k);
    arg(a, key, m->inertia_transverse);
    snprintf(key, sizeof key, "f%d", k);
    arg(a, key, m->com_fraction);
  }
  arg(a, "gravity", sm->gravity);
  arg(a, "omega2", sm->omega2);
  arg(a, "th2", st.crank_angle);
  arg(a, "th3", st.coupler_angle);
  arg(a, "th4", st.follower_angle);
  arg(a, "w3", st.coupler_omega);
  arg(a, "w4", st.follower_omega);
  const fb_engine *e = fb_engine_get(sm->model->engine, NULL);
  if (e && e->peer_args) e->peer_args(sm, h, put_arg, a);
  return FB_OK;
}

/* runs program path with args, its standard output and errors into out;
 * 0 when it exited 0, else a reason in why */
static int run_peer(const char *path, const arglist *a, char *out, size_t size, char *why,
                    size_t wsize) {
  char *argv[PEER_ARGS_MAX + 2];
  argv[0] = (char *)path;
  for (int i = 0; i < a->n; i++) argv[i + 1] = (char *)a->text[i];
  argv[a->n + 1] = NULL;
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) {
    snprintf(why, wsize, "cannot make a pipe: %s", strerror(errno));
    return -1;
  }
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&fa, fds[1], 1);
  posix_spawn_file_actions_adddup2(&fa, fds[1], 2);
  pid_t pid;
  const int rc = posix_spawn(&pid, path, &fa, NULL, argv, environ);
  posix_spawn_file_actions_destroy(&fa);
  close(fds[1]);
  if (rc != 0) {
    close(fds[0]);
    snprintf(why, wsize, "cannot start %.200s: %s", path, strerror(rc));
    return -1;
  }
  size_t len = 0;
  for (;;) {
    const ssize_t r = read(fds[0], out + len, size - 1 - len);
    if (r > 0) len += (size_t)r;
    else if (r == 0 || errno != EINTR) break;
    if (len == size - 1) { /* more than a peer says: drop the rest */
      char sink[4096];
      while (read(fds[0], sink, sizeof sink) > 0) {
      }
      break;
    }
  }
  out[len] = '\0';
  close(fds[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return 0;
  char *nl = strchr(out, '\n');
  if (nl) *nl = '\0';
  snprintf(why, wsize, "%.200s %s (%.160s)", path,
           WIFEXITED(status) ? "failed" : "was killed", out[0] ? out : "no output");
  return -1;
}

/* the peer's line: loop time, samples, steps and omega peaks */
static int read_peer(const char *out, double *loop_s, long *samples, long *steps, double peaks[4],
                     char *why, size_t wsize) {
  const char *line = strrchr(out, '{');
  while (line && line > out && line[-1] != '\n') line = NULL;
  if (!line) line = strchr(out, '{');
  json_error_t err;
  json_t *o = line ? json_loads(line, JSON_DISABLE_EOF_CHECK, &err) : NULL;
  if (!o) {
    snprintf(why, wsize, "peer output is not its JSON line: %.120s", out);
    return -1;
  }
  json_t *p = json_object_get(o, "peaks");
  static const char *const keys[4] = {"coupler_omega_max", "coupler_omega_min",
                                      "follower_omega_max", "follower_omega_min"};
  *loop_s = json_number_value(json_object_get(o, "loop_s"));
  *samples = (long)json_integer_value(json_object_get(o, "samples"));
  *steps = (long)json_integer_value(json_object_get(o, "steps"));
  for (int k = 0; k < 4; k++) peaks[k] = json_number_value(json_object_get(p, keys[k]));
  json_decref(o);
  return 0;
}

/* the engines with a peer program in this build (fb_engine.peer_args) */
static int has_peer(fb_engine_id id) {
  const fb_engine *e = fb_engine_available(id) ? fb_engine_get(id, NULL) : NULL;
  return e && e->peer_args;
}

int fb_peers_build(fb_mech_type t) { return fb_mech_of(t)->peers_build; }

/* the case of p's peer (its model alone, 2 revolutions at case c's step)
 * into *k: 1 when it runs, else 0 with why in p->status */
static int peer_case(fb_case *k, fb_peer_row *p, const fb_case *c, const char *dir) {
  if (!p->model) {
    snprintf(p->status, sizeof p->status, "no ideal nominal model for %s", p->engine);
    return 0;
  }
  /* the bare programs (tests/peers) build the four-bar alone */
  if (!fb_peers_build(c->mechanism)) {
    snprintf(p->status, sizeof p->status, "not run: %s builds the four-bar only, not a %s",
             p->peer, fb_case_mech(c)->type);
    return 0;
  }
  char path[4400];
  snprintf(path, sizeof path, "%s/%s", dir, p->peer);
  if (access(path, X_OK) != 0) {
    snprintf(p->status, sizeof p->status, "%.200s is not there: the peers are built with the tests "
             "(meson setup -Dtests=enabled, ninja -C build); or set %s", path, FB_PEERS_ENV);
    return 0;
  }
  *k = *c;
  k->revolutions = 2;
  k->model_count = 1;
  snprintf(k->models[0], FB_NAME_SIZE, "%s", p->model->name);
  return 1;
}

/* the row of engine e: its names and model, nothing measured */
static void peer_row(fb_peer_row *p, fb_engine_id e) {
  memset(p, 0, sizeof *p);
  snprintf(p->engine, sizeof p->engine, "%s", fb_engine_name(e));
  p->model = fb_model_match(e, FB_LENGTHS_NOMINAL, FB_JOINTS_IDEAL, FB_MODEL_LAW_NONE,
                            FB_COLLIDER_NONE);
  snprintf(p->peer, sizeof p->peer, "peer_%s", p->engine);
  p->harness_over_bare = p->harness_per_rev = p->bare_per_rev = p->peak_rel = NAN;
}

static const char *peers_dir(const char *dir) {
  if (!dir) dir = getenv(FB_PEERS_ENV);
  return dir && *dir ? dir : FB_PEERS_DIR;
}

fb_status fb_peers_estimate(double *cpu_s, double *pilot_s, const fb_case *c, const char *dir,
                            fb_diag *diag) {
  *cpu_s = 0.0;
  if (pilot_s) *pilot_s = 0.0;
  dir = peers_dir(dir);
  for (int e = 0; e < FB_ENGINE_COUNT; e++) {
    if (!has_peer((fb_engine_id)e)) continue;
    fb_peer_row p;
    peer_row(&p, (fb_engine_id)e);
    static fb_case k;
    if (!peer_case(&k, &p, c, dir)) continue;
    fb_pilot pl;
    fb_status st = fb_pilot_case(&pl, &k, diag);
    if (st != FB_OK) return st;
    /* each round runs the harness's model and the bare program, which
     * does no more than the model: counted as the harness twice */
    *cpu_s += 2.0 * FB_PEER_ROUNDS * pl.cpu_s;
    if (pilot_s) *pilot_s += pl.pilot_cpu_s;
  }
  return FB_OK;
}

fb_status fb_peers_run(fb_peer_row *rows, int *n, const fb_case *c, const char *dir,
                       void (*progress)(double fraction, void *user), void *user, fb_diag *diag) {
  *n = 0;
  dir = peers_dir(dir);
  int total = 0;
  for (int e = 0; e < FB_ENGINE_COUNT; e++) total += has_peer((fb_engine_id)e);
  int done = 0;
  static char out[PEER_OUTPUT_MAX];
  for (int e = 0; e < FB_ENGINE_COUNT; e++) {
    if (!has_peer((fb_engine_id)e)) continue;
    fb_peer_row *p = &rows[(*n)++];
    peer_row(p, (fb_engine_id)e);
    static fb_case k;
    if (!peer_case(&k, p, c, dir)) continue;
    char path[4400];
    snprintf(path, sizeof path, "%s/%s", dir, p->peer);
    static fb_run r;
    arglist args;
    double revs = 0.0;
    int ok = 1;
    for (int round = 0; round < FB_PEER_ROUNDS && ok; round++) {
      /* the harness, as fourbar run runs the model */
      fb_status st = fb_run_case(&r, &k, NULL, NULL, diag);
      if (st != FB_OK) return st;
      const fb_model_result *m = &r.model[0];
      if (m->run.stop.kind != FB_STOP_NONE || !m->has_peaks) {
        snprintf(p->status, sizeof p->status, "the harness's %s stopped", p->model->name);
        fb_run_free(&r);
        ok = 0;
        break;
      }
      p->harness_s[round] = m->run.wall_s - m->run.setup_s;
      const long harness_samples = (long)m->run.series.n;
      const double hp[4] = {m->peaks.coupler.omega_max, m->peaks.coupler.omega_min,
                            m->peaks.follower.omega_max, m->peaks.follower.omega_min};
      if (round == 0) {
        p->h = m->run.h;
        const fb_series *s = &m->run.series;
        revs = s->n > 1 ? s->t[s->n - 1] * k.crank_speed / (2.0 * M_PI) : 0.0;
        fb_model_scene sm;
        st = fb_scene_select(&sm, &r.scene, p->model, diag);
        if (st == FB_OK) st = peer_args(&args, &sm, r.t_window, diag);
        if (st != FB_OK) {
          fb_run_free(&r);
          return st;
        }
      }
      fb_run_free(&r);
      /* the peer, right after */
      double peaks[4];
      if (run_peer(path, &args, out, sizeof out, p->status, sizeof p->status) != 0 ||
          read_peer(out, &p->bare_s[round], &p->samples, &p->peer_steps, peaks, p->status,
                    sizeof p->status) != 0) {
        ok = 0;
        break;
      }
      if (p->samples != harness_samples) { /* not the same grid: no comparison */
        snprintf(p->status, sizeof p->status, "the peer kept %ld samples, the harness %ld",
                 p->samples, harness_samples);
        ok = 0;
        break;
      }
      p->rounds = round + 1;
      double worst = 0.0;
      for (int q = 0; q < 4; q++)
        worst = fmax(worst, fabs(peaks[q] - hp[q]) / fmax(fabs(hp[q]), 1e-300));
      p->peak_rel = round == 0 ? worst : fmax(p->peak_rel, worst);
    }
    if (progress) progress((double)++done / total, user);
    if (!ok) continue;
    double ratio[FB_PEER_ROUNDS];
    for (int q = 0; q < p->rounds; q++) ratio[q] = p->harness_s[q] / p->bare_s[q];
    p->harness_over_bare = median(ratio, p->rounds);
    if (revs > 0.0) {
      p->harness_per_rev = median(p->harness_s, p->rounds) / revs;
      p->bare_per_rev = median(p->bare_s, p->rounds) / revs;
    }
    p->ran = 1;
    snprintf(p->status, sizeof p->status, "ok");
  }
  return FB_OK;
}
