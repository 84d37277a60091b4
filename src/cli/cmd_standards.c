/* fourbar fit and fourbar tolerance: lookups in ISO 286-1 and ISO 2768-1.
 * Argument parsing and dispatch only. */
#include <getopt.h>
#include <jansson.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "iso2768.h"
#include "iso286.h"
#include "units.h"

static const char fit_help[] =
    "usage: fourbar fit FIT [--json]\n"
    "\n"
    "Limits of an ISO 286-1 fit such as 10H7/g6, '25 H8/f7' or 50H7/k6 (size in mm,\n"
    "up to 500 mm): hole and shaft deviations [um], minimum and maximum diametral\n"
    "clearance [um] (negative is interference) and the kind of fit.\n"
    "Letters: all of ISO 286-1 Tables 2 and 3: holes A B C CD D E EF F FG G H J JS\n"
    "K M N P R S T U V X Y Z ZA ZB ZC, shafts the same in lower case, e.g.\n"
    "30H7/u6 (a press fit), 10H7/j6; grades IT01, IT0, IT1..IT18. The standard's\n"
    "exceptions apply (M6 over 250 up to 315 mm is -9/-41 um) and its refusals too:\n"
    "A, B, a, b and N9..N11 not up to 1 mm; K above IT8 only as K9, K10 up to 3 mm;\n"
    "IT14..IT18 not up to 1 mm; T not up to 24 mm, V not up to 14 mm, Y not up to\n"
    "18 mm; CD, EF, FG only up to 10 mm; j only IT5..IT8 (j8 up to 3 mm), J only\n"
    "IT6..IT8.\n"
    "\n"
    "  --json   one JSON object (deviations and clearances in um, as the standard's\n"
    "           tables give them; the unit is in every key)\n"
    "Exit status: 0 ok, 2 bad input (a fit the standard does not define).\n";

static const char tol_help[] =
    "usage: fourbar tolerance SIZE_MM --class f|m|c|v [--json]\n"
    "\n"
    "ISO 2768-1 general tolerance (+-) for a linear size from 0.5 to 4000 mm.\n"
    "\n"
    "  --json   one JSON object: size_mm, class, plus_minus_mm, source\n"
    "Exit status: 0 ok, 2 bad input.\n";

int fb_cmd_fit(int argc, char **argv) {
  static const struct option opts[] = {
      {"json", no_argument, 0, 'j'}, {"help", no_argument, 0, 'h'}, {0, 0, 0, 0}};
  int json = 0, ch;
  optind = 1;
  while ((ch = fb_cli_getopt(argc, argv, "h", opts)) != -1) {
    if (ch == 'j') json = 1;
    else if (ch == 'h') { fputs(fit_help, stdout); return 0; }
    else { return fb_cli_bad_option(argv, "h"); }
  }
  if (argc - optind < 1) return fb_cli_fail("fit", 2, "a fit is required, e.g. 10H7/g6; see --help");
  /* "25 H8/f7" may arrive as two words */
  char text[128] = "";
  for (int i = optind; i < argc; i++) {
    strncat(text, argv[i], sizeof text - strlen(text) - 1);
  }
  fb_fit f;
  fb_diag d;
  if (fb_iso286_fit(&f, text, &d) != FB_OK) return fb_cli_fail("fit", 2, "%s", d.msg);
  const double um = 1.0 / FB_M_PER_UM;
  if (json) {
    json_t *o = json_object(), *h = json_object(), *s = json_object();
    json_object_set_new(o, "fit", json_string(text));
    json_object_set_new(o, "nominal_mm", json_real(f.nominal / FB_M_PER_MM));
    json_object_set_new(h, "class", json_string(f.hole));
    json_object_set_new(h, "upper_um", json_real(f.h.upper * um));
    json_object_set_new(h, "lower_um", json_real(f.h.lower * um));
    json_object_set_new(s, "class", json_string(f.shaft));
    json_object_set_new(s, "upper_um", json_real(f.s.upper * um));
    json_object_set_new(s, "lower_um", json_real(f.s.lower * um));
    json_object_set_new(o, "hole", h);
    json_object_set_new(o, "shaft", s);
    json_object_set_new(o, "clearance_min_um", json_real(f.clearance_min * um));
    json_object_set_new(o, "clearance_max_um", json_real(f.clearance_max * um));
    json_object_set_new(o, "kind", json_string(fb_fit_kind_name(f.kind)));
    json_object_set_new(o, "source", json_string("ISO 286-1:2010 Tables 1 to 3"));
    /* 15 digits: every size typed with up to 15 significant digits prints as
     * typed (500.0001 stays 500.0001); deviations are whole or half um */
    json_dumpf(o, stdout, JSON_INDENT(2) | JSON_REAL_PRECISION(15));
    fputc('\n', stdout);
    json_decref(o);
    return 0;
  }
  printf("%s %s/%s (ISO 286-1): %s fit\n", f.size_text, f.hole, f.shaft, fb_fit_kind_name(f.kind));
  printf("  hole  %-4s %+8.1f / %+8.1f um\n", f.hole, f.h.upper * um, f.h.lower * um);
  printf("  shaft %-4s %+8.1f / %+8.1f um\n", f.shaft, f.s.upper * um, f.s.lower * um);
  printf("  clearance %+.1f to %+.1f um (diametral; negative is interference)\n",
         f.clearance_min * um, f.clearance_max * um);
  return 0;
}

int fb_cmd_tolerance(int argc, char **argv) {
  static const struct option opts[] = {{"class", required_argument, 0, 'c'},
                                       {"json", no_argument, 0, 'j'},
                                       {"help", no_argument, 0, 'h'},
                                       {0, 0, 0, 0}};
  int json = 0, ch;
  const char *cls = NULL;
  optind = 1;
  while ((ch = fb_cli_getopt(argc, argv, "h", opts)) != -1) {
    if (ch == 'c') cls = optarg;
    else if (ch == 'j') json = 1;
    else if (ch == 'h') { fputs(tol_help, stdout); return 0; }
    else { return fb_cli_bad_option(argv, "h"); }
  }
  if (argc - optind != 1) return fb_cli_fail("tolerance", 2, "one SIZE_MM is required; see --help");
  if (!cls) return fb_cli_fail("tolerance", 2, "--class f|m|c|v is required");
  if (strlen(cls) != 1) return fb_cli_fail("tolerance", 2, "--class '%s': must be f, m, c or v", cls);
  double mm;
  if (!fb_cli_double("tolerance", "SIZE_MM", argv[optind], &mm)) return 2;
  double pm;
  char clause[128];
  fb_diag d;
  if (fb_iso2768_linear(&pm, cls[0], mm * FB_M_PER_MM, clause, sizeof clause, &d) != FB_OK)
    return fb_cli_fail("tolerance", 2, "%s", d.msg);
  if (json) {
    json_t *o = json_object();
    json_object_set_new(o, "size_mm", json_real(mm));
    json_object_set_new(o, "class", json_string(cls));
    json_object_set_new(o, "plus_minus_mm", json_real(pm / FB_M_PER_MM));
    json_object_set_new(o, "source", json_string(clause));
    json_dumpf(o, stdout, JSON_INDENT(2) | JSON_REAL_PRECISION(15)); /* sizes as typed */
    fputc('\n', stdout);
    json_decref(o);
    return 0;
  }
  /* the size exactly as typed; the deviation is a table value */
  printf("%s mm, class %s: +-%g mm (%s)\n", argv[optind], cls, pm / FB_M_PER_MM, clause);
  return 0;
}
