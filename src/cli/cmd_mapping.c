/* fourbar mapping: ERP and CFM against contact stiffness and step size.
 * Argument parsing and dispatch only: the grid is fb_mapping_grid_make's
 * (src/studies/mapping_grid.h), the output tables_mapping.h's. */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "casefile.h"
#include "cli.h"
#include "fileio.h"
#include "contact.h"
#include "figures.h"
#include "mapping_grid.h"
#include "tables_mapping.h"

static const char mapping_help[] =
    "usage: fourbar mapping [--mass-kg m] [--restitution cr]\n"
    "                       [--stiffness-n-m FROM:TO] [--h-s FROM:TO]\n"
    "                       [--per-decade N] [--mapping secant|matched]\n"
    "                       [--out DIR [--overwrite]] [--figure-format svg|png]\n"
    "                       [--json]\n"
    "\n"
    "ERP and CFM (secant: ERP = h k / (h k + c), CFM = 1 / (h k + c)) of a contact\n"
    "spring k [N/m] with the restitution law's damper c = 2 zeta sqrt(k m) (zeta\n"
    "giving restitution cr for mass m), on a logarithmic grid of stiffness and step\n"
    "size. Marks where ERP\n"
    "leaves [0.1, 0.99] ('<' or '>') and where h omega = h sqrt(k/m) passes 1 ('*':\n"
    "fewer than ~3 steps per contact; ODE's mapped spring then loses most of the\n"
    "restitution, see fourbar impact).\n"
    "By default (--mapping matched, as runs) ERP and CFM of the matched row: the\n"
    "one-step update of mass m has the continuous spring-damper's poles exp(s h)\n"
    "(b = m (e^{c h/m} - 1)/h, a = m (1 - e^{s1 h})(1 - e^{s2 h}) / (e^{-c h/m} h^2),\n"
    "ERP = h a / b, CFM = 1 / b); its ERP exceeds 1 wherever h omega is not small\n"
    "against zeta, which ODE accepts.\n"
    "\n"
    "  --mass-kg        effective mass (default 0.0849 kg: the reduced mass of the\n"
    "                   paper's crank and coupler, 0.12 x 0.29 / 0.41 kg)\n"
    "  --restitution    cr of the restitution law (default 0.9)\n"
    "  --stiffness-n-m  range, default 1e5:1e12\n"
    "  --h-s            range, default 1e-7:1e-3\n"
    "  --per-decade     grid points per decade (default 1)\n"
    "  --mapping        matched (default, as fourbar run: [clearance] mapping) or\n"
    "                   secant: ERP = h k/(h k + c), CFM = 1/(h k + c) (tangent is\n"
    "                   secant for this linear law)\n"
    "  --figure-format  svg (default) or png\n"
    "  --out DIR        also write DIR/mapping.csv and DIR/mapping.svg (ERP map with\n"
    "                   the h omega = 1 and ERP = 0.1, 0.99 contours)\n"
    "  --overwrite      replace those files when no fourbar mapping wrote them\n"
    "                   (without it such a file is refused, exit 2)\n"
    "Exit status: 0 ok, 1 failed, 2 bad input.\n";

static int parse_range(const char *t, double *a, double *b) {
  char tail;
  return sscanf(t, "%lf:%lf%c", a, b, &tail) == 2 && *a > 0 && *b > *a && isfinite(*b);
}

/* the grid, its table and files; returns the exit status */
static int mapping_out(double m, double cr, double k0, double k1, double h0, double h1, double per,
                       fb_mapping mapping, int json, const char *out, fb_figure_format fmt) {
  fb_diag rd;
  static fb_mapping_grid g;
  if (fb_mapping_grid_make(&g, m, cr, k0, k1, h0, h1, per, mapping, &rd) != FB_OK)
    return fb_cli_fail("mapping", 2, "%s", rd.msg);
  if (json) fb_report_mapping_json(stdout, &g);
  else fb_report_mapping_text(stdout, &g);
  if (out) {
    char figure[4096];
    fb_diag d, fd;
    if (fb_report_mapping_files(out, fmt, &g, figure, sizeof figure, &fd, &d) != FB_OK)
      return fb_cli_fail("mapping", 1, "%s", d.msg);
    if (!figure[0]) fprintf(stderr, "fourbar mapping: warning: %s\n", fd.msg);
    else if (!json) printf("\nwrote %s/mapping.csv and %s\n", out, figure);
  }
  return 0;
}

