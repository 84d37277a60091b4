/* The time-series writers (series_write.h) on a hand-made series whose
 * values are known: the sample selection of series_every keeps the
 * multiples of N and every sample of an impact episode with one either
 * side; the CSV reads back to 12 significant digits; the HDF5 file reads
 * back through the HDF5 C API bit for bit, with its units and attributes.
 *
 *   state   0 0 0 0 0 0 0 1 1 1 0 0 0 0 0 0 0 0 0 0 ... (impact at 7..9)
 *   kept    x . . . x . x x x x x . x . . . x . . .     (every = 4)
 */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fb_config.h"
#include "model_table.h"
#include "series_write.h"
#include "fb_test.h"

#if FB_HAVE_HDF5
#include <hdf5.h>
#endif

#define N_SAMPLES 1000
#define EVERY 4
#define IMPACT_FROM 7
#define IMPACT_TO 9 /* inclusive */
/* "%.12g" keeps 12 significant digits: half a unit in the 12th is 5e-12 */
#define CSV_REL_TOL 5e-12

static void make(fb_series *s) {
  assert_int_equal(fb_series_init(s, 16), FB_OK);
  assert_int_equal(fb_series_enable_contact(s, 1 << 1), FB_OK);
  assert_int_equal(fb_series_enable_loads(s), FB_OK);
  for (int i = 0; i < N_SAMPLES; i++) {
    fb_sample x;
    memset(&x, 0, sizeof x);
    x.t = i * 3.3e-6;
    x.crank_angle = -104.71975511965977 * x.t;
    x.coupler_alpha = 1234.5 * sin(0.01 * i) + 1.0 / 3.0;
    x.follower_omega = -exp(0.001 * i);
    const int in = i >= IMPACT_FROM && i <= IMPACT_TO;
    x.contact[1][FB_C_STATE] = in ? FB_STATE_IMPACT : FB_STATE_FREE;
    x.contact[1][FB_C_FORCE] = in ? 1e4 / 7.0 : 0.0;
    x.contact[1][FB_C_PEN] = in ? 1.234567e-7 : 0.0;
    x.reaction[2][0] = 3.0;
    x.reaction[2][1] = 4.0 + i;
    x.drive_torque = 1e-9 * i;
    assert_int_equal(fb_series_push(s, &x), FB_OK);
  }
}

/* Pushing past the initial room moves every column into a doubled mapping
 * (series.c): each value pushed must read back exactly, in the kinematic,
 * contact and load columns, across several growths (16 -> 1024). */
/* every value make() pushed reads back exactly */
static void check_made(const fb_series *s) {
  assert_int_equal(s->n, N_SAMPLES);
  for (int i = 0; i < N_SAMPLES; i++) {
    fb_sample x;
    fb_series_get(s, (size_t)i, &x);
    assert_true(x.t == i * 3.3e-6);
    assert_true(x.crank_angle == -104.71975511965977 * (i * 3.3e-6));
    assert_true(x.coupler_alpha == 1234.5 * sin(0.01 * i) + 1.0 / 3.0);
    assert_true(x.follower_omega == -exp(0.001 * i));
    const int in = i >= IMPACT_FROM && i <= IMPACT_TO;
    assert_true(x.contact[1][FB_C_STATE] == (in ? FB_STATE_IMPACT : FB_STATE_FREE));
    assert_true(x.contact[1][FB_C_FORCE] == (in ? 1e4 / 7.0 : 0.0));
    assert_true(x.contact[1][FB_C_PEN] == (in ? 1.234567e-7 : 0.0));
    assert_true(x.reaction[2][0] == 3.0);
    assert_true(x.reaction[2][1] == 4.0 + i);
    assert_true(x.drive_torque == 1e-9 * i);
  }
}

static void test_growth_keeps_every_column(void **state) {
  (void)state;
  fb_series s;
  make(&s);
  assert_true(s.cap >= N_SAMPLES);
  check_made(&s);
  fb_series_free(&s);
  assert_null(s.t);
  assert_int_equal(s.n, 0);
}

/* fb_series_touch maps the room after the held samples (one write per page,
 * series.h): the 1000 held samples span two 4 KiB pages of each column, so
 * a touch that wrote from sample 0 instead of n would zero sample 512 of
 * every column; a sample pushed after it reads back. */
