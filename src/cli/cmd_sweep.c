/* fourbar sweep and fourbar merge: argument parsing and dispatch only; the
 * sweep (its files and worker processes) is sweep_run.c's, the merge
 * sweep_merge.c's, the points study.c's. */
#define _POSIX_C_SOURCE 200809L
#include <getopt.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "figures.h"
#include "fileio.h"

#ifndef FB_VERSION
#define FB_VERSION "unknown"
#endif
#include "report.h"
#include "sweep_merge.h"
#include "sweep_run.h"

static const char sweep_help[] =
    "usage: fourbar sweep STUDY [--jobs J] [--shard I/N] [--out DIR] [--overwrite]\n"
    "       fourbar sweep STUDY --list N [--out DIR]\n"
    "\n"
    "Runs every point of a study's grid (cases/studies/*.ini): one row per point in\n"
    "DIR/points.jsonl (appended as points finish) and DIR/points.csv (written at the\n"
    "end, sorted). A rerun skips the points already in the JSON lines, so a killed\n"
    "sweep resumes without recomputing. Rows are resumed only when computed from the\n"
    "same study, case files and fourbar version (recorded in\n"
    "DIR/points.provenance.json); otherwise the sweep refuses and says what changed.\n"
    "A progress bar with ETA is drawn on a terminal.\n"
    "\n"
    "  --jobs J     J worker processes on this machine (default 1)\n"
    "  --shard I/N  only points with index % N == I (0 <= I < N), into\n"
    "               DIR/points.shard-I-of-N.jsonl: for Slurm job arrays\n"
    "               (--shard $SLURM_ARRAY_TASK_ID/N) or GNU parallel\n"
    "  --list N     print the N shard commands, one per line, for GNU parallel\n"
    "  --restart    discard the rows already in DIR (of this shard) and start fresh\n"
    "  --out DIR    default results/studies/<study name>; a run into DIR keeps the\n"
    "               sweep's files (docs/outputs.md, What fourbar replaces)\n"
    "  --overwrite  replace files of those names that no fourbar sweep wrote in DIR\n"
    "               (without it such a file is refused, exit 2)\n"
    "Then: fourbar merge DIR... joins shard outputs, checking no point is missing\n"
    "or duplicated.\n"
    "Exit status: 0 ok, 1 failed, 2 bad input.\n";

static const char merge_help[] =
    "usage: fourbar merge DIR... [--out DIR] [--study STUDY] [--overwrite]\n"
    "\n"
    "Joins the points*.jsonl files of the given folders into OUT/points.jsonl and\n"
    "OUT/points.csv (default OUT: the first DIR), after checking that they belong to\n"
    "one study and that every point 0..N-1 is present exactly once. With --study\n"
    "it also draws OUT/study.svg. Files of those names that no fourbar sweep or\n"
    "merge wrote in OUT are replaced only with --overwrite.\n"
    "Exit status: 0 ok, 1 failed, 2 bad input.\n";

/* --list N: the N shard commands, one per line, for GNU parallel */
static int list_shards(const char *study_path, const char *dir, long list) {
  fb_diag d;
  char exe[PATH_MAX];
  ssize_t l = readlink("/proc/self/exe", exe, sizeof exe - 1);
  exe[l > 0 ? l : 0] = '\0';
  char study_abs[PATH_MAX], dir_abs[PATH_MAX];
  if (!realpath(study_path, study_abs)) snprintf(study_abs, sizeof study_abs, "%s", study_path);
  if (fb_outdir_prepare(dir, &d) != FB_OK) return fb_cli_fail("sweep", 1, "%s", d.msg);
  if (!realpath(dir, dir_abs)) snprintf(dir_abs, sizeof dir_abs, "%s", dir);
  for (long k = 0; k < list; k++) {
    static char line[12 * PATH_MAX + 64]; /* a quote takes 4 characters */
    line[0] = '\0';
    int fits = fb_cli_shell_word(line, sizeof line, l > 0 ? exe : "fourbar");
    strcat(line, " sweep ");
    fits = fits && fb_cli_shell_word(line, sizeof line, study_abs);
    snprintf(line + strlen(line), sizeof line - strlen(line), " --shard %ld/%ld --out ", k, list);
    if (!fits || !fb_cli_shell_word(line, sizeof line, dir_abs))
      return fb_cli_fail("sweep", 2, "%s: path too long for a command line", dir_abs);
    puts(line);
  }
  return 0;
}

