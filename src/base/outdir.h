/* Result folders: one writer at a time, one run's results whole or nothing
 * new.
 *
 * A writer first locks the folder: an advisory lock (flock(2)) on the file
 * .<name>.lock beside the folder, which also holds the writer's PID, so a
 * second writer fails at once with a message naming the folder and the
 * holder. Every writer takes that lock: a whole-folder writer (run, sweep,
 * merge) exclusively, a writer of one part (a sweep shard) shared, plus a
 * lock of its own part. While holding the lock it removes what a killed
 * writer left behind: staging and old folders .<name>.staging.<pid> and
 * .<name>.old.<pid> beside the folder, and temporary files inside it, each
 * only when its name has exactly the form this program writes
 * (fb_outdir_temp_pid) and its process is gone. A name proves nothing by
 * itself: a folder beside is emptied only when it is a real folder (never
 * a symbolic link, nothing is followed), owned by this user, holding the
 * mark .fourbar-own.<pid> its maker put in it; anything else is left as it
 * is. An old set a writer killed within its commit had moved aside is moved
 * back when the folder is missing. A folder that is refused loses nothing.
 *
 * A run then writes its whole result set into a staging folder beside the
 * target and swaps it in at the end (renameat2 RENAME_EXCHANGE, then the old
 * set is removed): until the swap the old set stays whole, after it only the
 * new set is there. What is a run's is recorded, never guessed: the staging
 * folder gets the folder's manifest (manifest.h), listing this run's files;
 * the old folder's files that its manifest does not list as a run's (a
 * user's measured.csv, a sweep's points.jsonl, a bench.json) are kept,
 * hard-linked into the new set. A folder an older fourbar wrote (summary.json
 * but no manifest) has its files kept likewise, but for those this run
 * writes again by name. A folder that is not a fourbar result folder (files
 * but neither a manifest nor summary.json), or that holds a subfolder, a
 * link or another node a run cannot keep, is never replaced; neither is a
 * mount point or the current folder, and a symbolic link to nothing is
 * refused.
 *
 * On SIGINT, SIGTERM and SIGHUP the staging folder (when it still holds this
 * process's mark) and registered temporary files of this process are
 * removed (async-signal-safe code only), a note
 * (fb_cleanup_note) is written, then the signal takes its default action
 * (exit status 128 + the signal's number in a shell). */
#ifndef FB_OUTDIR_H
#define FB_OUTDIR_H

#include <sys/types.h>

#include "status.h"

#define FB_OUTDIR_PATH 4096

/* A locked output folder. */
typedef struct {
  char target[FB_OUTDIR_PATH]; /* the folder as the user named it, absolute */
  char stage[FB_OUTDIR_PATH];  /* staging folder beside it ("" before fb_outdir_stage) */
  char lock[FB_OUTDIR_PATH];   /* lock file beside it */
  int lock_fd;                 /* open lock file .<name>.lock, -1 when not held */
  int tag_fd;                  /* open lock file .<name>.<tag>.lock of a part, -1 for none */
  char kept[1024];             /* after fb_outdir_commit: the kept files no fourbar command
                                  wrote, ", "-separated (the first 8, then "...") */
  int kept_n;                  /* how many */
  int legacy;                  /* 1: the old folder had no manifest (an older fourbar's) */
} fb_outdir;

/* Creates the parent folders of dir, takes the lock and cleans a killed
 * writer's leftovers. With replace = 1 (a run's whole set) also checks that
 * dir may be replaced; with replace = 0 (an appending writer such as a sweep)
 * creates dir. tag (NULL for the whole folder) names a part of the folder
 * that writers of other parts may write at the same time (a sweep shard's
 * files): the lock file is then .<name>.<tag>.lock.
 * Errors: FB_ERR_ARG for a path the user cannot mean as an output folder
 * (empty, a file, a link to nothing, a FIFO or device, a mount point or
 * the current folder for a replacing writer, a folder that is not a result
 * folder or holds what a run cannot keep: bad input, exit status 2), each
 * naming --out, the path and the rule; FB_ERR_IO naming the folder for the
 * rest (the holder's PID when another process holds the lock). */
fb_status fb_outdir_lock(fb_outdir *o, const char *dir, int replace, const char *tag,
                         fb_diag *diag);

/* One writer per file that is rewritten in place of the old (a baseline of
 * fourbar check): takes an exclusive advisory lock (flock, without waiting)
 * on lock_path, created if missing, and writes this PID into it; *fd
 * receives the open lock file (close it to release; O_CLOEXEC, and closed
 * in forked workers, worker.h). name and what word the message. Errors:
 * FB_ERR_IO "<name>: another fourbar process (PID N) is writing <what>;
 * wait for it to finish", or why the lock file cannot be made. */
fb_status fb_lock_take(const char *lock_path, const char *name, const char *what, int *fd,
                       fb_diag *diag);

/* The PID named in a temporary file name of this program's exact forms
 * (<result file>.tmp.<pid>.XXXXXX, .figure.tmp.<pid>.<n>.svg|png, and
 * .fourbar-own.<pid>, the mark of a folder this program made), else 0. */
long fb_outdir_temp_pid(const char *name);

/* Creates the staging folder (o->stage) and registers it for removal on a
 * signal. Errors: FB_ERR_IO naming it. */
fb_status fb_outdir_stage(fb_outdir *o, fb_diag *diag);

/* Writes the folder's manifest into the staging folder (its files as the
 * run's), keeps the old folder's files that no run wrote (o->kept names
 * those no fourbar command wrote), swaps the staging folder in as the
 * target and removes the old set. Errors: FB_ERR_IO (the old set is then
 * untouched), among them a file no run wrote whose name this run writes. */
fb_status fb_outdir_commit(fb_outdir *o, fb_diag *diag);

/* Removes the staging folder if still there and releases the lock. */
void fb_outdir_release(fb_outdir *o);

/* Registers a temporary file (or, with is_dir = 1, a flat folder) for removal
 * when a signal ends this process; returns a slot for fb_cleanup_forget, or
 * -1 when the table (64 slots) is full. Installs the handlers once. */
int fb_cleanup_add(const char *path, int is_dir);

/* Forgets a slot (the file was renamed into place or removed). */
void fb_cleanup_forget(int slot);

/* What to say when SIGINT, SIGTERM or SIGHUP ends this process, after the
 * clean-up, on standard error (async-signal-safe writes only): one line
 * "<head> by SIG<NAME>: <text><count><tail>" (count NULL: no number; tail
 * may be NULL). The strings are the caller's and must live as long as the
 * process (static); the caller escapes any data in them (textsafe.h). Used
 * by run and sweep to say what was kept and the command that resumes.
 * Installs the handlers once. */
void fb_cleanup_note(const char *head, const char *text, const volatile long *count,
                     const char *tail);

/* Names the child process (gnuplot) writing into a registered folder, 0 for
 * none: on a signal it is killed and reaped before the folder is removed, so
 * it neither writes into a removed folder nor outlives this process. Forgets
 * the children fb_cleanup_child_add named. */
void fb_cleanup_child(pid_t pid);

/* Children that may run side by side (figures drawn in parallel). */
#define FB_CLEANUP_CHILDREN 8

/* Adds one more such child (several gnuplots drawing side by side); -1 when
 * FB_CLEANUP_CHILDREN are named already. fb_cleanup_child_forget(pid) when
 * it has been reaped. */
int fb_cleanup_child_add(pid_t pid);
void fb_cleanup_child_forget(pid_t pid);

#endif
