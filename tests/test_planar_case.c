/* A planar case: its sections read by the loader (setup/casefile_planar.c),
 * compiled into a description with the masses derived as bars
 * (physics/planar/planar_case.h), checked by the core, and refused by
 * every command until one runs it; the four-bar and the slider-crank as
 * instances of the description. Bad input names the file, line, key,
 * value and rule.
 *
 *   [joint.NAME] bodies = A, B   at_mm = x, y   kind   axis_deg
 *   [body.NAME]  mass_kg   inertia_kg_mm2   centre_mm   width_mm   thickness_mm
 *   [drive] joint = NAME         [clearance] joints = NAME, ... */
#include <string.h>
#include <unistd.h>

#include "analytic.h"
#include "bar_mass.h"
#include "casefile.h"
#include "fb_test.h"
#include "planar_case.h"
#include "planar_check.h"
#include "planar_path.h"
#include "slider_crank.h"

/* The bound for the paper's four-bar written as type = planar
 * against the built-in four-bar's analytic peaks: the template's C is
 * given to 1e-12 mm (lengths to 4e-15 relative), the peaks are refined to
 * the rounding level (test_planar_path.c); measured ~1e-14. */
#define PAPER_PEAK_REL 1e-9
/* Masses derived as bars, against the sums written here: a few roundings. */
#define BAR_REL 1e-13

/* writes text to a temporary case file and loads it as a planar case
 * (run = 1) or as every command does (run = 0) */
static fb_status load_text(fb_case *c, const char *text, int run, char *path, fb_diag *d) {
  snprintf(path, 64, "/tmp/fourbar-planar-XXXXXX");
  const int fd = mkstemp(path);
  if (fd < 0) return fb_diag_set(d, FB_ERR_IO, "no temporary file");
  const size_t n = strlen(text);
  const int whole = write(fd, text, n) == (ssize_t)n;
  close(fd);
  fb_status st = !whole ? FB_ERR_IO
                 : run  ? fb_casefile_load_planar(c, path, NULL, 0, d)
                        : fb_casefile_load(c, path, NULL, 0, d);
  unlink(path);
  return st;
}

/* a loaded case's error holds every needle; "@N" stands for "<file>:N" */
static void expect_error(const char *text, fb_status want, const char *const *needles) {
  fb_case c;
  fb_diag d;
  char path[64];
  const fb_status st = load_text(&c, text, 1, path, &d);
  if (fb_test_verbose()) fprintf(stderr, "  %s\n", d.msg);
  if (st != want) fail_msg("status %d, want %d: %s", st, want, d.msg);
  for (int i = 0; needles[i]; i++) {
    char needle[128];
    if (needles[i][0] == '@') snprintf(needle, sizeof needle, "%s:%s", path, needles[i] + 1);
    else snprintf(needle, sizeof needle, "%s", needles[i]);
    if (!strstr(d.msg, needle)) fail_msg("'%s' lacks '%s'", d.msg, needle);
  }
}

/* text loads with an error whose message does not hold word */
static void expect_no(const char *what, const char *text, const char *word) {
  fb_case c;
  fb_diag d;
  char path[64];
  if (load_text(&c, text, 1, path, &d) == FB_OK) fail_msg("%s: loaded", what);
  if (strstr(d.msg, word)) fail_msg("%s: '%s' holds '%s'", what, d.msg, word);
}

/* a four-bar of four joints (the crank-rocker of test_planar_check.c)
 * followed by extra lines */
#define HEAD "[linkage]\ntype = planar\n"                                             \
             "[joint.a]\nbodies = ground, crank\nat_mm = 0, 0\n"       /* lines 3-5 */ \
             "[joint.b]\nbodies = crank, coupler\nat_mm = 40, 0\n"     /* 6-8 */       \
             "[joint.c]\nbodies = coupler, follower\nat_mm = 100, 120\n" /* 9-11 */   \
             "[joint.d]\nbodies = follower, ground\nat_mm = 150, 0\n"  /* 12-14 */
#define DRIVE "[drive]\njoint = a\n"

