#include "cli.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <getopt.h>
#include <unistd.h>

#include "casefile.h"
#include "textsafe.h"

#ifndef FB_CASES_DIR
#define FB_CASES_DIR "cases"
#endif
#ifndef FB_BASELINES_DIR
#define FB_BASELINES_DIR "results/baselines"
#endif
#ifndef FB_DATA_FROM_BIN
#define FB_DATA_FROM_BIN ""
#endif
#ifndef FB_DATA_INSTALLED
#define FB_DATA_INSTALLED ""
#endif

int fb_cli_fail(const char *cmd, int status, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  fprintf(stderr, "fourbar %s: ", cmd);
  vfprintf(stderr, fmt, ap);
  fputc('\n', stderr);
  va_end(ap);
  return status;
}

int fb_cli_double(const char *cmd, const char *flag, const char *text, double *out) {
  double v;
  if (fb_casefile_underflows(text)) {
    fb_cli_fail(cmd, 2, "%s '%s': below the smallest normal double (2.2e-308), so it would read "
                "as %g: give a larger number", flag, text, strtod(text, NULL));
    return 0;
  }
  if (!fb_casefile_decimal(text, &v) || !isfinite(v)) {
    fb_cli_fail(cmd, 2, "%s '%s': not a finite decimal number", flag, text);
    return 0;
  }
  *out = v;
  return 1;
}

static int is_dir(const char *path) {
  struct stat sb;
  return path[0] && stat(path, &sb) == 0 && S_ISDIR(sb.st_mode);
}

/* the installed data folder <what> (cases, baselines), or the source tree's */
static const char *data_dir(const char *env_name, const char *what, const char *source_dir,
                            char *buf, size_t size) {
  const char *env = getenv(env_name);
  if (env && *env) return env;
  /* an installed copy next to the binary: <exe dir>/<FB_DATA_FROM_BIN>/<what> */
  char exe[4096];
  ssize_t n = FB_DATA_FROM_BIN[0] ? readlink("/proc/self/exe", exe, sizeof exe - 1) : -1;
  if (n > 0) {
    exe[n] = '\0';
    char *slash = strrchr(exe, '/');
    if (slash) {
      *slash = '\0';
      snprintf(buf, size, "%s/%s/%s", exe, FB_DATA_FROM_BIN, what);
      if (is_dir(buf)) return buf;
    }
  }
  /* ./build/fourbar without installing: the source tree it was built from */
  if (is_dir(source_dir)) return source_dir;
  snprintf(buf, size, "%s/%s", FB_DATA_INSTALLED, what);
  return FB_DATA_INSTALLED[0] && is_dir(buf) ? buf : source_dir;
}

