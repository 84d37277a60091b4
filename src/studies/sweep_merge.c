/* Merge: shards' rows joined and checked (sweep_merge.h). */
#define _POSIX_C_SOURCE 200809L
#include "sweep_merge.h"

#include <dirent.h>
#include <errno.h>
#include <jansson.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fileio.h"
#include "manifest.h"
#include "outdir.h"
#include "sweep_rows.h"

/* the rows read and their shards' common provenance */
typedef struct {
  fb_sweep_rowset all;
  json_t *prov;             /* the first file's provenance */
  char prov_from[8300];     /* its path */
  char prov_problem[20000]; /* the first provenance that is missing or differs ("": none) */
} merge_state;

/* 1 when the folder's points.jsonl is a merge's output (its provenance says so) */
static int merged_output(const char *dir) {
  char path[4300];
  snprintf(path, sizeof path, "%s/points.provenance.json", dir);
  json_t *p = json_load_file(path, 0, NULL);
  const int merged = json_is_true(json_object_get(p, "merged"));
  json_decref(p);
  return merged;
}

/* the provenance beside the rows file at path, compared with the first
 * one's: all equal, so rows of two studies, builds or environments are
 * never mixed (the first problem is reported after the rows' own checks) */
static void take_provenance(merge_state *m, const char *path) {
  char pp[8300];
  fb_sweep_rows_beside(pp, sizeof pp, path, ".provenance.json");
  json_t *p = json_load_file(pp, 0, NULL);
  char what[3000];
  if (m->prov_problem[0]) {
    /* the first problem is reported, after the rows' own checks */
  } else if (!p) {
    snprintf(m->prov_problem, sizeof m->prov_problem, "%s: its provenance %s is missing or "
             "unreadable, so which study its rows belong to is unknown: run that shard again "
             "(with --restart)", path, pp);
  } else if (!m->prov) {
    m->prov = p;
    snprintf(m->prov_from, sizeof m->prov_from, "%s", pp);
    p = NULL;
  } else if (fb_study_provenance_differs(m->prov, p, what, sizeof what)) {
    snprintf(m->prov_problem, sizeof m->prov_problem, "%s and %s: not one study's shards: %s",
             m->prov_from, pp, what);
  }
  json_decref(p);
}

/* the rows of every points*.jsonl in folder dir into m; out_real: the
 * output folder's real path. Returns the exit status. */
static int read_folder(merge_state *m, const char *dir, const char *out, const char *out_real) {
  DIR *dd = opendir(dir);
  if (!dd) return fb_study_fail("merge", 2, "%s: %s", dir, strerror(errno));
  char real[PATH_MAX];
  const int is_out = realpath(dir, real) && strcmp(real, out_real) == 0;
  struct dirent *e;
  int rc = 0;
  while (!rc && (e = readdir(dd))) {
    size_t l = strlen(e->d_name);
    if (strncmp(e->d_name, "points", 6) != 0 || l < 6 || strcmp(e->d_name + l - 6, ".jsonl") != 0) continue;
    char path[8192];
    snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
    if (strcmp(e->d_name, "points.jsonl") == 0 && merged_output(dir))
      continue; /* a previous merge's output: merged again from the shards */
    if (strcmp(e->d_name, "points.jsonl") == 0 && is_out) {
      rc = fb_study_fail("merge", 2, "%s holds a sweep's own rows (not a merge's output), which "
                         "merging into %s would replace: give another --out", path, out);
      break;
    }
    char err[9000];
    if (fb_sweep_rows_read(path, &m->all, 0, err, sizeof err) != 0) {
      rc = fb_study_fail("merge", 2, "%s", err);
      break;
    }
    take_provenance(m, path);
  }
  closedir(dd);
  return rc;
}

/* the rows are one study's grid, each point 0..N-1 once; returns the exit status */
static int check_points(const fb_sweep_rowset *all) {
  int rc = 0;
  size_t of = 0;
  fb_study_row_index(all->rows[0], &of); /* every row read was checked: 1 <= of <= 1e7 */
  unsigned char *count = calloc(of, 1);
  if (!count) return fb_study_fail("merge", 1, "out of memory for %zu points", of);
  json_t *row0 = json_loads(all->rows[0], 0, NULL);
  char study0[256];
  snprintf(study0, sizeof study0, "%s", json_string_value(json_object_get(row0, "study")));
  json_decref(row0);
  for (size_t k = 0; k < all->n && !rc; k++) {
    size_t o2 = 0;
    long i = fb_study_row_index(all->rows[k], &o2);
    json_t *row = json_loads(all->rows[k], 0, NULL); /* checked when read: "study" is a string */
    char study[256];
    snprintf(study, sizeof study, "%s", json_string_value(json_object_get(row, "study")));
    json_decref(row);
    if (strcmp(study, study0) != 0)
      rc = fb_study_fail("merge", 2, "rows of studies '%s' and '%s': not one study", study0, study);
    else if (o2 != of) rc = fb_study_fail("merge", 2, "rows of a %zu-point and a %zu-point grid: not one study", of, o2);
    else if (i < 0 || (size_t)i >= of) rc = fb_study_fail("merge", 2, "row index %ld outside 0..%zu", i, of - 1);
    else if (count[i]++) rc = fb_study_fail("merge", 2, "point %ld appears more than once", i);
  }
  if (!rc) {
    size_t missing = 0, first = 0;
    for (size_t i = 0; i < of; i++)
      if (!count[i] && missing++ == 0) first = i;
    if (missing) rc = fb_study_fail("merge", 2, "%zu of %zu points missing (first: %zu): run the missing "
                                    "shards, then merge again", missing, of, first);
  }
  free(count);
  return rc;
}

