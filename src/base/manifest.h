/* Who wrote which file of an output folder: the folder's manifest.
 *
 * The file .fourbar-manifest in an output folder holds one line per file
 * fourbar wrote there, "<writer> <name>": the writer is the command (run,
 * bench, penalty, mapping, sweep), the name the file's, in the folder. It is
 * the only proof that a file is fourbar's: a run replaces the files the
 * manifest names as a run's and keeps every other file of the folder
 * (outdir.h); a command that writes named files into a folder (bench.csv)
 * replaces an existing one only when the manifest names it as that
 * command's, or when the user asked with --overwrite (fileio.h,
 * fb_outpath_check). A folder written by a fourbar older than the manifest
 * has none: nothing in it is then provably fourbar's.
 *
 * The manifest is rewritten whole (a temporary file renamed into place) by
 * the writer holding the folder's lock (outdir.h). Lines that are not of
 * the form above are ignored; names are fourbar's own (no newline). */
#ifndef FB_MANIFEST_H
#define FB_MANIFEST_H

#include "status.h"

/* The manifest's file name inside its folder. */
#define FB_MANIFEST_NAME ".fourbar-manifest"

/* Longest writer word and file name a line holds (bytes, with the NUL). */
#define FB_MANIFEST_WRITER 16
#define FB_MANIFEST_FILE 256

/* One line: the command that wrote the file, and its name. */
typedef struct {
  char writer[FB_MANIFEST_WRITER]; /* "run", "bench", ... */
  char name[FB_MANIFEST_FILE];     /* "summary.json" */
} fb_manifest_entry;

/* A folder's manifest in memory. */
typedef struct {
  int present;              /* 1: the folder had a manifest when it was read */
  int n;                    /* entries held */
  int cap;                  /* entries allocated */
  fb_manifest_entry *entry; /* (n), heap; fb_manifest_free */
} fb_manifest;

/* Reads dir's manifest into m (empty, present = 0, when there is none).
 * Returns 0, or -1 when memory ran out (m is then empty). */
int fb_manifest_read(fb_manifest *m, const char *dir);

/* The writer m names for file name, or NULL when it names none. */
const char *fb_manifest_owner(const fb_manifest *m, const char *name);

/* Records that writer wrote name (replacing the writer of an entry of that
 * name). Returns 0, or -1 when memory ran out. */
int fb_manifest_set(fb_manifest *m, const char *writer, const char *name);

/* Writes m as dir's manifest: a temporary file in dir renamed over
 * FB_MANIFEST_NAME. Errors: FB_ERR_IO naming the file. */
fb_status fb_manifest_write(const fb_manifest *m, const char *dir, fb_diag *diag);

/* Reads dir's manifest, records writer's files names[0 .. n-1] in it and
 * writes it back (the caller holds the folder's lock). Errors: FB_ERR_IO,
 * FB_ERR_NOMEM. */
fb_status fb_manifest_record(const char *dir, const char *writer, const char *const *names, int n,
                             fb_diag *diag);

/* Frees m's entries (m is then empty). */
void fb_manifest_free(fb_manifest *m);

#endif