int fb_cmd_mapping(int argc, char **argv) {
  static const struct option opts[] = {{"mass-kg", required_argument, 0, 'm'},
                                       {"restitution", required_argument, 0, 'e'},
                                       {"stiffness-n-m", required_argument, 0, 'k'},
                                       {"h-s", required_argument, 0, 't'},
                                       {"per-decade", required_argument, 0, 'p'},
                                       {"out", required_argument, 0, 'o'},
                                       {"overwrite", no_argument, 0, 'w'},
                                       {"json", no_argument, 0, 'j'},
                                       {"figure-format", required_argument, 0, 'f'},
                                       {"mapping", required_argument, 0, 'M'},
                                       {"help", no_argument, 0, 'h'},
                                       {0, 0, 0, 0}};
  fb_figure_format fmt = FB_FIGURE_SVG;
  double m = 0.12 * 0.29 / (0.12 + 0.29), cr = 0.9, k0 = 1e5, k1 = 1e12, h0 = 1e-7, h1 = 1e-3, per = 1;
  const char *out = NULL;
  int json = 0, ch, overwrite = 0;
  fb_mapping mapping = FB_MAPPING_MATCHED; /* the case key's default, as runs */
  optind = 1;
  while ((ch = fb_cli_getopt(argc, argv, "h", opts)) != -1) {
    switch (ch) {
      case 'm': if (!fb_cli_double("mapping", "--mass-kg", optarg, &m)) return 2; break;
      case 'e': if (!fb_cli_double("mapping", "--restitution", optarg, &cr)) return 2; break;
      case 'k':
        if (!parse_range(optarg, &k0, &k1))
          return fb_cli_fail("mapping", 2, "--stiffness-n-m '%s': expected FROM:TO with 0 < FROM < TO", optarg);
        break;
      case 't':
        if (!parse_range(optarg, &h0, &h1))
          return fb_cli_fail("mapping", 2, "--h-s '%s': expected FROM:TO with 0 < FROM < TO", optarg);
        break;
      case 'p': if (!fb_cli_double("mapping", "--per-decade", optarg, &per)) return 2; break;
      case 'o': out = optarg; break;
      case 'w': overwrite = 1; break;
      case 'j': json = 1; break;
      case 'f':
        if (strcmp(optarg, "svg") == 0) fmt = FB_FIGURE_SVG;
        else if (strcmp(optarg, "png") == 0) fmt = FB_FIGURE_PNG;
        else return fb_cli_fail("mapping", 2, "--figure-format '%s': must be svg or png", optarg);
        break;
      case 'M':
        mapping = fb_mapping_parse(optarg);
        if (mapping == FB_MAPPING_COUNT)
          return fb_cli_fail("mapping", 2, "--mapping '%s': must be secant, tangent, matched or "
                             "matched-static",
                             optarg);
        break;
      case 'h': fputs(mapping_help, stdout); return 0;
      default: return fb_cli_bad_option(argv, "h");
    }
  }
  if (optind < argc) return fb_cli_fail("mapping", 2, "unexpected argument '%s'", argv[optind]);
  /* the ranges of fourbar run's case keys for the same quantities */
  fb_diag rd;
  if (fb_casefile_check_range("mass", "coupler_kg", m, "--mass-kg", &rd) != FB_OK ||
      fb_casefile_check_range("clearance", "penalty_n_m", k0, "--stiffness-n-m FROM", &rd) != FB_OK ||
      fb_casefile_check_range("clearance", "penalty_n_m", k1, "--stiffness-n-m TO", &rd) != FB_OK ||
      fb_casefile_check_range("solver", "h_s", h0, "--h-s FROM", &rd) != FB_OK ||
      fb_casefile_check_range("solver", "h_s", h1, "--h-s TO", &rd) != FB_OK)
    return fb_cli_fail("mapping", 2, "%s", rd.msg);
  if (!(cr > FB_RESTITUTION_MIN && cr <= 1))
    return fb_cli_fail("mapping", 2, "--restitution %g: must lie in (%.4f, 1] for the restitution law",
                       cr, FB_RESTITUTION_MIN);
  if (!(per >= 1 && per <= 10 && per == floor(per)))
    return fb_cli_fail("mapping", 2, "--per-decade %g: an integer from 1 to 10", per);
  /* its files: checked and the folder locked before any work (fileio.h) */
  const char *const names[2] = {"mapping.csv", fmt == FB_FIGURE_PNG ? "mapping.png" : "mapping.svg"};
  const fb_outpath_rule rule = {.flag = "--out", .overwrite = overwrite};
  static fb_outfiles files;
  if (out) {
    const fb_status ost = fb_outfiles_begin(&files, out, "mapping", names, 2, &rule, &rd);
    if (ost != FB_OK) return fb_cli_fail("mapping", ost == FB_ERR_ARG ? 2 : 1, "%s", rd.msg);
  }
  const int rc = mapping_out(m, cr, k0, k1, h0, h1, per, mapping, json, out, fmt);
  if (out && fb_outfiles_end(&files, &rd) != FB_OK && !rc)
    return fb_cli_fail("mapping", 1, "%s", rd.msg);
  return rc;
}
