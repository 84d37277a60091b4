/* Atomic output: every result file is written to a temporary file in the
 * same folder and renamed into place, so an interrupted run never leaves a
 * half-written file that looks whole.
 *
 * The output-path policy of every command that writes (fb_outpath_check,
 * docs/outputs.md "What fourbar replaces"): fourbar replaces nothing the user
 * did not ask it to replace. A path that is empty, a folder, a symbolic
 * link, a FIFO, a device or a socket, or the very file the command reads,
 * is never written; an existing regular file is replaced only when the user
 * gave --overwrite, or when the folder's manifest (manifest.h) names it as
 * the same command's earlier output (bench.csv of an earlier bench). */
#ifndef FB_FILEIO_H
#define FB_FILEIO_H

#include <stdio.h>

#include "outdir.h"
#include "status.h"

/* An output file being written. */
typedef struct {
  FILE *f;          /* write here */
  char path[4096];  /* final name */
  char tmp[4096];   /* temporary name, same folder: <path>.tmp.<pid>.XXXXXX */
  int cleanup;      /* slot of tmp in the signal-time cleanup table (outdir.h), or -1 */
  int noreplace;    /* 1: the commit never replaces a file that appeared at path meanwhile */
} fb_outfile;

/* What a command may replace at one output path (fb_outpath_check). */
typedef struct {
  const char *flag;   /* the flag that named the path or its folder, for messages ("--out") */
  int overwrite;      /* 1: the user gave --overwrite: an existing regular file may be replaced */
  const char *writer; /* a file a command names inside a folder (bench.csv): the command
                         ("bench"), whose own earlier file the folder's manifest may name;
                         NULL for a file the user named itself (export --out FILE) */
  const char *input;  /* a file the command reads (its case file), never replaced; NULL: none */
} fb_outpath_rule;

/* Checks that path may be written under rule: not empty; not a folder, a
 * symbolic link (even one to nothing), a FIFO, a device or a socket; not
 * rule->input (the same file, by device and inode); and, when it exists as
 * a regular file, replaced only with rule->overwrite or when the manifest
 * of its folder names rule->writer as its writer. Sets *exists (may be
 * NULL) to 1 when a file is there. Errors: FB_ERR_ARG (bad input: exit
 * status 2) with one sentence naming the path, the flag and the rule. */
fb_status fb_outpath_check(const char *path, const fb_outpath_rule *rule, int *exists,
                           fb_diag *diag);

/* fb_outpath_check, then fb_outfile_open; a path that did not exist is
 * committed without replacing what may appear there meanwhile
 * (renameat2 RENAME_NOREPLACE). Errors: those two functions'. */
fb_status fb_outfile_open_checked(fb_outfile *o, const char *path, const fb_outpath_rule *rule,
                                  fb_diag *diag);

/* Opens a temporary file beside path. Errors: FB_ERR_IO naming the folder. */
fb_status fb_outfile_open(fb_outfile *o, const char *path, fb_diag *diag);

/* Flushes, closes and renames into place. Errors: FB_ERR_IO (the temporary
 * file is removed and the final name untouched). */
fb_status fb_outfile_commit(fb_outfile *o, fb_diag *diag);

/* Closes and removes the temporary file. */
void fb_outfile_abort(fb_outfile *o);

/* A command that writes named files into a folder the user named (bench:
 * bench.csv, bench.json, bench.svg into --out DIR): the folder locked for
 * the whole command (outdir.h; a run or another writer of the folder is
 * refused meanwhile), each name checked up front, before any work, by
 * fb_outpath_check with writer's manifest entries as proof of ownership,
 * and the names recorded in the folder's manifest at the end. */
typedef struct {
  fb_outdir dir;         /* the locked folder */
  const char *writer;    /* "bench", "penalty", "mapping" */
  const char *const *names;
  int n;
} fb_outfiles;

/* Creates and locks dir, then checks dir/names[k] for k < n under rule
 * (rule->writer is writer). Errors: FB_ERR_IO (the folder: exit 1),
 * FB_ERR_ARG (a name: bad input, exit 2); nothing is held then. */
fb_status fb_outfiles_begin(fb_outfiles *f, const char *dir, const char *writer,
                            const char *const *names, int n, const fb_outpath_rule *rule,
                            fb_diag *diag);

/* fb_outpath_check of dir/names[k] for k < n, with writer's manifest
 * entries as proof of ownership (for a writer that locks its folder
 * itself: a sweep). Errors: FB_ERR_ARG, the first name refused. */
fb_status fb_outfiles_check(const char *dir, const char *writer, const char *const *names, int n,
                            const fb_outpath_rule *rule, fb_diag *diag);

/* Records the names that are now in the folder (and .gnuplot.log when a
 * figure left one) in its manifest as writer's, and releases the folder.
 * Errors: FB_ERR_IO (the folder is released all the same). */
fb_status fb_outfiles_end(fb_outfiles *f, fb_diag *diag);

/* Opens path for reading only when it is a regular file: the type is checked
 * with stat before the open and again on the opened descriptor, and the open
 * itself is non-blocking, so a FIFO, socket or device never blocks or
 * streams forever. Returns NULL with *not_regular = 1 for another type, or
 * with *not_regular = 0 and errno set when the file cannot be opened. */
FILE *fb_fopen_regular(const char *path, int *not_regular);

/* Creates folder dir and its parents (mkdir -p), then proves it writable by
 * creating and removing a temporary file. Errors: FB_ERR_IO. */
fb_status fb_outdir_prepare(const char *dir, fb_diag *diag);

#endif