int fb_cmd_sweep(int argc, char **argv) {
  static const struct option opts[] = {{"jobs", required_argument, 0, 'j'},
                                       {"shard", required_argument, 0, 's'},
                                       {"out", required_argument, 0, 'o'},
                                       {"list", required_argument, 0, 'l'},
                                       {"restart", no_argument, 0, 'r'},
                                       {"overwrite", no_argument, 0, 'w'},
                                       {"help", no_argument, 0, 'h'},
                                       {0, 0, 0, 0}};
  long jobs = 1, shard_i = 0, shard_n = 1, list = 0;
  int restart = 0, overwrite = 0;
  const char *out = NULL;
  int ch;
  optind = 1;
  while ((ch = fb_cli_getopt(argc, argv, "h", opts)) != -1) {
    char *end;
    switch (ch) {
      case 'j':
        jobs = strtol(optarg, &end, 10);
        if (*end || jobs < 1 || jobs > 256) return fb_cli_fail("sweep", 2, "--jobs '%s': 1 to 256", optarg);
        break;
      case 's':
        {
          int used = -1; /* the whole value: "0/2junk" is not a shard */
          if (sscanf(optarg, "%ld/%ld%n", &shard_i, &shard_n, &used) != 2 ||
              used != (int)strlen(optarg) || strspn(optarg, "0123456789/") != strlen(optarg))
            shard_n = 0;
        }
        if (shard_n < 1 || shard_n > 100000 || shard_i < 0 || shard_i >= shard_n)
          return fb_cli_fail("sweep", 2, "--shard '%s': expected I/N, decimal integers with 0 <= I < N <= 100000", optarg);
        break;
      case 'o': out = optarg; break;
      case 'r': restart = 1; break;
      case 'w': overwrite = 1; break;
      case 'l':
        list = strtol(optarg, &end, 10);
        if (*end || list < 1 || list > 100000) return fb_cli_fail("sweep", 2, "--list '%s': 1 to 100000", optarg);
        break;
      case 'h': fputs(sweep_help, stdout); return 0;
      default: return fb_cli_bad_option(argv, "h");
    }
  }
  if (argc - optind != 1) return fb_cli_fail("sweep", 2, "one STUDY file is required; see --help");
  const char *study_path = argv[optind];
  static fb_study s;
  fb_diag d;
  if (fb_study_load_with_cases(&s, study_path, fb_cli_cases_dir(), &d) != FB_OK)
    return fb_cli_fail("sweep", 2, "%s", d.msg);
  if (!list) fb_sweep_note_variants(&s);
  char dir[4096];
  if (out) snprintf(dir, sizeof dir, "%s", out);
  else snprintf(dir, sizeof dir, "results/studies/%s", s.name);
  if (list) return list_shards(study_path, dir, list);
  static char again[8192]; /* the command that resumes */
  fb_cli_command_line(again, sizeof again, argc, argv, "--restart");
  const fb_sweep_opts o = {.dir = dir, .jobs = jobs, .shard_i = shard_i, .shard_n = shard_n,
                           .restart = restart, .overwrite = overwrite, .again = again, .version = FB_VERSION,
                           .write_json = fb_report_write_json, .draw = fb_figures_study};
  return fb_sweep_run(&s, &o);
}

int fb_cmd_merge(int argc, char **argv) {
  static const struct option opts[] = {{"out", required_argument, 0, 'o'},
                                       {"study", required_argument, 0, 's'},
                                       {"overwrite", no_argument, 0, 'w'},
                                       {"help", no_argument, 0, 'h'},
                                       {0, 0, 0, 0}};
  const char *out = NULL, *study_path = NULL;
  int ch, overwrite = 0;
  optind = 1;
  while ((ch = fb_cli_getopt(argc, argv, "h", opts)) != -1) {
    if (ch == 'o') out = optarg;
    else if (ch == 'w') overwrite = 1;
    else if (ch == 's') study_path = optarg;
    else if (ch == 'h') { fputs(merge_help, stdout); return 0; }
    else { return fb_cli_bad_option(argv, "h"); }
  }
  if (optind >= argc) return fb_cli_fail("merge", 2, "at least one DIR is required; see --help");
  if (!out) out = argv[optind];
  const fb_merge_opts o = {.dirs = argv + optind, .ndirs = argc - optind, .out = out,
                           .study_path = study_path, .cases_dir = fb_cli_cases_dir(),
                           .version = FB_VERSION, .write_json = fb_report_write_json,
                           .draw = fb_figures_study, .overwrite = overwrite};
  return fb_sweep_merge(&o);
}
