/* fourbar export: flags in, the case's model text (src/report/export.h)
 * out to standard output or --out FILE (written whole, then renamed). */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "casefile.h"
#include "cli.h"
#include "export.h"
#include "fileio.h"

static const char export_help[] =
    "usage: fourbar export CASE --format mjcf|sdf [--ideal]\n"
    "                      [--set section.key=value]... [--out FILE [--overwrite]]\n"
    "\n"
    "The case's mechanism in a user's own model format, with its masses and\n"
    "inertias, the start, and each clearance joint as the contact the project\n"
    "verified at the case's step (docs/contact-params.md):\n"
    "  mjcf  MuJoCo 2.2 and 3.x: bodies crank, coupler, follower (ground is the\n"
    "        world), the loop closed by an equality connect, each clearance joint\n"
    "        as the tendon limit of mujoco-clearance-native, sites <joint>_pin and\n"
    "        <joint>_hole (crank-coupler_pin), an actuator \"drive\" holding the\n"
    "        case's crank speed at ctrl 0 and a keyframe \"start\"; a comment at the\n"
    "        top gives the start and the timesteps the file holds (up to 2 ms)\n"
    "  sdf   SDFormat 1.9 world for Gazebo (ODE physics at the case's step, gravity\n"
    "        along -y): links ground (welded to the world), crank, coupler,\n"
    "        follower; a revolute joint per ideal joint (the loop closed by the\n"
    "        fourth); frames <joint>_pin and <joint>_hole; each clearance joint as\n"
    "        a pin cylinder in a ring of boxes with kp, kd, max_vel, min_depth under\n"
    "        surface/contact/ode; the crank driven by Gazebo Sim's JointController\n"
    "\n"
    "  CASE       a case file, or a shipped case's name (paper_crank_rocker)\n"
    "  --format   mjcf or sdf\n"
    "  --ideal    the ideal mechanism (no clearance), whatever the case has\n"
    "  --set K=V  override case key K (section.key) with V before exporting, as\n"
    "             fourbar run takes it, e.g. --set solver.h_s=1e-6 (the step the\n"
    "             model's contacts are sized for) or --set pin.radial_clearance_um=50\n"
    "  --out      write FILE (whole, or not at all) instead of standard output;\n"
    "             never a folder, a link, a FIFO, a device or the case file itself\n"
    "  --overwrite  replace FILE when it exists (without it an existing FILE is\n"
    "             refused, exit 2)\n"
    "A slider-crank case ([linkage] type = slider-crank): mjcf writes its MuJoCo\n"
    "model (bodies crank, coupler, slider; the slide slider-ground along +x; the\n"
    "piston pin coupler-slider, as a tendon limit when it carries clearance); sdf\n"
    "is refused (exit 2): the SDF world written is the four-bar's.\n"
    "A planar case ([linkage] type = planar): mjcf writes the MJCF model MuJoCo's\n"
    "engine binding runs, bodies and joints by the case's names, keyframe \"start\":\n"
    "with --ideal (or no clearance joint) mujoco-ideal-nominal's mechanism, else\n"
    "mujoco-clearance-native's, each clearance pin the tendon JOINT_bore limited to\n"
    "the radial clearance, its contact sized for the case's step (a warning when\n"
    "that step does not resolve it; a slider in its guide is refused: give\n"
    "--ideal); sdf is refused (exit 2).\n"
    "Exit status: 0 ok, 1 the file could not be written, 2 bad input.\n";

/* generated text of the paper case: MJCF ~4 kB, SDF ~40 kB (a ring of 64
 * boxes per clearance joint) */
#define EXPORT_SIZE (1 << 20)

int fb_cmd_export(int argc, char **argv) {
  static const struct option opts[] = {{"format", required_argument, 0, 'f'},
                                       {"out", required_argument, 0, 'o'},
                                       {"ideal", no_argument, 0, 'i'},
                                       {"overwrite", no_argument, 0, 'w'},
                                       {"set", required_argument, 0, 's'},
                                       {"help", no_argument, 0, 'h'},
                                       {0, 0, 0, 0}};
  const char *P = "export", *format = NULL, *out = NULL;
  int ch, ideal = 0, overwrite = 0, nsets = 0;
  const char *sets[FB_CLI_MAX_SETS];
  optind = 1;
  while ((ch = fb_cli_getopt(argc, argv, "h", opts)) != -1) {
    switch (ch) {
      case 'f': format = optarg; break;
      case 'o': out = optarg; break;
      case 'i': ideal = 1; break;
      case 'w': overwrite = 1; break;
      case 's':
        if (nsets == FB_CLI_MAX_SETS)
          return fb_cli_fail(P, 2, "more than %d --set", FB_CLI_MAX_SETS);
        sets[nsets++] = optarg;
        break;
      case 'h': fputs(export_help, stdout); return 0;
      default: return fb_cli_fail(P, 2, "unknown option '%s'; see fourbar export --help",
                                  argv[optind - 1]);
    }
  }
  if (optind >= argc) return fb_cli_fail(P, 2, "CASE is required; see fourbar export --help");
  if (optind + 1 < argc) return fb_cli_fail(P, 2, "unexpected argument '%s'", argv[optind + 1]);
  if (!format) return fb_cli_fail(P, 2, "--format is required: mjcf or sdf");
  const int sdf = strcmp(format, "sdf") == 0;
  if (!sdf && strcmp(format, "mjcf") != 0)
    return fb_cli_fail(P, 2, "--format '%s': must be mjcf or sdf", format);
  if (overwrite && !out) return fb_cli_fail(P, 2, "--overwrite without --out: it replaces the file --out names");
  char path[4096];
  fb_cli_case_path(path, sizeof path, argv[optind]);
  /* the output path first: refused before any work (fileio.h) */
  const fb_outpath_rule rule = {.flag = "--out", .overwrite = overwrite, .input = path};
  fb_diag d;
  if (out && fb_outpath_check(out, &rule, NULL, &d) != FB_OK) return fb_cli_fail(P, 2, "%s", d.msg);
  static fb_case cs;
  if (fb_cli_case_file(P, path, sets, nsets, &cs) != 0) return 2;
  char *text = malloc(EXPORT_SIZE);
  if (!text) return fb_cli_fail(P, 1, "out of memory");
  fb_status st = sdf ? fb_export_sdf(text, EXPORT_SIZE, &cs, ideal, &d)
                     : fb_export_mjcf(text, EXPORT_SIZE, &cs, ideal, &d);
  if (st != FB_OK) {
    free(text);
    return fb_cli_fail(P, st == FB_ERR_NOMEM ? 1 : 2, "%s: %s", path, d.msg);
  }
  if (d.msg[0]) fprintf(stderr, "fourbar export: warning: %s\n", d.msg);
  if (!out) {
    fputs(text, stdout);
    free(text);
    return 0;
  }
  fb_outfile o;
  if (fb_outfile_open_checked(&o, out, &rule, &d) != FB_OK) {
    free(text);
    return fb_cli_fail(P, 2, "%s", d.msg);
  }
  fputs(text, o.f);
  free(text);
  if (fb_outfile_commit(&o, &d) != FB_OK) return fb_cli_fail(P, 1, "%s", d.msg);
  return 0;
}
