/* Merge: the rows files of a sweep's shards (sweep_run.h) joined into one
 * folder, after checking that they are one study's and that every point is
 * there exactly once. The command line (fourbar merge, cmd_sweep.c) parses
 * the flags and calls fb_sweep_merge. */
#ifndef FB_SWEEP_MERGE_H
#define FB_SWEEP_MERGE_H

#include "study.h"

/* What to merge (the flags of fourbar merge). */
typedef struct {
  char **dirs;            /* folders holding points*.jsonl files */
  int ndirs;
  const char *out;        /* the output folder (the command line's default: dirs[0]) */
  const char *study_path; /* --study: the study to draw with (must be the shards'), or NULL */
  const char *cases_dir;  /* the shipped cases, for that study's case (NULL: none) */
  const char *version;    /* fourbar's version, as a sweep records it in the provenance */
  fb_study_json_writer write_json; /* writes OUT/points.provenance.json */
  fb_study_drawer draw;   /* draws OUT/study.svg (with --study) */
  int overwrite;          /* --overwrite: replace its files that no fourbar sweep wrote there */
} fb_merge_opts;

/* Locks o->out (outdir.h) before reading anything (no shard may be writing
 * it), reads every points*.jsonl of o->dirs (a previous merge's output in
 * them is merged again from the shards; a sweep's own points.jsonl in the
 * output folder is refused), checks that the rows are one study's (the
 * rows' study and grid, the provenance beside each file, and --study's)
 * and that every point 0..N-1 is there once, then writes OUT/points.jsonl,
 * OUT/points.provenance.json (marked "merged") and OUT/points.csv, and with
 * --study draws OUT/study.svg. Returns the exit status: 0 ok, 1 failed,
 * 2 bad input, having said why on stderr ("fourbar merge: ..."). */
int fb_sweep_merge(const fb_merge_opts *o);

#endif