static void test_touch_keeps_held_samples(void **state) {
  (void)state;
  fb_series s;
  make(&s);
  const size_t cap = s.cap;
  fb_series_touch(&s);
  assert_int_equal(s.cap, cap);
  check_made(&s);
  fb_sample x, y;
  memset(&x, 0, sizeof x);
  x.t = 1.5;
  x.contact[1][FB_C_FORCE] = 2.5;
  x.reaction[3][1] = -7.0;
  assert_int_equal(fb_series_push(&s, &x), FB_OK);
  fb_series_get(&s, N_SAMPLES, &y);
  assert_true(y.t == 1.5 && y.contact[1][FB_C_FORCE] == 2.5 && y.reaction[3][1] == -7.0);
  fb_series_free(&s);
}

static void test_keep_rule(void **state) {
  (void)state;
  fb_series s;
  make(&s);
  unsigned char keep[N_SAMPLES];
  const size_t kept = fb_series_keep(&s, EVERY, keep);
  size_t count = 0;
  for (int i = 0; i < N_SAMPLES; i++) {
    const int want = i % EVERY == 0 || i == N_SAMPLES - 1 ||
                     (i >= IMPACT_FROM - 1 && i <= IMPACT_TO + 1);
    if (keep[i] != want) fail_msg("sample %d: kept %d, expected %d", i, keep[i], want);
    count += (size_t)want;
  }
  assert_int_equal(kept, count);
  assert_int_equal(fb_series_keep(&s, 1, keep), N_SAMPLES);
  fb_series_free(&s);
}

static char dir[] = "/tmp/fb_series_write_XXXXXX";

static void test_csv_reads_back(void **state) {
  (void)state;
  fb_series s;
  make(&s);
  unsigned char keep[N_SAMPLES];
  fb_series_keep(&s, EVERY, keep);
  char path[256];
  snprintf(path, sizeof path, "%s/m.csv", dir);
  fb_diag diag;
  assert_int_equal(fb_series_write_csv(path, &s, keep, &diag), FB_OK);
  FILE *f = fopen(path, "r");
  assert_non_null(f);
  static char line[1 << 16];
  assert_non_null(fgets(line, sizeof line, f));
  const size_t nc = fb_series_column_count(&s);
  char name[96];
  /* the header: the column names in order */
  char *p = line;
  for (size_t k = 0; k < nc; k++) {
    const size_t len = strlen(fb_series_column_name(&s, k, name, sizeof name));
    assert_memory_equal(p, name, len);
    assert_true(p[len] == (k + 1 < nc ? ',' : '\n'));
    p += len + 1;
  }
  size_t rows = 0;
  for (int i = 0; i < N_SAMPLES; i++) {
    if (!keep[i]) continue;
    assert_non_null(fgets(line, sizeof line, f));
    p = line;
    for (size_t k = 0; k < nc; k++) {
      char *end;
      const double v = strtod(p, &end), want = fb_series_value(&s, k, (size_t)i);
      assert_true(end > p);
      assert_near(v, want, CSV_REL_TOL * fabs(want));
      p = end + 1;
    }
    rows++;
  }
  assert_null(fgets(line, sizeof line, f));
  fclose(f);
  unlink(path);
  fb_series_free(&s);
}

#if FB_HAVE_HDF5
static double read_attr_double(hid_t obj, const char *name) {
  double v = NAN;
  hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
  assert_true(a >= 0);
  assert_true(H5Aread(a, H5T_NATIVE_DOUBLE, &v) >= 0);
  H5Aclose(a);
  return v;
}

static void read_attr_string(hid_t obj, const char *name, char *out, size_t size) {
  hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
  assert_true(a >= 0);
  hid_t t = H5Aget_type(a);
  assert_true(H5Tis_variable_str(t) > 0);
  char *text = NULL;
  assert_true(H5Aread(a, t, &text) >= 0);
  assert_non_null(text);
  assert_true(strlen(text) < size);
  snprintf(out, size, "%s", text);
  H5free_memory(text);
  H5Tclose(t);
  H5Aclose(a);
}