static void test_sixbar_loads_and_compiles(void **state) {
  (void)state;
  fb_case c;
  fb_diag d;
  if (fb_test_shipped_case_planar(&c, "watt_sixbar.ini", &d) != FB_OK) fail_msg("%s", d.msg);
  assert_true(c.planar.on);
  assert_int_equal(c.planar.njoints, 7);
  assert_int_equal(c.planar.nbodies, 6);
  assert_int_equal(c.planar.drive, 0);
  assert_int_equal(c.clearance.mask, 1 << 5); /* rod-output */
  assert_near(c.crank_speed, 300.0 * 2.0 * M_PI / 60.0, 1e-12);
  fb_planar *m;
  assert_int_equal(fb_planar_of_case(&m, &c, &c.nominal, &d), FB_OK);
  /* the ternary (C, D, E): three bars of the default section, steel */
  const fb_bar bar = fb_bar_default();
  const int t = fb_planar_find_body(m, "ternary");
  assert_true(t > 0);
  const double *p[3] = {c.planar.joint[2].at, c.planar.joint[3].at, c.planar.joint[4].at};
  double mass = 0.0, cx = 0.0, cy = 0.0;
  for (int i = 0; i < 3; i++) {
    const double *u = p[i], *v = p[(i + 1) % 3];
    const double l = hypot(v[0] - u[0], v[1] - u[1]), mi = c.density * bar.width * bar.thickness * l;
    mass += mi;
    cx += mi * 0.5 * (u[0] + v[0]);
    cy += mi * 0.5 * (u[1] + v[1]);
  }
  cx /= mass;
  cy /= mass;
  double inertia = 0.0;
  for (int i = 0; i < 3; i++) {
    const double *u = p[i], *v = p[(i + 1) % 3];
    const double l = hypot(v[0] - u[0], v[1] - u[1]), mi = c.density * bar.width * bar.thickness * l;
    const double dx = 0.5 * (u[0] + v[0]) - cx, dy = 0.5 * (u[1] + v[1]) - cy;
    inertia += mi * (l * l + bar.width * bar.width) / 12.0 + mi * (dx * dx + dy * dy);
  }
  assert_near(m->body[t].mass, mass, BAR_REL * mass);
  assert_near(m->body[t].inertia, inertia, BAR_REL * inertia);
  assert_near(m->body[t].centre[0], cx, BAR_REL);
  assert_near(m->body[t].centre[1], cy, BAR_REL);
  assert_int_equal(m->body[t].derived, FB_PLANAR_DERIVED_MASS | FB_PLANAR_DERIVED_INERTIA |
                                           FB_PLANAR_DERIVED_CENTRE);
  /* its frame: from its joint with the ground (D) to its first other joint (C) */
  assert_near(m->body[t].angle0, atan2(p[0][1] - p[1][1], p[0][0] - p[1][0]), 1e-15);
  /* the crank, a binary link: one bar, its angle along A -> B */
  const int k = fb_planar_find_body(m, "crank");
  assert_near(m->body[k].mass, c.density * bar.width * bar.thickness * 0.04, BAR_REL);
  assert_near(m->body[k].angle0, 0.0, 1e-15);
  fb_planar_free(m);
}

/* A body whose joint points lie on one bar (each within half the bar's
 * width of the line through the two farthest apart) is that one bar, end
 * to end: a lever with a pin in its middle is not a triangle of three
 * bars. The six-bar's ternary (C, D, E) with C moved onto D-E, 9 mm off
 * the line (inside the 20 mm bar's half width: one bar D-E), then 11 mm off
 * (outside: the triangle). Compiled only: the moved C does not assemble. */
