/* fourbar kinematics: argument parsing and dispatch only: fb_kinematics_run
 * (src/studies/kinematics.h), the result printed by tables_kinematics.h.
 * The mechanism is data: its length flags are its description's length
 * names (--<name>-mm, mechanism.h), what else it takes and its part of the
 * study and the output are its kind's (kinematics_kinds.h). */
#include <getopt.h>
#include <stdio.h>
#include <string.h>

#include "casefile.h"
#include "cli.h"
#include "kinematics.h"
#include "kinematics_kinds.h"
#include "tables_kinematics.h"
#include "units.h"

static const char kin_help[] =
    "usage: fourbar kinematics [CASE] [--crank-mm L] [--coupler-mm L]\n"
    "                          [--follower-mm L] [--ground-mm L] [--speed-rpm N]\n"
    "                          [--direction cw|ccw] [--branch open|crossed]\n"
    "                          [--type four-bar|slider-crank] [--offset-mm E]\n"
    "                          [--json]\n"
    "\n"
    "Exact peaks of coupler and follower angular velocity [rad/s] and angular\n"
    "acceleration [rad/s^2] over one crank revolution at constant speed, the\n"
    "Grashof class and the transmission angle range [deg].\n"
    "A slider-crank (a CASE with [linkage] type = slider-crank, or --type\n"
    "slider-crank): its class (full-turn when the coupler, the connecting rod, is\n"
    "longer than crank + |offset|) and margin, the stroke, the dead centres (the\n"
    "slider's x and the crank angle at each), the quick-return ratio (the slower\n"
    "stroke's time over the faster's) with each stroke's crank angle and time, the\n"
    "transmission angle range, and the exact peaks of the rod's omega [rad/s] and\n"
    "alpha [rad/s^2] and the slider's velocity [m/s] and acceleration [m/s^2].\n"
    "A planar case ([linkage] type = planar, docs/planar.md): every moving body's\n"
    "omega and alpha extremes by name and the drive angle of each; every output\n"
    "point's position, velocity and acceleration extremes ([point.NAME]); every\n"
    "prismatic joint's stroke, dead centres (its slide and the drive angle at each),\n"
    "quick-return ratio and slide extremes; the transmission angle (90 deg -\n"
    "|pressure angle|) wherever a binary link drives another moving body, its\n"
    "extremes and their drive angles, or that it is undefined (the planar core;\n"
    "--speed-rpm and --direction apply, the length flags do not).\n"
    "\n"
    "CASE: a case file (or the name of a shipped case, e.g. paper_crank_rocker);\n"
    "its nominal lengths, speed, direction and branch, each replaced by a flag\n"
    "given. Without CASE the four lengths and --speed-rpm are required (a\n"
    "slider-crank's --crank-mm, --coupler-mm and --speed-rpm; --offset-mm is 0\n"
    "unless given).\n"
    "\n"
    "  --direction   crank direction seen from +z (default: the case's, else cw as\n"
    "                in case files)\n"
    "  --branch      assembly branch (default: the case's, else open)\n"
    "  --type        the mechanism (default: the case's, else four-bar)\n"
    "  --offset-mm   a slider-crank's guide offset along +y, either sign (as\n"
    "                [linkage] offset_mm)\n"
    "  --json        one JSON object on standard output\n"
    "The Grashof line compares s + l (shortest and longest link) with p + q (the\n"
    "other two): below, the shortest link turns fully; equal, a change-point\n"
    "linkage, which folds flat at crank angle 0 or 180 deg (no exact peaks: exit 1).\n"
    "A slider-crank's --follower-mm, --ground-mm and --branch, and a four-bar's\n"
    "--offset-mm, are refused (exit 2).\n"
    "Exit status: 0 ok, 1 the crank cannot turn fully (or the linkage folds flat),\n"
    "2 bad input.\n";

/* Every mechanism's length flags: each description's length names as
 * "--<name>-mm", each once, in type then length order (--crank-mm,
 * --coupler-mm, --follower-mm, --ground-mm, --offset-mm). */
#define KIN_MAX_LENGTHS (FB_MECH_COUNT * FB_MECH_MAX_LENGTHS)
typedef struct {
  int n;
  const char *name[KIN_MAX_LENGTHS]; /* "crank" */
  char flag[KIN_MAX_LENGTHS][40];    /* "--crank-mm" */
} kin_length_flags;

/* getopt's value of length flag u */
#define KIN_LENGTH_OPT 256

