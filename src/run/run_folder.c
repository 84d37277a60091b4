/* A case run into its output folder (run_folder.h). */
#include "run_folder.h"

#include <stdio.h>
#include <sys/stat.h>

#include "manifest.h"
#include "clock.h"
#include "outdir.h"
#include "textsafe.h"

/* what the commit kept of the old folder (outdir.h), said on stderr */
static void say_kept(const fb_outdir *od, const char *esc_dir) {
  if (!od->kept_n) return;
  char names[4 * sizeof od->kept];
  fb_text_escape(names, sizeof names, od->kept);
  if (od->legacy)
    fprintf(stderr, "fourbar run: note: %s had no %s (an older fourbar wrote it), so nothing in it "
            "is provably a run's: kept its %d file%s this run did not write again: %s; delete "
            "those that are stale\n", esc_dir, FB_MANIFEST_NAME, od->kept_n,
            od->kept_n > 1 ? "s" : "", names);
  else
    fprintf(stderr, "fourbar run: note: %s: kept %d file%s no fourbar command wrote there (%s "
            "lists what fourbar wrote): %s\n", esc_dir, od->kept_n, od->kept_n > 1 ? "s" : "",
            FB_MANIFEST_NAME, names);
}

fb_run_folder_result fb_folder_run(const fb_folder_job *j, int *write_rc, fb_diag *diag) {
  *write_rc = 0;
  /* one writer per folder; the whole set goes to a staging folder beside it,
   * swapped in at the end (outdir.h): both checked before any simulation */
  static fb_outdir od;
  fb_status st = fb_outdir_lock(&od, j->dir, 1, NULL, diag);
  struct stat sb;
  const int existed = st == FB_OK && stat(od.target, &sb) == 0;
  if (st == FB_OK) st = fb_outdir_stage(&od, diag);
  if (st != FB_OK) {
    fb_outdir_release(&od);
    return st == FB_ERR_ARG ? FB_RUN_FOLDER_BAD : FB_RUN_FOLDER_DIR;
  }
  /* stopped by a signal: what the folder keeps and the command that runs it again */
  static char note_text[4 * 4096 + 64], note_tail[8192 + 64], esc_dir[4 * 4096];
  fb_text_escape(esc_dir, sizeof esc_dir, j->dir);
  snprintf(note_text, sizeof note_text, existed ? "%s keeps the results it held (nothing of this "
           "run was written)" : "%s was not created (nothing of this run was written)", esc_dir);
  snprintf(note_tail, sizeof note_tail, "; to run it again: %s", j->again);
  fb_cleanup_note("fourbar run: stopped", note_text, NULL, note_tail);

  st = j->run(j->user, diag);
  if (st != FB_OK) {
    fb_outdir_release(&od);
    return FB_RUN_FOLDER_RUN;
  }
  *write_rc = j->write(od.stage, j->user);
  if (*write_rc) {
    j->discard(j->user);
    fb_outdir_release(&od);
    return FB_RUN_FOLDER_WRITE;
  }
  st = fb_outdir_commit(&od, diag);
  if (st == FB_OK) { /* a signal from here on finds this run's set in place */
    snprintf(note_text, sizeof note_text, "%s holds this run's results, whole", esc_dir);
    fb_cleanup_note("fourbar run: stopped", note_text, NULL, NULL);
    say_kept(&od, esc_dir);
  }
  fb_outdir_release(&od);
  if (st != FB_OK) {
    j->discard(j->user);
    return FB_RUN_FOLDER_DIR;
  }
  return FB_RUN_FOLDER_OK;
}

/* fb_run_into_folder's job as fb_folder_run's callbacks */
typedef struct {
  fb_run *r;
  const fb_run_folder_job *j;
} case_job;

static fb_status case_run(void *user, fb_diag *diag) {
  case_job *x = user;
  const fb_run_folder_job *j = x->j;
  fb_status st = fb_run_case(x->r, j->c, j->progress, j->progress_user, diag);
  if (st == FB_OK) {
    const double tv = fb_clock_s();
    st = fb_run_variants(x->r, j->variants, j->nvariants, j->progress, j->progress_user, diag);
    x->r->variants_s = fb_clock_s() - tv;
    if (st != FB_OK) fb_run_free(x->r);
  }
  if (st == FB_OK && j->after_run) j->after_run(x->r, j->write_user);
  return st;
}

static int case_write(const char *stage, void *user) {
  case_job *x = user;
  return x->j->write(stage, x->r, x->j->write_user);
}

static void case_discard(void *user) { fb_run_free(((case_job *)user)->r); }

fb_run_folder_result fb_run_into_folder(fb_run *r, const fb_run_folder_job *j, int *write_rc,
                                        fb_diag *diag) {
  case_job x = {r, j};
  const fb_folder_job fj = {j->dir, j->again, case_run, case_write, case_discard, &x};
  return fb_folder_run(&fj, write_rc, diag);
}
