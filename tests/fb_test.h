/* Shared test helpers: double-precision near-equality (cmocka 1.1's float
 * assertion casts to float, which hides errors below 1e-7), and an
 * environment switch FB_TEST_VERBOSE=1 that prints the actual residuals, for
 * choosing tolerances honestly. */
#ifndef FB_TEST_H
#define FB_TEST_H

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

static inline int fb_test_verbose(void) {
  const char *v = getenv("FB_TEST_VERBOSE");
  return v && *v && *v != '0';
}

/* |a - b| <= tol, with both values printed on failure */
#define assert_near(a, b, tol)                                                          \
  do {                                                                                  \
    double fb_a_ = (a), fb_b_ = (b), fb_t_ = (tol);                                     \
    if (!(fabs(fb_a_ - fb_b_) <= fb_t_))                                                \
      fail_msg("%s = %.17g, %s = %.17g, |diff| = %.3g > tol %.3g", #a, fb_a_, #b, fb_b_, \
               fabs(fb_a_ - fb_b_), fb_t_);                                             \
  } while (0)

/* |a - b| <= rel * |b| */
#define assert_rel(a, b, rel) assert_near((a), (b), (rel) * fabs(b))

/* max |a - b| over max |b| of two 2 x 2 tensors */
static inline double fb_test_tensor_rel_diff(double a[2][2], double b[2][2]) {
  double d = 0.0, s = 0.0;
  for (int r = 0; r < 2; r++)
    for (int q = 0; q < 2; q++) {
      d = fmax(d, fabs(a[r][q] - b[r][q]));
      s = fmax(s, fabs(b[r][q]));
    }
  return d / s;
}

/* prints a measured residual when FB_TEST_VERBOSE is set */
#define report_residual(name, value, tol)                                      \
  do {                                                                         \
    if (fb_test_verbose())                                                     \
      fprintf(stderr, "  residual %-40s %.3e (tol %.1e)\n", name, (double)(value), \
              (double)(tol));                                                  \
  } while (0)

/* Loads the shipped paper case (FOURBAR_CASES_DIR or ./cases) with overrides;
 * exits with a message if it does not load, since every test using it
 * depends on it. */
#ifdef FB_CASEFILE_H
static inline void fb_test_paper_case(fb_case *c, const char **sets, int n) {
  const char *d = getenv("FOURBAR_CASES_DIR");
  char path[4096];
  snprintf(path, sizeof path, "%s/paper_crank_rocker.ini", d ? d : "cases");
  fb_diag diag;
  if (fb_casefile_load(c, path, sets, n, &diag) != FB_OK) {
    fprintf(stderr, "cannot load %s: %s\n", path, diag.msg);
    exit(1);
  }
}

/* Loads a case from its text (written to a temporary file, removed after)
 * with overrides into *c: fb_casefile_load's status, its message in diag.
 * A test's own case, stated beside the assertions it serves. */
#include <unistd.h>
static inline fb_status fb_test_case_text(fb_case *c, const char *text, const char **sets, int n,
                                          fb_diag *diag) {
  char path[] = "/tmp/fourbar-test-case-XXXXXX";
  const int fd = mkstemp(path);
  if (fd < 0) return fb_diag_set(diag, FB_ERR_IO, "no temporary case file");
  const size_t len = strlen(text);
  const int whole = write(fd, text, len) == (ssize_t)len;
  close(fd);
  const fb_status st = whole ? fb_casefile_load(c, path, sets, n, diag)
                             : fb_diag_set(diag, FB_ERR_IO, "the temporary case file is short");
  unlink(path);
  return st;
}

/* The key table as fourbar keys writes it (fb_casefile_write_keys: rows
 * "| [section] key | unit | default | rule | meaning |"), malloc'd: the
 * caller frees it. */
static inline char *fb_test_key_table(void) {
  char *text = NULL;
  size_t len = 0;
  FILE *f = open_memstream(&text, &len);
  assert_non_null(f);
  fb_casefile_write_keys(f);
  fclose(f);
  return text;
}

/* Loads the shipped case cases/<file> (FOURBAR_CASES_DIR or ./cases) with
 * overrides into *c: fb_casefile_load's status, its message in diag. */