/* the flags given, not yet checked against the mechanism */
typedef struct {
  int type;                   /* fb_mech_type given with --type, -1 none */
  double mm[KIN_MAX_LENGTHS]; /* length flag u's value [mm] */
  int seen[KIN_MAX_LENGTHS];  /* length flag u's place among the flags given (1, 2, ..), 0 none */
  int branch_seen;            /* --branch's place, 0 none */
  int count;                  /* places taken */
  fb_branch branch;           /* --branch's value */
  double rpm;                 /* --speed-rpm [rpm], -1 none */
  int dir;                    /* --direction: -1 cw, +1 ccw, 0 none */
  int json;                   /* --json */
} kin_flags;

/* index of length name in lf, -1 none */
static int kin_length_index(const kin_length_flags *lf, const char *name) {
  for (int u = 0; u < lf->n; u++)
    if (strcmp(lf->name[u], name) == 0) return u;
  return -1;
}

/* every mechanism's length flags into lf */
static void kin_length_flags_of_all(kin_length_flags *lf) {
  lf->n = 0;
  for (int t = 0; t < FB_MECH_COUNT; t++) {
    const fb_mech_desc *m = fb_mech_of((fb_mech_type)t);
    for (int i = 0; i < m->nlengths; i++) {
      if (kin_length_index(lf, m->length[i]) >= 0) continue;
      lf->name[lf->n] = m->length[i];
      snprintf(lf->flag[lf->n], sizeof lf->flag[lf->n], "--%s-mm", m->length[i]);
      lf->n++;
    }
  }
}

/* 1 when m's description has a length called name */
static int kin_has_length(const fb_mech_desc *m, const char *name) {
  for (int i = 0; i < m->nlengths; i++)
    if (strcmp(m->length[i], name) == 0) return 1;
  return 0;
}

/* items joined by ", ", the last by `last` ("a, b or c"), into buf */
static const char *kin_join(char *buf, size_t size, const char *const *item, int n,
                            const char *last) {
  size_t used = 0;
  buf[0] = '\0';
  for (int i = 0; i < n && used < size; i++)
    used += (size_t)snprintf(buf + used, size - used, "%s%s",
                             i == 0 ? "" : i == n - 1 ? last : ", ", item[i]);
  return buf;
}

/* the case files' defaults (the key table's, fb_case_default): the
 * mechanism without a [linkage] type, the [drive] direction, the [linkage]
 * branch */
static const fb_case *kin_defaults(void) {
  static fb_case d;
  static int done = 0;
  if (!done) fb_case_default(&d);
  done = 1;
  return &d;
}

/* the flags into fl; exit status, or -1 to go on */
static int kin_parse(int argc, char **argv, const kin_length_flags *lf, kin_flags *fl) {
  static struct option opts[KIN_MAX_LENGTHS + 8];
  static const struct option fixed[] = {{"speed-rpm", required_argument, 0, 'n'},
                                        {"direction", required_argument, 0, 'd'},
                                        {"branch", required_argument, 0, 'r'},
                                        {"type", required_argument, 0, 't'},
                                        {"json", no_argument, 0, 'j'},
                                        {"help", no_argument, 0, 'h'},
                                        {0, 0, 0, 0}};
  int n = 0;
  for (int u = 0; u < lf->n; u++)
    opts[n++] = (struct option){lf->flag[u] + 2, required_argument, 0, KIN_LENGTH_OPT + u};
  memcpy(opts + n, fixed, sizeof fixed);
  char types[128];
  const char *type_name[FB_MECH_COUNT];
  for (int t = 0; t < FB_MECH_COUNT; t++) type_name[t] = fb_mech_of((fb_mech_type)t)->type;
  int ch;
  optind = 1;
  while ((ch = fb_cli_getopt(argc, argv, "h", opts)) != -1) {
    const int u = ch - KIN_LENGTH_OPT;
    if (u >= 0 && u < lf->n) {
      if (!fb_cli_double("kinematics", lf->flag[u], optarg, &fl->mm[u])) return 2;
      if (!fl->seen[u]) fl->seen[u] = ++fl->count;
      continue;
    }
    switch (ch) {
      case 'n': if (!fb_cli_double("kinematics", "--speed-rpm", optarg, &fl->rpm)) return 2; break;
      case 'd':
        if (strcmp(optarg, "cw") == 0) fl->dir = -1;
        else if (strcmp(optarg, "ccw") == 0) fl->dir = +1;
        else return fb_cli_fail("kinematics", 2, "--direction '%s': must be cw or ccw", optarg);
        break;
      case 'r':
        if (!fl->branch_seen) fl->branch_seen = ++fl->count;
        if (strcmp(optarg, "open") == 0) fl->branch = FB_BRANCH_OPEN;
        else if (strcmp(optarg, "crossed") == 0) fl->branch = FB_BRANCH_CROSSED;
        else return fb_cli_fail("kinematics", 2, "--branch '%s': must be open or crossed", optarg);
        break;
      case 't':
        if ((fl->type = fb_mech_find(optarg)) < 0)
          return fb_cli_fail("kinematics", 2, "--type '%s': must be %s", optarg,
                             kin_join(types, sizeof types, type_name, FB_MECH_COUNT, " or "));
        break;
      case 'j': fl->json = 1; break;
      case 'h': fputs(kin_help, stdout); return 0;
      default: return fb_cli_bad_option(argv, "h");
    }
  }
  return -1;
}