static void test_collinear_points_are_one_bar(void **state) {
  (void)state;
  fb_case c;
  fb_diag d;
  if (fb_test_shipped_case_planar(&c, "watt_sixbar.ini", &d) != FB_OK) fail_msg("%s", d.msg);
  const fb_bar bar = fb_bar_default();
  const double *D = c.planar.joint[3].at, *E = c.planar.joint[4].at;
  for (int off_mm = 9; off_mm <= 11; off_mm += 2) {
    c.planar.joint[2].at[0] = 0.5 * (D[0] + E[0]);
    c.planar.joint[2].at[1] = 0.5 * (D[1] + E[1]) + off_mm * 1e-3;
    const double *C = c.planar.joint[2].at;
    fb_planar *m;
    if (fb_planar_compile(&m, &c.planar, c.density, NULL, &d) != FB_OK) fail_msg("%s", d.msg);
    const int t = fb_planar_find_body(m, "ternary");
    const double rwt = c.density * bar.width * bar.thickness, de = hypot(E[0] - D[0], E[1] - D[1]);
    if (off_mm == 9) {
      const double mass = rwt * de;
      assert_near(m->body[t].mass, mass, BAR_REL * mass);
      assert_near(m->body[t].centre[0], 0.5 * (D[0] + E[0]), BAR_REL);
      assert_near(m->body[t].centre[1], 0.5 * (D[1] + E[1]), BAR_REL);
      const double inertia = mass * (de * de + bar.width * bar.width) / 12.0;
      assert_near(m->body[t].inertia, inertia, BAR_REL * inertia);
    } else {
      const double mass = rwt * (de + hypot(C[0] - D[0], C[1] - D[1]) + hypot(C[0] - E[0], C[1] - E[1]));
      assert_near(m->body[t].mass, mass, BAR_REL * mass);
    }
    fb_planar_free(m);
  }
}

/* every command's loader reads and checks a planar case, then refuses it */
static void test_commands_refuse(void **state) {
  (void)state;
  fb_case c;
  fb_diag d;
  assert_int_equal(fb_test_shipped_case(&c, "watt_sixbar.ini", NULL, 0, &d), FB_ERR_ARG);
  if (fb_test_verbose()) fprintf(stderr, "  %s\n", d.msg);
  assert_non_null(strstr(d.msg, "watt_sixbar.ini"));
  assert_non_null(strstr(d.msg, "the description checks (5 moving bodies, 7 joints"));
  assert_non_null(strstr(d.msg, "masses derived as bars: crank, coupler, ternary, rod, output"));
  assert_non_null(strstr(d.msg, "this command does not run a planar case yet: fourbar run, "
                                 "kinematics, stackup, penalty, bench, check, contact-params --case and "
                                 "export (mjcf) do"));
}

/* the paper's four-bar as a planar case (the shipped template) gives the
 * built-in four-bar's analytic peaks, and the paper's masses */
static void test_paper_fourbar_as_planar(void **state) {
  (void)state;
  fb_case c, paper;
  fb_diag d;
  if (fb_test_shipped_case_planar(&c, "templates/planar_fourbar.ini", &d) != FB_OK)
    fail_msg("%s", d.msg);
  fb_test_paper_case(&paper, NULL, 0);
  fb_planar *m;
  assert_int_equal(fb_planar_of_case(&m, &c, &c.nominal, &d), FB_OK);
  for (int b = 0; b < 3; b++) {
    assert_near(m->body[b + 1].mass, paper.link[b].mass, 1e-15);
    assert_near(m->body[b + 1].inertia, paper.link[b].inertia, 1e-18);
  }
  assert_int_equal(c.clearance.mask, 1 << FB_JOINT_B);
  fb_planar_kin *k;
  assert_int_equal(fb_planar_kin_new(&k, m, &d), FB_OK);
  fb_planar_peaks p[4];
  const double omega = fb_case_omega2(&c);
  assert_near(omega, fb_case_omega2(&paper), 0.0);
  if (fb_planar_peaks_of(p, k, omega, &d) != FB_OK) fail_msg("%s", d.msg);
  fb_peaks a;
  assert_int_equal(fb_analytic_peaks(&a, &paper.nominal, paper.branch, omega, &d), FB_OK);
  const fb_body_peaks *ab[2] = {&a.coupler, &a.follower};
  double worst = 0.0;
  for (int b = 0; b < 2; b++) {
    const double got[4] = {p[2 + b].omega_max, p[2 + b].omega_min, p[2 + b].alpha_max, p[2 + b].alpha_min};
    const double want[4] = {ab[b]->omega_max, ab[b]->omega_min, ab[b]->alpha_max, ab[b]->alpha_min};
    for (int x = 0; x < 4; x++) worst = fmax(worst, fabs(got[x] - want[x]) / fabs(want[x]));
  }
  report_residual("paper four-bar as type = planar vs analytic peaks (rel)", worst, PAPER_PEAK_REL);
  assert_true(worst <= PAPER_PEAK_REL);
  fb_planar_kin_free(k);
  fb_planar_free(m);
}