int fb_cli_shell_word(char *out, size_t size, const char *text) {
  size_t k = strlen(out);
  const size_t start = k;
  const size_t n = strlen(text);
  if (n && strspn(text, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_./=,:+@%-") == n) {
    if (k + n + 1 > size) return 0; /* a plain word needs no quotes */
    memcpy(out + k, text, n + 1);
    return 1;
  }
  if (k + 1 >= size) return 0;
  out[k++] = '\'';
  for (const char *p = text; *p;) {
    /* a control character (textsafe.h) as bash's $'\xHH', so the word
     * stays one line and nothing raw reaches a terminal */
    size_t unit;
    char esc[16];
    const int control = fb_text_unit(p, strlen(p), &unit);
    if (control) unit = 1;
    if (control) snprintf(esc, sizeof esc, "'$'\\x%02x''", (unsigned char)*p);
    const char *piece = control ? esc : *p == '\'' ? "'\\''" : NULL;
    const size_t l = piece ? strlen(piece) : unit;
    if (k + l + 2 >= size) {
      out[start] = '\0';
      return 0;
    }
    memcpy(out + k, piece ? piece : p, l);
    k += l;
    p += unit;
  }
  out[k++] = '\'';
  out[k] = '\0';
  return 1;
}

void fb_cli_command_line(char *out, size_t size, int argc, char **argv, const char *drop) {
  snprintf(out, size, "%s", argv[0]);
  for (int i = 1; i < argc; i++) {
    if (drop && strcmp(argv[i], drop) == 0) continue;
    strncat(out, " ", size - strlen(out) - 1);
    if (!fb_cli_shell_word(out, size, argv[i])) {
      strncat(out, " ...", size - strlen(out) - 1);
      break;
    }
  }
}

const char *fb_cli_cases_dir(void) {
  static char buf[4600];
  return data_dir("FOURBAR_CASES_DIR", "cases", FB_CASES_DIR, buf, sizeof buf);
}

const char *fb_cli_baselines_dir(void) {
  static char buf[4600];
  return data_dir("FOURBAR_BASELINES_DIR", "baselines", FB_BASELINES_DIR, buf, sizeof buf);
}

static int is_file(const char *path) {
  struct stat sb;
  return path[0] && stat(path, &sb) == 0 && !S_ISDIR(sb.st_mode);
}

const char *fb_cli_case_path(char *out, size_t size, const char *arg) {
  snprintf(out, size, "%s", arg);
  if (is_file(arg) || arg[0] == '/') return out;
  /* a relative name not found here: the shipped case of that name, with or
   * without .ini (as the default case is found from any folder) */
  const char *dir = fb_cli_cases_dir();
  const size_t n = strlen(arg);
  const int has_ini = n > 4 && strcmp(arg + n - 4, ".ini") == 0;
  char cand[8192];
  snprintf(cand, sizeof cand, "%s/%s%s", dir, arg, has_ini ? "" : ".ini");
  if (is_file(cand) && strlen(cand) < size) snprintf(out, size, "%s", cand);
  else if (strlen(dir) + n + 30 < size) /* the load's error names both places */
    snprintf(out, size, "%s (not in %s either)", arg, dir);
  return out;
}

int fb_cli_load_case(const char *cmd, int argc, char **argv, int optind_, const char *const *sets,
                     int nsets, fb_case *c, char *path, size_t path_size) {
  if (argc - optind_ > 1)
    return fb_cli_fail(cmd, 2, "one case file at most (got %d); see --help", argc - optind_);
  if (optind_ < argc) {
    const char *arg = argv[optind_];
    fb_cli_case_path(path, path_size, arg);
    struct stat sb;
    if (arg[0] && stat(arg, &sb) != 0 && stat(path, &sb) != 0) {
      /* found nowhere: how a case argument resolves, and where it looked */
      const size_t n = strlen(arg);
      const int has_ini = n > 4 && strcmp(arg + n - 4, ".ini") == 0;
      char cwd[4096];
      if (!getcwd(cwd, sizeof cwd)) snprintf(cwd, sizeof cwd, ".");
      if (arg[0] == '/') return fb_cli_fail(cmd, 2, "%s: cannot open case file: no such file", arg);
      return fb_cli_fail(cmd, 2,
                         "%s: cannot open case file: a case is a path (from the current folder: "
                         "%s/%s) or the name of a shipped case (%s/%s%s), and neither exists (ls %s "
                         "lists the shipped cases)",
                         arg, cwd, arg, fb_cli_cases_dir(), arg, has_ini ? "" : ".ini",
                         fb_cli_cases_dir());
    }
  } else {
    snprintf(path, path_size, "%s/paper_crank_rocker.ini", fb_cli_cases_dir());
  }
  return fb_cli_case_file(cmd, path, sets, nsets, c);
}

/* the commands that run a planar case ([linkage] type = planar,
 * docs/planar.md); the others refuse one after checking it */
static const char *const planar_commands[] = {"run", "kinematics", "stackup", "penalty",
                                               "bench", "export", "contact-params"};

static int runs_planar(const char *cmd) {
  for (size_t i = 0; i < sizeof planar_commands / sizeof planar_commands[0]; i++)
    if (strcmp(cmd, planar_commands[i]) == 0) return 1;
  return 0;
}

int fb_cli_case_file(const char *cmd, const char *path, const char *const *sets, int nsets,
                     struct fb_case_s *c) {
  fb_diag d;
  if ((runs_planar(cmd) ? fb_casefile_load_planar : fb_casefile_load)(c, path, sets, nsets, &d) !=
      FB_OK)
    return fb_cli_fail(cmd, 2, "%s", d.msg);
  const int torque = c->planar.torque_joint >= 0;
  if (c->planar.undriven && strcmp(cmd, "run") != 0) /* the others follow or load a drive */
    return fb_cli_fail(cmd, 2, "%s: %s: an undriven case runs by fourbar run only (its reference "
                       "and the engines' models, from %s); %s follows a drive at constant speed",
                       path, torque ? "[drive] torque_n_m" : "[drive] joint = none",
                       torque ? "[drive] speed0_rpm" : "the bodies' initial_omega_rad_s", cmd);
  /* values within the rules yet unlikely to be meant: said, and run as given */
  char notes[8][FB_DIAG_SIZE];
  const int n = fb_casefile_plausibility(c, notes, 8);
  for (int i = 0; i < n; i++) fprintf(stderr, "fourbar %s: warning: %s: %s\n", cmd, path, notes[i]);
  return 0;
}

int fb_cli_getopt(int argc, char **argv, const char *shortopts, const struct option *opts) {
  int which = -1;
  const int ch = getopt_long(argc, argv, shortopts, opts, &which);
  if (ch == -1 || ch == '?' || which < 0) return ch;
  /* the word given: "--name" or "--name=value", at optind - 1, or at
   * optind - 2 when its value was the next word */
  int at = optind - 1;
  if (optarg && at > 0 && optarg == argv[at]) at--;
  const char *word = argv[at];
  if (strncmp(word, "--", 2) == 0) {
    const size_t n = strcspn(word + 2, "=");
    if (strlen(opts[which].name) != n || strncmp(opts[which].name, word + 2, n) != 0) {
      /* a prefix of a longer option's name: refused, never taken for it */
      optind = at + 1; /* fb_cli_bad_option reads the word at optind - 1 */
      optopt = 0;
      return '?';
    }
  }
  return ch;
}

int fb_cli_bad_option(char **argv, const char *shortopts) {
  const char *token = optind > 0 ? argv[optind - 1] : "";
  char name[128];
  int needs_value = 0;
  if (token && strncmp(token, "--", 2) == 0) {
    /* a long option: the whole word up to '=' */
    snprintf(name, sizeof name, "%.*s", (int)strcspn(token, "="), token);
    needs_value = optopt != 0; /* getopt_long sets optopt for a known option without its value */
  } else {
    snprintf(name, sizeof name, "-%c", optopt ? optopt : '?');
    needs_value = optopt != 0 && optopt != ':' && strchr(shortopts, optopt) != NULL;
  }
  fprintf(stderr, "%s: %s '%s'%s (%s --help lists the options)\n", argv[0],
          needs_value ? "option" : "unknown option", name, needs_value ? " needs a value" : "",
          argv[0]);
  return 2;
}
