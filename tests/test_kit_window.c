/* The engine kit's window (kit.h fb_kit_series.window): a run that keeps
 * only its last few samples, read one behind the kit as the kit adapter
 * reads them, gives every sample bit for bit as a run that keeps them all
 * (fb_kit_run): time, every body's angle, omega and alpha, the drift, the
 * drive torque and every joint's reaction; at a fixed step and at the
 * adaptive one, whose steps span many samples (the longest 20 here), on
 * ODE's binding (accelerations from the step's difference) and MuJoCo's
 * (its own, and the samples inside a step filled once the next step has
 * begun). A window that is no power of two, or shorter than fb_kit_window,
 * is refused. The planar template four-bar, every joint ideal. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "casefile.h"
#include "kit.h"
#include "planar_case.h"
#include "planar_run.h"

/* samples compared: at the adaptive step's grid (1 us) 3 ms, 150 of its
 * longest steps; at the fixed step (the case's) as many */
#define SAMPLES 3000

/* the drive's speed [rad/s]: the template's 1000 rpm */
#define OMEGA (1000.0 * 2.0 * M_PI / 60.0)

typedef struct {
  fb_kit_series s;
  double *block;
} series;

/* columns for n samples of m kept in L each (L = n: every sample) */
static void series_new(series *x, const fb_planar *m, size_t n, size_t window, double h,
                       int loads) {
  const size_t L = window ? window : n, nb = (size_t)m->nbodies - 1;
  const size_t cols = 2 + 3 * nb + (loads ? 1 + 3 * (size_t)m->njoints : 0);
  x->block = calloc(cols * L, sizeof *x->block);
  assert_non_null(x->block);
  x->s = (fb_kit_series){.n = n, .h = h, .window = window, .t = x->block};
  x->s.q = x->s.t + L;
  x->s.drift = x->s.q + 3 * nb * L;
  if (loads) x->s.torque = x->s.drift + L, x->s.reaction = x->s.torque + L;
}

/* sample i's value of column c (L long, index mask M) */
static double at(const double *c, size_t L, size_t M, size_t col, size_t i) {
  return c[col * L + (i & M)];
}

/* the whole run and the windowed one of model `name` on the template
 * (sets: the case's overrides), sample by sample */
static void compare(const char *name, const char *const *sets, int nsets) {
  char path[4096];
  const char *dir = getenv("FOURBAR_CASES_DIR");
  snprintf(path, sizeof path, "%s/templates/planar_fourbar.ini", dir ? dir : "cases");
  fb_case c;
  fb_diag d;
  fb_planar *m;
  if (fb_casefile_load_planar(&c, path, sets, nsets, &d) != FB_OK) fail_msg("%s", d.msg);
  if (fb_planar_of_case(&m, &c, &c.nominal, &d) != FB_OK) fail_msg("%s", d.msg);
  const fb_kit_binding *b = fb_planar_kit_of(name);
  if (!b) {
    print_message("%s: no binding in this build\n", name);
    fb_planar_free(m);
    return;
  }
  const int adaptive = c.solver.h_mode == FB_STEP_ADAPTIVE;
  const double h = adaptive ? c.solver.h_min : c.solver.h;
  const fb_kit_world o = {.gravity = c.gravity, .h = h, .solver = &c.solver,
                          .nbodies = m->nbodies - 1, .njoints = m->njoints, .c = &c};
  const int loads = b->reactions != NULL;
  const size_t n = SAMPLES, window = fb_kit_window(&o);
  if (adaptive) assert_true(window >= 2 * 20 + 4); /* h_max / h_min = 20 */
  series whole, win;
  series_new(&whole, m, n, 0, h, loads);
  series_new(&win, m, n, window, h, loads);
  if (fb_kit_run(b, m, OMEGA, &o, NULL, &whole.s, &d) != FB_OK) fail_msg("%s", d.msg);
  fb_kit_runner *k;
  if (fb_kit_open(&k, b, m, OMEGA, &o, NULL, &win.s, &d) != FB_OK) fail_msg("%s", d.msg);
  const size_t nb = (size_t)m->nbodies - 1, M = window - 1;
  const size_t ncols = 2 + 3 * nb + (loads ? 1 + 3 * (size_t)m->njoints : 0);
  size_t differ = 0;
  for (size_t i = 0; i < n; i++) {
    /* as the adapter reads: sample i once sample i + 1 is filled, and the
     * sample before it still there */
    if (fb_kit_advance(k, i + 2 < n ? i + 2 : n, &d) != FB_OK) fail_msg("%s", d.msg);
    for (size_t u = i > 0 ? i - 1 : 0; u <= i; u++)
      for (size_t col = 0; col < ncols; col++)
        differ += at(whole.block, n, SIZE_MAX, col, u) != at(win.block, window, M, col, u);
  }
  assert_int_equal(fb_kit_written(k), n);
  fb_kit_close(k);
  if (differ) fail_msg("%s: %zu values differ from the whole run's", name, differ);
  /* no power of two; shorter than the run's steps need */
  series bad;
  series_new(&bad, m, n, window - 1, h, loads);
  assert_int_equal(fb_kit_open(&k, b, m, OMEGA, &o, NULL, &bad.s, &d), FB_ERR_ARG);
  free(bad.block);
  series_new(&bad, m, n, window / 2, h, loads);
  assert_int_equal(fb_kit_open(&k, b, m, OMEGA, &o, NULL, &bad.s, &d), FB_ERR_ARG);
  assert_non_null(strstr(d.msg, "window"));
  free(bad.block);
  free(whole.block);
  free(win.block);
  fb_planar_free(m);
}

static const char *const fixed[] = {"solver.h_s=1e-5"};
static const char *const adaptive[] = {"solver.h_s=adaptive", "solver.h_min_s=1e-6",
                                       "solver.h_max_s=2e-5"};

static void test_ode_fixed(void **state) {
  (void)state;
  compare("ode-ideal-nominal", fixed, 1);
}

static void test_ode_adaptive(void **state) {
  (void)state;
  compare("ode-ideal-nominal", adaptive, 3);
}

static void test_mujoco_fixed(void **state) {
  (void)state;
  compare("mujoco-ideal-nominal", fixed, 1);
}

static void test_mujoco_adaptive(void **state) {
  (void)state;
  compare("mujoco-ideal-nominal", adaptive, 3);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_ode_fixed),
      cmocka_unit_test(test_ode_adaptive),
      cmocka_unit_test(test_mujoco_fixed),
      cmocka_unit_test(test_mujoco_adaptive),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
