/* Case files: unit conversion at the edge, overrides, and every class of bad
 * input giving one message that names where, what and which rule. */
#include <dirent.h>
#include <string.h>
#include <unistd.h>

#include "casefile.h"
#include "casefile_internal.h"
#include "fb_config.h"
#include "fb_test.h"
#include "model_table.h"
#include "suggest.h"

/* conversions are exact multiplications by decimal constants: a few ulp */
#define SI_TOL 1e-15

static char paper_path[4096];

static const char *cases_dir(void) {
  const char *d = getenv("FOURBAR_CASES_DIR");
  return d ? d : "cases";
}

/* writes text to a fresh temporary case file and returns its path */
static const char *write_case(const char *text) {
  static char path[64];
  snprintf(path, sizeof path, "/tmp/fb_case_XXXXXX");
  int fd = mkstemp(path);
  assert_true(fd >= 0);
  assert_int_equal(write(fd, text, strlen(text)), (ssize_t)strlen(text));
  close(fd);
  return path;
}

static void expect_error(const char *text, const char *const *sets, int nsets, fb_status want,
                         const char *const *needles) {
  fb_case c;
  fb_diag d;
  const char *p = text ? write_case(text) : NULL;
  fb_status st = fb_casefile_load(&c, p, sets, nsets, &d);
  if (fb_test_verbose()) fprintf(stderr, "  message: %s\n", d.msg);
  assert_int_equal(st, want);
  for (int i = 0; needles[i]; i++)
    if (!strstr(d.msg, needles[i])) fail_msg("message '%s' lacks '%s'", d.msg, needles[i]);
  if (p) unlink(p);
}

static void test_paper_case_in_si(void **state) {
  (void)state;
  fb_case c;
  fb_diag d;
  assert_int_equal(fb_casefile_load(&c, paper_path, NULL, 0, &d), FB_OK);
  assert_string_equal(c.name, "paper_crank_rocker");
  assert_near(c.nominal.length[FB_CRANK], 0.108, SI_TOL);
  assert_near(c.nominal.length[FB_COUPLER], 0.2794, SI_TOL);
  assert_near(c.plus_minus[FB_CRANK], 0.3e-3, SI_TOL); /* from ISO 2768-1 class m */
  assert_near(c.plus_minus[FB_GROUND], 0.5e-3, SI_TOL);
  assert_non_null(strstr(c.tolerance_source[FB_CRANK], "ISO 2768-1 class m, over 30 up to 120"));
  assert_near(c.radial_clearance, 14.5e-6, 1e-18); /* 10H7/g6: 29 um / 2 */
  assert_non_null(strstr(c.clearance_source, "10H7/g6"));
  assert_near(c.crank_speed, 1000.0 * 2.0 * M_PI / 60.0, 1e-12);
  assert_int_equal(c.direction, -1);
  assert_near(c.youngs_modulus, 207e9, 1.0);
  assert_near(c.link[FB_COUPLER].inertia, 2070.46e-6, 1e-18);
  fb_linkage su;
  fb_case_stackup_lengths(&c, &su);
  assert_near(su.length[FB_CRANK], 0.1083, SI_TOL);
  assert_near(su.length[FB_GROUND], 0.2545, SI_TOL);
  /* in-plane moments against slender rods m L^2 / 12: the links carry pin
   * bosses, so they exceed the rod, but by less than 1.6 times */
  for (int i = 0; i < 3; i++) {
    double rod = c.link[i].mass * c.nominal.length[i] * c.nominal.length[i] / 12.0;
    assert_true(c.link[i].inertia > rod);
    assert_true(c.link[i].inertia < 1.6 * rod);
    assert_true(c.link[i].inertia >= c.link[i].inertia_transverse);
  }
}

static void test_overrides(void **state) {
  (void)state;
  const char *sets[] = {"drive.speed_rpm=1500", "solver.h_s = 2e-5", "drive.speed_rpm=600",
                        "tolerance.stackup=+-0+", "run.models=analytic"};
  fb_case c;
  fb_diag d;
  assert_int_equal(fb_casefile_load(&c, paper_path, sets, 5, &d), FB_OK);
  assert_near(c.crank_speed, 600.0 * 2.0 * M_PI / 60.0, 1e-12); /* later wins */
  assert_near(c.solver.h, 2e-5, 0.0);
  assert_int_equal(c.stackup.corner[FB_COUPLER], -1);
  assert_int_equal(c.stackup.corner[FB_FOLLOWER], 0);
  assert_int_equal(c.model_count, 1);
}

/* a pattern adds every model of the table it matches that this build has,
 * in table order, once; a name listed before it is not repeated */
static void test_model_patterns(void **state) {
  (void)state;
  const char *sets[] = {"run.models=ode-ideal-stackup, *-ideal-*, reference"};
  fb_case c;
  fb_diag d;
  assert_int_equal(fb_casefile_load(&c, paper_path, sets, 1, &d), FB_OK);
  const char *want[64]; /* more than the model table holds */
  assert_true(fb_model_count + 1 <= 64);
  int n = 0;
  want[n++] = "ode-ideal-stackup";
  for (int i = 0; i < fb_model_count; i++)
    if (strstr(fb_models[i].name, "-ideal-") && fb_engine_available(fb_models[i].engine) &&
        !fb_models[i].by_name_only && /* a row patterns leave out (model_table.h) */
        strcmp(fb_models[i].name, "ode-ideal-stackup") != 0)
      want[n++] = fb_models[i].name;
  want[n++] = "reference";
  assert_true(n >= 3); /* ode-ideal-nominal at least, whatever the build */
  assert_int_equal(c.model_count, n);
  for (int i = 0; i < n; i++) assert_string_equal(c.models[i], want[i]);
  assert_string_equal(c.models[1], "ode-ideal-nominal"); /* table order: ODE first */
}