/* rows, their provenance (marked as a merge's), then the table, and the
 * figure of study st (NULL: none); returns the exit status */
static int write_merged(const fb_merge_opts *o, merge_state *m, const fb_study *st) {
  const char *out = o->out;
  char path[4200];
  fb_diag d;
  int rc = 0;
  snprintf(path, sizeof path, "%s/points.jsonl", out);
  fb_outfile f;
  if (fb_outfile_open(&f, path, &d) != FB_OK) {
    rc = fb_study_fail("merge", 1, "%s", d.msg);
  } else {
    for (size_t k = 0; k < m->all.n; k++) fputs(m->all.rows[k], f.f);
    if (fb_outfile_commit(&f, &d) != FB_OK) rc = fb_study_fail("merge", 1, "%s", d.msg);
  }
  json_object_set_new(m->prov, "merged", json_true());
  snprintf(path, sizeof path, "%s/points.provenance.json", out);
  if (!rc && o->write_json(path, m->prov, &d) != FB_OK) rc = fb_study_fail("merge", 1, "%s", d.msg);
  snprintf(path, sizeof path, "%s/points.csv", out);
  if (!rc && fb_study_write_csv(path, m->all.rows, m->all.n, &d) != FB_OK)
    rc = fb_study_fail("merge", 1, "%s", d.msg);
  if (!rc) printf("merged %zu points into %s/points.jsonl and points.csv\n", m->all.n, out);
  if (!rc && st) {
    if (o->draw(st, out, &d) != FB_OK) rc = fb_study_fail("merge", 1, "%s", d.msg);
    else printf("drew %s/study.svg\n", out);
  }
  return rc;
}

int fb_sweep_merge(const fb_merge_opts *o) {
  /* the output folder, locked before anything is read: no shard may be
   * writing it; compared by its real path, not its spelling (D and D/) */
  static fb_outdir od;
  fb_diag d;
  const fb_status lst = fb_outdir_lock(&od, o->out, 0, NULL, &d);
  if (lst != FB_OK) return fb_study_fail("merge", lst == FB_ERR_ARG ? 2 : 1, "%s", d.msg);
  char out_real[PATH_MAX];
  if (!realpath(o->out, out_real)) snprintf(out_real, sizeof out_real, "%s", od.target);
  /* a study given to draw with must be the shards' study: loaded first */
  static fb_study st;
  json_t *study_prov = NULL;
  if (o->study_path) {
    if (fb_study_load_with_cases(&st, o->study_path, o->cases_dir, &d) != FB_OK)
      return fb_study_fail("merge", 2, "--study: %s", d.msg);
    study_prov = fb_study_provenance(&st);
    json_object_set_new(study_prov, "fourbar_version", json_string(o->version));
  }
  static merge_state m;
  memset(&m, 0, sizeof m);
  int rc = 0;
  for (int a = 0; a < o->ndirs && !rc; a++) rc = read_folder(&m, o->dirs[a], o->out, out_real);
  if (!rc && m.all.n == 0) rc = fb_study_fail("merge", 2, "no points*.jsonl rows in the given folders");
  if (!rc) rc = check_points(&m.all);
  if (!rc && m.prov_problem[0]) rc = fb_study_fail("merge", 2, "%s", m.prov_problem);
  char what[3000];
  if (!rc && study_prov && fb_study_provenance_differs(m.prov, study_prov, what, sizeof what))
    rc = fb_study_fail("merge", 2, "--study %s is not the study of these shards (%s): give the "
                       "study file they were computed from", o->study_path, what);
  /* its files: replaced only when a sweep wrote them, or asked (fileio.h) */
  static const char *const names[4] = {"points.jsonl", "points.provenance.json", "points.csv",
                                       "study.svg"};
  const fb_outpath_rule rule = {.flag = "--out", .overwrite = o->overwrite};
  if (!rc && fb_outfiles_check(o->out, "sweep", names, 4, &rule, &d) != FB_OK)
    rc = fb_study_fail("merge", 2, "%s", d.msg);
  if (!rc && fb_manifest_record(od.target, "sweep", names, 4, &d) != FB_OK)
    rc = fb_study_fail("merge", 1, "%s", d.msg);
  if (!rc) rc = write_merged(o, &m, o->study_path ? &st : NULL);
  json_decref(m.prov);
  json_decref(study_prov);
  fb_sweep_rows_free(&m.all);
  fb_outdir_release(&od);
  return rc;
}