static inline fb_status fb_test_shipped_case(fb_case *c, const char *file, const char **sets,
                                             int n, fb_diag *diag) {
  const char *d = getenv("FOURBAR_CASES_DIR");
  char path[4096];
  snprintf(path, sizeof path, "%s/%s", d ? d : "cases", file);
  return fb_casefile_load(c, path, sets, n, diag);
}

/* The shipped paper case as fb_test_paper_case loads it with no overrides,
 * read once per test program (a copy: the caller may change it). */
static inline fb_case fb_test_paper_once(void) {
  static fb_case paper;
  static int loaded = 0;
  if (!loaded) fb_test_paper_case(&paper, NULL, 0), loaded = 1;
  return paper;
}

/* Loads the shipped planar case cases/<file> ([linkage] type = planar)
 * with fb_casefile_load_planar into *c. */
static inline fb_status fb_test_shipped_case_planar(fb_case *c, const char *file, fb_diag *diag) {
  const char *d = getenv("FOURBAR_CASES_DIR");
  char path[4096];
  snprintf(path, sizeof path, "%s/%s", d ? d : "cases", file);
  return fb_casefile_load_planar(c, path, NULL, 0, diag);
}
#endif

/* Calls fn(path, file name, user) for every .ini file in the shipped
 * cases/hard folder (FOURBAR_CASES_DIR or ./cases); returns how many. */
#include <dirent.h>
#include <string.h>
static inline int fb_test_each_hard_case(void (*fn)(const char *path, const char *name, void *user),
                                         void *user) {
  const char *dir = getenv("FOURBAR_CASES_DIR");
  char hard[4096];
  snprintf(hard, sizeof hard, "%s/hard", dir ? dir : "cases");
  DIR *dd = opendir(hard);
  if (!dd) {
    fprintf(stderr, "cannot open %s\n", hard);
    exit(1);
  }
  struct dirent *e;
  int n = 0;
  while ((e = readdir(dd))) {
    size_t l = strlen(e->d_name);
    if (l < 4 || strcmp(e->d_name + l - 4, ".ini") != 0) continue;
    char path[8192];
    snprintf(path, sizeof path, "%s/%s", hard, e->d_name);
    fn(path, e->d_name, user);
    n++;
  }
  closedir(dd);
  return n;
}

/* Builds the scene of case c through the scene stage (fb_scene_from_case,
 * with every clearance model of the table listed so that both laws are
 * resolved), applies edit(def, user) if edit is not NULL, selects model row m
 * (a table row or a test's own) and creates its engine instance. Fails the
 * test on any error. Returns the instance; *e and *sm receive the engine and
 * the model's view (sm points into def, which must outlive the instance). */
#ifdef FB_ENGINE_H
static inline void *fb_test_engine_row(const fb_engine **e, fb_model_scene *sm, fb_scene *def,
                                       const fb_case *c, const fb_model *m,
                                       void (*edit)(fb_scene *def, void *user), void *user) {
  fb_case k = *c;
  k.model_count = 2;
  snprintf(k.models[0], sizeof k.models[0], "%s", "ode-clearance-impact");
  snprintf(k.models[1], sizeof k.models[1], "%s", "ode-clearance-restitution");
  if (!k.clearance.mask) k.model_count = 0;
  fb_diag diag;
  if (fb_scene_from_case(def, &k, &diag) != FB_OK) fail_msg("scene: %s", diag.msg);
  if (edit) edit(def, user);
  if (fb_scene_select(sm, def, m, &diag) != FB_OK) fail_msg("select: %s", diag.msg);
  *e = fb_engine_get(m->engine, &diag);
  if (!*e) fail_msg("%s", diag.msg);
  void *self = NULL;
  if ((*e)->create(&self, sm, &diag) != FB_OK) fail_msg("create: %s", diag.msg);
  return self;
}

/* fb_test_engine_row for the model table's row named model */
static inline void *fb_test_engine(const fb_engine **e, fb_model_scene *sm, fb_scene *def,
                                   const fb_case *c, const char *model,
                                   void (*edit)(fb_scene *def, void *user), void *user) {
  const fb_model *m = fb_model_find(model);
  if (!m) fail_msg("unknown model %s", model);
  return fb_test_engine_row(e, sm, def, c, m, edit, user);
}
#endif

#endif