static void test_missing_file(void **state) {
  (void)state;
  fb_case c;
  fb_diag d;
  assert_int_equal(fb_casefile_load(&c, "/nonexistent/x.ini", NULL, 0, &d), FB_ERR_IO);
  assert_non_null(strstr(d.msg, "/nonexistent/x.ini"));
}

static void test_bad_inputs_name_place_value_rule(void **state) {
  (void)state;
  expect_error("[linkage]\ncrank_mm = 108\nthis line is wrong\n", NULL, 0, FB_ERR_PARSE,
               (const char *[]){":3:", "malformed line", "this line is wrong", NULL});
  expect_error("[linkage]\ncupler_mm = 279\n", NULL, 0, FB_ERR_PARSE,
               (const char *[]){":2:", "unknown key 'cupler_mm'", "coupler_mm", NULL});
  expect_error("[linkge]\ncrank_mm = 108\n", NULL, 0, FB_ERR_PARSE,
               (const char *[]){":2:", "unknown section [linkge]", "[linkage]", NULL});
  expect_error("[linkage]\ncrank_mm = 108\ncrank_mm = 100\n", NULL, 0, FB_ERR_PARSE,
               (const char *[]){":3:", "duplicate key 'crank_mm'", ":2", NULL});
  /* the time-series keys (docs/series.md) */
  expect_error("[run]\nseries = xml\n", NULL, 0, FB_ERR_PARSE,
               (const char *[]){":2:", "series = 'xml'", "csv, hdf5 or none", NULL});
  expect_error("[run]\nseries_every = 0\n", NULL, 0, FB_ERR_RANGE,
               (const char *[]){":2:", "series_every = 0", "from 1", NULL});
#if !FB_HAVE_HDF5
  expect_error("[run]\nseries = hdf5\n", NULL, 0, FB_ERR_ARG,
               (const char *[]){":2:", "built without HDF5", "libhdf5-dev", "-Dhdf5=enabled", NULL});
#endif
  expect_error("[linkage]\ncrank_mm = -3\n", NULL, 0, FB_ERR_RANGE,
               (const char *[]){":2:", "crank_mm = -3", "must be positive", NULL});
  expect_error("[linkage]\ncrank_mm = nan\n", NULL, 0, FB_ERR_PARSE,
               (const char *[]){":2:", "finite", NULL});
  expect_error("[linkage]\ncrank_mm = -inf\n", NULL, 0, FB_ERR_PARSE,
               (const char *[]){":2:", "crank_mm = '-inf'", "finite", NULL});
  expect_error("[mass]\ncoupler_kg = -0.29\n", NULL, 0, FB_ERR_RANGE,
               (const char *[]){":2:", "coupler_kg = -0.29", "a mass must be positive", NULL});
  expect_error("[clearance]\nrestitution = 1.5\n", NULL, 0, FB_ERR_RANGE,
               (const char *[]){":2:", "restitution = 1.5", "cr must lie in", NULL});
  expect_error("[solver]\nh_s = adaptive\nh_min_s = 1e-5\nh_max_s = 1e-6\n", NULL, 0, FB_ERR_RANGE,
               (const char *[]){"h_max_s = 1e-06", "must not be below", "h_min_s = 1e-05", NULL});
  expect_error("[solver]\naccuracy = 0\n", NULL, 0, FB_ERR_RANGE,
               (const char *[]){":2:", "accuracy = 0", "(0, 1]", NULL});
  expect_error("[linkage]\ncrank_mm = 12abc\n", NULL, 0, FB_ERR_PARSE,
               (const char *[]){"not a number", NULL});
  expect_error("[material]\npoisson_ratio = 0.5\n", NULL, 0, FB_ERR_RANGE,
               (const char *[]){"poisson_ratio = 0.5", "(-1, 0.5)", NULL});
  expect_error("[drive]\ndirection = left\n", NULL, 0, FB_ERR_PARSE,
               (const char *[]){"direction = 'left'", "cw or ccw", NULL});
  expect_error("[run]\nmodels = analytic, ode-magic\n", NULL, 0, FB_ERR_PARSE,
               (const char *[]){"unknown model 'ode-magic'", "ode-ideal-nominal", NULL});
  expect_error("[run]\nmodels = analytic, zz-*\n", NULL, 0, FB_ERR_PARSE,
               (const char *[]){":2:", "pattern 'zz-*' matches no model", "ode-ideal-nominal", NULL});
  expect_error("[clearance]\ncollider = libccd\n", NULL, 0, FB_ERR_PARSE,
               (const char *[]){":2:", "collider = 'libccd'", "exact, faceted or ccd", NULL});
  expect_error("[clearance]\nsegments = 4\n", NULL, 0, FB_ERR_RANGE,
               (const char *[]){":2:", "segments = 4", "8 to 65536", NULL});
  expect_error("[clearance]\nbore = oval\n", NULL, 0, FB_ERR_PARSE,
               (const char *[]){"bore = 'oval'", "circle or ellipse", NULL});
  expect_error("[mujoco]\nnative_bore = ring\n", NULL, 0, FB_ERR_PARSE,
               (const char *[]){":2:", "native_bore = 'ring'", "tendon or facets", NULL});
  expect_error("[clearance]\novality_um = -2\n", NULL, 0, FB_ERR_RANGE,
               (const char *[]){"ovality_um = -2", "[0, 1000) um", NULL});
  /* whole-case rules */
  expect_error("[clearance]\novality_um = 5\n", NULL, 0, FB_ERR_ARG,
               (const char *[]){"ovality_um = 5 with bore = circle", "bore = ellipse", NULL});
  expect_error("[clearance]\nbore = ellipse\novality_um = 5\n[run]\nmodels = ode-clearance-impact\n",
               NULL, 0, FB_ERR_ARG, (const char *[]){"bore = ellipse", "ode-clearance-ccd", NULL});
  expect_error("[linkage]\ncrank_mm = 10\ncoupler_mm = 10\nfollower_mm = 10\nground_mm = 1000\n",
               NULL, 0, FB_ERR_ASSEMBLY, (const char *[]){"cannot be assembled", NULL});
  /* a double-rocker: crank cannot turn fully; message names the reachable range */
  expect_error("[linkage]\ncrank_mm = 300\ncoupler_mm = 100\nfollower_mm = 250\nground_mm = 350\n",
               NULL, 0, FB_ERR_ASSEMBLY,
               (const char *[]){"cannot", "crank angles with |theta2| in [", NULL});
  expect_error("[solver]\nh_s = 0.5\n", NULL, 0, FB_ERR_RANGE,
               (const char *[]){"[solver] h_s = 0.5", "smaller than the run", "h_s at", ":2)", NULL});
  expect_error(NULL, (const char *[]){"linkage.crank_mm"}, 1, FB_ERR_PARSE,
               (const char *[]){"--set", "section.key=value", NULL});
  expect_error(NULL, (const char *[]){"linkage.crank_mm=-1"}, 1, FB_ERR_RANGE,
               (const char *[]){"--set", "crank_mm = -1", "positive", NULL});
  /* a value past the entry's room: its length, the limit, and the way a
   * long list of models fits */
  char long_set[400] = "run.models=";
  for (int i = 0; i < 30; i++) strcat(long_set, "reference,");
  strcat(long_set, "reference");
  expect_error(NULL, (const char *[]){long_set}, 1, FB_ERR_PARSE,
               (const char *[]){"--set #1", "the value holds 309 characters, at most 255",
                                "by pattern", NULL});
}