/* a slider-crank written as a planar case (a prismatic joint) moves as the
 * closed form's */
static void test_planar_slider_crank(void **state) {
  (void)state;
  const double a = 50, b = 200, e = 10; /* mm */
  const double x0 = a + sqrt(b * b - e * e);
  char text[1024];
  snprintf(text, sizeof text,
           "[linkage]\ntype = planar\n"
           "[joint.ground-crank]\nbodies = ground, crank\nat_mm = 0, 0\n"
           "[joint.crank-coupler]\nbodies = crank, coupler\nat_mm = %g, 0\n"
           "[joint.coupler-slider]\nbodies = coupler, slider\nat_mm = %.17g, %g\n"
           "[joint.slider-ground]\nbodies = slider, ground\nat_mm = %.17g, %g\n"
           "kind = prismatic\naxis_deg = 0\n"
           "[body.slider]\nmass_kg = 0.5\ninertia_kg_mm2 = 100\n"
           "[drive]\njoint = ground-crank\nspeed_rpm = 600\ndirection = ccw\n",
           a, x0, e, x0, e);
  fb_case c;
  fb_diag d;
  char path[64];
  if (load_text(&c, text, 1, path, &d) != FB_OK) fail_msg("%s", d.msg);
  fb_planar *m;
  assert_int_equal(fb_planar_of_case(&m, &c, &c.nominal, &d), FB_OK);
  assert_int_equal(m->joint[3].kind, FB_KIND_PRISMATIC);
  assert_near(m->body[3].centre[0], x0 * 1e-3, 1e-15); /* no bar: the centre at its point */
  fb_planar_kin *k;
  assert_int_equal(fb_planar_kin_new(&k, m, &d), FB_OK);
  const fb_slider_crank sc = {a * 1e-3, b * 1e-3, e * 1e-3};
  double q[9], qd[9];
  fb_planar_assembly(m, q);
  for (int i = 1; i <= 12; i++) {
    const double phi = i * M_PI / 6.0;
    assert_int_equal(fb_planar_position(k, q, phi, NULL, &d), FB_OK);
    const fb_planar_drive dr = {phi, fb_case_omega2(&c), 0};
    assert_int_equal(fb_planar_motion(k, qd, NULL, q, &dr, NULL, &d), FB_OK);
    fb_slider_crank_state st;
    assert_int_equal(fb_slider_crank_solve(&st, &sc, phi, fb_case_omega2(&c), 0, &d), FB_OK);
    assert_near(q[6], st.slider_x, 1e-15);
    assert_near(qd[6], st.slider_v, 1e-12);
  }
  fb_planar_kin_free(k);
  fb_planar_free(m);
}

/* the four-bar and the slider-crank of today's keys as descriptions: the
 * names of mechanism.h, driven at ground-crank */
