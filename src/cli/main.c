/* fourbar: the command-line interface. Dispatch only; no physics here. */
#include <errno.h>
#include <getopt.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>

#include "casefile.h"
#include "clock.h"
#include "cli.h"
#include "suggest.h"
#include "tables_models.h"
#include "textsafe.h"

#ifndef FB_VERSION
#define FB_VERSION "unknown"
#endif

static const char main_help[] =
    "usage: fourbar COMMAND [options]   (fourbar COMMAND --help for each)\n"
    "       fourbar --version\n"
    "\n"
    "Planar linkages (the four-bar and the slider-crank built in, or any planar\n"
    "mechanism written as a case file) with tolerance stack-up and clearance joints\n"
    "in the Open Dynamics Engine and (in builds with them) MuJoCo, Simbody, Bullet,\n"
    "Siconos and DART (fourbar models lists them), checked against the exact\n"
    "analytic solution and a high-accuracy reference.\n"
    "\n"
    "commands:\n"
    "  run          run a case file's models; write summary.json and CSV series\n"
    "  kinematics   exact peaks, Grashof class and transmission angle of a linkage\n"
    "  stackup      tolerance stack-up: corners, RSS, Monte Carlo, sensitivities\n"
    "  fit          limits of an ISO 286 fit, e.g. 10H7/g6\n"
    "  tolerance    ISO 2768-1 general tolerance of a size\n"
    "  penalty      contact stiffness and penalty parameter per crank speed\n"
    "  impact       one impact in ODE or Bullet against a reference integration\n"
    "  check        rerun cases and compare spike metrics with committed baselines\n"
    "  sweep        run a study's grid (jobs, shards for GNU parallel and Slurm)\n"
    "  merge        join shard outputs of a sweep\n"
    "  mapping      ERP and CFM against contact stiffness and step size\n"
    "  contact-params  a physical contact as ODE, Gazebo, MuJoCo, Bullet settings\n"
    "  export       a case's mechanism as MuJoCo MJCF or SDFormat for Gazebo\n"
    "  bench        every engine's configurations on one error-against-cost chart\n"
    "  keys         list every case-file key with unit, default and rule\n"
    "  models       list every model: engine, lengths, joints, law, collider\n"
    "\n"
    "All outputs are SI; names carry the unit (omega_max_rad_s, h_s).\n"
    "Documentation: README.md and docs/ in the source tree.\n";

int fb_cmd_keys(int argc, char **argv) {
  if (argc > 1 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)) {
    puts("usage: fourbar keys\n\nPrints every case-file key as a Markdown table.");
    return 0;
  }
  if (argc > 1) return fb_cli_fail("keys", 2, "unexpected argument '%s'", argv[1]);
  fb_casefile_write_keys(stdout);
  fb_casefile_planar_write_keys(stdout); /* a planar case's description, the same table */
  return 0;
}

static const char models_help[] =
    "usage: fourbar models [--json]\n"
    "\n"
    "Prints every model a case file's [run] models may name, as a Markdown table:\n"
    "its engine, whether this build has that engine, its link lengths (nominal or\n"
    "the stack-up corner), its joints (ideal or the case's clearance joints), the\n"
    "contact law and collider of its clearance joints, the reference model it is\n"
    "compared with and the mechanisms it builds ([linkage] type); then how to get\n"
    "each engine this build lacks.\n"
    "\n"
    "  --json      the same as one JSON object (\"models\", \"engines\")\n"
    "  -h, --help  this text\n"
    "\n"
    "An ODE row whose collider is exact takes the case's [clearance] collider.\n"
    "Exit status: 0 ok, 2 bad input.\n"
    "Documentation: docs/commands.md; how each model works: docs/models.md.\n";

int fb_cmd_models(int argc, char **argv) {
  int json = 0;
  for (int i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
      fputs(models_help, stdout);
      return 0;
    }
    if (strcmp(argv[i], "--json") == 0) json = 1;
    else return fb_cli_fail("models", 2, "unexpected argument '%s' (fourbar models --help)", argv[i]);
  }
  if (json) fb_report_models_json(stdout);
  else fb_report_models_text(stdout);
  return 0;
}

static int dispatch(int argc, char **argv);

/* Output lost without notice is an error: whatever a command printed must
 * reach standard output (a full disk, /dev/full, a closed pipe). */
