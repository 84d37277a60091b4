/* A sweep: every point of a study's grid (study.h) computed into a folder,
 * resumable, on one process or on worker processes. The command line
 * (cmd_sweep.c) parses the flags and calls fb_sweep_run; the rows files are
 * sweep_rows.h's, the joining of shards sweep_merge.h's.
 *
 * Files, in DIR: points.jsonl (points.shard-I-of-N.jsonl for a shard), one
 * row per point appended as it finishes (fsync'ed), so a killed sweep
 * resumes without recomputing; points[...].provenance.json, what the rows
 * are computed from (fb_study_provenance, with "fourbar_version"): rows are
 * resumed only when it is unchanged; points[...].csv written at the end,
 * sorted (fb_study_write_csv). */
#ifndef FB_SWEEP_RUN_H
#define FB_SWEEP_RUN_H

#include "study.h"

/* How a sweep runs (the flags of fourbar sweep). */
typedef struct {
  const char *dir;          /* output folder */
  long jobs;                /* worker processes (1: this process computes) [1, 256] */
  long shard_i, shard_n;    /* only points with index % shard_n == shard_i (0/1: all) */
  int restart;              /* discard this shard's rows, CSV and provenance first */
  int overwrite;            /* --overwrite: replace its files that no fourbar sweep wrote there */
  const char *again;        /* the command that resumes, quoted for a shell: said when a
                               signal stops the sweep (copied) */
  const char *version;      /* fourbar's version, recorded in the provenance */
  fb_study_json_writer write_json; /* writes the provenance file */
  fb_study_drawer draw;     /* draws the study figure once the folder holds every point */
} fb_sweep_opts;

/* On stderr, a note when the study's case has [variant.*] sections: a
 * sweep runs each point's case alone, without them. */
void fb_sweep_note_variants(const fb_study *s);

/* Locks o->dir (outdir.h; a shard locks its own part; held until the
 * process ends), resumes from the rows the folder holds, computes the rest
 * (on a terminal with a progress bar and ETA on stderr), then writes the CSV
 * of every row and prints what it holds on stdout. Workers (o->jobs > 1)
 * are forked processes tied to this one (worker.h), each computing every
 * jobs-th remaining point and sending its rows through a pipe; this process
 * alone writes the rows file. SIGINT, SIGTERM and SIGHUP are answered with
 * the rows kept and the command that resumes (fb_cleanup_note).
 * Returns the exit status: 0 ok, 1 failed, 2 bad input (rows of other
 * inputs or another grid in the folder), having said why on stderr
 * ("fourbar sweep: ..."). Once the folder (not a shard) holds every point,
 * the study figure is drawn (o->draw; when it fails, a warning). */
int fb_sweep_run(const fb_study *s, const fb_sweep_opts *o);

#endif