/* Every number key's refusal states the range its row holds (the table's
 * lo, hi and open ends, in the key's file unit), whatever its rule's prose
 * says: the injected-error scales once said "a scale must be positive" of
 * a range (0, 1e6]. Generated over the table: for each K_DOUBLE and K_INT
 * row, a value past each finite end (the end itself where it is open) is
 * refused as out of range, and the message holds the range text. A planar
 * row is tried on a planar case, the others on the default four-bar. */
static void test_every_range_refusal_states_the_range(void **state) {
  (void)state;
  static const char planar_head[] =
      "[linkage]\ntype = planar\n[joint.a]\nbodies = ground, crank\nat_mm = 0, 0\n"
      "[joint.b]\nbodies = crank, rod\nat_mm = 50, 0\n[joint.c]\nbodies = rod, ground\n"
      "at_mm = 100, 80\n[drive]\njoint = a\n";
  int tried = 0;
  for (int i = 0; i < fb_casefile_key_count(); i++) {
    const key_spec *k = fb_casefile_spec(i);
    if (k->kind != K_DOUBLE && k->kind != K_INT) continue;
    char range[96];
    fb_casefile_range_text(k, range, sizeof range);
    for (int end = 0; end < 2; end++) {
      const double b = end ? k->hi : k->lo;
      if (!isfinite(b)) continue;
      const int open = end ? k->hi_open : k->lo_open;
      const double step = k->kind == K_INT ? 1.0 : fmax(1.0, fabs(b));
      const double v = open && k->kind == K_DOUBLE ? b : b + (end ? step : -step);
      char text[1024];
      fb_case c;
      fb_diag d;
      for (int planar = 0; planar < 2; planar++) {
        snprintf(text, sizeof text, "%s[%s]\n%s = %.17g\n", planar ? planar_head : "",
                 k->section, k->key, v);
        const fb_status st = fb_casefile_load_text(&c, "r.ini", text, strlen(text), &d);
        if (st == FB_ERR_PARSE && strstr(d.msg, "unknown")) continue; /* the other kind's key */
        if (st != FB_ERR_RANGE || !strstr(d.msg, range))
          fail_msg("[%s] %s = %.17g: status %d, '%s' (the range %s not stated)", k->section,
                   k->key, v, st, d.msg, range);
        tried++;
        break;
      }
    }
  }
  if (fb_test_verbose()) fprintf(stderr, "  %d ends of number keys refused with their range\n", tried);
  assert_true(tried > 100);
  /* the example: (0, 1e6] of the injected-error scales */
  fb_case c;
  fb_diag d;
  const char *sets[] = {"clearance.engine_stiffness_scale=2e6"};
  assert_int_equal(fb_casefile_load(&c, NULL, sets, 1, &d), FB_ERR_RANGE);
  assert_non_null(strstr(d.msg, "(0, 1e6]"));
}

/* [run] start, pin_start, peaks and [clearance] penetration_limit_um: the
 * words, the angle in degrees, and the whole-case rule on revolutions */