static int stdout_written(const char *cmd, int rc) {
  errno = 0;
  if (fflush(stdout) == 0 && !ferror(stdout)) return rc;
  const int e = errno;
  if (e == EPIPE) return rc ? rc : 1; /* the reader stopped reading (| head): it knows */
  fprintf(stderr, "fourbar %s: cannot write to standard output: %s\n", cmd,
          e ? strerror(e) : "write error");
  return rc ? rc : 1;
}

int main(int argc, char **argv) {
  fb_clock_process_start_s(); /* the run's clock starts with the process (timing.json) */
  /* no control character of data (a case file's text, a flag, a path) reaches
   * the terminal raw: stdout and stderr escape them (textsafe.h); with both on
   * one file or pipe (2>&1) stdout goes out a line at a time, so a message on
   * stderr never lands inside one of its lines */
  fb_text_safe_std();
  const char *cmd = argc > 1 ? argv[1] : "";
  char name[64];
  snprintf(name, sizeof name, "%s", cmd);
  return stdout_written(name, dispatch(argc, argv));
}

static int dispatch(int argc, char **argv) {
  if (argc < 2 || strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0 ||
      strcmp(argv[1], "help") == 0) {
    fputs(main_help, argc < 2 ? stderr : stdout);
    return argc < 2 ? 2 : 0;
  }
  /* a child that stops reading (gnuplot on an error, `| head`) gives EPIPE on
   * write, reported as an I/O error, never a signal */
  signal(SIGPIPE, SIG_IGN);
  if (strcmp(argv[1], "--version") == 0 || strcmp(argv[1], "version") == 0) {
    printf("fourbar %s\ncases: %s\nbaselines: %s\n", FB_VERSION, fb_cli_cases_dir(),
           fb_cli_baselines_dir());
    return 0;
  }
  const char *cmd = argv[1];
  /* getopt prints nothing: an unknown option or a missing value is one line
   * of the command's own (fb_cli_bad_option) */
  opterr = 0;
  /* argv[0] then reads "fourbar <command>" in every message */
  static char prog[64];
  snprintf(prog, sizeof prog, "fourbar %s", cmd);
  argv[1] = prog;
  if (strcmp(cmd, "run") == 0) return fb_cmd_run(argc - 1, argv + 1);
  if (strcmp(cmd, "kinematics") == 0) return fb_cmd_kinematics(argc - 1, argv + 1);
  if (strcmp(cmd, "impact") == 0) return fb_cmd_impact(argc - 1, argv + 1);
  if (strcmp(cmd, "penalty") == 0) return fb_cmd_penalty(argc - 1, argv + 1);
  if (strcmp(cmd, "fit") == 0) return fb_cmd_fit(argc - 1, argv + 1);
  if (strcmp(cmd, "tolerance") == 0) return fb_cmd_tolerance(argc - 1, argv + 1);
  if (strcmp(cmd, "stackup") == 0) return fb_cmd_stackup(argc - 1, argv + 1);
  if (strcmp(cmd, "check") == 0) return fb_cmd_check(argc - 1, argv + 1);
  if (strcmp(cmd, "sweep") == 0) return fb_cmd_sweep(argc - 1, argv + 1);
  if (strcmp(cmd, "merge") == 0) return fb_cmd_merge(argc - 1, argv + 1);
  if (strcmp(cmd, "mapping") == 0) return fb_cmd_mapping(argc - 1, argv + 1);
  if (strcmp(cmd, "contact-params") == 0) return fb_cmd_contact_params(argc - 1, argv + 1);
  if (strcmp(cmd, "export") == 0) return fb_cmd_export(argc - 1, argv + 1);
  if (strcmp(cmd, "bench") == 0) return fb_cmd_bench(argc - 1, argv + 1);
  if (strcmp(cmd, "keys") == 0) return fb_cmd_keys(argc - 1, argv + 1);
  if (strcmp(cmd, "models") == 0) return fb_cmd_models(argc - 1, argv + 1);
  /* a misspelt command: the nearest by edit distance, then the list */
  static const char *const commands[] = {"run", "kinematics", "stackup", "fit", "tolerance",
                                         "penalty", "impact", "check", "sweep", "merge",
                                         "mapping", "contact-params", "export", "bench", "keys", "models", "version", "help"};
  const char *near = fb_suggest(cmd, commands, (int)(sizeof commands / sizeof commands[0]));
  if (near)
    fprintf(stderr, "fourbar: unknown command '%s'; did you mean 'fourbar %s'?\n\n%s", cmd, near,
            main_help);
  else
    fprintf(stderr, "fourbar: unknown command '%s'\n\n%s", cmd, main_help);
  return 2;
}