static void test_hdf5_reads_back(void **state) {
  (void)state;
  static fb_run r;
  memset(&r, 0, sizeof r);
  fb_case_default(&r.c);
  snprintf(r.c.name, sizeof r.c.name, "made_up");
  r.c.series_every = EVERY;
  r.n = 1;
  snprintf(r.model[0].run.name, sizeof r.model[0].run.name, "ode-clearance-impact");
  r.model[0].run.model = fb_model_find("ode-clearance-impact");
  assert_non_null(r.model[0].run.model);
  r.model[0].run.h = 3.3e-6;
  fb_series *s = &r.model[0].run.series;
  make(s);
  unsigned char keep_buf[N_SAMPLES];
  const size_t kept = fb_series_keep(s, EVERY, keep_buf);
  unsigned char *keep[FB_MAX_MODELS] = {keep_buf};
  char path[256];
  snprintf(path, sizeof path, "%s/series.h5", dir);
  fb_diag diag;
  assert_int_equal(fb_series_write_hdf5(path, &r, keep, "{\"case\": \"made_up\"}", &diag), FB_OK);

  hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  assert_true(file >= 0);
  char text[512];
  read_attr_string(file, "case", text, sizeof text);
  assert_string_equal(text, "made_up");
  read_attr_string(file, "summary_json", text, sizeof text);
  assert_string_equal(text, "{\"case\": \"made_up\"}");
  hid_t g = H5Gopen2(file, "ode-clearance-impact", H5P_DEFAULT);
  assert_true(g >= 0);
  assert_true(read_attr_double(g, "h_s") == 3.3e-6);
  assert_true(read_attr_double(g, "samples_written") == (double)kept);
  const size_t nc = fb_series_column_count(s);
  double *got = malloc(N_SAMPLES * sizeof *got);
  for (size_t k = 0; k < nc; k++) {
    char name[96];
    fb_series_column_name(s, k, name, sizeof name);
    hid_t d = H5Dopen2(g, name, H5P_DEFAULT);
    if (d < 0) fail_msg("dataset %s missing", name);
    hid_t sp = H5Dget_space(d);
    hsize_t dims[1];
    assert_int_equal(H5Sget_simple_extent_dims(sp, dims, NULL), 1);
    assert_int_equal(dims[0], kept);
    /* compressed: the filter pipeline holds deflate */
    hid_t dcpl = H5Dget_create_plist(d);
    int has_deflate = 0;
    for (int q = 0; q < H5Pget_nfilters(dcpl); q++) {
      unsigned flags;
      size_t ncd = 0;
      unsigned cd[4];
      char fname[64];
      unsigned cfg;
      if (H5Pget_filter2(dcpl, (unsigned)q, &flags, &ncd, cd, sizeof fname, fname, &cfg) ==
          H5Z_FILTER_DEFLATE)
        has_deflate = 1;
    }
    assert_true(has_deflate);
    assert_int_equal(H5Pget_layout(dcpl), H5D_CHUNKED);
    H5Pclose(dcpl);
    assert_true(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, got) >= 0);
    size_t w = 0;
    for (size_t i = 0; i < N_SAMPLES; i++)
      if (keep_buf[i]) {
        const double want = fb_series_value(s, k, i);
        if (memcmp(&got[w], &want, sizeof want) != 0)
          fail_msg("%s[%zu] = %.17g, written %.17g", name, w, got[w], want);
        w++;
      }
    char unit[32];
    read_attr_string(d, "unit", unit, sizeof unit);
    const char *want_unit = strstr(name, "alpha") ? "rad/s^2"
                            : strstr(name, "omega") ? "rad/s"
                            : strstr(name, "angle") ? "rad"
                            : strcmp(name, "time_s") == 0 ? "s"
                            : strstr(name, "torque") ? "N m"
                            : strstr(name, "_state") ? "1"
                            : strcmp(name + strlen(name) - 2, "_n") == 0 ? "N"
                                                                         : "m";
    if (strcmp(unit, want_unit) != 0) fail_msg("%s: unit '%s', expected '%s'", name, unit, want_unit);
    H5Sclose(sp);
    H5Dclose(d);
  }
  free(got);
  H5Gclose(g);
  H5Fclose(file);
  unlink(path);
  fb_series_free(s);
}
#endif

int main(void) {
  if (!mkdtemp(dir)) return 1;
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_growth_keeps_every_column),
      cmocka_unit_test(test_touch_keeps_held_samples),
      cmocka_unit_test(test_keep_rule),
      cmocka_unit_test(test_csv_reads_back),
#if FB_HAVE_HDF5
      cmocka_unit_test(test_hdf5_reads_back),
#endif
  };
  const int rc = cmocka_run_group_tests(tests, NULL, NULL);
  rmdir(dir);
  return rc;
}