static void test_start_peaks_and_limit_keys(void **state) {
  (void)state;
  fb_case c;
  fb_diag d;
  const char *p = write_case("[run]\nstart = rest\npin_start = -90\npeaks = all\nrevolutions = 1\n"
                             "[clearance]\npenetration_limit_um = none\n");
  assert_int_equal(fb_casefile_load(&c, p, NULL, 0, &d), FB_OK);
  assert_int_equal(c.start, FB_START_REST);
  assert_int_equal(c.pin_start, FB_PIN_ANGLE);
  assert_near(c.pin_start_angle, -0.5 * M_PI, SI_TOL);
  assert_int_equal(c.peaks, FB_PEAKS_ALL);
  assert_true(isinf(fb_case_penetration_limit(&c)));
  assert_near(fb_case_peak_window_from(&c), 0.0, 0.0);
  /* a later --set replaces none by a number; clearance (or 0) is the radial clearance */
  const char *num[] = {"clearance.penetration_limit_um=20", "run.pin_start=resting"};
  assert_int_equal(fb_casefile_load(&c, p, num, 2, &d), FB_OK);
  assert_near(fb_case_penetration_limit(&c), 20e-6, SI_TOL * 20e-6);
  assert_int_equal(c.pin_start, FB_PIN_RESTING);
  const char *cl[] = {"clearance.penetration_limit_um=clearance"};
  assert_int_equal(fb_casefile_load(&c, p, cl, 1, &d), FB_OK);
  assert_near(fb_case_penetration_limit(&c), c.radial_clearance, 0.0);
  /* the defaults: today's start and window */
  assert_int_equal(fb_casefile_load(&c, NULL, NULL, 0, &d), FB_OK);
  assert_int_equal(c.start, FB_START_STEADY);
  assert_int_equal(c.pin_start, FB_PIN_CENTRED);
  assert_int_equal(c.peaks, FB_PEAKS_STEADY);
  assert_near(fb_case_penetration_limit(&c), c.radial_clearance, 0.0);
  /* bad words and the revolutions rule */
  expect_error("[run]\nstart = moving\n", NULL, 0, FB_ERR_PARSE,
               (const char *[]){":2:", "start = 'moving'", "steady or rest", NULL});
  expect_error("[run]\npin_start = centered\n", NULL, 0, FB_ERR_PARSE,
               (const char *[]){":2:", "pin_start = 'centered'", "centred, resting", NULL});
  expect_error("[run]\npeaks = some\n", NULL, 0, FB_ERR_PARSE,
               (const char *[]){":2:", "peaks = 'some'", "steady or all", NULL});
  expect_error("[clearance]\npenetration_limit_um = off\n", NULL, 0, FB_ERR_PARSE,
               (const char *[]){":2:", "penetration_limit_um = 'off'", "none", NULL});
  expect_error("[clearance]\npenetration_limit_um = -1\n", NULL, 0, FB_ERR_RANGE,
               (const char *[]){":2:", "penetration_limit_um = -1", "none", NULL});
  expect_error("[run]\nrevolutions = 1\n", NULL, 0, FB_ERR_RANGE,
               (const char *[]){"revolutions = 1", "peaks = all", NULL});
  expect_error("[run]\nrevolutions = 0\npeaks = all\n", NULL, 0, FB_ERR_RANGE,
               (const char *[]){"revolutions = 0", "at least 1", NULL});
  expect_error("[run]\nensemble = 0\n", NULL, 0, FB_ERR_RANGE,
               (const char *[]){":2:", "ensemble = 0", "from 1 to 64", NULL});
  expect_error("[run]\nensemble = 2.5\n", NULL, 0, FB_ERR_PARSE,
               (const char *[]){":2:", "ensemble = '2.5'", "not an integer", NULL});
}

static void test_every_key_documented(void **state) {
  (void)state;
  char path[4096];
  snprintf(path, sizeof path, "%s/../docs/keys.md", cases_dir());
  FILE *f = fopen(path, "r");
  assert_non_null(f);
  static char doc[1 << 16];
  size_t n = fread(doc, 1, sizeof doc - 1, f);
  doc[n] = '\0';
  fclose(f);
  for (int i = 0; i < fb_casefile_key_count(); i++) {
    char name[128], row[160];
    fb_casefile_key_name(i, name, sizeof name);
    char *dot = strrchr(name, '.'); /* a section may hold a dot, a key not */
    *dot = '\0';
    snprintf(row, sizeof row, "| [%s] %s |", name, dot + 1);
    if (!strstr(doc, row)) fail_msg("docs/keys.md does not document %s", row);
  }
}

/* one source of defaults: fb_case_default is the key table's defaults read
 * by the file parser, so a key's documented default and the value a case
 * without that key gets are the same double (they differed in the last place
 * for coupler_inertia_transverse_kg_mm2 and pin length_mm before) */
static void test_defaults_come_from_the_key_table(void **state) {
  (void)state;
  fb_diag d;
  if (fb_casefile_defaults_check(&d) != FB_OK) fail_msg("%s", d.msg);
  fb_case c;
  fb_case_default(&c);
  const char *sets[] = {"pin.length_mm=13", "mass.coupler_width_mm=20"};
  fb_case k;
  if (fb_casefile_load_text(&k, "sets", "", 0, &d) != FB_OK) fail_msg("%s", d.msg);
  assert_true(k.pin_length == c.pin_length);
  /* masses and inertias have no table default: both derive them from the
   * same default bar, to the same double */
  assert_true(k.link[FB_COUPLER].inertia_transverse == c.link[FB_COUPLER].inertia_transverse);
  if (fb_casefile_load(&k, NULL, sets, 2, &d) != FB_OK) fail_msg("%s", d.msg);
  assert_true(k.pin_length == c.pin_length);
  assert_true(k.link[FB_COUPLER].inertia_transverse == c.link[FB_COUPLER].inertia_transverse);
}

/* engine options are written once, in the key rows: each engine's options
 * default (fb_mujoco_opts_default, fb_bullet_opts_default,
 * fb_simbody_opts_default) is its section's rows' documented defaults. Three
 * checks per field: a row sets it (the rows' defaults applied over two
 * different fills of the case leave no trace of either fill), it equals the
 * default a case without the key gets, and it equals the value the row's
 * default text (as fourbar keys prints it for docs/keys.md) gives through
 * --set. Every comparison is exact: the same text read by the same parser. */
#define ENGINE_SECTIONS 3
static const char *const engine_sections[ENGINE_SECTIONS] = {"mujoco", "bullet", "simbody"};

/* "section.key=default" for every key row of the engines' sections, from
 * the key table as fourbar keys writes it: "| [section] key | unit |
 * default | rule | meaning |"; returns how many */
static int engine_default_sets(char sets[][160], const char **ptr, int max) {
  char *text = fb_test_key_table();
  int n = 0;
  char *save = NULL;
  for (char *line = strtok_r(text, "\n", &save); line; line = strtok_r(NULL, "\n", &save)) {
    for (int s = 0; s < ENGINE_SECTIONS; s++) {
      char head[64];
      snprintf(head, sizeof head, "| [%s] ", engine_sections[s]);
      if (strncmp(line, head, strlen(head)) != 0) continue;
      const char *key = line + strlen(head);
      const char *unit = strstr(key, " | ");
      assert_non_null(unit);
      const char *def = strstr(unit + 3, " | ");
      assert_non_null(def);
      const char *def_end = strstr(def + 3, " | ");
      assert_non_null(def_end);
      assert_true(n < max);
      snprintf(sets[n], 160, "%s.%.*s=%.*s", engine_sections[s], (int)(unit - key), key,
               (int)(def_end - def - 3), def + 3);
      ptr[n] = sets[n];
      n++;
    }
  }
  free(text);
  return n;
}

