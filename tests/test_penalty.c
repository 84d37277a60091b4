/* Paper mode reproduces the paper's Tables I to III (docs/paper.md) to their
 * printed precision; physical mode is checked against its own formulas. */
#include "contact.h"
#include "casefile.h"
#include "fb_test.h"
#include "invdyn.h"
#include "penalty.h"

/* half a unit in the last printed digit, widened by 1e-9 relative for the
 * decimal-to-binary conversion of the printed value */
#define HALF_UNIT(decimals) (0.5 * pow(10.0, -(decimals)) * (1.0 + 1e-9))

static const double table1[15][2] = {
    {0.01, 0.01}, {0.04, 0.04}, {0.09, 0.10}, {0.17, 0.18}, {0.26, 0.27},
    {0.38, 0.39}, {0.52, 0.54}, {0.67, 0.70}, {0.85, 0.89}, {1.05, 1.10},
    {1.27, 1.33}, {1.51, 1.58}, {1.78, 1.85}, {2.06, 2.15}, {2.37, 2.47}};
static const double table2[15][2] = {
    {97.33, 99.40},     {194.67, 189.85},   {292.00, 300.17},   {389.33, 402.72},
    {486.66, 493.23},   {584.00, 592.79},   {681.33, 697.54},   {778.66, 794.18},
    {875.99, 895.50},   {973.33, 995.56},   {1070.66, 1094.71}, {1167.99, 1193.16},
    {1265.33, 1291.09}, {1362.66, 1391.84}, {1459.99, 1491.83}};
static const double table3[15][2] = {
    {0.0090, 0.0093}, {0.0227, 0.0219}, {0.0390, 0.0404}, {0.0572, 0.0598}, {0.0770, 0.0784},
    {0.0982, 0.1002}, {0.1206, 0.1244}, {0.1441, 0.1479}, {0.1686, 0.1736}, {0.1940, 0.2000},
    {0.2203, 0.2269}, {0.2474, 0.2546}, {0.2753, 0.2828}, {0.3039, 0.3126}, {0.3332, 0.3429}};

static fb_case paper;

static void test_paper_mode_reproduces_tables(void **state) {
  (void)state;
  for (int i = 0; i < 15; i++) {
    double rpm = 100.0 * (i + 1);
    fb_penalty_row r[2];
    assert_int_equal(fb_penalty_rows(r, &paper, FB_PENALTY_PAPER, rpm * 2 * M_PI / 60, NULL),
                     FB_OK);
    for (int j = 0; j < 2; j++) {
      if (fabs(r[j].force - table1[i][j]) > HALF_UNIT(2) ||
          fabs(r[j].penalty - table2[i][j]) > HALF_UNIT(2) ||
          fabs(r[j].approach * 1e6 - table3[i][j]) > HALF_UNIT(4))
        fail_msg("%g rpm %s: F %.6f (Table I %.2f), P %.4f (Table II %.2f), delta %.6f um "
                 "(Table III %.4f)",
                 rpm, fb_pin_joint_name(r[j].joint), r[j].force, table1[i][j], r[j].penalty,
                 table2[i][j], r[j].approach * 1e6, table3[i][j]);
    }
  }
}

static void test_paper_mode_shapes(void **state) {
  (void)state;
  /* force ~ rpm^2, crank-coupler penalty exactly linear: 0.97333 per rpm */
  fb_penalty_row a[2], b[2];
  fb_penalty_rows(a, &paper, FB_PENALTY_PAPER, 500 * 2 * M_PI / 60, NULL);
  fb_penalty_rows(b, &paper, FB_PENALTY_PAPER, 1000 * 2 * M_PI / 60, NULL);
  assert_rel(b[0].force / a[0].force, 4.0, 1e-12);
  assert_rel(b[0].penalty / a[0].penalty, 2.0, 1e-12);
  assert_near(b[0].penalty / 1000.0, 0.97333, 5e-6);
}

static void test_physical_mode_formulas(void **state) {
  (void)state;
  const double w = 1000 * 2 * M_PI / 60;
  fb_penalty_row r[2];
  assert_int_equal(fb_penalty_rows(r, &paper, FB_PENALTY_PHYSICAL, w, NULL), FB_OK);
  double fmax[4];
  fb_invdyn_peaks(fmax, NULL, &paper.nominal, paper.branch, paper.link, paper.gravity, -w, 3600, NULL);
  assert_rel(r[0].force, fmax[1], 1e-15);
  assert_rel(r[1].force, fmax[2], 1e-15);
  const double es = fb_contact_modulus(207e9, 0.29, 207e9, 0.29);
  assert_rel(r[0].approach, fb_contact_johnson_approach(r[0].force, 0.013, es, 14.5e-6), 1e-15);
  assert_rel(r[0].penalty, r[0].stiffness * pow(14.5e-6, 1.5), 1e-15);
  /* and a real joint reaction is orders of magnitude above the paper's force */
  fb_penalty_row p[2];
  fb_penalty_rows(p, &paper, FB_PENALTY_PAPER, w, NULL);
  assert_true(r[0].force > 100.0 * p[0].force);
}

int main(void) {
  fb_test_paper_case(&paper, NULL, 0);
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_paper_mode_reproduces_tables),
      cmocka_unit_test(test_paper_mode_shapes),
      cmocka_unit_test(test_physical_mode_formulas),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
