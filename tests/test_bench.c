/* fourbar bench's bookkeeping: the Pareto front and the cheapest
 * configuration per error target, on rows whose answer is known. */
#include <string.h>

#include "bench.h"
#include "fb_test.h"

static fb_bench_row row(const char *model, double error, double wall) {
  fb_bench_row r;
  memset(&r, 0, sizeof r);
  snprintf(r.model, sizeof r.model, "%s", model);
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
  assert_int_equal(fb_bench_cheapest(rows, 7, "a", 1e-2), 1);
  assert_int_equal(fb_bench_cheapest(rows, 7, "a", 1e-3), 3);
  assert_int_equal(fb_bench_cheapest(rows, 7, "a", 1e-5), -1);
  assert_int_equal(fb_bench_cheapest(rows, 7, "a", 1.0), 0); /* the stopped row never counts */
  assert_int_equal(fb_bench_cheapest(rows, 7, "b", 1e-2), -1);
}

int main(void) {
  const struct CMUnitTest tests[] = {cmocka_unit_test(test_pareto_and_cheapest)};
  return cmocka_run_group_tests(tests, NULL, NULL);
}
