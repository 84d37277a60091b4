/* The fourbar binary end to end: the paper case runs and writes what the
 * README promises; bad input exits non-zero naming file/line or field and
 * writes nothing. argv[1] is the path of the built binary. */
#include <dirent.h>
#include <jansson.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "fb_config.h"
#include "fb_test.h"
#include "mechanism.h"

static const char *exe;
static char tmpdir[64];

/* runs `exe args` with stdout and stderr captured; returns the exit status */
static int run(const char *args, char *out, size_t out_size, char *err, size_t err_size) {
  char cmd[8192];
  snprintf(cmd, sizeof cmd, "%s %s >%s/out.txt 2>%s/err.txt", exe, args, tmpdir, tmpdir);
  int rc = system(cmd);
  char path[256];
  char *bufs[2] = {out, err};
  size_t sizes[2] = {out_size, err_size};
  const char *names[2] = {"out.txt", "err.txt"};
  for (int i = 0; i < 2; i++) {
    if (!bufs[i]) continue;
    snprintf(path, sizeof path, "%s/%s", tmpdir, names[i]);
    FILE *f = fopen(path, "r");
    size_t n = f ? fread(bufs[i], 1, sizes[i] - 1, f) : 0;
    bufs[i][n] = '\0';
    if (f) fclose(f);
  }
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

static double now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* timing.json's parts (issue 54) sum to its run_wall_s, which ends where
 * timing.json is written: only the folder's swap into place (its manifest),
 * the printed table and the exit follow. That is checked by order, never
 * by a clock against a clock (a loaded machine's scheduling would move the
 * process's wall time away from run_wall_s, and the verdict with it):
 * timing.json is the last file of the set written (no other file's
 * modification time after its own), and run_wall_s, measured inside the
 * process, is at most the process's wall time measured outside it (plus
 * TIMING_CLOCKS_S for the two clocks' reading). */
#define TIMING_CLOCKS_S 0.02
/* the parts are summed in double: equal to run_wall_s to rounding */
#define TIMING_SUM_REL 1e-9

/* the parts of DIR/timing.json against its run_wall_s and the process's
 * wall time measured outside it (wall_s); every model of summary.json has
 * its setup, stepping and check part; the printed last line (last_line, or
 * NULL) names the run's time */
static void check_timing(const char *dir, double wall_s, const char *last_line) {
  char path[256];
  snprintf(path, sizeof path, "%s/%s/timing.json", tmpdir, dir);
  json_error_t je;
  json_t *t = json_load_file(path, 0, &je);
  if (!t) fail_msg("%s: %s", path, je.text);
  const double run_wall = json_real_value(json_object_get(t, "run_wall_s"));
  json_t *parts = json_object_get(t, "parts");
  assert_true(json_is_object(parts));
  double sum = 0.0;
  const char *name;
  json_t *v;
  json_object_foreach(parts, name, v) {
    if (!json_is_number(v)) fail_msg("part %s is not a number", name);
    /* a part measured twice would show as a negative remainder */
    if (json_real_value(v) < -TIMING_SUM_REL * run_wall) fail_msg("part %s = %g s", name, json_real_value(v));
    sum += json_real_value(v);
  }
  if (!(fabs(sum - run_wall) <= TIMING_SUM_REL * run_wall))
    fail_msg("parts sum to %.9f s, run_wall_s %.9f s", sum, run_wall);
  const char *named[] = {"start", "ensemble", "series", "figures", "report", "other", NULL};
  for (int k = 0; named[k]; k++)
    if (!json_is_number(json_object_get(parts, named[k]))) fail_msg("no part %s", named[k]);
  size_t i;
  json_t *m;
  json_array_foreach(json_object_get(t, "models"), i, m) {
    const char *suffix[3] = {"setup", "stepping", "check"};
    for (int k = 0; k < 3; k++) {
      char key[160];
      snprintf(key, sizeof key, "%s.%s", json_string_value(json_object_get(m, "name")), suffix[k]);
      if (!json_is_number(json_object_get(parts, key))) fail_msg("no part %s", key);
    }
  }
  if (fb_test_verbose())
    fprintf(stderr, "  %s: run_wall_s %.3f s of the process's %.3f s\n", dir, run_wall, wall_s);
  if (!(run_wall <= wall_s + TIMING_CLOCKS_S))
    fail_msg("run_wall_s %.3f s against the process's %.3f s", run_wall, wall_s);
  /* timing.json last: every other file of the set (the hidden manifest,
   * written by the swap, aside) is no newer */
  struct stat ts;
  if (stat(path, &ts) != 0) fail_msg("%s: no timing.json", dir);
  char folder[256];
  snprintf(folder, sizeof folder, "%s/%s", tmpdir, dir);
  DIR *dd = opendir(folder);
  assert_non_null(dd);
  for (struct dirent *de; (de = readdir(dd)) != NULL;) {
    if (de->d_name[0] == '.') continue;
    char other[512];
    struct stat os;
    snprintf(other, sizeof other, "%s/%s", folder, de->d_name);
    if (stat(other, &os) != 0) continue;
    const int newer = os.st_mtim.tv_sec > ts.st_mtim.tv_sec ||
                      (os.st_mtim.tv_sec == ts.st_mtim.tv_sec &&
                       os.st_mtim.tv_nsec > ts.st_mtim.tv_nsec);
    if (newer) fail_msg("%s: %s was written after timing.json", dir, de->d_name);
  }
  closedir(dd);
  if (last_line) {
    char want[64];
    snprintf(want, sizeof want, "time %.2f s:", run_wall);
    if (strncmp(last_line, want, strlen(want)) != 0) fail_msg("last line '%s', not '%s ...'", last_line, want);
  }
  json_decref(t);
}

/* the last line of text */
static const char *last_line_of(char *text) {
  size_t n = strlen(text);
  while (n > 0 && text[n - 1] == '\n') text[--n] = '\0';
  const char *nl = strrchr(text, '\n');
  return nl ? nl + 1 : text;
}

static const char *write_file(const char *name, const char *text) {
  static char path[256];
  snprintf(path, sizeof path, "%s/%s", tmpdir, name);
  FILE *f = fopen(path, "w");
  fputs(text, f);
  fclose(f);
  return path;
}

/* ODE's joint feedback belongs to the configuration at the start of each
 * step (a crank-angle lag of omega h = 1e-3 rad at 1000 rpm, h = 1e-5 s) and
 * its hinges are softened by CFM 1e-10: measured 3e-5 relative on the peaks;
 * 1e-3 is the lag's first-order bound */
#define LOADS_ODE_VS_INVDYN_REL 1e-3
/* the same inverse dynamics sampled every 0.06 deg (the run) and on
 * penalty's grid: a smooth peak sampled off its top by half a step moves by
 * ~(half step)^2 / 2 relative, well under 1e-5; 1e-4 for margin */
#define LOADS_GRID_REL 1e-4

static void test_paper_case_runs_and_writes_summary(void **state) {
  (void)state;
  static char out[1 << 16], err[1 << 16];
  char args[512];
  snprintf(args, sizeof args, "run --out %s/paper", tmpdir);
  const double t0 = now_s();
  assert_int_equal(run(args, out, sizeof out, err, sizeof err), 0);
  const double wall = now_s() - t0;
  assert_non_null(strstr(out, "ode-ideal-nominal"));
  check_timing("paper", wall, last_line_of(out));
  char path[256];
  /* gnuplot's log stays only when gnuplot said something: no empty hidden file */
  snprintf(path, sizeof path, "%s/paper/.gnuplot.log", tmpdir);
  struct stat lst;
  if (stat(path, &lst) == 0 && lst.st_size == 0) fail_msg("an empty %s is left behind", path);
  snprintf(path, sizeof path, "%s/paper/summary.json", tmpdir);
  json_error_t je;
  json_t *j = json_load_file(path, 0, &je);
  if (!j) fail_msg("summary.json does not parse: %s", je.text);
  assert_string_equal(json_string_value(json_object_get(j, "case")), "paper_crank_rocker");
  json_t *models = json_object_get(j, "models");
  /* analytic, two ideal ODE models, the two ODE clearance models and the
   * reference of each law (issue 55: the case checks what it runs) */
  assert_int_equal(json_array_size(models), 7);
  /* the paper gives its masses: used as given and listed as the case's */
  json_t *crank = json_array_get(json_object_get(json_object_get(j, "masses"), "links"), 0);
  assert_near(json_real_value(json_object_get(crank, "mass_kg")), 0.12, 0.0);
  assert_string_equal(json_string_value(json_object_get(crank, "mass_source")), "case");
  assert_string_equal(json_string_value(json_object_get(crank, "inertia_source")), "case");
  /* the paper case's impact model stays with the reference: it does not
   * leave it within the run, and every impact is matched one to one within
   * the bound (issue 25); its restitution model leaves reference-restitution
   * (at 2.85 ms) and is judged on its members' statistics (docs/verdicts.md);
   * no model is left unchecked (issue 55) */
  int with_divergence = 0;
  for (size_t q = 0; q < json_array_size(models); q++) {
    json_t *mq = json_array_get(models, q);
    assert_string_not_equal(json_string_value(json_object_get(mq, "verdict")), "unchecked");
    json_t *dv = json_object_get(mq, "divergence");
    if (!dv) continue;
    with_divergence++;
    if (strcmp(json_string_value(json_object_get(mq, "name")), "ode-clearance-restitution") == 0) {
      assert_true(json_is_true(json_object_get(dv, "diverged")));
      assert_string_equal(json_string_value(json_object_get(mq, "verdict_basis")), "statistics");
      continue;
    }
    assert_true(json_is_false(json_object_get(dv, "diverged")));
    assert_true(json_is_null(json_object_get(dv, "time_s")));
    assert_true(json_is_true(json_object_get(dv, "one_to_one")));
    const json_int_t n = json_integer_value(json_object_get(dv, "impacts_matched"));
    assert_true(n >= 10);
    assert_int_equal(n, json_integer_value(json_object_get(dv, "impacts_reference")));
    assert_int_equal((int)json_array_size(json_object_get(dv, "matched_impacts")), (int)n);
    assert_true(json_real_value(json_object_get(dv, "force_rel_max")) <= 0.05);
    assert_int_equal(json_array_size(json_object_get(json_array_get(models, q), "warnings")), 0);
  }
  assert_int_equal(with_divergence, 2); /* each clearance model against its reference */
  /* wall times live in timing.json, so summary.json is the same on every rerun */
  const char *keys[] = {"name", "kind", "status", "h_s", "steps", "coupler",
                        "follower", "error_vs_analytic", NULL};
  const char *peak_keys[] = {"omega_max_rad_s", "omega_min_rad_s", "alpha_max_rad_s2",
                             "alpha_min_rad_s2", NULL};
  size_t i;
  json_t *m;
  json_array_foreach(models, i, m) {
    for (int k = 0; keys[k]; k++)
      if (!json_object_get(m, keys[k])) fail_msg("model %zu lacks key %s", i, keys[k]);
    for (int b = 0; b < 2; b++) {
      json_t *body = json_object_get(m, b ? "follower" : "coupler");
      for (int k = 0; peak_keys[k]; k++) assert_true(json_is_number(json_object_get(body, peak_keys[k])));
    }
    assert_null(json_object_get(m, "wall_s"));
    const char *kind = json_string_value(json_object_get(m, "kind"));
    assert_true(strcmp(kind, "analytic") == 0 || strcmp(kind, "ode") == 0 ||
                strcmp(kind, "reference") == 0);
    /* ok, or (the restitution model, which parts from its reference) why
     * its peaks are not compared one by one */
    const char *status = json_string_value(json_object_get(m, "status"));
    if (strcmp(status, "ok") != 0) assert_int_equal(strncmp(status, "divergent: ", 11), 0);
    /* every model wrote its CSV, with a unit-suffixed header */
    snprintf(path, sizeof path, "%s/paper/%s.csv", tmpdir,
             json_string_value(json_object_get(m, "name")));
    FILE *f = fopen(path, "r");
    assert_non_null(f);
    char header[512];
    assert_non_null(fgets(header, sizeof header, f));
    fclose(f);
    assert_non_null(strstr(header, "time_s,crank_angle_rad,coupler_angle_rad,coupler_omega_rad_s"));
  }
  /* the acceptance bound: ode-ideal-nominal omega peaks within 1e-4 */
  json_t *ode = json_array_get(models, 1);
  assert_string_equal(json_string_value(json_object_get(ode, "name")), "ode-ideal-nominal");
  json_t *e = json_object_get(ode, "error_vs_analytic");
  for (int b = 0; b < 2; b++) {
    json_t *body = json_object_get(e, b ? "follower" : "coupler");
    assert_true(fabs(json_real_value(json_object_get(body, "omega_max_rel"))) < 1e-4);
    assert_true(fabs(json_real_value(json_object_get(body, "omega_min_rel"))) < 1e-4);
  }
  /* the paper's two clearance models carry spike metrics; the others null */
  const char *spike_keys[] = {"alpha_peak_ratio_coupler", "alpha_peak_ratio_follower",
                              "omega_dev_max_rad_s", "force_max_n", "penetration_max_m",
                              "impacts", "free_flight_fraction", NULL};
  for (size_t k = 3; k < 5; k++) {
    json_t *cm = json_array_get(models, k);
    assert_non_null(strstr(json_string_value(json_object_get(cm, "name")), "ode-clearance-"));
    json_t *sp = json_object_get(cm, "spikes");
    for (int q = 0; spike_keys[q]; q++)
      if (!json_is_number(json_object_get(sp, spike_keys[q])))
        fail_msg("model %zu spikes lacks %s", k, spike_keys[q]);
    /* the clearance makes spikes: peak |alpha| above the ideal stack-up model's */
    assert_true(json_real_value(json_object_get(sp, "alpha_peak_ratio_coupler")) > 1.0);
  }
  assert_true(json_is_null(json_object_get(json_array_get(models, 2), "spikes")));
  /* the impact model is measured against the reference of its law */
  json_t *evr = json_object_get(json_array_get(models, 4), "error_vs_reference");
  assert_string_equal(json_string_value(json_object_get(evr, "reference")), "reference");
  assert_true(json_is_number(json_object_get(evr, "force_max_rel")));
  /* the clearance model's CSV has the contact columns */
  snprintf(path, sizeof path, "%s/paper/ode-clearance-impact.csv", tmpdir);
  FILE *f = fopen(path, "r");
  char header[1024];
  assert_non_null(fgets(header, sizeof header, f));
  fclose(f);
  assert_non_null(strstr(header, "crank_coupler_force_n,crank_coupler_penetration_m,"
                                 "crank_coupler_ecc_x_m,crank_coupler_ecc_y_m,crank_coupler_state"));
  /* ... and the loads: drive torque and every joint's reaction, in N */
  assert_non_null(strstr(header, "drive_torque_n_m,ground_crank_reaction_x_n,ground_crank_reaction_y_n,"
                                 "ground_crank_reaction_n,crank_coupler_reaction_x_n"));
  assert_non_null(strstr(header, "follower_ground_reaction_n"));
  /* loads: the ODE model's joint feedback against the analytic model's inverse
   * dynamics (independent methods), and the analytic crank-coupler peak
   * against penalty --mode physical's force (the same inverse dynamics,
   * sampled on another grid) */
  json_t *la = json_object_get(json_array_get(models, 0), "loads");
  json_t *lo = json_object_get(ode, "loads");
  assert_true(json_is_object(la) && json_is_object(lo));
  const char *tk[3] = {"drive_torque_max_n_m", "drive_torque_min_n_m", "drive_torque_abs_max_n_m"};
  for (int k = 0; k < 3; k++)
    assert_rel(json_real_value(json_object_get(lo, tk[k])), json_real_value(json_object_get(la, tk[k])),
               LOADS_ODE_VS_INVDYN_REL);
  const char *jn[4] = {"ground_crank", "crank_coupler", "coupler_follower", "follower_ground"};
  for (int k = 0; k < 4; k++)
    assert_rel(json_real_value(json_object_get(json_object_get(lo, "reaction_max_n"), jn[k])),
               json_real_value(json_object_get(json_object_get(la, "reaction_max_n"), jn[k])),
               LOADS_ODE_VS_INVDYN_REL);
  assert_true(json_is_null(json_object_get(json_array_get(models, 5), "loads"))); /* reference: none */
  static char pout[1 << 14], perr[4096];
  assert_int_equal(run("penalty --mode physical --speeds-rpm 1000 --json", pout, sizeof pout, perr, sizeof perr), 0);
  json_t *pj = json_loads(pout, 0, NULL);
  assert_non_null(pj);
  assert_rel(json_real_value(json_object_get(json_object_get(la, "reaction_max_n"), "crank_coupler")),
             json_real_value(json_object_get(json_array_get(json_object_get(pj, "rows"), 0), "force_n")),
             LOADS_GRID_REL);
  json_decref(pj);
  json_decref(j);
}

/* --json prints 12 significant digits: each value rounds by up to 5e-12
 * relative, two of them compared: 1e-11 */
#define JSON12_REL_TOL 1e-11

static void test_json_flag_and_kinematics(void **state) {
  (void)state;
  static char out[1 << 16], err[4096];
  assert_int_equal(run("kinematics --crank-mm 108 --coupler-mm 279.4 --follower-mm 270.5 "
                       "--ground-mm 254 --speed-rpm 1000 --direction cw --json",
                       out, sizeof out, err, sizeof err), 0);
  json_error_t je;
  json_t *j = json_loads(out, 0, &je);
  if (!j) fail_msg("kinematics --json output does not parse: %s", je.text);
  assert_string_equal(json_string_value(json_object_get(j, "grashof")), "crank-rocker");
  assert_true(json_is_number(json_object_get(j, "transmission_angle_min_deg")));
  assert_true(json_is_number(json_object_get(j, "transmission_angle_max_deg")));
  double amax = json_real_value(json_object_get(json_object_get(j, "coupler"), "alpha_min_rad_s2"));
  double w = 1000.0 * 2 * M_PI / 60;
  assert_near(fabs(amax) / (w * w), 1.091571, 5e-7); /* docs/paper.md's ratio */
  const double peak = json_real_value(json_object_get(json_object_get(j, "coupler"), "alpha_min_rad_s2"));
  json_decref(j);
  /* the case file gives the same linkage, speed and direction (the same
   * computation on the same doubles: equal to the printed 12 digits) */
  assert_int_equal(run("kinematics paper_crank_rocker --json", out, sizeof out, err, sizeof err), 0);
  j = json_loads(out, 0, &je);
  if (!j) fail_msg("kinematics CASE --json does not parse: %s (%s)", je.text, err);
  assert_string_equal(json_string_value(json_object_get(j, "direction")), "cw");
  assert_rel(json_real_value(json_object_get(json_object_get(j, "coupler"), "alpha_min_rad_s2")),
             peak, JSON12_REL_TOL);
  json_decref(j);
  /* without a case and without --direction: cw, as case files */
  assert_int_equal(run("kinematics --crank-mm 108 --coupler-mm 279.4 --follower-mm 270.5 "
                       "--ground-mm 254 --speed-rpm 1000 --json", out, sizeof out, err, sizeof err), 0);
  j = json_loads(out, 0, &je);
  assert_non_null(j);
  assert_string_equal(json_string_value(json_object_get(j, "direction")), "cw");
  assert_true(json_real_value(json_object_get(j, "crank_omega_rad_s")) < 0.0);
  json_decref(j);
}


static void test_penalty_and_impact_json(void **state) {
  (void)state;
  static char out[1 << 17], err[4096];
  assert_int_equal(run("penalty --mode paper --speeds-rpm 1000 --json", out, sizeof out, err, sizeof err), 0);
  json_error_t je;
  json_t *j = json_loads(out, 0, &je);
  if (!j) fail_msg("penalty --json does not parse: %s", je.text);
  assert_string_equal(json_string_value(json_object_get(j, "mode")), "paper");
  json_t *rows = json_object_get(j, "rows");
  assert_int_equal(json_array_size(rows), 2);
  const char *keys[] = {"speed_rpm", "joint", "force_n", "stiffness_n_m", "penalty", "approach_um", NULL};
  for (int k = 0; keys[k]; k++) assert_non_null(json_object_get(json_array_get(rows, 0), keys[k]));
  /* Table II at 1000 rpm, crank-coupler: 973.33 */
  assert_near(json_real_value(json_object_get(json_array_get(rows, 0), "penalty")), 973.33, 0.005);
  /* each unit its own column, in every mode: 1 N mm^0.5 = sqrt(1e-3) N m^0.5 */
  assert_near(json_real_value(json_object_get(json_array_get(rows, 0), "penalty_n_mm0_5")), 973.33, 0.005);
  assert_near(json_real_value(json_object_get(json_array_get(rows, 0), "penalty_n_m0_5")),
              973.33 * sqrt(1e-3), 0.005 * sqrt(1e-3));
  json_decref(j);
  assert_int_equal(run("penalty --mode physical --speeds-rpm 500,1000 --json", out, sizeof out, err, sizeof err), 0);
  j = json_loads(out, 0, &je);
  assert_non_null(j);
  assert_int_equal(json_array_size(json_object_get(j, "rows")), 4);
  json_t *r0 = json_array_get(json_object_get(j, "rows"), 0);
  assert_rel(json_real_value(json_object_get(r0, "penalty_n_m0_5")),
             json_real_value(json_object_get(r0, "penalty_n_mm0_5")) * sqrt(1e-3), JSON12_REL_TOL);
  json_decref(j);
  /* one default with fourbar run: the case's [clearance] penalty (physical) */
  assert_int_equal(run("penalty --speeds-rpm 1000 --json", out, sizeof out, err, sizeof err), 0);
  j = json_loads(out, 0, &je);
  assert_non_null(j);
  assert_string_equal(json_string_value(json_object_get(j, "mode")), "physical");
  json_decref(j);
  assert_int_equal(run("penalty --speeds-rpm 1000 --json --set clearance.penalty=paper", out, sizeof out,
                       err, sizeof err), 0);
  j = json_loads(out, 0, &je);
  assert_non_null(j);
  assert_string_equal(json_string_value(json_object_get(j, "mode")), "paper");
  json_decref(j);

  assert_int_equal(run("impact --law hertz --json", out, sizeof out, err, sizeof err), 0);
  j = json_loads(out, 0, &je);
  if (!j) fail_msg("impact --json does not parse: %s", je.text);
  const char *groups[] = {"ode", "reference", "closed_form", NULL};
  const char *ikeys[] = {"penetration_max_m", "contact_duration_s", "force_max_n", "restitution_achieved", NULL};
  for (int g = 0; groups[g]; g++)
    for (int k = 0; ikeys[k]; k++)
      assert_true(json_is_number(json_object_get(json_object_get(j, groups[g]), ikeys[k])));
  /* one default with fourbar run: the matched mapping */
  assert_string_equal(json_string_value(json_object_get(j, "mapping")), "matched");
  json_decref(j);
  /* no closed form for a hysteresis law: null, not made up */
  assert_int_equal(run("impact --law flores --restitution 0.5 --json", out, sizeof out, err, sizeof err), 0);
  j = json_loads(out, 0, &je);
  assert_true(json_is_null(json_object_get(j, "closed_form")));
  json_decref(j);
}

/* contact-params --json: the contract keys (issue 27) and a verification
 * row per engine and form this build has */
static void test_contact_params_json(void **state) {
  (void)state;
  static char out[1 << 17], err[4096];
  json_error_t je;
  assert_int_equal(run("contact-params --verify --json", out, sizeof out, err, sizeof err), 0);
  json_t *j = json_loads(out, 0, &je);
  if (!j) fail_msg("contact-params --json does not parse: %s", je.text);
  json_t *p = json_object_get(j, "params");
  const char *engines[] = {"ode", "gazebo", "mujoco", "bullet", NULL};
  for (int i = 0; engines[i]; i++) assert_non_null(json_object_get(p, engines[i]));
  json_t *v = json_object_get(j, "verify");
  assert_true(json_array_size(v) >= 4);
  size_t i;
  json_t *x;
  int ode_matched = 0;
  json_array_foreach(v, i, x) {
    const char *keys[] = {"restitution", "restitution_target", "penetration_max_m",
                          "penetration_target_m", NULL};
    for (int k = 0; keys[k]; k++) assert_true(json_is_number(json_object_get(x, keys[k])));
    assert_non_null(json_string_value(json_object_get(x, "engine")));
    assert_non_null(json_string_value(json_object_get(x, "form")));
    if (strcmp(json_string_value(json_object_get(x, "engine")), "ode") == 0 &&
        strcmp(json_string_value(json_object_get(x, "form")), "matched") == 0) {
      ode_matched = 1;
      /* the test of the numbers is test_contact_params; here: one impact,
       * the law's cr 0.9 as its target */
      assert_near(json_real_value(json_object_get(x, "restitution_target")), 0.9, 1e-6);
    }
  }
  assert_true(ode_matched);
  json_decref(j);
}

/* contact-params at a user's coarse step (issue 44): the steel
 * Hertz contact at MuJoCo's 2 ms is not recommended there, exit 0, and the
 * JSON carries largest_step_s and at_step rows whose verify[] entries are
 * all recommended and faithful; the lankarani-nikravesh command
 * exits 0 with every recommended row faithful */
static void expect_all_faithful(json_t *verify, const char *what) {
  size_t i, n = 0;
  json_t *x;
  json_array_foreach(verify, i, x) {
    if (!json_is_true(json_object_get(x, "recommended"))) continue;
    n++;
    if (!json_is_true(json_object_get(x, "faithful")))
      fail_msg("%s: %s %s not faithful", what, json_string_value(json_object_get(x, "engine")),
               json_string_value(json_object_get(x, "form")));
  }
  assert_true(n >= 2); /* ODE and Gazebo at least */
}

static void test_contact_params_coarse_step(void **state) {
  (void)state;
  static char out[1 << 18], err[4096];
  json_error_t je;
  assert_int_equal(run("contact-params --law hertz --stiffness 1.5e10 --restitution 0.8 "
                       "--mass-kg 0.5 --speed-m-s 0.3 --h-s 2e-3 --json",
                       out, sizeof out, err, sizeof err), 0);
  json_t *j = json_loads(out, 0, &je);
  if (!j) fail_msg("contact-params --json does not parse: %s", je.text);
  assert_true(json_is_false(json_object_get(j, "recommended")));
  assert_true(json_is_null(json_object_get(j, "params")));
  const double hl = json_real_value(json_object_get(j, "largest_step_s"));
  assert_true(hl > 0.0 && hl < 2e-3);
  json_t *a = json_object_get(j, "at_step");
  assert_near(json_real_value(json_object_get(a, "h_s")), 2e-3, 1e-15);
  assert_true(json_real_value(json_object_get(a, "penetration_m")) > 0.0);
  assert_true(json_real_value(json_object_get(a, "contact_duration_s")) > 0.0);
  assert_non_null(json_object_get(json_object_get(a, "params"), "mujoco"));
  expect_all_faithful(json_object_get(a, "verify"), "at_step 2 ms");
  /* with --h-s: no engine default steps */
  assert_int_equal(json_array_size(json_object_get(j, "at_default_steps")), 0);
  json_decref(j);
  /* without --h-s: at_step also at MuJoCo's 2 ms and Gazebo's 1 ms */
  assert_int_equal(run("contact-params --law hertz --stiffness 1.5e10 --restitution 0.8 "
                       "--mass-kg 0.5 --speed-m-s 0.3 --json",
                       out, sizeof out, err, sizeof err), 0);
  j = json_loads(out, 0, &je);
  if (!j) fail_msg("contact-params --json does not parse: %s", je.text);
  json_t *ds = json_object_get(j, "at_default_steps");
  assert_int_equal(json_array_size(ds), 2);
  const char *engines[] = {"mujoco", "gazebo"};
  const double hs[] = {2e-3, 1e-3};
  for (size_t i = 0; i < 2; i++) {
    json_t *e = json_array_get(ds, i);
    assert_string_equal(json_string_value(json_object_get(e, "engine")), engines[i]);
    assert_near(json_real_value(json_object_get(e, "h_s")), hs[i], 1e-15);
    assert_true(json_real_value(json_object_get(e, "penetration_m")) > 0.0);
    assert_non_null(json_object_get(json_object_get(e, "params"), "gazebo"));
    expect_all_faithful(json_object_get(e, "verify"), engines[i]);
  }
  assert_int_equal(json_integer_value(json_object_get(j, "failed_recommended_rows")), 0);
  json_decref(j);
  assert_int_equal(run("contact-params --law lankarani-nikravesh --stiffness 1.5e10 --exponent 1.5 "
                       "--restitution 0.8 --mass-kg 0.5 --speed-m-s 0.3 --verify --json",
                       out, sizeof out, err, sizeof err), 0);
  j = json_loads(out, 0, &je);
  if (!j) fail_msg("contact-params --json does not parse: %s", je.text);
  assert_true(json_is_true(json_object_get(j, "recommended")));
  expect_all_faithful(json_object_get(j, "verify"), "lankarani-nikravesh");
  assert_int_equal(json_integer_value(json_object_get(j, "failed_recommended_rows")), 0);
  json_decref(j);
}

/* contact-params --case: the paper's crank-coupler joint with the run's own
 * restitution law and its effective-mass range (0.09 to 0.95 kg, issue 27),
 * at h omega_c = 0.1; the matched rows of ODE, Gazebo and Bullet within 1 %
 * in restitution and 2 % in penetration at every mass verified */
#define CASE_RESTITUTION_REL_TOL 0.01
#define CASE_PENETRATION_REL_TOL 0.02
static void test_contact_params_case(void **state) {
  (void)state;
  static char out[1 << 17], err[4096];
  json_error_t je;
  assert_int_equal(run("contact-params --case paper_crank_rocker --h-s 7.9e-7 --verify --json",
                       out, sizeof out, err, sizeof err), 0);
  json_t *j = json_loads(out, 0, &je);
  if (!j) fail_msg("contact-params --case --json does not parse: %s", je.text);
  json_t *cs = json_object_get(j, "case");
  assert_string_equal(json_string_value(json_object_get(cs, "joint")), "crank-coupler");
  assert_string_equal(json_string_value(json_object_get(cs, "model")), "clearance-restitution");
  json_t *m = json_object_get(j, "mass_kg");
  const double lo = json_real_value(json_object_get(m, "min"));
  const double hi = json_real_value(json_object_get(m, "max"));
  if (!(lo > 0.09 && lo < 0.1 && hi > 0.9 && hi < 1.0))
    fail_msg("effective mass %g to %g kg: the paper joint's is 0.09 to 0.95 kg", lo, hi);
  size_t i;
  json_t *x;
  int matched = 0;
  int mujoco = 0;
  json_array_foreach(json_object_get(j, "verify"), i, x) {
    const char *engine = json_string_value(json_object_get(x, "engine"));
    const char *form = json_string_value(json_object_get(x, "form"));
    /* MuJoCo's solref is per unit of effective mass (its constraint force is
     * the mass times k d + b v): one setting holds at the mass it names, so
     * the form to hold is direct at each mass; "direct" for the whole range
     * is shown beside it, with its error at the ends */
    if (strcmp(engine, "mujoco") == 0) {
      if (strcmp(form, "direct-at-mass") != 0) continue;
      mujoco++;
    } else {
      if (strcmp(form, "matched") != 0) continue;
      if (strcmp(engine, "ode") && strcmp(engine, "gazebo") && strcmp(engine, "bullet")) continue;
    }
    matched++;
    const double er = json_real_value(json_object_get(x, "restitution")) /
                          json_real_value(json_object_get(x, "restitution_target")) - 1.0;
    const double ep = json_real_value(json_object_get(x, "penetration_max_m")) /
                          json_real_value(json_object_get(x, "penetration_target_m")) - 1.0;
    if (!(fabs(er) <= CASE_RESTITUTION_REL_TOL && fabs(ep) <= CASE_PENETRATION_REL_TOL))
      fail_msg("%s matched at %g kg: restitution %+.3e, penetration %+.3e", engine,
               json_real_value(json_object_get(x, "mass_kg")), er, ep);
  }
  assert_true(matched >= 6); /* ODE and Gazebo at three masses, Bullet too where built */
  assert_int_equal(mujoco, FB_HAVE_MUJOCO ? 3 : 0); /* MuJoCo at the three masses where built */
  json_decref(j);
}

static void test_fit_tolerance_stackup_json(void **state) {
  (void)state;
  static char out[1 << 17], err[4096];
  json_error_t je;
  assert_int_equal(run("fit 10H7/g6 --json", out, sizeof out, err, sizeof err), 0);
  json_t *j = json_loads(out, 0, &je);
  if (!j) fail_msg("fit --json does not parse: %s", je.text);
  assert_near(json_real_value(json_object_get(j, "nominal_mm")), 10, 0);
  assert_near(json_real_value(json_object_get(json_object_get(j, "hole"), "upper_um")), 15, 1e-9);
  assert_near(json_real_value(json_object_get(json_object_get(j, "shaft"), "lower_um")), -14, 1e-9);
  assert_near(json_real_value(json_object_get(j, "clearance_min_um")), 5, 1e-9);
  assert_near(json_real_value(json_object_get(j, "clearance_max_um")), 29, 1e-9);
  assert_string_equal(json_string_value(json_object_get(j, "kind")), "clearance");
  json_decref(j);
  assert_int_equal(run("fit 25 H8/f7 --json", out, sizeof out, err, sizeof err), 0);
  j = json_loads(out, 0, &je);
  assert_near(json_real_value(json_object_get(j, "clearance_max_um")), 74, 1e-9);
  json_decref(j);
  /* a zero deviation prints as 0.0, never -0.0 */
  assert_int_equal(run("fit 10H7/h6 --json", out, sizeof out, err, sizeof err), 0);
  assert_null(strstr(out, "-0.0"));
  assert_int_equal(run("tolerance 279.4 --class m --json", out, sizeof out, err, sizeof err), 0);
  j = json_loads(out, 0, &je);
  assert_near(json_real_value(json_object_get(j, "plus_minus_mm")), 0.5, 1e-12);
  assert_string_equal(json_string_value(json_object_get(j, "class")), "m");
  assert_near(json_real_value(json_object_get(j, "size_mm")), 279.4, 1e-12);
  json_decref(j);
  assert_int_equal(run("stackup --samples 200 --seed 3 --json", out, sizeof out, err, sizeof err), 0);
  j = json_loads(out, 0, &je);
  if (!j) fail_msg("stackup --json does not parse: %s", je.text);
  json_t *o0 = json_array_get(json_object_get(j, "outputs"), 0);
  assert_string_equal(json_string_value(json_object_get(o0, "name")), "coupler_omega_max_rad_s");
  const char *groups[] = {"corners", "rss", "montecarlo", "sensitivity_per_m", NULL};
  for (int g = 0; groups[g]; g++) assert_non_null(json_object_get(o0, groups[g]));
  /* 200 samples bound the median on both sides, not the 0.135 % quantile from below */
  json_t *mc = json_object_get(o0, "montecarlo");
  assert_true(json_is_real(json_object_get(mc, "q50_ci_lo")) && json_is_real(json_object_get(mc, "q50_ci_hi")));
  assert_true(json_is_null(json_object_get(mc, "q00135_ci_lo")));
  json_decref(j);
}

/* fourbar penalty prints the contact a run uses through the same scene stage:
 * the summary's `contact` objects and the penalty's agree in every law
 * figure, printed alike (%.6g in text; in JSON to 12 digits, the penalty's
 * precision) */
#define CONTACT_AGREE_REL_TOL 1e-11

static void test_penalty_contact_is_the_runs(void **state) {
  (void)state;
  static char out[1 << 20], err[8192];
  assert_int_equal(run("penalty --json --speeds-rpm 1000", out, sizeof out, err, sizeof err), 0);
  json_t *pj = json_loads(out, 0, NULL);
  assert_non_null(pj);
  char cmd[512];
  snprintf(cmd, sizeof cmd,
           "run --json --out %s/contact --set run.revolutions=1 "
           "--set run.models=ode-clearance-impact,ode-clearance-restitution --set run.peaks=all",
           tmpdir);
  assert_int_equal(run(cmd, out, sizeof out, err, sizeof err), 0);
  json_t *rj = json_loads(out, 0, NULL);
  assert_non_null(rj);
  const char *keys[] = {"stiffness", "exponent", "damping_n_s_m", "damping_depth_m",
                        "restitution", "damping_ratio", NULL};
  size_t i;
  json_t *pc;
  int compared = 0;
  json_array_foreach(json_object_get(pj, "contact"), i, pc) {
    const char *model = json_string_value(json_object_get(pc, "model"));
    size_t k;
    json_t *m;
    json_array_foreach(json_object_get(rj, "models"), k, m) {
      if (strcmp(json_string_value(json_object_get(m, "name")), model) != 0) continue;
      json_t *rc = json_array_get(json_object_get(m, "contact"), 0);
      assert_non_null(rc);
      assert_string_equal(json_string_value(json_object_get(rc, "law")),
                          json_string_value(json_object_get(pc, "law")));
      assert_string_equal(json_string_value(json_object_get(rc, "mapping")),
                          json_string_value(json_object_get(pc, "mapping")));
      for (int q = 0; keys[q]; q++) {
        json_t *a = json_object_get(pc, keys[q]), *b = json_object_get(rc, keys[q]);
        if (!a || !json_is_number(a) || !b || !json_is_number(b)) continue;
        assert_rel(json_number_value(b), json_number_value(a), CONTACT_AGREE_REL_TOL);
        compared++;
      }
      /* the run's provenance: its effective mass lies in the penalty's estimate */
      json_t *em = json_object_get(rc, "effective_mass_kg");
      json_t *ee = json_object_get(pc, "effective_mass_estimate_kg");
      assert_true(json_number_value(json_object_get(em, "min")) >=
                  0.99 * json_number_value(json_object_get(ee, "min")));
      assert_true(json_number_value(json_object_get(em, "max")) <=
                  1.01 * json_number_value(json_object_get(ee, "max")));
      assert_true(json_is_true(json_object_get(rc, "resolved")));
    }
  }
  /* impact: stiffness, exponent, c_max, d_max; restitution: stiffness,
   * exponent, restitution, damping ratio */
  assert_int_equal(compared, 8);
  json_decref(pj);
  json_decref(rj);
}

/* fourbar bench --grid peers: bench.json's peers[] under the contract's
 * names (issue 43: peers[].engine, peers[].harness_over_bare), one per
 * engine of the build, each run; the case made cheap (no clearance joint,
 * 20,000 rpm: 2 revolutions are 6 ms of motion) */
static void test_bench_peers_json(void **state) {
  (void)state;
  static char out[1 << 20], err[8192];
  char args[1024];
  snprintf(args, sizeof args,
           "bench --grid peers --json --out %s/peers --set clearance.joints=none "
           "--set drive.speed_rpm=20000 --set solver.drive_torque_max_n_m=1e7 "
           "--set run.models=ode-ideal-stackup",
           tmpdir);
  assert_int_equal(run(args, out, sizeof out, err, sizeof err), 0);
  json_error_t je;
  json_t *j = json_loads(out, 0, &je);
  assert_non_null(j);
  assert_string_equal(json_string_value(json_object_get(j, "grid")), "peers");
  json_t *peers = json_object_get(j, "peers");
  const size_t want = 1 + FB_HAVE_MUJOCO + FB_HAVE_BULLET + FB_HAVE_SIMBODY + FB_HAVE_DART;
  assert_int_equal(json_array_size(peers), want);
  for (size_t i = 0; i < json_array_size(peers); i++) {
    json_t *p = json_array_get(peers, i);
    assert_non_null(json_string_value(json_object_get(p, "engine")));
    assert_true(json_is_true(json_object_get(p, "ran")));
    assert_true(json_number_value(json_object_get(p, "harness_over_bare")) > 0.0);
  }
  assert_string_equal(json_string_value(json_object_get(json_array_get(peers, 0), "engine")), "ode");
  json_decref(j);
}

static void test_check_catches_stiffness_regression(void **state) {
  (void)state;
  static char out[1 << 18], err[8192];
  /* unchanged: passes */
  assert_int_equal(run("check --cases paper_crank_rocker", out, sizeof out, err, sizeof err), 0);
  assert_non_null(strstr(out, " 0 failed"));
  /* contact stiffness scaled by 1.2: fails, naming the moved metrics. The
   * case's step is h_s = auto, which follows the stiffness: it is pinned at
   * the baseline's own value (fourbar penalty --json: h_auto_s) so that only
   * the contact moves */
  assert_int_equal(run("penalty --json --speeds-rpm 1000", out, sizeof out, err, sizeof err), 0);
  const char *ha = strstr(out, "\"h_auto_s\":");
  assert_non_null(ha);
  char moved_cmd[256];
  snprintf(moved_cmd, sizeof moved_cmd,
           "check --cases paper_crank_rocker --set clearance.stiffness_scale=1.2 "
           "--set solver.h_s=%.17g",
           strtod(ha + strlen("\"h_auto_s\":"), NULL));
  assert_int_equal(run(moved_cmd, out, sizeof out, err, sizeof err), 1);
  /* (the restitution model's largest penetration moves by 2 % only, inside its
   * calibrated spread of the chaotic impact sequence; its force by 17 %) */
  const char *moved[] = {"ode-clearance-impact.spikes.penetration_max_m",
                         "ode-clearance-restitution.spikes.force_max_n", NULL};
  for (int i = 0; moved[i]; i++) {
    const char *line = strstr(out, moved[i]);
    if (!line) fail_msg("check output lacks %s", moved[i]);
    const char *eol = strchr(line, '\n');
    const char *fail = strstr(line, "FAIL");
    if (!fail || (eol && fail > eol)) fail_msg("%s is not marked FAIL", moved[i]);
  }
  /* ideal models do not move: the check does not cry wolf */
  const char *still = strstr(out, "ode-ideal-stackup.coupler.omega_max_rad_s");
  assert_non_null(still);
  assert_true(strstr(still, "pass") < strchr(still, '\n'));
  /* --update on a copy rewrites the values and says what changed */
  char cmd[1024];
  snprintf(cmd, sizeof cmd, "mkdir -p %s/bl && cp %s/../results/baselines/paper_crank_rocker.json %s/bl/",
           tmpdir, getenv("FOURBAR_CASES_DIR"), tmpdir);
  assert_int_equal(system(cmd), 0);
  /* a variant (--set) never rewrites a baseline (issue 24 item 5): refused,
   * the baseline byte-identical */
  snprintf(cmd, sizeof cmd, "FOURBAR_BASELINES_DIR=%s/bl %s check --update --set clearance.stiffness_scale=1.2 >%s/up.txt 2>&1",
           tmpdir, exe, tmpdir);
  assert_int_equal(WEXITSTATUS(system(cmd)), 2);
  snprintf(cmd, sizeof cmd, "grep -q 'variant' %s/up.txt && cmp -s %s/bl/paper_crank_rocker.json "
           "%s/../results/baselines/paper_crank_rocker.json", tmpdir, tmpdir, getenv("FOURBAR_CASES_DIR"));
  assert_int_equal(system(cmd), 0);
  /* the case file itself changed: --update rewrites the values and says what moved */
  snprintf(cmd, sizeof cmd, "mkdir -p %s/cs && sed 's/^\\[clearance\\]$/[clearance]\\nstiffness_scale = 1.2/' "
           "%s/paper_crank_rocker.ini > %s/cs/paper_crank_rocker.ini && grep -q '^stiffness_scale = 1.2' "
           "%s/cs/paper_crank_rocker.ini", tmpdir, getenv("FOURBAR_CASES_DIR"), tmpdir, tmpdir);
  assert_int_equal(system(cmd), 0);
  snprintf(cmd, sizeof cmd, "FOURBAR_CASES_DIR=%s/cs FOURBAR_BASELINES_DIR=%s/bl %s check --update >%s/up.txt 2>&1",
           tmpdir, tmpdir, exe, tmpdir);
  assert_int_equal(system(cmd), 0);
  snprintf(cmd, sizeof cmd, "grep -q 'penetration_max_m: .* -> .* (moved)' %s/up.txt", tmpdir);
  assert_int_equal(system(cmd), 0);
  snprintf(cmd, sizeof cmd, "FOURBAR_CASES_DIR=%s/cs FOURBAR_BASELINES_DIR=%s/bl %s check >/dev/null 2>&1",
           tmpdir, tmpdir, exe);
  assert_int_equal(system(cmd), 0);
}

static void expect_fail(const char *args, const char *const *needles) {
  static char err[8192];
  int rc = run(args, NULL, 0, err, sizeof err);
  if (fb_test_verbose()) fprintf(stderr, "  [%d] %s", rc, err);
  if (rc == 0) fail_msg("'%s' exited 0", args);
  for (int i = 0; needles[i]; i++)
    if (!strstr(err, needles[i])) fail_msg("'%s': stderr '%s' lacks '%s'", args, err, needles[i]);
}

static void test_bad_input_exits_nonzero_with_message(void **state) {
  (void)state;
  char args[1024];
  snprintf(args, sizeof args, "run %s/none.ini --out %s/x", tmpdir, tmpdir);
  expect_fail(args, (const char *[]){"none.ini", "cannot open", NULL});
  const char *p = write_file("malformed.ini", "[linkage]\ncrank_mm 108\n");
  snprintf(args, sizeof args, "run %s --out %s/x", p, tmpdir);
  expect_fail(args, (const char *[]){"malformed.ini:2", "malformed line", NULL});
  p = write_file("unknown.ini", "[drive]\nspeed = 100\n");
  snprintf(args, sizeof args, "run %s --out %s/x", p, tmpdir);
  expect_fail(args, (const char *[]){"unknown.ini:2", "unknown key 'speed'", "speed_rpm", NULL});
  p = write_file("negative.ini", "[linkage]\nfollower_mm = -270.5\n");
  snprintf(args, sizeof args, "run %s --out %s/x", p, tmpdir);
  expect_fail(args, (const char *[]){"negative.ini:2", "follower_mm = -270.5", "positive", NULL});
  p = write_file("apart.ini", "[linkage]\ncrank_mm = 10\ncoupler_mm = 20\nfollower_mm = 20\n"
                              "ground_mm = 500\n");
  snprintf(args, sizeof args, "run %s --out %s/x", p, tmpdir);
  expect_fail(args, (const char *[]){"apart.ini", "cannot be assembled", NULL});
  p = write_file("rocker.ini", "[linkage]\ncrank_mm = 300\ncoupler_mm = 100\nfollower_mm = 250\n"
                               "ground_mm = 350\n");
  snprintf(args, sizeof args, "run %s --out %s/x", p, tmpdir);
  expect_fail(args, (const char *[]){"rocker.ini", "crank cannot turn fully", "deg", NULL});
  expect_fail("run --set drive.speed_rpm=-5 --out /tmp/x",
              (const char *[]){"--set", "speed_rpm = -5", NULL});
  expect_fail("kinematics --crank-mm 108", (const char *[]){"--coupler-mm is required", NULL});
  /* a length flag's -1 is a value, refused as such (it once meant "not given": the case's) */
  expect_fail("kinematics paper_crank_rocker --crank-mm -1",
              (const char *[]){"--crank-mm = -1", "must be positive", NULL});
  expect_fail("kinematics --crank-mm 300 --coupler-mm 100 --follower-mm 250 --ground-mm 350 "
              "--speed-rpm 10", (const char *[]){"double-rocker", "cannot turn fully", NULL});
  expect_fail("penalty --speeds-rpm 0:10:1", (const char *[]){"--speeds-rpm", NULL});
  expect_fail("penalty --mode guess", (const char *[]){"paper or physical", NULL});
  expect_fail("run --jobs 0 --out /tmp/x", (const char *[]){"--jobs 0", "from 1 to 64", NULL});
  expect_fail("check --jobs two", (const char *[]){"--jobs two", "from 1 to 64", NULL});
  expect_fail("impact --restitution 1.5", (const char *[]){"--restitution 1.5", "(0, 1]", NULL});
  expect_fail("impact --law restitution --restitution 0.1", (const char *[]){"critical damping", NULL});
  expect_fail("impact --law bouncy", (const char *[]){"--law 'bouncy'", NULL});
  expect_fail("contact-params --stiffness -5", (const char *[]){"--stiffness -5", "positive", NULL});
  expect_fail("contact-params --mass-kg 0.9:0.1", (const char *[]){"--mass-kg", "A <= B", NULL});
  expect_fail("contact-params --mass-kg 1e-5:1", (const char *[]){"B/A <= ", NULL});
  expect_fail("contact-params --restitution 0.1", (const char *[]){"(0.135, 1]", NULL});
  expect_fail("contact-params --law hertz --damping-n-s-m 5",
              (const char *[]){"--damping-n-s-m", "--restitution", NULL});
  expect_fail("contact-params --h-s -1e-3", (const char *[]){"--h-s", "positive", NULL});
  expect_fail("contact-params --speed-m-s 500", (const char *[]){"--speed-m-s 500", "m/s", NULL});
  expect_fail("contact-params --case two_clearance_joints",
              (const char *[]){"2 clearance joints", "--joint", NULL});
  expect_fail("contact-params --case two_clearance_joints --joint ground-crank",
              (const char *[]){"not a clearance joint", "crank-coupler, coupler-follower", NULL});
  expect_fail("contact-params --case paper_crank_rocker --stiffness 1e8",
              (const char *[]){"from the case", "drop --stiffness", NULL});
  expect_fail("contact-params --joint crank-coupler", (const char *[]){"give --case", NULL});
  expect_fail("contact-params --case no_such_case", (const char *[]){"no_such_case", NULL});
  p = write_file("press.ini", "[pin]\nfit = 30H7/s6\n");
  snprintf(args, sizeof args, "run %s --out %s/x", p, tmpdir);
  expect_fail(args, (const char *[]){"press.ini:2", "interference fit", "clearance joint", NULL});
  /* the shipped press-fit case (issue 31): 30 H7/u6 is refused as bad input */
  snprintf(args, sizeof args, "run %s/press_fit.ini --out %s/x", getenv("FOURBAR_CASES_DIR"),
           tmpdir);
  {
    static char err[8192];
    assert_int_equal(run(args, NULL, 0, err, sizeof err), 2); /* 2: bad input (README) */
    const char *needles[] = {"press_fit.ini:11", "30H7/u6", "interference fit",
                             "an interference fit has no clearance", "-61.0 to -27.0 um", NULL};
    for (int i = 0; needles[i]; i++)
      if (!strstr(err, needles[i])) fail_msg("'%s': stderr '%s' lacks '%s'", args, err, needles[i]);
  }
  p = write_file("both.ini", "[pin]\nfit = 10H7/g6\nradial_clearance_um = 10\n");
  snprintf(args, sizeof args, "run %s --out %s/x", p, tmpdir);
  expect_fail(args, (const char *[]){"both.ini:3", "give one", NULL});
  expect_fail("fit 10Q7/g6", (const char *[]){"letter 'Q'", NULL});
  expect_fail("fit 500.0001H7/g6", (const char *[]){"500.0001 mm", NULL}); /* size as typed */
  expect_fail("fit 1A11/h11", (const char *[]){"A for nominal sizes up to 1 mm", NULL});
  expect_fail("fit 10H7-g6", (const char *[]){"expected <size mm>", NULL});
  expect_fail("tolerance 2 --class v", (const char *[]){"no value", NULL});
  expect_fail("stackup --method guess", (const char *[]){"corners, rss or montecarlo", NULL});
  expect_fail("stackup --jobs 0", (const char *[]){"--jobs 0", "from 1 to", NULL});
  expect_fail("frobnicate", (const char *[]){"unknown command 'frobnicate'", NULL});
  /* nothing was written for the failed runs */
  snprintf(args, sizeof args, "%s/x/summary.json", tmpdir);
  struct stat st;
  assert_int_not_equal(stat(args, &st), 0);
  /* an unwritable output folder is reported before any simulation */
  expect_fail("run --out /proc/fourbar-cannot-write", (const char *[]){"/proc/fourbar-cannot-write", NULL});
}

/* a variant's reference against the paper's published value: the reference
 * is converged to < 1e-6 on these peaks (its error_estimate), so the
 * difference is the model's and the paper's; docs/paper.md quotes -0.13 %
 * (IMPACT, goldsmith) and -0.06 % (POISSON, goldsmith-cr0.14): 0.5 % keeps
 * the claim "closest to the paper's row" honest without pinning digits */
#define PAPER_ROW_REL 5e-3

/* the relative difference a variant's model reports against the paper's
 * coupler omega max */
static double variant_vs_paper(json_t *j, const char *variant, const char *model) {
  json_t *vs = json_object_get(j, "variants");
  for (size_t i = 0; i < json_array_size(vs); i++) {
    json_t *v = json_array_get(vs, i);
    if (strcmp(json_string_value(json_object_get(v, "name")), variant) != 0) continue;
    json_t *ms = json_object_get(v, "models");
    for (size_t k = 0; k < json_array_size(ms); k++) {
      json_t *m = json_array_get(ms, k);
      if (strcmp(json_string_value(json_object_get(m, "name")), model) == 0)
        return json_real_value(json_object_get(
            json_object_get(json_object_get(m, "vs_published"), "coupler"), "omega_max_rel"));
    }
  }
  fail_msg("no variant %s with model %s in summary.json", variant, model);
  return NAN;
}

/* cases/paper_adams.ini (issue 28): the paper's rows printed beside the
 * run's models and its two variants, with the difference in percent */
static void test_paper_adams_rows_and_variants(void **state) {
  (void)state;
  static char out[1 << 17], err[1 << 14];
  char args[1024];
  const char *cases = getenv("FOURBAR_CASES_DIR");
  snprintf(args, sizeof args, "run %s/paper_adams.ini --out %s/adams --no-figures --no-report",
           cases ? cases : "cases", tmpdir);
  const int rc = run(args, out, sizeof out, err, sizeof err);
  if (rc != 0) fail_msg("paper_adams.ini: exit %d: %s", rc, err);
  const char *needles[] = {"published values of the impact law", "published values of the "
                           "restitution law", "goldsmith: reference ", "goldsmith-cr0.14: "
                           "reference-restitution", "134.50", "89.51", " %)", NULL};
  for (int i = 0; needles[i]; i++)
    if (!strstr(out, needles[i])) fail_msg("paper_adams.ini's table lacks '%s'", needles[i]);
  char path[256];
  snprintf(path, sizeof path, "%s/adams/summary.json", tmpdir);
  json_error_t je;
  json_t *j = json_load_file(path, 0, &je);
  if (!j) fail_msg("summary.json does not parse: %s", je.text);
  assert_near(json_real_value(json_object_get(json_object_get(json_object_get(
                  json_object_get(j, "published"), "impact"), "coupler"), "omega_max_rad_s")),
              134.50, 0.0);
  const double imp = variant_vs_paper(j, "goldsmith", "reference");
  const double poi = variant_vs_paper(j, "goldsmith-cr0.14", "reference-restitution");
  if (fb_test_verbose()) fprintf(stderr, "  goldsmith %+.3e, goldsmith-cr0.14 %+.3e\n", imp, poi);
  assert_true(fabs(imp) < PAPER_ROW_REL);
  assert_true(fabs(poi) < PAPER_ROW_REL);
  /* the case's own reference (the paper's Table II stiffness) is far off:
   * the comparison can fail */
  json_t *ms = json_object_get(j, "models");
  for (size_t i = 0; i < json_array_size(ms); i++) {
    json_t *m = json_array_get(ms, i);
    if (strcmp(json_string_value(json_object_get(m, "name")), "reference") == 0)
      assert_true(fabs(json_real_value(json_object_get(json_object_get(
                      json_object_get(m, "vs_published"), "coupler"), "omega_max_rel"))) > 0.1);
  }
  json_decref(j);
}

/* cases/engines.ini: both engines in one run, or, in a build without MuJoCo,
 * a refusal that says how to get it */
static void test_engines_case(void **state) {
  (void)state;
  /* --json holds each clearance model's matched impacts (issue 25): ~90 kB */
  static char out[1 << 19], err[1 << 16];
  char args[1024];
  const char *cases = getenv("FOURBAR_CASES_DIR");
  snprintf(args, sizeof args, "run %s/engines.ini --set run.revolutions=2 --out %s/engines --json",
           cases ? cases : "cases", tmpdir);
  /* its [run] models are patterns (*-ideal-nominal, ...): a build without
   * MuJoCo runs the ODE rows alone */
  const int rc = run(args, out, sizeof out, err, sizeof err);
  if (rc != 0) fail_msg("engines.ini: exit %d: %s", rc, err);
  json_error_t je;
  json_t *j = json_loads(out, 0, &je);
  if (!j) fail_msg("--json output does not parse: %s", je.text);
  int kinds[2] = {0, 0};
  json_t *m;
  size_t i;
  json_array_foreach(json_object_get(j, "models"), i, m) {
    const char *kind = json_string_value(json_object_get(m, "kind"));
    assert_string_equal(json_string_value(json_object_get(m, "status")), "ok");
    if (strcmp(kind, "ode") == 0) kinds[0]++;
    if (strcmp(kind, "mujoco") == 0) {
      kinds[1]++;
      assert_non_null(json_object_get(json_object_get(m, "mujoco"), "integrator"));
    }
  }
  assert_int_equal(kinds[0], 3);
  assert_int_equal(kinds[1], FB_HAVE_MUJOCO ? 3 : 0);
  json_decref(j);
  /* a MuJoCo model named outright is refused by such a build, saying how to enable it */
  if (!FB_HAVE_MUJOCO)
    expect_fail("run --set run.models=mujoco-ideal-nominal --out /tmp/x",
                (const char *[]){"mujoco-ideal-nominal", "libmujoco-dev", "-Dmujoco=enabled",
                                 NULL});
}

/* a help text fits a terminal of HELP_COLUMNS columns */
#define HELP_COLUMNS 80
static void expect_width(const char *cmd, const char *text) {
  for (const char *line = text; *line;) {
    const char *end = strchr(line, '\n');
    const size_t n = end ? (size_t)(end - line) : strlen(line);
    if (n > HELP_COLUMNS)
      fail_msg("%s --help: a line of %zu columns (at most %d): '%.*s'", cmd, n, HELP_COLUMNS,
               (int)n, line);
    line += n + (end != NULL);
  }
}

static void test_help_answers(void **state) {
  (void)state;
  static char out[8192];
  assert_int_equal(run("run --help", out, sizeof out, NULL, 0), 0);
  assert_non_null(strstr(out, "--set"));
  assert_int_equal(run("kinematics --help", out, sizeof out, NULL, 0), 0);
  assert_non_null(strstr(out, "--branch"));
  /* kinematics takes every description's lengths as flags, and its help
   * names them and every type */
  for (int t = 0; t < FB_MECH_COUNT; t++) {
    const fb_mech_desc *m = fb_mech_of((fb_mech_type)t);
    if (!strstr(out, m->type)) fail_msg("kinematics --help does not name the %s", m->type);
    for (int i = 0; i < m->nlengths; i++) {
      char flag[64], args[128];
      static char err[4096];
      snprintf(flag, sizeof flag, "--%s-mm", m->length[i]);
      if (!strstr(out, flag)) fail_msg("kinematics --help lacks %s (the %s's)", flag, m->type);
      snprintf(args, sizeof args, "kinematics --type %s %s 1", m->type, flag);
      run(args, NULL, 0, err, sizeof err);
      if (strstr(err, "unknown option")) fail_msg("'%s': %s", args, err);
    }
  }
  assert_int_equal(run("--help", out, sizeof out, NULL, 0), 0);
  assert_non_null(strstr(out, "kinematics"));
  /* every command answers --help with its usage and its exit status */
  static const char *const cmds[] = {"run", "kinematics", "stackup", "fit", "tolerance", "penalty",
                                     "impact", "check", "sweep", "merge", "mapping", "bench",
                                     "contact-params", "export", "models", NULL};
  for (int i = 0; cmds[i]; i++) {
    char args[64], usage[64];
    snprintf(args, sizeof args, "%s --help", cmds[i]);
    snprintf(usage, sizeof usage, "usage: fourbar %s", cmds[i]);
    static char text[16384];
    assert_int_equal(run(args, text, sizeof text, NULL, 0), 0);
    if (!strstr(text, usage)) fail_msg("%s --help lacks '%s'", cmds[i], usage);
    if (!strstr(text, "Exit status")) fail_msg("%s --help does not state its exit status", cmds[i]);
    expect_width(cmds[i], text);
  }
  assert_int_equal(run("--help", out, sizeof out, NULL, 0), 0);
  expect_width("fourbar", out);
}

/* fourbar models lists the model table: the same names, in the same order,
 * as the list `run` gives for an unknown model (fb_model_list, another path
 * through the table); one Markdown row per model; an engine the build lacks
 * has its models marked unavailable and its how-to; a stray argument is bad
 * input */
static void test_models_lists_the_table(void **state) {
  (void)state;
  static char out[65536], err[8192];
  assert_int_equal(run("run --set run.models=no-such-model", NULL, 0, err, sizeof err), 2);
  const char *known = strstr(err, "known: ");
  assert_non_null(known);
  known += strlen("known: ");
  assert_int_equal(run("models --json", out, sizeof out, NULL, 0), 0);
  json_error_t jerr;
  json_t *j = json_loads(out, 0, &jerr);
  if (!j) fail_msg("models --json is not JSON: %s", jerr.text);
  json_t *models = json_object_get(j, "models"), *engines = json_object_get(j, "engines");
  assert_true(json_array_size(models) > 0);
  size_t i;
  json_t *m;
  const char *at = known;
  json_array_foreach(models, i, m) {
    const char *name = json_string_value(json_object_get(m, "name"));
    const size_t n = strlen(name);
    if (strncmp(at, name, n) != 0 || (at[n] != ',' && at[n] != ')'))
      fail_msg("models row %zu '%s' is not next in run's list '%s'", i, name, known);
    at += n + (at[n] == ',' ? 2 : 0);
    const char *engine = json_string_value(json_object_get(m, "engine"));
    json_t *e;
    size_t k;
    int found = 0;
    json_array_foreach(engines, k, e) {
      if (strcmp(json_string_value(json_object_get(e, "name")), engine) != 0) continue;
      found = 1;
      assert_int_equal(json_is_true(json_object_get(m, "available")),
                       json_is_true(json_object_get(e, "available")));
      assert_int_equal(json_is_null(json_object_get(e, "howto")),
                       json_is_true(json_object_get(e, "available")));
    }
    if (!found) fail_msg("model '%s' names engine '%s', which engines lacks", name, engine);
    const int clear = strcmp(json_string_value(json_object_get(m, "joints")), "clearance") == 0;
    if (clear == (strcmp(json_string_value(json_object_get(m, "law")), "none") == 0))
      fail_msg("model '%s': clearance joints and a contact law go together", name);
  }
  assert_int_equal(*at, ')');
  const size_t count = json_array_size(models);
  json_decref(j);
  assert_int_equal(run("models", out, sizeof out, NULL, 0), 0);
  size_t rows = 0;
  for (const char *line = out; line && *line; line = strchr(line, '\n') ? strchr(line, '\n') + 1 : NULL)
    if (strncmp(line, "| ", 2) == 0) {
      rows++;
      int bars = 0; /* a row's cell borders: a '|' inside a cell is escaped '\|' */
      for (const char *c = line; *c && *c != '\n'; c++) bars += *c == '|' && (c == line || c[-1] != '\\');
      if (bars != 11) fail_msg("models: a row of %d cell borders, not 11: %.*s", bars,
                               (int)strcspn(line, "\n"), line);
    }
  assert_int_equal(rows, count + 1); /* the header and one row per model */
  assert_int_equal(run("models --bogus", NULL, 0, err, sizeof err), 2);
  assert_non_null(strstr(err, "--bogus"));
}

/* --set without --out writes into results/<case>/ and says so, the second
 * time that it replaced a run; the fit/clearance clash names the way out */
static void test_set_without_out_says_so(void **state) {
  (void)state;
  char dir[256], cmd[8192], path[300];
  snprintf(dir, sizeof dir, "%s/cwd", tmpdir);
  mkdir(dir, 0755);
  static char err[1 << 14];
  for (int pass = 0; pass < 2; pass++) {
    snprintf(cmd, sizeof cmd, "cd %s && %s run --no-figures --set run.revolutions=2 --set run.models=analytic "
             ">/dev/null 2>err.txt", dir, exe);
    assert_int_equal(WEXITSTATUS(system(cmd)), 0);
    snprintf(path, sizeof path, "%s/err.txt", dir);
    FILE *f = fopen(path, "r");
    assert_non_null(f);
    err[fread(err, 1, sizeof err - 1, f)] = '\0';
    fclose(f);
    if (!strstr(err, "--set without --out") || !strstr(err, "results/paper_crank_rocker/"))
      fail_msg("pass %d: no note about --set without --out: %s", pass, err);
    if (pass == 1 && !strstr(err, "replacing the run that was there"))
      fail_msg("second run does not say it replaced the first: %s", err);
  }
  /* with --out: no note */
  snprintf(cmd, sizeof cmd, "cd %s && %s run --no-figures --out other --set run.revolutions=2 "
           "--set run.models=analytic >/dev/null 2>err.txt && ! grep -q 'without --out' err.txt", dir, exe);
  assert_int_equal(WEXITSTATUS(system(cmd)), 0);
  static char out[1 << 14];
  assert_int_equal(run("run --no-figures --set pin.radial_clearance_um=10", out, sizeof out, err, sizeof err), 2);
  assert_non_null(strstr(err, "pin.fit=none"));
}

/* the printed loads table names the window its peaks come from: the steady
 * window by default, the whole run with [run] peaks = all (it once said
 * "after the first revolution" for both) */
static void test_loads_table_names_its_window(void **state) {
  (void)state;
  static char out[1 << 16];
  char args[512];
  snprintf(args, sizeof args, "run --no-figures --out %s/loads_steady --set run.revolutions=2 "
           "--set run.models=analytic", tmpdir);
  assert_int_equal(run(args, out, sizeof out, NULL, 0), 0);
  if (!strstr(out, "loads (peaks over the revolutions after the first;"))
    fail_msg("steady window: loads header does not name it:\n%s", out);
  snprintf(args, sizeof args, "run --no-figures --out %s/loads_all --set run.revolutions=1 "
           "--set run.peaks=all --set run.models=analytic", tmpdir);
  assert_int_equal(run(args, out, sizeof out, NULL, 0), 0);
  if (!strstr(out, "loads (peaks over the whole run;"))
    fail_msg("peaks = all: loads header does not name the whole run:\n%s", out);
}

/* a default quoted in --help is the one the command uses: mapping's
 * effective mass (help rounds it to 3 significant digits) */
#define HELP_DEFAULT_ROUNDING_REL 1e-3
static void test_mapping_help_default_mass(void **state) {
  (void)state;
  static char out[1 << 16];
  assert_int_equal(run("mapping --help", out, sizeof out, NULL, 0), 0);
  const char *q = strstr(out, "--mass-kg        effective mass");
  assert_non_null(q);
  const char *p = strstr(q, "(default ");
  assert_non_null(p);
  const double help_m = atof(p + strlen("(default "));
  assert_int_equal(run("mapping --json", out, sizeof out, NULL, 0), 0);
  json_error_t e;
  json_t *j = json_loads(out, 0, &e);
  assert_non_null(j);
  const double m = json_real_value(json_object_get(j, "mass_kg"));
  json_decref(j);
  if (!(fabs(help_m - m) <= HELP_DEFAULT_ROUNDING_REL * m))
    fail_msg("mapping --help says default mass %g kg, the command uses %g kg", help_m, m);
}

/* An own four-bar that gives no masses and no drive: each link is the default
 * bar (20 x 6.5 mm steel, docs/keys.md), by hand crank 60 mm: m = 7800 *
 * 0.02 * 0.0065 * 0.06 = 0.06084 kg, I = m (0.06^2 + 0.02^2) / 12 =
 * 0.06084 * 0.004 / 12 = 2.028e-5 kg m^2; coupler 160 mm: m = 0.16224 kg,
 * I = 0.16224 * 0.0260 / 12 = 3.5152e-4 kg m^2. The run lists them as
 * derived in summary.json, report.md and the printed header, and report.md
 * no longer says "case" for the drive the case never set. */
static void test_own_fourbar_derived_masses(void **state) {
  (void)state;
  const char *path = write_file("own.ini",
                                "[case]\nname = own\n[linkage]\ncrank_mm = 60\ncoupler_mm = 160\n"
                                "follower_mm = 140\nground_mm = 150\n[clearance]\njoints = none\n"
                                "[run]\nrevolutions = 2\nmodels = analytic, ode-ideal-nominal\n");
  static char out[1 << 16], err[1 << 14];
  char args[1024];
  snprintf(args, sizeof args, "run --no-figures --out %s/own %s", tmpdir, path);
  if (run(args, out, sizeof out, err, sizeof err) != 0) fail_msg("own case failed: %s", err);
  if (!strstr(out, "link masses: crank 0.06084 kg, I 20.28 kg mm^2") || !strstr(out, "(derived"))
    fail_msg("the printed header does not list the derived masses:\n%s", out);
  char p[512];
  snprintf(p, sizeof p, "%s/own/summary.json", tmpdir);
  json_error_t je;
  json_t *j = json_load_file(p, 0, &je);
  if (!j) fail_msg("summary.json does not parse: %s", je.text);
  json_t *links = json_object_get(json_object_get(j, "masses"), "links");
  assert_int_equal(json_array_size(links), 3);
  const double mass[2] = {0.06084, 0.16224}, inertia[2] = {2.028e-5, 3.5152e-4};
  for (int i = 0; i < 2; i++) {
    json_t *l = json_array_get(links, (size_t)i);
    assert_rel(json_real_value(json_object_get(l, "mass_kg")), mass[i], JSON12_REL_TOL);
    assert_rel(json_real_value(json_object_get(l, "inertia_kg_m2")), inertia[i], JSON12_REL_TOL);
    assert_string_equal(json_string_value(json_object_get(l, "mass_source")), "derived");
    assert_string_equal(json_string_value(json_object_get(l, "inertia_source")), "derived");
    assert_string_equal(json_string_value(json_object_get(l, "com_fraction_source")), "default");
  }
  assert_string_equal(json_string_value(json_object_get(json_object_get(j, "masses"),
                                                        "density_source")), "default");
  json_decref(j);
  snprintf(p, sizeof p, "%s/own/report.md", tmpdir);
  FILE *f = fopen(p, "r");
  assert_non_null(f);
  static char md[1 << 16];
  md[fread(md, 1, sizeof md - 1, f)] = '\0';
  fclose(f);
  if (!strstr(md, "| crank mass | 0.06084 kg | derived |"))
    fail_msg("report.md does not list the derived crank mass:\n%s", md);
  if (!strstr(md, "| crank speed | 1000 rpm cw | default |"))
    fail_msg("report.md gives a source other than default for the drive the case never set");
}

/* The printed run table (issue 30): a verdict per model first, every line
 * at most 120 columns with the longest model name of the build, the peaks
 * printed once, the clearance effect not called an error; the terminal is
 * the oracle's width */
#define TABLE_COLUMNS 120
/* with an ensemble in worker processes, timing.json counts its members too */
static void test_timing_counts_an_ensemble(void **state) {
  (void)state;
  static char out[1 << 16], err[1 << 14];
  char args[512];
  snprintf(args, sizeof args, "run --out %s/ens --set run.revolutions=2 --set run.ensemble=3 "
           "--set run.models=ode-clearance-impact,reference --jobs 2 --no-figures --no-report "
           "--series none", tmpdir);
  const double t0 = now_s();
  if (run(args, out, sizeof out, err, sizeof err) != 0) fail_msg("%s", err);
  check_timing("ens", now_s() - t0, last_line_of(out));
  char path[256];
  snprintf(path, sizeof path, "%s/ens/timing.json", tmpdir);
  json_t *t = json_load_file(path, 0, NULL);
  assert_non_null(t);
  json_t *parts = json_object_get(t, "parts");
  /* the members ran, and the reference's check integration (not theirs) */
  assert_true(json_real_value(json_object_get(parts, "ensemble")) > 0.0);
  assert_true(json_real_value(json_object_get(parts, "reference.check")) > 0.0);
  assert_true(json_real_value(json_object_get(parts, "ode-clearance-impact.check")) == 0.0);
  json_decref(t);
}

static void test_run_table_fits_and_says_it_once(void **state) {
  (void)state;
  static char out[1 << 16], err[1 << 14];
  char args[512];
  snprintf(args, sizeof args,
           "run --no-figures --out %s/table --set run.revolutions=1 --set run.peaks=all "
           "--set run.models=analytic,ode-clearance-impact,reference%s",
           tmpdir, FB_HAVE_MUJOCO ? ",mujoco-clearance-restitution" : "");
  if (run(args, out, sizeof out, err, sizeof err) != 0) fail_msg("run failed: %s", err);
  int lineno = 0;
  for (const char *p = out; *p;) {
    const char *nl = strchr(p, '\n');
    const size_t len = nl ? (size_t)(nl - p) : strlen(p);
    lineno++;
    if (len > TABLE_COLUMNS) fail_msg("line %d is %zu columns wide:\n%.*s", lineno, len, (int)len, p);
    p = nl ? nl + 1 : p + len;
  }
  /* the verdict is the first table, before the header's stack-up lines */
  const char *verdict = strstr(out, "\nverdict (");
  const char *stackup = strstr(out, "stack-up corner");
  if (!verdict || !stackup || verdict > stackup) fail_msg("the verdict does not come first:\n%s", out);
  assert_non_null(strstr(verdict, "\nanalytic "));
  assert_null(strstr(out, "peak err vs exact"));
  assert_null(strstr(out, "angular velocity, rad/s\n")); /* the old second copy of the peaks */
  assert_non_null(strstr(out, "clearance effect"));
  /* the model column holds the longest name: its row's verdict column
   * starts where the header's does */
  const char *name = FB_HAVE_MUJOCO ? "mujoco-clearance-restitution" : "ode-clearance-impact";
  const char *row = strstr(verdict, name);
  assert_non_null(row);
  assert_true(row[strlen(name)] == ' ');
  /* each model's coupler omega max appears once, in the peaks table */
  json_error_t je;
  char path[512];
  snprintf(path, sizeof path, "%s/table/summary.json", tmpdir);
  json_t *j = json_load_file(path, 0, &je);
  assert_non_null(j);
  json_t *m0 = json_array_get(json_object_get(j, "models"), 0);
  char peak[32];
  snprintf(peak, sizeof peak, " %.4f ", json_real_value(json_object_get(json_object_get(m0, "coupler"), "omega_max_rad_s")));
  const char *first = strstr(out, peak);
  if (!first || strstr(first + 1, peak)) fail_msg("'%s' is not printed exactly once:\n%s", peak, out);
  json_decref(j);
}

/* an unknown option is one line naming it and pointing at --help, exit 2
 * (it printed the whole help) */
static void test_unknown_option_is_one_line(void **state) {
  (void)state;
  static char out[1 << 14], err[1 << 14];
  const char *cmds[] = {"run --bogus", "stackup --nope=3", "sweep -q", "fit --zzz 10H7/g6"};
  const char *names[] = {"'--bogus'", "'--nope'", "'-q'", "'--zzz'"};
  for (size_t i = 0; i < sizeof cmds / sizeof cmds[0]; i++) {
    assert_int_equal(run(cmds[i], out, sizeof out, err, sizeof err), 2);
    const char *nl = strchr(err, '\n');
    if (!nl || nl[1] != '\0') fail_msg("%s: not one line:\n%s", cmds[i], err);
    if (!strstr(err, names[i]) || !strstr(err, "--help") || strstr(err, "usage:"))
      fail_msg("%s: %s", cmds[i], err);
  }
  assert_int_equal(run("run --out", out, sizeof out, err, sizeof err), 2);
  assert_non_null(strstr(err, "'--out' needs a value"));
}

/* stackup prints all four length sensitivities of every output, with the
 * unit, equal to --json's sensitivity_per_m (printed with 5 digits) */
#define SENS_PRINT_REL 5e-5
static void test_stackup_prints_every_sensitivity(void **state) {
  (void)state;
  static char out[1 << 16], err[1 << 14];
  assert_int_equal(run("stackup --method corners", out, sizeof out, err, sizeof err), 0);
  const char *t = strstr(out, "\nsensitivities ");
  assert_non_null(t);
  const char *row = strstr(t, "\ncoupler_alpha_max_rad_s2 ");
  assert_non_null(row);
  double v[4];
  char unit[32];
  assert_int_equal(sscanf(row, " coupler_alpha_max_rad_s2 %lf %lf %lf %lf %31[^\n]", &v[0], &v[1], &v[2], &v[3], unit), 5);
  assert_string_equal(unit, "rad/s^2 per m");
  assert_int_equal(run("stackup --method corners --json", out, sizeof out, err, sizeof err), 0);
  json_error_t je;
  json_t *j = json_loads(out, 0, &je);
  assert_non_null(j);
  json_t *outs = json_object_get(j, "outputs");
  const char *links[4] = {"crank", "coupler", "follower", "ground"};
  for (size_t i = 0; i < json_array_size(outs); i++) {
    json_t *o = json_array_get(outs, i);
    if (strcmp(json_string_value(json_object_get(o, "name")), "coupler_alpha_max_rad_s2") != 0) continue;
    for (int k = 0; k < 4; k++) {
      const double want = json_real_value(json_object_get(json_object_get(o, "sensitivity_per_m"), links[k]));
      assert_rel(v[k], want, SENS_PRINT_REL);
    }
  }
  json_decref(j);
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: test_cli PATH_TO_FOURBAR\n");
    return 2;
  }
  exe = argv[1];
  snprintf(tmpdir, sizeof tmpdir, "/tmp/fb_cli_XXXXXX");
  if (!mkdtemp(tmpdir)) return 2;
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_paper_case_runs_and_writes_summary),
      cmocka_unit_test(test_json_flag_and_kinematics),
      cmocka_unit_test(test_penalty_and_impact_json),
      cmocka_unit_test(test_fit_tolerance_stackup_json),
      cmocka_unit_test(test_contact_params_json),
      cmocka_unit_test(test_contact_params_case),
      cmocka_unit_test(test_contact_params_coarse_step),
      cmocka_unit_test(test_penalty_contact_is_the_runs),
      cmocka_unit_test(test_check_catches_stiffness_regression),
      cmocka_unit_test(test_bad_input_exits_nonzero_with_message),
      cmocka_unit_test(test_engines_case),
      cmocka_unit_test(test_paper_adams_rows_and_variants),
      cmocka_unit_test(test_help_answers),
      cmocka_unit_test(test_models_lists_the_table),
      cmocka_unit_test(test_set_without_out_says_so),
      cmocka_unit_test(test_loads_table_names_its_window),
      cmocka_unit_test(test_mapping_help_default_mass),
      cmocka_unit_test(test_own_fourbar_derived_masses),
      cmocka_unit_test(test_run_table_fits_and_says_it_once),
      cmocka_unit_test(test_timing_counts_an_ensemble),
      cmocka_unit_test(test_unknown_option_is_one_line),
      cmocka_unit_test(test_stackup_prints_every_sensitivity),
      cmocka_unit_test(test_bench_peers_json),
  };
  int rc = cmocka_run_group_tests(tests, NULL, NULL);
  char cmd[128];
  snprintf(cmd, sizeof cmd, "rm -rf %s", tmpdir);
  if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", tmpdir);
  return rc;
}