static void test_instances_of_cases(void **state) {
  (void)state;
  fb_case c;
  fb_diag d;
  fb_test_paper_case(&c, NULL, 0);
  fb_planar *m;
  assert_int_equal(fb_planar_of_case(&m, &c, &c.nominal, &d), FB_OK);
  assert_int_equal(m->nbodies, 4);
  for (int j = 0; j < 4; j++) assert_string_equal(m->joint[j].name, fb_mech_fourbar.joint[j].name);
  assert_string_equal(m->body[3].name, "follower");
  assert_int_equal(m->drive, 0);
  assert_int_equal(fb_planar_check(m, NULL, &d), FB_OK);
  fb_planar_free(m);
  assert_int_equal(fb_test_shipped_case(&c, "slider_crank_flores.ini", NULL, 0, &d), FB_OK);
  fb_linkage lk;
  fb_case_stackup_lengths(&c, &lk);
  assert_int_equal(fb_planar_of_case(&m, &c, &lk, &d), FB_OK);
  assert_string_equal(m->body[3].name, "slider");
  assert_string_equal(m->joint[3].name, "slider-ground");
  assert_int_equal(m->joint[3].kind, FB_KIND_PRISMATIC);
  assert_int_equal(fb_planar_check(m, NULL, &d), FB_OK);
  fb_planar_free(m);
}

static void test_bad_values(void **state) {
  (void)state;
  expect_error(HEAD "[joint.e]\nbodies = crank, follower\nat_mm = 1, 2, 3\n" DRIVE, FB_ERR_PARSE,
               (const char *[]){"@17", "[joint.e] at_mm = '1, 2, 3'", "two numbers x, y", NULL});
  expect_error(HEAD "[joint.e]\nat_mm = abc, 2\n" DRIVE, FB_ERR_PARSE,
               (const char *[]){"@16", "at_mm = 'abc, 2'", "not a decimal number", NULL});
  expect_error(HEAD "[joint.e]\nat_mm = 2e5, 0\n" DRIVE, FB_ERR_RANGE,
               (const char *[]){"@16", "at_mm = 2e5, 0", "from -1e5 to 1e5", NULL});
  expect_error(HEAD "[joint.e]\nbodies = crank\n" DRIVE, FB_ERR_PARSE,
               (const char *[]){"@16", "bodies = 'crank'", "two body names", NULL});
  expect_error(HEAD "[joint.e]\nbodies = crank, crank\n" DRIVE, FB_ERR_PARSE,
               (const char *[]){"@16", "two different bodies", NULL});
  expect_error(HEAD "[joint.e]\nkind = hinge\n" DRIVE, FB_ERR_PARSE,
               (const char *[]){"@16", "kind = 'hinge'", "revolute or prismatic", NULL});
  expect_error(HEAD "[joint.e]\npivot = 1\n" DRIVE, FB_ERR_PARSE,
               (const char *[]){"@16", "unknown key 'pivot' in [joint.e]", "at_mm", NULL});
  expect_error(HEAD "[body.ground]\nmass_kg = 1\n" DRIVE, FB_ERR_PARSE,
               (const char *[]){"@16", "the ground is fixed", NULL});
  expect_error(HEAD "[body.crank]\nmass_kg = -1\n" DRIVE, FB_ERR_RANGE,
               (const char *[]){"@16", "mass_kg = -1", "a mass must be positive", NULL});
  expect_error(HEAD "[body.crank]\ncentre_mm = 1\n" DRIVE, FB_ERR_PARSE,
               (const char *[]){"@16", "centre_mm = '1'", NULL});
  expect_error(HEAD "[joint.bad name]\nat_mm = 0, 0\n" DRIVE, FB_ERR_PARSE,
               (const char *[]){"@16", "a joint name is 1 to 43 characters", NULL});
}