static void test_engine_option_defaults_are_the_key_rows(void **state) {
  (void)state;
  static fb_case zero, fill, dflt, given;
  memset(&zero, 0x00, sizeof zero);
  memset(&fill, 0xA5, sizeof fill);
  for (int s = 0; s < ENGINE_SECTIONS; s++) {
    fb_casefile_section_defaults(&zero, engine_sections[s]);
    fb_casefile_section_defaults(&fill, engine_sections[s]);
  }
  fb_case_default(&dflt);
  char sets[32][160];
  const char *ptr[32];
  const int n = engine_default_sets(sets, ptr, 32);
  assert_int_equal(n, 10); /* 6 mujoco, 2 bullet, 2 simbody rows */
  fb_diag d;
  if (fb_casefile_load(&given, NULL, ptr, n, &d) != FB_OK) fail_msg("%s", d.msg);
  const fb_mujoco_opts mj = fb_mujoco_opts_default();
  const fb_bullet_opts bt = fb_bullet_opts_default();
  const fb_simbody_opts sb = fb_simbody_opts_default();
#define ROW_DEFAULT(opts, engine, field)                  \
  do {                                                    \
    assert_true(zero.engine.field == fill.engine.field);  \
    assert_true(opts.field == zero.engine.field);         \
    assert_true(opts.field == dflt.engine.field);         \
    assert_true(opts.field == given.engine.field);        \
  } while (0)
  ROW_DEFAULT(mj, mujoco, integrator);
  ROW_DEFAULT(mj, mujoco, loop_stiffness);
  ROW_DEFAULT(mj, mujoco, loop_damping);
  ROW_DEFAULT(mj, mujoco, loop_impedance);
  ROW_DEFAULT(mj, mujoco, drive_armature);
  ROW_DEFAULT(mj, mujoco, native_bore);
  ROW_DEFAULT(bt, bullet, solver);
  ROW_DEFAULT(bt, bullet, iterations);
  ROW_DEFAULT(sb, simbody, integrator);
  ROW_DEFAULT(sb, simbody, accuracy);
#undef ROW_DEFAULT
  /* the wall-time estimate scales from this number (run.c): the row's own */
  assert_true(sb.accuracy == FB_SIMBODY_ACCURACY_DEFAULT);
}

/* a product of decimal constants and a sum of squares, against the same
 * arithmetic done by hand to all digits: a few roundings, each 1.1e-16 */
#define BAR_REL_TOL 1e-14

/* An own four-bar without masses: each link a steel bar, crank 60 x 15 x 5
 * mm, rho = 7800 kg/m^3. By hand: m = 7800 * 0.015 * 0.005 * 0.06 = 0.0351
 * kg; I (hinge) = m (L^2 + w^2) / 12 = 0.0351 * 0.003825 / 12 =
 * 1.1188125e-5 kg m^2; I (long) = m (w^2 + t^2) / 12 = 0.0351 * 0.00025 / 12
 * = 7.3125e-7; I (across) = m (L^2 + t^2) / 12 = 0.0351 * 0.003625 / 12 =
 * 1.0603125e-5. Coupler 160 mm: m = 0.0936 kg, I = 0.0936 * 0.025825 / 12 =
 * 2.01435e-4 kg m^2. */
static void test_masses_derived_from_bars(void **state) {
  (void)state;
  static const char own[] =
      "[linkage]\ncrank_mm = 60\ncoupler_mm = 160\nfollower_mm = 140\nground_mm = 150\n"
      "[mass]\ncrank_width_mm = 15\ncrank_thickness_mm = 5\ncoupler_width_mm = 15\n"
      "coupler_thickness_mm = 5\nfollower_width_mm = 15\nfollower_thickness_mm = 5\n"
      "[material]\ndensity_kg_m3 = 7800\n";
  fb_case c;
  fb_diag d;
  const char *p = write_case(own);
  if (fb_casefile_load(&c, p, NULL, 0, &d) != FB_OK) fail_msg("%s", d.msg);
  assert_rel(c.link[FB_CRANK].mass, 0.0351, BAR_REL_TOL);
  assert_rel(c.link[FB_CRANK].inertia, 1.1188125e-5, BAR_REL_TOL);
  assert_rel(c.link[FB_CRANK].inertia_long, 7.3125e-7, BAR_REL_TOL);
  assert_rel(c.link[FB_CRANK].inertia_transverse, 1.0603125e-5, BAR_REL_TOL);
  assert_rel(c.link[FB_COUPLER].mass, 0.0936, BAR_REL_TOL);
  assert_rel(c.link[FB_COUPLER].inertia, 2.01435e-4, BAR_REL_TOL);
  assert_near(c.link[FB_CRANK].com_fraction, 0.5, 0.0);
  for (int i = 0; i < 3; i++) {
    assert_int_equal(c.link_source[i].mass, FB_SOURCE_DERIVED);
    assert_int_equal(c.link_source[i].inertia, FB_SOURCE_DERIVED);
    assert_int_equal(c.link_source[i].inertia_long, FB_SOURCE_DERIVED);
    assert_int_equal(c.link_source[i].inertia_transverse, FB_SOURCE_DERIVED);
    assert_int_equal(c.link_source[i].com_fraction, FB_SOURCE_DEFAULT);
  }
  assert_string_equal(fb_value_source_name(c.link_source[0].mass), "derived");
  /* a given mass is kept and the bar's shape scales it: I = 0.05 * 0.003825
   * / 12 = 1.59375e-5 kg m^2; a given inertia is kept as given */
  const char *sets[] = {"mass.crank_kg=0.05", "mass.follower_inertia_kg_mm2=134"};
  if (fb_casefile_load(&c, p, sets, 2, &d) != FB_OK) fail_msg("%s", d.msg);
  assert_near(c.link[FB_CRANK].mass, 0.05, 0.0);
  assert_int_equal(c.link_source[FB_CRANK].mass, FB_SOURCE_CASE);
  assert_rel(c.link[FB_CRANK].inertia, 1.59375e-5, BAR_REL_TOL);
  assert_int_equal(c.link_source[FB_CRANK].inertia, FB_SOURCE_DERIVED);
  assert_rel(c.link[FB_FOLLOWER].inertia, 134e-6, BAR_REL_TOL);
  assert_int_equal(c.link_source[FB_FOLLOWER].inertia, FB_SOURCE_CASE);
  assert_int_equal(c.link_source[FB_FOLLOWER].mass, FB_SOURCE_DERIVED);
  assert_true(fb_casefile_given(&c, "mass", "crank_kg"));
  assert_false(fb_casefile_given(&c, "mass", "coupler_kg"));
  assert_true(fb_casefile_given(&c, "material", "density_kg_m3"));
  unlink(p);
  /* a bar too light for the mass rule: named, with the keys to change */
  expect_error("[mass]\ncrank_width_mm = 0.001\ncrank_thickness_mm = 0.001\n", NULL, 0,
               FB_ERR_RANGE,
               (const char *[]){"[mass] crank_kg not given", "crank_width_mm = 0.001",
                                "a mass must be positive", NULL});
  expect_error("[material]\ndensity_kg_m3 = 0\n", NULL, 0, FB_ERR_RANGE,
               (const char *[]){":2:", "density_kg_m3 = 0", "a density must lie in", NULL});
}

