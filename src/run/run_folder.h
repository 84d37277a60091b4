/* A case run into its output folder: the one owner of the folder's
 * lifetime for `fourbar run`. The folder is locked (one writer), the whole
 * result set is written into a staging folder beside it and swapped in at
 * the end (outdir.h), and the lock is released on every path, whatever
 * failed. The writers are the caller's (report.h and figures.h sit a floor
 * above): a callback writes the set into the staging folder. */
#ifndef FB_RUN_FOLDER_H
#define FB_RUN_FOLDER_H

#include "run.h"

/* Writes the result set of run r into the staging folder stage. Returns 0,
 * or a non-zero exit status having said on stderr what failed (nothing of
 * the set is then swapped in: the folder keeps what it held). */
typedef int (*fb_run_set_writer)(const char *stage, const fb_run *r, void *user);

/* One run into one folder. */
typedef struct {
  const char *dir;          /* the output folder, replaced whole */
  const fb_case *c;         /* the case (preflighted: fb_run_preflight) */
  const fb_case *variants;  /* its [variant.*] cases, loaded (fb_casefile_load_variant) */
  int nvariants;
  fb_progress_fn progress;  /* each model's progress (may be NULL) */
  void *progress_user;
  const char *again;        /* the command that runs it again, quoted for a shell: said when a
                               signal stops the run (copied) */
  fb_run_set_writer write;  /* writes the set into the staging folder */
  void *write_user;
  void (*after_run)(fb_run *r, void *user); /* may be NULL: what the command adds to the run
                                               before it is written (cmd_run: the step's
                                               single-impact verification, run.h
                                               step_check), with write_user */
} fb_run_folder_job;

/* What fb_run_into_folder did. */
typedef enum {
  FB_RUN_FOLDER_OK = 0, /* the set is in place; r holds the run (fb_run_free) */
  FB_RUN_FOLDER_DIR,    /* the folder could not be locked, staged or swapped in: diag says why */
  FB_RUN_FOLDER_BAD,    /* the output path is one no run may write (outdir.h FB_ERR_ARG): bad
                           input, diag says why */
  FB_RUN_FOLDER_RUN,    /* the case or a variant did not run: diag says why */
  FB_RUN_FOLDER_WRITE   /* the writer failed and said why (the exit status is its own) */
} fb_run_folder_result;

/* Locks j->dir and makes its staging folder (both before any simulation),
 * names on SIGINT, SIGTERM and SIGHUP what the folder keeps and the command
 * that runs it again (fb_cleanup_note: "fourbar run: stopped by SIG...:
 * <dir> keeps the results it held (nothing of this run was written); to run
 * it again: ...", or "<dir> was not created" when there was none; once
 * swapped in, "<dir> holds this run's results, whole"),
 * runs the case and its variants (fb_run_case, fb_run_variants), has
 * j->write write the set into the staging folder, swaps it in keeping the
 * old folder's files no run wrote (said on stderr), and releases the folder
 * on every path. On FB_RUN_FOLDER_OK r holds the run; on any
 * other result r is freed (and *write_rc, for FB_RUN_FOLDER_WRITE, is the
 * writer's exit status). */
fb_run_folder_result fb_run_into_folder(fb_run *r, const fb_run_folder_job *j, int *write_rc,
                                        fb_diag *diag);

/* Any run into its folder, as fb_run_into_folder (which is this with the
 * four-bar's run): dir locked and staged, the note a signal prints (what
 * dir keeps, the command again that runs it again), then run (user's
 * simulation; its error: FB_RUN_FOLDER_RUN, nothing to discard), write
 * (the set into the staging folder; non-zero: FB_RUN_FOLDER_WRITE, the
 * run discarded), the swap (the old folder's files no run wrote kept and
 * said), discard on a failed swap. A planar case's run uses it too
 * (cmd_run_planar.c), so that both say the same on a signal. */
typedef struct {
  const char *dir;   /* the output folder, replaced whole */
  const char *again; /* the command that runs it again, quoted for a shell (copied) */
  fb_status (*run)(void *user, fb_diag *diag);
  int (*write)(const char *stage, void *user);
  void (*discard)(void *user); /* frees what run made, after a failed write or swap */
  void *user;
} fb_folder_job;

fb_run_folder_result fb_folder_run(const fb_folder_job *j, int *write_rc, fb_diag *diag);

#endif