static void test_bad_sections(void **state) {
  (void)state;
  expect_error(HEAD "[body.ghost]\nmass_kg = 1\n" DRIVE, FB_ERR_PARSE,
               (const char *[]){"@16", "[body.ghost]", "no joint names body 'ghost'", NULL});
  expect_error(HEAD "[joint.e]\nbodies = crank, follower\n" DRIVE, FB_ERR_PARSE,
               (const char *[]){"@16", "[joint.e] has no at_mm", NULL});
  expect_error(HEAD "[joint.e]\nbodies = crank, follower\nat_mm = 1, 1\nkind = prismatic\n" DRIVE,
               FB_ERR_PARSE, (const char *[]){"@16", "has no axis_deg", NULL});
  expect_error(HEAD "[joint.e]\nbodies = crank, follower\nat_mm = 1, 1\naxis_deg = 30\n" DRIVE,
               FB_ERR_PARSE, (const char *[]){"@16", "a revolute joint has no axis", NULL});
  expect_error(HEAD, FB_ERR_PARSE, (const char *[]){"needs [drive] joint", NULL});
  expect_error(HEAD "[drive]\njoint = z\n", FB_ERR_PARSE,
               (const char *[]){"@16", "[drive] joint: 'z' is not a joint of the case",
                                "joints: a, b, c, d", NULL});
  expect_error(HEAD DRIVE "[clearance]\njoints = b, y\n", FB_ERR_PARSE,
               (const char *[]){"@18", "'y' is not a joint of the case", NULL});
  expect_error(HEAD DRIVE "[linkage]\ncrank_mm = 40\n", FB_ERR_PARSE,
               (const char *[]){"[linkage] crank_mm is a four-bar or slider-crank key", NULL});
  expect_error(HEAD DRIVE "[mass]\ncrank_kg = 1\n", FB_ERR_PARSE,
               (const char *[]){"@18", "[mass] crank_kg is a four-bar", NULL});
  expect_error("[joint.a]\nbodies = ground, crank\n", FB_ERR_PARSE,
               (const char *[]){"@2", "describes a planar mechanism", "type = planar", NULL});
  expect_error("[drive]\njoint = a\n", FB_ERR_PARSE,
               (const char *[]){"@2", "describes a planar mechanism", NULL});
}