/* [run] models not given: a case with clearance joints runs the clearance
 * models with their references after the ideal list; one without, the
 * ideal list alone; a given list is run as given */
static void test_default_models_follow_the_joints(void **state) {
  (void)state;
  fb_case c;
  fb_diag d;
  static const char *const ideal[] = {"analytic", "analytic-stackup", "ode-ideal-nominal",
                                      "ode-ideal-stackup"};
  static const char *const clear[] = {"ode-clearance-impact", "ode-clearance-restitution",
                                      "reference", "reference-restitution"};
  /* the default joint is crank-coupler */
  if (fb_casefile_load_text(&c, "t", "", 0, &d) != FB_OK) fail_msg("%s", d.msg);
  assert_int_equal(c.clearance.mask, 1 << FB_JOINT_B);
  assert_int_equal(c.model_count, 8);
  for (int i = 0; i < 4; i++) assert_string_equal(c.models[i], ideal[i]);
  for (int i = 0; i < 4; i++) assert_string_equal(c.models[4 + i], clear[i]);
  static const char none[] = "[clearance]\njoints = none\n";
  if (fb_casefile_load_text(&c, "t", none, sizeof none - 1, &d) != FB_OK) fail_msg("%s", d.msg);
  assert_int_equal(c.model_count, 4);
  static const char given[] = "[run]\nmodels = analytic\n";
  if (fb_casefile_load_text(&c, "t", given, sizeof given - 1, &d) != FB_OK) fail_msg("%s", d.msg);
  assert_int_equal(c.model_count, 1);
  assert_string_equal(c.models[0], "analytic");
}

/* the shipped template loads as shipped: its masses derived from its bars
 * (crank 7800 * 0.015 * 0.005 * 0.06 = 0.0351 kg by hand), the clearance
 * models run by default */
static void test_template_loads(void **state) {
  (void)state;
  char path[4200];
  snprintf(path, sizeof path, "%s/templates/own_fourbar.ini", cases_dir());
  fb_case c;
  fb_diag d;
  if (fb_casefile_load(&c, path, NULL, 0, &d) != FB_OK) fail_msg("%s", d.msg);
  assert_rel(c.link[FB_CRANK].mass, 0.0351, BAR_REL_TOL);
  assert_int_equal(c.link_source[FB_CRANK].mass, FB_SOURCE_DERIVED);
  assert_int_equal(c.link_source[FB_FOLLOWER].inertia, FB_SOURCE_DERIVED);
  assert_int_equal(c.direction, +1);
  assert_int_equal(c.model_count, 8);
  assert_string_equal(c.models[7], "reference-restitution");
}

/* [variant.NAME] sections and published values: read as written, a
 * variant loads as the case with its overrides after the command line's,
 * and every malformed variant is refused naming the variant and the rule */
