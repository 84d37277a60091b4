/* fourbar bench's bookkeeping: the Pareto front and the cheapest
 * configuration per error target, on rows whose answer is known. */
#include <jansson.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bench.h"
#include "fb_test.h"
#include "figures.h"

/* a row of the model named model ("a" and "b": two rows of the table) */
static fb_bench_row row(const char *model, double error, double wall) {
  fb_bench_row r;
  memset(&r, 0, sizeof r);
  r.row = strcmp(model, "a") == 0 ? &fb_models[0]
          : strcmp(model, "b") == 0 ? &fb_models[1]
                                   : fb_model_find(model);
  assert_non_null(r.row);
  snprintf(r.model, sizeof r.model, "%s", r.row->name);
  r.error = error;
  r.wall_per_rev = wall;
  return r;
}

static void test_pareto_and_cheapest(void **state) {
  (void)state;
  fb_bench_row rows[7] = {
      row("a", 1e-1, 1.0),  /* 0: front (cheapest) */
      row("a", 1e-2, 2.0),  /* 1: front */
      row("a", 5e-2, 3.0),  /* 2: dominated by 1 */
      row("a", 1e-4, 10.0), /* 3: front (most accurate) */
      row("a", NAN, 0.1),   /* 4: stopped: never on the front */
      row("b", 1e-1, 5.0),  /* 5: alone in its model: front */
      row("a", 1e-2, 2.0),  /* 6: ties 1: neither dominates the other */
  };
  fb_bench_mark_pareto(rows, 7);
  const int want[7] = {1, 1, 0, 1, 0, 1, 1};
  for (int i = 0; i < 7; i++)
    if (rows[i].pareto != want[i]) fail_msg("row %d: pareto %d, want %d", i, rows[i].pareto, want[i]);
  assert_int_equal(fb_bench_cheapest(rows, 7, &fb_models[0], 1e-2), 1);
  assert_int_equal(fb_bench_cheapest(rows, 7, &fb_models[0], 1e-3), 3);
  assert_int_equal(fb_bench_cheapest(rows, 7, &fb_models[0], 1e-5), -1);
  assert_int_equal(fb_bench_cheapest(rows, 7, &fb_models[0], 1.0), 0); /* the stopped row never counts */
  assert_int_equal(fb_bench_cheapest(rows, 7, &fb_models[1], 1e-2), -1);
}

/* bench.svg draws the measured rows only: no placeholder point, so the
 * plotted extremes lie within the data's (a stopped row, NaN error, and a
 * row with no cost per revolution are left out), one manifest curve per model */
static void test_bench_figure_extremes(void **state) {
  (void)state;
  fb_bench_row rows[6] = {
      row("ode-ideal-stackup", 1e-3, 0.5),  row("ode-ideal-stackup", 1e-5, 4.0),
      row("ode-ideal-stackup", NAN, 0.01),  /* stopped */
      row("ode-clearance-impact", 2e-2, 1.0), row("ode-clearance-impact", 3e-4, 8.0),
      row("ode-clearance-impact", 1e-2, NAN), /* stopped within its first step: no cost */
  };
  fb_bench_mark_pareto(rows, 6);
  char dir[] = "/tmp/fb_bench_fig_XXXXXX";
  assert_non_null(mkdtemp(dir));
  char path[256], mpath[256];
  snprintf(path, sizeof path, "%s/bench.svg", dir);
  snprintf(mpath, sizeof mpath, "%s/bench.figure.json", dir);
  fb_diag d;
  if (fb_figures_bench(path, FB_FIGURE_SVG, "synthetic", rows, 6, &d) != FB_OK) fail_msg("%s", d.msg);
  json_error_t je;
  json_t *m = json_load_file(mpath, 0, &je);
  assert_non_null(m);
  json_t *curves = json_object_get(json_array_get(json_object_get(m, "figures"), 0), "curves");
  assert_int_equal(json_array_size(curves), 2);
  /* data extremes per model, from the rows with a finite error and cost */
  const double want[2][4] = {{0.5, 4.0, 1e-5, 1e-3}, {1.0, 8.0, 3e-4, 2e-2}};
  const char *keys[4] = {"x_min", "x_max", "y_min", "y_max"};
  for (size_t q = 0; q < 2; q++) {
    json_t *c = json_array_get(curves, q);
    assert_int_equal(json_integer_value(json_object_get(c, "points")), 2);
    for (int k = 0; k < 4; k++)
      assert_rel(json_real_value(json_object_get(c, keys[k])), want[q][k], 1e-12);
  }
  /* each model in its own colour, the one every figure gives it: shades of
   * ODE's blue by rank among the ODE rows of the model table (docs/figures.md;
   * ode-ideal-stackup is the 2nd, ode-clearance-impact the 4th) */
  assert_string_equal(json_string_value(json_object_get(json_array_get(curves, 0), "color")), "#3182bd");
  assert_string_equal(json_string_value(json_object_get(json_array_get(curves, 1), "color")), "#2171b5");
  json_decref(m);
  /* no 1e9 anywhere in the drawing */
  FILE *f = fopen(path, "r");
  assert_non_null(f);
  static char svg[1 << 20];
  svg[fread(svg, 1, sizeof svg - 1, f)] = '\0';
  fclose(f);
  assert_null(strstr(svg, "1e9"));
  assert_null(strstr(svg, "1e+09"));
  unlink(path);
  unlink(mpath);
  char log[256];
  snprintf(log, sizeof log, "%s/.gnuplot.log", dir);
  unlink(log);
  rmdir(dir);
}

int main(void) {
  const struct CMUnitTest tests[] = {cmocka_unit_test(test_pareto_and_cheapest),
                                     cmocka_unit_test(test_bench_figure_extremes)};
  return cmocka_run_group_tests(tests, NULL, NULL);
}
