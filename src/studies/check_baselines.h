/* fourbar check's work on the committed baselines (results/baselines/
 * <case>.json; check.h holds the metrics and the calibration): the files
 * listed and read, each case rerun and compared metric by metric, the
 * values rewritten (--update) or measured anew (--calibrate). A baseline
 * being rewritten is locked (.<case>.json.lock beside it, fb_lock_take)
 * from the read to the write, and its bytes compared before the write, so
 * neither another fourbar nor another program's change is lost. The
 * command line (cmd_check.c) parses the flags and calls fb_check_command. */
#ifndef FB_CHECK_BASELINES_H
#define FB_CHECK_BASELINES_H

#include "check.h"
#include "study.h"

/* What to check (the flags of fourbar check). */
typedef struct {
  const char *baselines_dir;      /* the committed baselines */
  const char *cases_dir;          /* case files relative to it (as baselines record them) */
  const char *cases;              /* --cases: comma list of case names, or NULL for all */
  const char *const *sets;        /* --set overrides of every case */
  int nsets;
  int update, calibrate, json;    /* --update, --calibrate, --json */
  int jobs;                       /* --jobs: a case's ensemble members' worker processes */
  char **case_files;              /* the command's arguments: case files to calibrate */
  int ncase_files;
  fb_study_json_writer write_json; /* writes a baseline file */
} fb_check_opts;

/* Runs fourbar check as o asks: --calibrate with case files calibrates
 * them; else every baseline (of --cases' names, each of which must have
 * one) is calibrated anew (--calibrate), rewritten with the values of now
 * (--update, printing what changed), or compared (a table per case, or
 * with --json one object of every comparison, on stdout; then "N passed,
 * N failed"). A baseline whose models' engine this build lacks is
 * skipped, and said so. Returns the exit status: 0 ok, 1 a metric moved
 * beyond its tolerance or a run failed, 2 bad input, having said why on
 * stderr ("fourbar check: ..."). */
int fb_check_command(const fb_check_opts *o);

#endif