static void test_variants_and_published(void **state) {
  (void)state;
  const char *text = "[published]\nsource = a book\n[published.impact]\n"
                     "coupler_omega_max_rad_s = 134.5\n"
                     "[variant.stiff]\nset = clearance.stiffness_scale=2; drive.speed_rpm=500\n"
                     "models = reference\ndescription = twice as stiff\n"
                     "[variant.slow]\nset = drive.speed_rpm = 300 ; clearance.restitution=0.5\n";
  const char *p = write_case(text);
  fb_case c, v;
  fb_diag d;
  if (fb_casefile_load(&c, p, NULL, 0, &d) != FB_OK) fail_msg("%s", d.msg);
  assert_string_equal(c.published_source, "a book");
  assert_true(c.published[FB_PUBLISHED_IMPACT].coupler.omega_max == 134.5);
  assert_true(isnan(c.published[FB_PUBLISHED_IMPACT].coupler.alpha_max));
  assert_true(isnan(c.published[FB_PUBLISHED_RESTITUTION].follower.omega_max));
  assert_int_equal(c.variant_count, 2);
  assert_string_equal(c.variant[0].name, "stiff");
  assert_string_equal(c.variant[0].models, "reference");
  assert_string_equal(c.variant[1].name, "slow");
  /* the variant's overrides come after the command line's */
  const char *sets[] = {"drive.speed_rpm=700", "clearance.stiffness_scale=3"};
  if (fb_casefile_load_variant(&v, p, sets, 2, &c.variant[0], &d) != FB_OK) fail_msg("%s", d.msg);
  assert_rel(v.crank_speed, 500.0 * 2.0 * M_PI / 60.0, SI_TOL);
  assert_rel(v.clearance.stiffness_scale, 2.0, SI_TOL);
  assert_int_equal(v.model_count, 1);
  assert_string_equal(v.models[0], "reference");
  assert_int_equal(v.variant_count, 0); /* a variant runs none of its own */
  if (fb_casefile_load_variant(&v, p, sets, 2, &c.variant[1], &d) != FB_OK) fail_msg("%s", d.msg);
  assert_rel(v.crank_speed, 300.0 * 2.0 * M_PI / 60.0, SI_TOL);
  assert_rel(v.clearance.restitution, 0.5, SI_TOL); /* " ;" separates, it starts no comment */
  assert_rel(v.clearance.stiffness_scale, 3.0, SI_TOL);
  assert_int_equal(v.model_count, c.model_count);
  unlink(p);
  /* a value the variant's case refuses: named with the variant */
  p = write_case("[variant.bad]\nset = drive.speed_rpm=-5\n");
  if (fb_casefile_load(&c, p, NULL, 0, &d) != FB_OK) fail_msg("%s", d.msg);
  assert_int_equal(fb_casefile_load_variant(&v, p, NULL, 0, &c.variant[0], &d), FB_ERR_RANGE);
  assert_non_null(strstr(d.msg, "variant bad"));
  assert_non_null(strstr(d.msg, "crank speed must be positive"));
  unlink(p);
  expect_error("[variant.x]\nmodels = reference\n", NULL, 0, FB_ERR_PARSE,
               (const char *[]){"[variant.x] has no set", NULL});
  expect_error("[variant.x]\nset =;;\n", NULL, 0, FB_ERR_PARSE,
               (const char *[]){"[variant.x] set is empty", NULL});
  expect_error("[variant.x]\nset = drive.speed=5\n", NULL, 0, FB_ERR_PARSE,
               (const char *[]){"'drive.speed=5' is not section.key=value", NULL});
  expect_error("[variant.x]\nset = case.name=y\n", NULL, 0, FB_ERR_PARSE,
               (const char *[]){"[case] keys cannot vary", NULL});
  expect_error("[variant.x]\nset = drive.speed_rpm=5\nspeed = 3\n", NULL, 0, FB_ERR_PARSE,
               (const char *[]){"unknown key 'speed' in [variant.x]", NULL});
  expect_error("[variant./x]\nset = drive.speed_rpm=5\n", NULL, 0, FB_ERR_PARSE,
               (const char *[]){"a variant name is", NULL});
  expect_error("[published.impact]\ncoupler_omega_max_rad_s = fast\n", NULL, 0, FB_ERR_PARSE,
               (const char *[]){"not a number", NULL});
  char many[2048] = "";
  for (int i = 0; i <= FB_MAX_VARIANTS; i++)
    snprintf(many + strlen(many), sizeof many - strlen(many), "[variant.v%d]\nset = drive.speed_rpm=%d\n",
             i, 100 + i);
  expect_error(many, NULL, 0, FB_ERR_PARSE, (const char *[]){"more than 8 variants", NULL});
}

/* the paper's case gives every mass and inertia: read as "case", to the
 * digit (173.92 kg mm^2 = 1.7392e-4 kg m^2), also through a base file */
static void test_paper_masses_are_the_case(void **state) {
  (void)state;
  const char *files[] = {"paper_crank_rocker.ini", "engines.ini", "hard/crossed_branch.ini"};
  for (int f = 0; f < 3; f++) {
    char path[4200];
    snprintf(path, sizeof path, "%s/%s", cases_dir(), files[f]);
    fb_case c;
    fb_diag d;
    if (fb_casefile_load(&c, path, NULL, 0, &d) != FB_OK) fail_msg("%s", d.msg);
    assert_near(c.link[FB_CRANK].mass, 0.12, 0.0);
    assert_near(c.link[FB_COUPLER].mass, 0.29, 0.0);
    assert_near(c.link[FB_FOLLOWER].mass, 0.28, 0.0);
    assert_rel(c.link[FB_CRANK].inertia, 173.92e-6, SI_TOL);
    assert_rel(c.link[FB_COUPLER].inertia_long, 15.49e-6, SI_TOL);
    assert_rel(c.link[FB_FOLLOWER].inertia_transverse, 1974.43e-6, SI_TOL);
    for (int i = 0; i < 3; i++) {
      assert_int_equal(c.link_source[i].mass, FB_SOURCE_CASE);
      assert_int_equal(c.link_source[i].inertia, FB_SOURCE_CASE);
      assert_int_equal(c.link_source[i].inertia_long, FB_SOURCE_CASE);
      assert_int_equal(c.link_source[i].inertia_transverse, FB_SOURCE_CASE);
    }
  }
}

static void test_fuzz_regressions_give_errors_not_crashes(void **state) {
  (void)state;
  /* inputs that once crashed, hung or were accepted wrongly: each must now
   * load or fail with a message (tests/fuzz/regressions) */
  char dir[4096];
  snprintf(dir, sizeof dir, "%s/../tests/fuzz/regressions", cases_dir());
  DIR *d = opendir(dir);
  assert_non_null(d);
  struct dirent *e;
  int n = 0;
  while ((e = readdir(d))) {
    if (e->d_name[0] == '.') continue;
    char path[8192];
    snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
    FILE *f = fopen(path, "rb");
    static char buf[1 << 16];
    size_t len = fread(buf, 1, sizeof buf, f);
    fclose(f);
    fb_case c;
    fb_diag diag;
    fb_status st = fb_casefile_load_text(&c, path, buf, len, &diag);
    if (fb_test_verbose()) fprintf(stderr, "  %s: %s\n", e->d_name, st == FB_OK ? "ok" : diag.msg);
    if (st != FB_OK) assert_true(diag.msg[0] != '\0');
    /* the known bad ones are refused */
    if (strstr(e->d_name, "base_") || strstr(e->d_name, "infinite") || strstr(e->d_name, "fit_and") ||
        strstr(e->d_name, "empty_joint"))
      assert_int_not_equal(st, FB_OK);
    n++;
  }
  closedir(d);
  assert_true(n >= 5);
}