static void test_bad_mechanisms(void **state) {
  (void)state;
  /* a zero-length link (the crank's joints at one point, its mass given) and
   * a 0.5 um one: the four-bar's rule for crank_mm (LEN_RULE), at the later
   * joint's at_mm (line 8) */
  expect_error("[linkage]\ntype = planar\n[joint.a]\nbodies = ground, crank\nat_mm = 0, 0\n"
               "[joint.b]\nbodies = crank, coupler\nat_mm = 0, 0\n"
               "[joint.c]\nbodies = coupler, follower\nat_mm = 100, 120\n"
               "[joint.d]\nbodies = follower, ground\nat_mm = 150, 0\n"
               "[body.crank]\nmass_kg = 0.1\ninertia_kg_mm2 = 10\n" DRIVE, FB_ERR_RANGE,
               (const char *[]){"@8", "[joint.b] at_mm = 0, 0", "body 'crank' has a link of 0 mm",
                                "a link length must be positive, from 0.001 mm", NULL});
  expect_error("[linkage]\ntype = planar\n[joint.a]\nbodies = ground, crank\nat_mm = 0, 0\n"
               "[joint.b]\nbodies = crank, coupler\nat_mm = 0.0005, 0\n"
               "[joint.c]\nbodies = coupler, follower\nat_mm = 100, 120\n"
               "[joint.d]\nbodies = follower, ground\nat_mm = 150, 0\n" DRIVE, FB_ERR_RANGE,
               (const char *[]){"@8", "a link of 0.0005 mm", NULL});
  /* a compound hinge is no zero-length link: the follower's joints c and e
   * at one pin C (coupler, follower and arm meet there), its d elsewhere */
  {
    fb_case c;
    fb_diag d;
    char path[64];
    if (load_text(&c, HEAD "[joint.e]\nbodies = follower, arm\nat_mm = 100, 120\n"
                           "[joint.f]\nbodies = arm, link\nat_mm = 150, 250\n"
                           "[joint.g]\nbodies = link, ground\nat_mm = 260, 120\n" DRIVE,
                  1, path, &d) != FB_OK)
      fail_msg("a compound hinge: %s", d.msg);
  }
  /* a body hanging from one joint, its mass not given: the joint it
   * lacks is what is wrong (the count), not its mass (which was said) */
  expect_error(HEAD "[joint.e]\nbodies = follower, pin\nat_mm = 150, 0\n" DRIVE, FB_ERR_ARG,
               (const char *[]){"2 degrees of freedom", "a joint is missing", NULL});
  expect_no("HEAD + pin", HEAD "[joint.e]\nbodies = follower, pin\nat_mm = 150, 0\n" DRIVE,
            "mass");
  /* the four-bar with the follower's ground joint left out and no masses */
  expect_error("[linkage]\ntype = planar\n[joint.a]\nbodies = ground, crank\nat_mm = 0, 0\n"
               "[joint.b]\nbodies = crank, coupler\nat_mm = 40, 0\n"
               "[joint.c]\nbodies = coupler, follower\nat_mm = 100, 120\n" DRIVE, FB_ERR_ARG,
               (const char *[]){"3 degrees of freedom", "a joint is missing", NULL});
  /* a body whose mass no bar gives, in a mechanism whose joints are
   * right: a slider's two joints at one point, a crank driven alone */
  expect_error("[linkage]\ntype = planar\n[joint.a]\nbodies = ground, crank\nat_mm = 0, 0\n"
               "[joint.b]\nbodies = crank, rod\nat_mm = 40, 0\n"
               "[joint.c]\nbodies = rod, slider\nat_mm = 150, 0\n"
               "[joint.d]\nbodies = slider, ground\nat_mm = 150, 0\nkind = prismatic\n"
               "axis_deg = 0\n" DRIVE, FB_ERR_ARG,
               (const char *[]){"@10", "body 'slider' has 2 joints at one point",
                                "give [body.slider] mass_kg and inertia_kg_mm2", NULL});
  expect_error("[linkage]\ntype = planar\n[joint.a]\nbodies = ground, crank\nat_mm = 0, 0\n"
               DRIVE, FB_ERR_ARG,
               (const char *[]){"body 'crank' has one joint ('a')", "mass_kg", NULL});
  /* a body joined by one pin: two degrees of freedom */
  expect_error(HEAD "[joint.e]\nbodies = follower, extra\nat_mm = 120, 60\n"
               "[body.extra]\nmass_kg = 0.1\ninertia_kg_mm2 = 10\n" DRIVE, FB_ERR_ARG,
               (const char *[]){"2 degrees of freedom", NULL});
  /* a clearance at the driven joint with an engine's clearance model,
   * which the engine kit builds and the kit drives an ideal joint only:
   * refused at load where the keys were given (it was refused at run time,
   * after analytic, naming no line); analytic and the references take it */
  expect_error(HEAD DRIVE "[clearance]\njoints = a\n[run]\nmodels = analytic, ode-clearance-impact\n",
               FB_ERR_ARG,
               (const char *[]){"@18", "[clearance] joints names 'a', the driven joint",
                                "'ode-clearance-impact'", "engine kit", "[drive] joint at",
                                "[run] models at", "@20", NULL});
  {
    fb_case c;
    fb_diag d;
    char path[64];
    if (load_text(&c, HEAD DRIVE "[clearance]\njoints = a\n[run]\nmodels = analytic, reference\n",
                  1, path, &d) != FB_OK)
      fail_msg("analytic and reference with a clearance at the driven joint: %s", d.msg);
  }
  /* a crank too long for its loop locks: the section of the joint it locks at */
  expect_error("[linkage]\ntype = planar\n"
               "[joint.a]\nbodies = ground, crank\nat_mm = 0, 0\n"
               "[joint.b]\nbodies = crank, coupler\nat_mm = 100, 0\n"
               "[joint.c]\nbodies = coupler, follower\nat_mm = 140, 90\n"
               "[joint.d]\nbodies = follower, ground\nat_mm = 150, 0\n" DRIVE,
               FB_ERR_ASSEMBLY,
               (const char *[]){"@10", "[joint.c]", "cannot turn a full revolution", "locks at",
                                NULL});
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_sixbar_loads_and_compiles),
      cmocka_unit_test(test_collinear_points_are_one_bar),
      cmocka_unit_test(test_commands_refuse),
      cmocka_unit_test(test_paper_fourbar_as_planar),
      cmocka_unit_test(test_planar_slider_crank),
      cmocka_unit_test(test_instances_of_cases),
      cmocka_unit_test(test_bad_values),
      cmocka_unit_test(test_bad_sections),
      cmocka_unit_test(test_bad_mechanisms),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
