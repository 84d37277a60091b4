/* Helpers shared by the fourbar commands: argument parsing only, no physics. */
#ifndef FB_CLI_H
#define FB_CLI_H

#include <stddef.h>

#include "work.h"

/* Prints "fourbar <cmd>: <message>" to stderr and returns exit status 2
 * (usage) or 1 (failure) as given. */
int fb_cli_fail(const char *cmd, int status, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

struct option;

/* getopt_long for every command, with one difference: a long option is
 * taken only by its whole name. getopt_long accepts any unambiguous prefix
 * (--no-figure for --no-figures), so that a misspelt or a future option
 * would silently become another; here a prefix returns '?' with optopt 0,
 * optind just past the word (fb_cli_bad_option then names it as an unknown
 * option). Returns what getopt_long returns. */
int fb_cli_getopt(int argc, char **argv, const char *shortopts, const struct option *opts);

/* After getopt_long returned '?' (opterr is 0, main.c): prints one line,
 * "fourbar <cmd>: unknown option '--x' (fourbar <cmd> --help lists the
 * options)" or "...: option '--out' needs a value (...)", naming the option
 * from argv, optind and optopt; shortopts is the string given to
 * getopt_long. Returns exit status 2. */
int fb_cli_bad_option(char **argv, const char *shortopts);

/* Parses a finite double from a flag value; returns 0 and prints a message
 * naming the flag on failure. */
int fb_cli_double(const char *cmd, const char *flag, const char *text, double *out);

struct fb_case_s;

/* The case file named by arg into out (size bytes), returned: arg itself when
 * it names a file here or is absolute; else the shipped case of that name
 * (<cases folder>/<arg> or <arg>.ini, fb_cli_cases_dir) when there is one;
 * else "arg (not in <cases folder> either)", which the load refuses naming
 * both places. */
const char *fb_cli_case_path(char *out, size_t size, const char *arg);

/* Loads the case file argv[optind] (or the paper's case when there is none)
 * with the --set overrides; on error prints "fourbar <cmd>: <diagnostic>" and
 * returns exit status 2, else 0. path receives the file used: a bare name
 * resolves in the shipped cases folder (fb_cli_case_path). Fails with 2
 * when more than one positional argument is given. */
int fb_cli_load_case(const char *cmd, int argc, char **argv, int optind_, const char *const *sets,
                     int nsets, struct fb_case_s *c, char *path, size_t path_size);

/* The --set overrides one command takes at most (run, bench, check, export,
 * penalty, stackup): past it the command refuses, exit 2. */
#define FB_CLI_MAX_SETS 256

/* Loads the case file path with the --set overrides into c, the one way
 * every command loads a case: on error prints "fourbar <cmd>: <diagnostic>"
 * and returns exit status 2 (a planar case too, unless cmd runs one:
 * cli.c's list, docs/planar.md); else prints each plausibility warning
 * (fb_casefile_plausibility: "fourbar <cmd>: warning: <path>: ...") and
 * returns 0. */
int fb_cli_case_file(const char *cmd, const char *path, const char *const *sets, int nsets,
                     struct fb_case_s *c);

/* Appends text to out (size bytes, NUL-terminated) as one word for a POSIX
 * shell: as is when it holds only letters, digits and _./=,:+@%-, else in
 * single quotes with each ' written as '\'' and each control character
 * (textsafe.h) as $'\xHH' (bash, ksh, zsh; POSIX.1-2024 sh). Returns 0 when
 * out is too small (out is then left as it was). */
int fb_cli_shell_word(char *out, size_t size, const char *text);

/* The command line argv[0..argc) (argv[0] is "fourbar <command>", main.c)
 * as one line for a POSIX shell (fb_cli_shell_word), leaving out the
 * option drop (NULL: none) wherever it appears: the command that runs the
 * same thing again. Cut with " ..." when out (size bytes) is too small. */
void fb_cli_command_line(char *out, size_t size, int argc, char **argv, const char *drop);

/* The directory holding the shipped case files: $FOURBAR_CASES_DIR, else the
 * installed share/fourbar/cases beside the binary (meson install), else the
 * source tree the binary was built from, else the configured prefix's. */
const char *fb_cli_cases_dir(void);

/* The same for the committed baselines of fourbar check
 * ($FOURBAR_BASELINES_DIR, share/fourbar/baselines, results/baselines). */
const char *fb_cli_baselines_dir(void);

int fb_cmd_run(int argc, char **argv);
/* fourbar run's part for a planar case c loaded from case_path with the
 * --set overrides sets (nsets; where a refused key was given) (cmd_run_planar.c):
 * its models into folder dir, summary.json printed with json, command for
 * report.md, again the command a signal's note says runs it again; the
 * figures unless figures is 0 (png 1: PNG, else SVG), report.html unless
 * html is 0. Returns the exit status. */
int fb_cmd_run_planar(const struct fb_case_s *c, const char *case_path,
                      const char *const *sets, int nsets, const char *dir, int json,
                      const char *command, const char *again, int figures, int png, int html);
int fb_cmd_kinematics(int argc, char **argv);
/* kinematics, stackup and penalty's parts for a planar case c (its speed and
 * direction as the command resolved them; cmd_planar_tools.c): output on
 * stdout, JSON with json. penalty: physical mode at the nspeeds speeds rpm.
 * Return the exit status. */
int fb_cmd_kinematics_planar(const struct fb_case_s *c, int json);
/* A stack-up's Monte Carlo as fourbar stackup's command line asks it. */
typedef struct {
  size_t samples;      /* samples (>= 1) */
  unsigned long seed;  /* mt19937 seed */
  int jobs;            /* threads evaluating them */
  fb_progress *progress; /* the progress line (work.h) */
} fb_cli_mc;
/* A stack-up's work said before it starts and bounded by [run] max_wall_s
 * (work.h; cli_work.c): rss_evals evaluations for the RSS band, corners
 * (may be INFINITY) and, with FB_TOL_MONTECARLO in mask, mc's samples on
 * its jobs (bytes of memory), each each [s] of CPU measured on case c;
 * unit names an evaluation ("a revolution's peaks"). The Monte Carlo's
 * estimate is said when long, or always with always. Returns 0, or the
 * exit status having said why (2: beyond the limit, naming the cheaper
 * methods and the option that runs it anyway). */
int fb_cli_stackup_work(const struct fb_case_s *c, int mask, double rss_evals, double corners,
                        const fb_cli_mc *mc, double each, double bytes, int always,
                        const char *unit);
/* fb_progress_draw as a progress callback of the studies (user: the line) */
void fb_cli_progress_corners(double fraction, void *user);
void fb_cli_progress_rss(double fraction, void *user);
void fb_cli_progress_mc(double fraction, void *user);
/* stackup: mask of FB_TOL_CORNERS (the worst case over every corner) and
 * FB_TOL_MONTECARLO (mc's samples); the RSS band always */
int fb_cmd_stackup_planar(const struct fb_case_s *c, int mask, const fb_cli_mc *mc, int json);
int fb_cmd_penalty_planar(const struct fb_case_s *c, const double *rpm, int nspeeds, int json,
                          const char *out_dir);
int fb_cmd_keys(int argc, char **argv);
int fb_cmd_models(int argc, char **argv);
int fb_cmd_impact(int argc, char **argv);
int fb_cmd_contact_params(int argc, char **argv);
int fb_cmd_export(int argc, char **argv);
int fb_cmd_penalty(int argc, char **argv);
int fb_cmd_fit(int argc, char **argv);
int fb_cmd_tolerance(int argc, char **argv);
int fb_cmd_stackup(int argc, char **argv);
int fb_cmd_check(int argc, char **argv);
int fb_cmd_sweep(int argc, char **argv);
int fb_cmd_merge(int argc, char **argv);
int fb_cmd_mapping(int argc, char **argv);
int fb_cmd_bench(int argc, char **argv);

#endif