/* suggestions by edit distance (a swap of neighbours is one error) and the
 * plausibility of lengths */
static void test_suggest_and_plausibility(void **state) {
  (void)state;
  assert_int_equal(fb_edit_distance("lenght", "length"), 1);
  assert_int_equal(fb_edit_distance("kinemtics", "kinematics"), 1);
  assert_int_equal(fb_edit_distance("", "abc"), 3);
  assert_int_equal(fb_edit_distance("crank_mm", "crank_mm"), 0);
  static const char *const names[] = {"run", "kinematics", "sweep"};
  assert_string_equal(fb_suggest("sweap", names, 3), "sweep");
  assert_null(fb_suggest("xyzzy", names, 3));
  fb_case c;
  fb_diag d;
  char notes[4][FB_DIAG_SIZE];
  if (fb_casefile_load(&c, paper_path, NULL, 0, &d) != FB_OK) fail_msg("%s", d.msg);
  assert_int_equal(fb_casefile_plausibility(&c, notes, 4), 0);
  static const char metres[] = "[linkage]\ncrank_mm = 0.045\ncoupler_mm = 170\nfollower_mm = 120\n"
                               "ground_mm = 150\n[pin]\nlength_mm = 13000\n";
  if (fb_casefile_load_text(&c, "m", metres, sizeof metres - 1, &d) != FB_OK) fail_msg("%s", d.msg);
  assert_int_equal(fb_casefile_plausibility(&c, notes, 4), 2);
  assert_non_null(strstr(notes[0], "[linkage] crank_mm = 0.045: a length below 1 mm"));
  assert_non_null(strstr(notes[1], "[pin] length_mm = 13000: a length above 10 m"));
  assert_null(fb_casefile_length_implausible(FB_PLAUSIBLE_LENGTH_MIN_M));
  assert_null(fb_casefile_length_implausible(FB_PLAUSIBLE_LENGTH_MAX_M));
}

/* The shipped cases run the reference of every law their models use (issue
 * 55): a clearance model whose reference row could measure it (its case's
 * one clearance joint the one the reference integrates, no friction) never
 * runs without it, so `fourbar run` leaves it unchecked nowhere; the paper
 * case runs reference-restitution beside ode-clearance-restitution. Cases
 * with two clearance joints or friction have no reference by design. */
static void test_shipped_cases_run_their_references(void **state) {
  (void)state;
  const char *dirs[3] = {"", "hard/", "templates/"};
  int checked = 0, paper = 0;
  for (int d = 0; d < 3; d++) {
    char dir[4096];
    snprintf(dir, sizeof dir, "%s/%s", cases_dir(), dirs[d]);
    DIR *dp = opendir(dir);
    assert_non_null(dp);
    struct dirent *de;
    while ((de = readdir(dp)) != NULL) {
      const size_t len = strlen(de->d_name);
      if (len < 5 || strcmp(de->d_name + len - 4, ".ini") != 0) continue;
      char path[8192];
      snprintf(path, sizeof path, "%s%s", dir, de->d_name);
      static fb_case c;
      fb_diag diag;
      if (fb_casefile_load(&c, path, NULL, 0, &diag) != FB_OK) continue; /* a refusal's case */
      const int cj = fb_case_mech(&c)->reference_joint;
      if (c.clearance.mask != (1 << cj) || c.clearance.friction > 0.0) continue;
      for (int i = 0; i < c.model_count; i++) {
        const fb_model *m = fb_model_find(c.models[i]);
        const fb_model *ref = m ? fb_model_reference_of(m) : NULL;
        if (!ref) continue;
        int has = 0;
        for (int k = 0; k < c.model_count; k++) has |= strcmp(c.models[k], ref->name) == 0;
        if (!has) fail_msg("%s runs %s without %s", path, m->name, ref->name);
        checked++;
        paper += strcmp(de->d_name, "paper_crank_rocker.ini") == 0 &&
                 strcmp(m->name, "ode-clearance-restitution") == 0;
      }
    }
    closedir(dp);
  }
  assert_true(checked > 20);
  assert_int_equal(paper, 1);
}

int main(void) {
  snprintf(paper_path, sizeof paper_path, "%s/paper_crank_rocker.ini", cases_dir());
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_paper_case_in_si),
      cmocka_unit_test(test_overrides),
      cmocka_unit_test(test_model_patterns),
      cmocka_unit_test(test_missing_file),
      cmocka_unit_test(test_bad_inputs_name_place_value_rule),
      cmocka_unit_test(test_every_range_refusal_states_the_range),
      cmocka_unit_test(test_start_peaks_and_limit_keys),
      cmocka_unit_test(test_every_key_documented),
      cmocka_unit_test(test_shipped_cases_run_their_references),
      cmocka_unit_test(test_defaults_come_from_the_key_table),
      cmocka_unit_test(test_engine_option_defaults_are_the_key_rows),
      cmocka_unit_test(test_masses_derived_from_bars),
      cmocka_unit_test(test_paper_masses_are_the_case),
      cmocka_unit_test(test_default_models_follow_the_joints),
      cmocka_unit_test(test_template_loads),
      cmocka_unit_test(test_variants_and_published),
      cmocka_unit_test(test_fuzz_regressions_give_errors_not_crashes),
      cmocka_unit_test(test_suggest_and_plausibility),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