/* a planar case: its geometry is its joints' (docs/planar.md), so the
 * default mechanism's length flags are refused, then --branch, --type and
 * the other length flags; exit status */
static int kin_planar(fb_case *c, const kin_length_flags *lf, const kin_flags *fl) {
  const fb_mech_desc *m = fb_mech_of(kin_defaults()->mechanism);
  for (int i = 0; i < m->nlengths; i++) {
    const int u = kin_length_index(lf, m->length[i]);
    if (fl->seen[u])
      return fb_cli_fail("kinematics", 2, "%s: the case is a planar one, whose lengths are its "
                         "joints' positions ([joint.NAME] at_mm)", lf->flag[u]);
  }
  const char *other[KIN_MAX_LENGTHS + 2] = {"--branch", "--type"};
  int n = 2, given = fl->branch_seen || fl->type >= 0;
  for (int u = 0; u < lf->n; u++)
    if (!kin_has_length(m, lf->name[u])) {
      other[n++] = lf->flag[u];
      given = given || fl->seen[u];
    }
  char list[256];
  if (given)
    return fb_cli_fail("kinematics", 2, "%s do not apply to a planar case (its joints' positions "
                       "give its branch and shape)", kin_join(list, sizeof list, other, n, " and "));
  fb_diag rd;
  if (fl->rpm != -1 &&
      fb_casefile_check_range("drive", "speed_rpm", fl->rpm, "--speed-rpm", &rd) != FB_OK)
    return fb_cli_fail("kinematics", 2, "%s", rd.msg);
  if (fl->rpm != -1) c->crank_speed = fl->rpm * FB_RAD_S_PER_RPM;
  if (fl->dir != 0) c->direction = fl->dir;
  return fb_cmd_kinematics_planar(c, fl->json);
}

/* the first mechanism type whose description has the length called name,
 * or (name NULL) whose kind has branches; 0 for none */
static int kin_owner(const char *name) {
  for (int t = 0; t < FB_MECH_COUNT; t++)
    if (name ? kin_has_length(fb_mech_of((fb_mech_type)t), name)
             : fb_report_kinematics_kind((fb_mech_type)t)->branch)
      return t;
  return 0;
}

/* The first flag given (in command-line order) that the mechanism lacks: a
 * length its description does not name, or --branch for a kind without
 * branches. Refused naming the first mechanism that takes it and what to
 * give instead: for the default mechanism (perhaps not chosen) --type, for
 * another its own length flags. Exit status or 0. */
static int kin_foreign_flag(const fb_kinematics *k, const kin_length_flags *lf,
                            const kin_flags *fl) {
  const fb_mech_desc *m = fb_mech_of(k->mech);
  const char *flag = NULL;
  int first = 0, owner = -1;
  for (int u = 0; u < lf->n; u++)
    if (fl->seen[u] && !kin_has_length(m, lf->name[u]) && (!flag || fl->seen[u] < first)) {
      flag = lf->flag[u];
      first = fl->seen[u];
      owner = kin_owner(lf->name[u]);
    }
  if (fl->branch_seen && !k->kind->branch && (!flag || fl->branch_seen < first)) {
    flag = "--branch";
    owner = kin_owner(NULL);
  }
  if (!flag) return 0;
  const char *own = fb_mech_of((fb_mech_type)owner)->type;
  if (k->mech == kin_defaults()->mechanism)
    return fb_cli_fail("kinematics", 2, "%s is a %s flag, but the mechanism is a %s: add --type "
                       "%s (or give a %s case)", flag, own, m->type, own, own);
  const char *mine[FB_MECH_MAX_LENGTHS];
  for (int i = 0; i < m->nlengths; i++) mine[i] = lf->flag[kin_length_index(lf, m->length[i])];
  char list[256];
  return fb_cli_fail("kinematics", 2, "%s is a %s flag, but the mechanism is a %s: give %s", flag,
                     own, m->type, kin_join(list, sizeof list, mine, m->nlengths, ", "));
}

/* the mechanism and its kind into k: the case's, else --type's, else the
 * case files' default; a flag it lacks refused; exit status or 0 */
