#include "cli.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

#include "casefile.h"

#ifndef FB_CASES_DIR
#define FB_CASES_DIR "cases"
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
  char *end;
  double v = strtod(text, &end);
  if (end == text || *end != '\0' || !isfinite(v)) {
    fb_cli_fail(cmd, 2, "%s '%s': not a finite number", flag, text);
    return 0;
  }
  *out = v;
  return 1;
}

const char *fb_cli_cases_dir(void) {
  const char *env = getenv("FOURBAR_CASES_DIR");
  return env && *env ? env : FB_CASES_DIR;
}

int fb_cli_load_case(const char *cmd, int argc, char **argv, int optind_, const char *const *sets,
                     int nsets, fb_case *c, char *path, size_t path_size) {
  if (argc - optind_ > 1)
    return fb_cli_fail(cmd, 2, "one case file at most (got %d); see --help", argc - optind_);
  if (optind_ < argc)
    snprintf(path, path_size, "%s", argv[optind_]);
  else
    snprintf(path, path_size, "%s/paper_crank_rocker.ini", fb_cli_cases_dir());
  fb_diag d;
  if (fb_casefile_load(c, path, sets, nsets, &d) != FB_OK) return fb_cli_fail(cmd, 2, "%s", d.msg);
  return 0;
}
