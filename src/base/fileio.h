/* Atomic output: every result file is written to a temporary file in the
 * same folder and renamed into place, so an interrupted run never leaves a
 * half-written file that looks whole. */
#ifndef FB_FILEIO_H
#define FB_FILEIO_H

#include <stdio.h>

#include "status.h"

/* An output file being written. */
typedef struct {
  FILE *f;          /* write here */
  char path[4096];  /* final name */
  char tmp[4096];   /* temporary name, same folder: <path>.tmp.<pid>.XXXXXX */
  int cleanup;      /* slot of tmp in the signal-time cleanup table (outdir.h), or -1 */
} fb_outfile;

/* Opens a temporary file beside path. Errors: FB_ERR_IO naming the folder. */
fb_status fb_outfile_open(fb_outfile *o, const char *path, fb_diag *diag);

/* Flushes, closes and renames into place. Errors: FB_ERR_IO (the temporary
 * file is removed and the final name untouched). */
fb_status fb_outfile_commit(fb_outfile *o, fb_diag *diag);

/* Closes and removes the temporary file. */
void fb_outfile_abort(fb_outfile *o);

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