static int kin_mechanism(fb_kinematics *k, const kin_length_flags *lf, const kin_flags *fl,
                         const fb_case *c) {
  if (c && fl->type >= 0 && fl->type != (int)c->mechanism)
    return fb_cli_fail("kinematics", 2, "--type %s: the case is a %s ([linkage] type = %s)",
                       fb_mech_of((fb_mech_type)fl->type)->type, fb_mech_of(c->mechanism)->type,
                       fb_mech_of(c->mechanism)->type);
  k->mech = c ? c->mechanism
              : fl->type >= 0 ? (fb_mech_type)fl->type : kin_defaults()->mechanism;
  k->kind = fb_report_kinematics_kind(k->mech);
  return kin_foreign_flag(k, lf, fl);
}

/* the lengths [mm] into k: each from its flag, else the case (c, NULL for
 * none), else required (the kind's offset: 0), checked with the ranges of
 * fourbar run's case keys; exit status or 0 */
static int kin_lengths(fb_kinematics *k, const kin_length_flags *lf, const kin_flags *fl,
                       const fb_case *c) {
  const fb_mech_desc *m = fb_mech_of(k->mech);
  for (int i = 0; i < FB_LINK_COUNT; i++) {
    if (i >= m->nlengths) {
      k->lk.length[i] = k->mm[i] = 0.0;
      continue;
    }
    const int u = kin_length_index(lf, m->length[i]), offset = i == k->kind->offset_length;
    double mm = 0.0; /* an offset not given */
    if (fl->seen[u]) mm = fl->mm[u];
    else if (c) mm = c->nominal.length[i] / FB_M_PER_MM;
    else if (!offset) return fb_cli_fail("kinematics", 2, "%s is required; see --help", lf->flag[u]);
    char key[48];
    snprintf(key, sizeof key, "%s_mm", m->length[i]);
    fb_diag rd; /* the ranges of fourbar run's case keys */
    if (fb_casefile_check_range("linkage", key, mm, lf->flag[u], &rd) != FB_OK)
      return fb_cli_fail("kinematics", 2, "%s", rd.msg);
    k->lk.length[i] = mm * FB_M_PER_MM;
    k->mm[i] = mm;
    const char *why = offset ? NULL /* an offset may be 0 or small */
                             : fb_casefile_length_implausible(k->lk.length[i]);
    if (why && !k->case_path[0]) /* (a case's lengths: said by fb_cli_load_case) */
      fprintf(stderr, "fourbar kinematics: warning: %s %g: a link length %s; the flag is in "
              "millimetres\n", lf->flag[u], mm, why);
  }
  return 0;
}

int fb_cmd_kinematics(int argc, char **argv) {
  static kin_length_flags lf;
  if (lf.n == 0) kin_length_flags_of_all(&lf);
  static kin_flags fl;
  memset(&fl, 0, sizeof fl);
  fl.type = -1;
  fl.rpm = -1;
  int rc = kin_parse(argc, argv, &lf, &fl);
  if (rc >= 0) return rc;
  /* a case gives what no flag gave; without one the case files' defaults */
  char case_path[4096] = "";
  static fb_case c;
  const fb_case *from = NULL;
  if (optind < argc) {
    if (fb_cli_load_case("kinematics", argc, argv, optind, NULL, 0, &c, case_path,
                         sizeof case_path) != 0)
      return 2;
    if (c.planar.on) return kin_planar(&c, &lf, &fl);
    from = &c;
  }
  static fb_kinematics k;
  memset(&k, 0, sizeof k);
  k.case_path = case_path;
  if ((rc = kin_mechanism(&k, &lf, &fl, from)) != 0) return rc;
  double rpm = fl.rpm;
  const fb_case *given = from ? from : kin_defaults();
  if (from && rpm == -1) rpm = from->crank_speed / FB_RAD_S_PER_RPM;
  k.dir = fl.dir != 0 ? fl.dir : given->direction;
  k.branch = fl.branch_seen ? fl.branch : given->branch;
  if ((rc = kin_lengths(&k, &lf, &fl, from)) != 0) return rc;
  if (rpm == -1) return fb_cli_fail("kinematics", 2, "--speed-rpm is required; see --help");
  fb_diag rd;
  if (fb_casefile_check_range("drive", "speed_rpm", rpm, "--speed-rpm", &rd) != FB_OK)
    return fb_cli_fail("kinematics", 2, "%s", rd.msg);
  k.rpm = rpm;
  fb_diag diag;
  if (fb_kinematics_run(&k, &diag) != FB_OK) return fb_cli_fail("kinematics", 1, "%s", diag.msg);
  if (fl.json) fb_report_kinematics_json(stdout, &k);
  else fb_report_kinematics_text(stdout, &k);
  return 0;
}
