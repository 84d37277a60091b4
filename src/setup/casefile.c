#include "casefile.h"
#include "fileio.h"
#include "ini_lines.h"

#include <errno.h>
#include <float.h>
#include <fnmatch.h>
#include <ini.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "bar_mass.h"
#include "contact.h"
#include "iso2768.h"
#include "iso286.h"
#include "linkage.h"
#include "model_table.h"
#include "suggest.h"
#include "textsafe.h"
#include "tolerance.h"
#include "units.h"
#include "fb_config.h"

/* ---- the key table -------------------------------------------------------- */

typedef enum {
  K_DOUBLE,    /* number, multiplied by scale to SI */
  K_INT,       /* integer */
  K_ULONG,     /* unsigned integer */
  K_NAME,      /* identifier-like string */
  K_TEXT,      /* free text, kept for the reader only */
  K_STRING,    /* free text the writers print (fb_case.published_source) */
  K_BRANCH,    /* open | crossed */
  K_DIRECTION, /* cw | ccw */
  K_STEPPER,   /* world | quick */
  K_STEP,      /* a step size in seconds, or auto */
  K_STACKUP,   /* nominal | max | min | four corner characters from + - 0 */
  K_MODELS,    /* comma-separated model names */
  K_CLASS,     /* ISO 2768-1 class letter f m c v */
  K_DIST,      /* normal | uniform */
  K_OUTPUT,    /* a stack-up output name */
  K_FIT,       /* an ISO 286 fit string, checked after reading */
  K_JOINTS,    /* comma-separated joint names (bit mask) */
  K_PENALTY,   /* physical | paper | explicit */
  K_MAPPING,   /* secant | tangent | matched */
  K_MJINT,     /* euler | implicit | rk4 | auto */
  K_MJBORE,    /* tendon | facets */
  K_START,     /* steady | rest */
  K_PINSTART,  /* centred | resting | an eccentricity angle in degrees */
  K_PEAKS,     /* steady | all */
  K_SERIES,    /* csv | hdf5 | none */
  K_LIMIT,     /* a number (scaled like K_DOUBLE) | none | clearance */
  K_UNUSED,    /* a number checked against its range and not stored (no model uses it) */
  K_COLLIDER,  /* exact | faceted | ccd */
  K_BORE,      /* circle | ellipse */
  K_BTSOLVER   /* sequential-impulse | mlcp-dantzig */,
  K_SBINT      /* rkmerson | rkfeldberg | rk3 | cpodes | verlet */
} key_kind;

typedef struct {
  const char *section;
  const char *key;
  key_kind kind;
  size_t offset; /* into fb_case */
  double scale;  /* file unit -> SI (K_DOUBLE) */
  double lo, hi; /* allowed range in file units */
  int lo_open;   /* 1: lo excluded */
  int hi_open;   /* 1: hi excluded */
  const char *unit;
  const char *def; /* default as written in a file */
  const char *rule;
  const char *doc;
} key_spec;

#define OFF(field) offsetof(fb_case, field)
#define INF HUGE_VAL
/* honest physical ranges (issue 13): outside them ODE's closed-loop solve
 * degenerates (dxNormalize4 aborts were measured at CFM 1e-18 and at
 * extreme mass ratios) and the mechanism is no four-bar this program models */
#define LEN_RULE "a link length must be positive, from 0.001 mm to 1e5 mm (1 um to 100 m)"
#define TOL_RULE "a tolerance must be >= 0"
#define MASS_RULE "a mass must be positive, from 1e-6 kg to 1e4 kg (1 mg to 10 t)"
#define INERTIA_RULE "a moment of inertia must be positive, from 1e-6 to 1e12 kg mm^2"
#define COM_RULE "the centre of mass lies between the link's joints (0 to 1)"

/* run by default, after the key's default list, when a case has clearance
 * joints and does not give [run] models: each clearance model with its
 * reference (issue 25: the step was shrunk for a contact no model ran) */
#define FB_CLEARANCE_DEFAULT_MODELS \
  "ode-clearance-impact, ode-clearance-restitution, reference, reference-restitution"
static const char *const clearance_default_models[] = {
    "ode-clearance-impact", "ode-clearance-restitution", "reference", "reference-restitution"};

#define DERIVED "(derived)"
#define DERIVED_DOC(what) "; default: " what " of the link's bar (docs/keys.md, Masses and inertias)"
#define LINK_MASS_KEYS(i, nm, w, t)                                                        \
  {"mass", nm "_kg", K_DOUBLE, OFF(link[i].mass), 1.0, FB_MASS_MIN_KG, FB_MASS_MAX_KG, 0, 0, "kg", \
   DERIVED, MASS_RULE, "mass of the " nm DERIVED_DOC("density x width x thickness x length")}, \
  {"mass", nm "_inertia_kg_mm2", K_DOUBLE, OFF(link[i].inertia), FB_KG_M2_PER_KG_MM2, 1e-6, 1e12, 0, 0,       \
   "kg mm^2", DERIVED, INERTIA_RULE,                                                       \
   "moment of inertia of the " nm " about the hinge (out-of-plane) axis through its "      \
   "centre of mass" DERIVED_DOC("m (L^2 + w^2) / 12")},                                   \
  {"mass", nm "_inertia_long_kg_mm2", K_DOUBLE, OFF(link[i].inertia_long), FB_KG_M2_PER_KG_MM2, 1e-6, 1e12, \
   0, 0, "kg mm^2", DERIVED, INERTIA_RULE,                                                 \
   "moment about the " nm "'s long axis (no effect on planar motion with ideal hinges)"    \
   DERIVED_DOC("m (w^2 + t^2) / 12")},                                                     \
  {"mass", nm "_inertia_transverse_kg_mm2", K_DOUBLE, OFF(link[i].inertia_transverse),     \
   FB_KG_M2_PER_KG_MM2, 1e-6, 1e12, 0, 0, "kg mm^2", DERIVED, INERTIA_RULE,                \
   "moment about the in-plane axis across the " nm " (no effect on planar motion)"         \
   DERIVED_DOC("m (L^2 + t^2) / 12")},                                                     \
  {"mass", nm "_com_fraction", K_DOUBLE, OFF(link[i].com_fraction), 1.0, 0, 1, 0, 0, "-",  \
   "0.5", COM_RULE, "centre of mass position along the " nm ", from its first joint"},     \
  {"mass", nm "_width_mm", K_DOUBLE, OFF(link_width[i]), FB_M_PER_MM, 1e-3, 1e5, 0, 0, "mm", w, \
   "a bar width must be positive, from 0.001 mm to 1e5 mm",                                \
   "width w of the " nm "'s bar in the mechanism plane, across the link (for the masses "  \
   "and inertias the case does not give)"},                                                \
  {"mass", nm "_thickness_mm", K_DOUBLE, OFF(link_thickness[i]), FB_M_PER_MM, 1e-3, 1e5, 0, 0, "mm", t, \
   "a bar thickness must be positive, from 0.001 mm to 1e5 mm",                            \
   "thickness t of the " nm "'s bar out of the mechanism plane (for the masses and "       \
   "inertias the case does not give)"}

/* a publication's peaks of one law's clearance model: compared, never used */
#define PUBLISHED_KEY(sec, law, nm, body, field, suffix, unit)                            \
  {sec, #body "_" #field "_" suffix, K_DOUBLE, OFF(published[law].body.field), 1.0, -INF, INF, \
   1, 1, unit, "(none)", "a finite number",                                                 \
   "the published " #body " " #field " of the " nm "-law clearance model (compared, not "   \
   "used: fourbar run prints every model of that law, and every variant's, beside it)"}
#define PUBLISHED_KEYS(sec, law, nm)                                                        \
  PUBLISHED_KEY(sec, law, nm, coupler, omega_max, "rad_s", "rad/s"),                        \
  PUBLISHED_KEY(sec, law, nm, coupler, omega_min, "rad_s", "rad/s"),                        \
  PUBLISHED_KEY(sec, law, nm, coupler, alpha_max, "rad_s2", "rad/s^2"),                     \
  PUBLISHED_KEY(sec, law, nm, coupler, alpha_min, "rad_s2", "rad/s^2"),                     \
  PUBLISHED_KEY(sec, law, nm, follower, omega_max, "rad_s", "rad/s"),                       \
  PUBLISHED_KEY(sec, law, nm, follower, omega_min, "rad_s", "rad/s"),                       \
  PUBLISHED_KEY(sec, law, nm, follower, alpha_max, "rad_s2", "rad/s^2"),                    \
  PUBLISHED_KEY(sec, law, nm, follower, alpha_min, "rad_s2", "rad/s^2")

static const key_spec keys[] = {
    {"case", "name", K_NAME, OFF(name), 0, 0, 0, 0, 0, "-", "case", "letters, digits, - _ .",
     "case name; run output goes to results/<name>/"},
    {"case", "base", K_TEXT, 0, 0, 0, 0, 0, 0, "-", "(none)", "a case file path",
     "case file read first (relative to this one); this file's keys override it"},
    {"case", "description", K_TEXT, 0, 0, 0, 0, 0, 0, "-", "", "free text",
     "one line describing the case (not used by the solver)"},

    {"linkage", "crank_mm", K_DOUBLE, OFF(nominal.length[FB_CRANK]), FB_M_PER_MM, 1e-3, 1e5, 0, 0, "mm",
     "108", LEN_RULE, "basic crank length, A to B"},
    {"linkage", "coupler_mm", K_DOUBLE, OFF(nominal.length[FB_COUPLER]), FB_M_PER_MM, 1e-3, 1e5, 0, 0,
     "mm", "279.4", LEN_RULE, "basic coupler length, B to C"},
    {"linkage", "follower_mm", K_DOUBLE, OFF(nominal.length[FB_FOLLOWER]), FB_M_PER_MM, 1e-3, 1e5, 0, 0,
     "mm", "270.5", LEN_RULE, "basic follower (rocker) length, D to C"},
    {"linkage", "ground_mm", K_DOUBLE, OFF(nominal.length[FB_GROUND]), FB_M_PER_MM, 1e-3, 1e5, 0, 0,
     "mm", "254", LEN_RULE, "basic ground length, A to D along +x"},
    {"linkage", "branch", K_BRANCH, OFF(branch), 0, 0, 0, 0, 0, "-", "open", "open or crossed",
     "assembly branch: open (C left of B->D) or crossed"},
    {"linkage", "crank_angle0_deg", K_DOUBLE, OFF(crank_angle0), FB_RAD_PER_DEG, -360, 360, 0, 0,
     "deg", "0", "an angle from -360 to 360 deg (one turn either way)", "crank angle at t = 0, counter-clockwise from +x"},

    {"tolerance", "crank_plus_minus_mm", K_DOUBLE, OFF(plus_minus[FB_CRANK]), FB_M_PER_MM, 0, INF, 0,
     1, "mm", "0", TOL_RULE, "symmetric tolerance of the crank length"},
    {"tolerance", "coupler_plus_minus_mm", K_DOUBLE, OFF(plus_minus[FB_COUPLER]), FB_M_PER_MM, 0, INF,
     0, 1, "mm", "0", TOL_RULE, "symmetric tolerance of the coupler length"},
    {"tolerance", "follower_plus_minus_mm", K_DOUBLE, OFF(plus_minus[FB_FOLLOWER]), FB_M_PER_MM, 0,
     INF, 0, 1, "mm", "0", TOL_RULE, "symmetric tolerance of the follower length"},
    {"tolerance", "ground_plus_minus_mm", K_DOUBLE, OFF(plus_minus[FB_GROUND]), FB_M_PER_MM, 0, INF, 0,
     1, "mm", "0", TOL_RULE, "symmetric tolerance of the ground length"},
    {"tolerance", "class", K_CLASS, OFF(tolerance_class), 0, 0, 0, 0, 0, "-", "(none)",
     "f, m, c or v",
     "ISO 2768-1 general tolerance class for every link without an explicit "
     "<link>_plus_minus_mm"},
    {"tolerance", "stackup", K_STACKUP, OFF(stackup), 0, 0, 0, 0, 0, "-", "max",
     "nominal, max, min, worst, or 4 characters from + - 0",
     "stack-up corner for the *-stackup models: every link at max or min, one "
     "character per link in the order crank, coupler, follower, ground (e.g. +-+-), or "
     "worst: the corner that maximises |worst_output|"},
    {"tolerance", "worst_output", K_OUTPUT, OFF(stackup.worst_output), 0, 0, 0, 0, 0, "-",
     "coupler_omega_max", "a stack-up output name (fourbar stackup --help)",
     "output whose magnitude the worst corner maximises"},
    {"tolerance", "distribution", K_DIST, OFF(distribution), 0, 0, 0, 0, 0, "-", "normal",
     "normal or uniform",
     "Monte Carlo length distribution: normal with 3 sigma at the tolerance limit, or "
     "uniform over the tolerance band"},

    {"drive", "speed_rpm", K_DOUBLE, OFF(crank_speed), FB_RAD_S_PER_RPM, 0, 1e6, 1, 0, "rpm",
     "1000", "crank speed must be positive (at most 1e6 rpm)",
     "constant crank speed (magnitude)"},
    {"drive", "direction", K_DIRECTION, OFF(direction), 0, 0, 0, 0, 0, "-", "cw", "cw or ccw",
     "crank direction seen from +z: cw (clockwise) or ccw"},

    {"environment", "gravity_m_s2", K_DOUBLE, OFF(gravity), 1.0, 0, 1e3, 0, 0, "m/s^2",
     "9.80665", "gravity must be between 0 and 1000 m/s^2",
     "gravity, acting along -y in the (vertical) mechanism plane"},

    LINK_MASS_KEYS(0, "crank", "20", "6.5"),
    LINK_MASS_KEYS(1, "coupler", "20", "6.5"),
    LINK_MASS_KEYS(2, "follower", "20", "6.5"),

    {"material", "density_kg_m3", K_DOUBLE, OFF(density), 1.0, 1, 1e5, 0, 0, "kg/m^3", "7800",
     "a density must lie in [1, 1e5] kg/m^3 (foam to beyond osmium)",
     "density of the links (steel by default): gives the masses and inertias the case does "
     "not give"},
    {"material", "youngs_modulus_gpa", K_DOUBLE, OFF(youngs_modulus), FB_PA_PER_GPA, 0, INF, 1, 1, "GPa",
     "207", "Young's modulus must be positive", "Young's modulus E of links and pins"},
    {"material", "poisson_ratio", K_DOUBLE, OFF(poisson_ratio), 1.0, -1, 0.5, 1, 1, "-", "0.29",
     "Poisson's ratio must lie in (-1, 0.5)", "Poisson's ratio nu of links and pins"},

    {"pin", "diameter_mm", K_DOUBLE, OFF(pin_diameter), FB_M_PER_MM, 0, INF, 1, 1, "mm", "10",
     "a pin diameter must be positive", "nominal diameter of the joint pins"},
    {"pin", "length_mm", K_DOUBLE, OFF(pin_length), FB_M_PER_MM, 0, INF, 1, 1, "mm", "13",
     "a pin length must be positive", "pin length in contact with its hole"},
    {"pin", "fit", K_FIT, OFF(fit), 0, 0, 0, 0, 0, "-", "(none)",
     "an ISO 286 clearance fit, e.g. 10H7/g6",
     "fit of the clearance joints; gives the pin diameter and the radial clearance "
     "(maximum clearance / 2); do not also give radial_clearance_um; none cancels a "
     "base case's fit"},
    {"pin", "radial_clearance_um", K_DOUBLE, OFF(radial_clearance), FB_M_PER_UM, 0, INF, 1, 1,
     "um", "14.5", "a radial clearance must be positive",
     "radial clearance c = R_hole - R_pin of the clearance joints (default: the 10 H7/g6 "
     "maximum, 29 um diametral)"},

    {"clearance", "joints", K_JOINTS, OFF(clearance.mask), 0, 0, 0, 0, 0, "-", "crank-coupler",
     "joint names: ground-crank, crank-coupler, coupler-follower, follower-ground, or none",
     "joints modelled as a pin in a hole (ode-clearance-* models); the others stay ideal "
     "hinges and get no contact geometry"},
    {"clearance", "penalty", K_PENALTY, OFF(clearance.penalty), 0, 0, 0, 0, 0, "-", "physical",
     "physical, paper, explicit or goldsmith",
     "stiffness source: physical (Johnson line contact at the inverse-dynamics reaction), "
     "paper (the paper's Kc and P read in N and mm), explicit (the stiffness keys), goldsmith "
     "(paper Eq. 3-5: K = 4 / (3 (s1 + s2)) sqrt(R_pin R_hole / c), s = (1 - nu^2)/E, n = 1.5; "
     "the restitution law's p is its tangent at the joint's largest ideal reaction)"},
    {"clearance", "restitution", K_DOUBLE, OFF(clearance.restitution), 1.0, FB_RESTITUTION_MIN,
     1, 1, 0, "-", "0.9", "cr must lie in (0.1353, 1] (the restitution law's range)",
     "coefficient of restitution of the restitution model"},
    {"clearance", "stiffness_impact_n_m1_5", K_DOUBLE, OFF(clearance.stiffness_impact), 1.0, 0,
     INF, 1, 1, "N/m^1.5", "1e11", "a stiffness must be positive",
     "impact-model stiffness K when penalty = explicit"},
    {"clearance", "penalty_n_m", K_DOUBLE, OFF(clearance.stiffness_linear), 1.0, 1e2, 1e16, 0, 0,
     "N/m", "1e9", "a penalty must be positive, from 1e2 to 1e16 N/m (a rubber pad to "
     "hardened steel, with margin)",
     "restitution-model penalty p when penalty = explicit"},
    {"clearance", "exponent", K_DOUBLE, OFF(clearance.exponent), 1.0, 1, 3, 0, 0, "-", "1.5",
     "the exponent must lie in [1, 3]", "impact-model force exponent n"},
    {"clearance", "damping_n_s_m", K_DOUBLE, OFF(clearance.damping), 1.0, 0, INF, 0, 1, "N s/m",
     "1e4", "damping must be >= 0", "impact-model maximum damping c_max"},
    {"clearance", "damping_depth_um", K_DOUBLE, OFF(clearance.damping_depth), FB_M_PER_UM, 0, INF,
     1, 1, "um", "1", "the full-damping depth must be positive",
     "impact-model penetration at full damping d_max (cubic STEP below it)"},
    {"clearance", "mapping", K_MAPPING, OFF(clearance.mapping), 0, 0, 0, 0, 0, "-", "matched",
     "secant, tangent, matched or matched-static",
     "per-step mapping of the law into ERP/CFM (matched: exact discretisation on the effective "
     "mass along the normal; matched-static: matched, then the law's own stiffness once a "
     "contact has lasted one contact period, so a sustained load rests at the law's depth)"},
    {"clearance", "friction", K_DOUBLE, OFF(clearance.friction), 1.0, 0, 10, 0, 0, "-", "0",
     "a friction coefficient must lie in [0, 10]", "Coulomb friction coefficient at the pin"},
    {"clearance", "penetration_limit_um", K_LIMIT, OFF(clearance.penetration_limit), FB_M_PER_UM,
     0, INF, 0, 1, "um", "clearance", "a limit >= 0 (0: the radial clearance), clearance or none",
     "every clearance model, ODE and reference, stops ('unstable') beyond this penetration; "
     "clearance (or 0): the radial clearance; none: no limit. Either way a run whose "
     "penetration passes 2 times the radial clearance gets the warning \"outside the penalty "
     "model's validity\""},

    {"clearance", "stiffness_scale", K_DOUBLE, OFF(clearance.stiffness_scale), 1.0, 0, 1e6, 1, 0,
     "-", "1", "a scale must be positive", "multiplies the contact stiffness from any penalty source"},
    {"clearance", "faceted_n", K_INT, OFF(clearance.faceted_n), 0, 3, 4096, 0, 0, "-", "64",
     "3 to 4096 boxes",
     "boxes in the hole ring of ode-clearance-faceted (ODE's generic box-cylinder path)"},
    {"clearance", "collider", K_COLLIDER, OFF(clearance.collider), 0, 0, 0, 0, 0, "-", "exact",
     "exact, faceted or ccd",
     "how ode-clearance-impact and ode-clearance-restitution find the contact: closed form, "
     "ring of ODE boxes, or libccd ring of convex segments (docs/colliders.md)"},
    {"clearance", "segments", K_INT, OFF(clearance.segments), 0, 8, 65536, 0, 0, "-", "256",
     "8 to 65536 segments",
     "convex segments in the libccd bore ring (ode-clearance-ccd, collider = ccd); when given, "
     "also the faceted collider's boxes"},
    {"clearance", "bore", K_BORE, OFF(clearance.bore), 0, 0, 0, 0, 0, "-", "circle",
     "circle or ellipse", "bore shape of the libccd collider (ellipse: a worn hole)"},
    {"clearance", "ovality_um", K_DOUBLE, OFF(clearance.ovality), FB_M_PER_UM, 0, 1000, 0, 1, "um",
     "0", "ovality must lie in [0, 1000) um",
     "bore = ellipse: diameter along the hole body's x axis minus the hole diameter"},

    {"expect", "outcome", K_NAME, OFF(expect.outcome), 0, 0, 0, 0, 0, "-", "(none)",
     "stable or unstable", "hard cases: what the expect.model run must do (checked by tests)"},
    {"expect", "model", K_NAME, OFF(expect.model), 0, 0, 0, 0, 0, "-", "(none)", "a model name",
     "the model the expectation is about"},
    {"expect", "omega_peak_rel_max", K_DOUBLE, OFF(expect.omega_peak_rel_max), 1.0, 0, INF, 1, 1,
     "-", "(none)", "a positive bound",
     "stable: bound on the model's angular-velocity peak error against the analytic solution"},
    {"expect", "force_peak_rel_max", K_DOUBLE, OFF(expect.force_peak_rel_max), 1.0, 0, INF, 1, 1,
     "-", "(none)", "a positive bound",
     "stable: bound on the clearance model's peak-force error against the reference"},
    {"expect", "reason", K_NAME, OFF(expect.reason), 0, 0, 0, 0, 0, "-", "(none)",
     "letters, digits, - _ .", "unstable: a word the model's status must contain"},

    {"solver", "h_s", K_STEP, OFF(solver.h), 1.0, 0, 1, 1, 0, "s", "1e-5",
     "the step size must be positive (at most 1 s), auto or adaptive",
     "step size h of the ODE models; auto: the largest with h omega_c <= 0.5 at the stiffest "
     "contact, at most one revolution / 6000; adaptive: from h_min_s to h_max_s following the "
     "contact (docs/step-size.md); not given: auto for a case with clearance joints, else the "
     "default"},
    {"solver", "h_min_s", K_DOUBLE, OFF(solver.h_min), 1.0, 0, 1e-3, 1, 0, "s", "1e-6",
     "the shortest adaptive step must be positive, at most 1e-3 s",
     "h_s = adaptive: the shortest step, and the output grid's step"},
    {"solver", "h_max_s", K_DOUBLE, OFF(solver.h_max), 1.0, 0, 1e-2, 1, 0, "s", "2e-5",
     "the longest adaptive step must be positive, at most 1e-2 s, and not below h_min_s",
     "h_s = adaptive: the longest step (continuous contact, ideal joints)"},
    {"solver", "accuracy", K_DOUBLE, OFF(solver.accuracy), 1.0, 0, 1, 1, 0, "-", "0.3",
     "the adaptive accuracy must lie in (0, 1]",
     "h_s = adaptive: the largest h omega_c (omega_c the contact's local frequency on the "
     "effective mass) in an impact and before one; MuJoCo: also the penetration's largest "
     "relative change per step in continuous contact (ODE steps continuous contact on the "
     "ideal load's schedule: docs/step-size.md)"},
    {"solver", "rocking_h_omega", K_DOUBLE, OFF(solver.rocking_h_omega), 1.0, 0, 1, 0, 0, "-", "0",
     "the rocking bound must lie in [0, 1]",
     "h_s = adaptive, ODE: in contact, the largest h omega_t, omega_t = sqrt(F / (m_t e)) "
     "the pin's rocking along the wall (F the ideal joint load ahead, m_t the effective mass "
     "along the wall, e the eccentricity's length); also takes the matched row with the mean-force "
     "correction in continuous contact and carries the velocities across a step change as "
     "leapfrog does; 0: off (docs/step-size.md)"},
    {"solver", "stepper", K_STEPPER, OFF(solver.stepper), 0, 0, 0, 0, 0, "-", "world",
     "world or quick", "world: dWorldStep (direct LCP); quick: dWorldQuickStep (SOR)"},
    {"solver", "quick_iterations", K_INT, OFF(solver.quick_iterations), 0, 1, 1e6, 0, 0, "-",
     "20", "iterations must be 1 to 1000000", "dWorldQuickStep iterations"},
    {"solver", "world_erp", K_DOUBLE, OFF(solver.world_erp), 1.0, 0, 1, 0, 0, "-", "0.2",
     "ERP must lie in [0, 1]", "error reduction parameter of the ideal joints (dWorldSetERP)"},
    {"solver", "world_cfm", K_DOUBLE, OFF(solver.world_cfm), 1.0, 1e-12, 1, 0, 0, "m/(N s)", "1e-10",
     "CFM must lie in [1e-12, 1] (below, the closed loop's redundant hinge rows make ODE's "
     "LCP singular and ODE aborts)", "constraint force mixing of the ideal joints (dWorldSetCFM)"},
    {"solver", "drive_torque_max_n_m", K_DOUBLE, OFF(solver.drive_torque_max), 1.0, 0, INF, 1, 1,
     "N m", "1e4", "the drive torque limit must be positive",
     "torque limit of the crank's velocity motor (dParamFMax); 100 times the 102 N m "
     "peak the paper's case needs at 1000 rpm, so the crank speed is held exactly"},
    {"solver", "seed", K_ULONG, OFF(solver.seed), 0, 0, 0, 0, 0, "-", "1",
     "a non-negative integer", "seed of ODE's random generator (dRandSetSeed)"},

    {"mujoco", "integrator", K_MJINT, OFF(mujoco.integrator), 0, 0, 0, 0, 0, "-", "auto",
     "euler, implicit, rk4 or auto",
     "integrator of the mujoco-* models (MuJoCo's option integrator); auto: euler for the "
     "ideal models, rk4 for the clearance models (the most accurate of the three for each, "
     "measured at h = 1e-5 s; see docs/engines.md)"},
    {"mujoco", "loop_stiffness_1_s2", K_DOUBLE, OFF(mujoco.loop_stiffness), 1.0, 0, INF, 0, 1,
     "1/s^2", "0", "the stiffness must be >= 0",
     "loop closure (the connect equality at the coupler-follower joint): MuJoCo's direct-form "
     "solref stiffness (mass-normalised); 0: 1/h^2, which with euler removes a violation in "
     "one step"},
    {"mujoco", "loop_damping_1_s", K_DOUBLE, OFF(mujoco.loop_damping), 1.0, 0, INF, 0, 1, "1/s",
     "0", "the damping must be >= 0",
     "loop closure: MuJoCo's direct-form solref damping; 0: 1/h"},
    {"mujoco", "loop_impedance", K_DOUBLE, OFF(mujoco.loop_impedance), 1.0, 0, 1, 1, 1, "-",
     "0.9999", "the impedance must lie in (0, 1)",
     "loop closure: MuJoCo's solimp dmin = dmax (how much of the reference acceleration the "
     "constraint enforces; 1 would be rigid)"},
    {"mujoco", "drive_armature_kg_m2", K_DOUBLE, OFF(mujoco.drive_armature), 1.0, 0, INF, 1, 1,
     "kg m^2", "1e6", "the armature must be positive",
     "armature of the crank hinge: the crank is a flywheel set to the crank speed at t = 0, "
     "so the reaction torques barely change its speed (the crank-angle error is reported)"},
    {"mujoco", "native_bore", K_MJBORE, OFF(mujoco.native_bore), 0, 0, 0, 0, 0, "-", "tendon",
     "tendon or facets",
     "the hole of mujoco-clearance-native, solved by MuJoCo's constraint solver: tendon, a "
     "spatial tendon from the hole's centre to the pin's limited to the radial clearance (one "
     "limit row along the eccentricity); facets, a sphere pin in a ring of [clearance] "
     "faceted_n boxes (one contact per touching box; see docs/engines.md)"},

    {"bullet", "solver", K_BTSOLVER, OFF(bullet.solver), 0, 0, 0, 0, 0, "-", "mlcp-dantzig",
     "sequential-impulse or mlcp-dantzig",
     "constraint solver of the bullet-* models: btSequentialImpulseConstraintSolver "
     "(iterative) or btMLCPSolver with btDantzigSolver (direct; the default, which reaches the "
     "analytic solution to 1e-4: docs/engines.md)"},
    {"bullet", "iterations", K_INT, OFF(bullet.iterations), 0, 1, 100000, 0, 0, "-", "100",
     "iterations must be 1 to 100000",
     "sequential-impulse sweeps per step of the bullet-* models (btContactSolverInfo "
     "m_numIterations; also the MLCP's fallback)"},
    {"simbody", "integrator", K_SBINT, OFF(simbody.integrator), 0, 0, 0, 0, 0, "-", "rkmerson",
     "rkmerson, rkfeldberg, rk3, cpodes or verlet",
     "integrator of the simbody-* models: Simbody's RungeKuttaMerson, RungeKuttaFeldberg, "
     "RungeKutta3, CPodes (BDF, for stiff problems) or Verlet integrator, each with its own "
     "error control (docs/engines.md)"},
    {"simbody", "accuracy", K_DOUBLE, OFF(simbody.accuracy), 1.0, FB_SIMBODY_ACCURACY_MIN,
     FB_SIMBODY_ACCURACY_MAX, 0, 0, "-", FB_SIMBODY_ACCURACY_DEFAULT_TEXT,
     "the accuracy must lie in [1e-12, 0.1]",
     "the simbody-* models' integrator accuracy (Integrator::setAccuracy, a relative error "
     "per step); the output is sampled every h whatever the internal steps are"},

    {"published", "source", K_STRING, OFF(published_source), 0, 0, 0, 0, 0, "-", "(none)",
     "free text, at most 159 characters",
     "where the [published.impact] and [published.restitution] values come from (printed "
     "with them)"},
    PUBLISHED_KEYS("published.impact", FB_PUBLISHED_IMPACT, "impact"),
    PUBLISHED_KEYS("published.restitution", FB_PUBLISHED_RESTITUTION, "restitution"),

    {"run", "revolutions", K_INT, OFF(revolutions), 0, 1, 1e6, 0, 0, "-", "3",
     "at least 2 with peaks = steady (the first revolution is a run-in); at least 1 with "
     "peaks = all",
     "crank revolutions simulated"},
    {"run", "max_wall_s", K_DOUBLE, OFF(max_wall_s), 1.0, 0, INF, 1, 1, "s", "86400",
     "the wall-time limit must be positive",
     "before simulating, fourbar estimates each model's memory and wall time from its step "
     "count, its engine's options and the [run] ensemble's members; a run estimated to take "
     "longer than this is refused (one that cannot fit in memory always is), and a model "
     "still running this long after the run began stops there (status wall-time)"},
    {"run", "start", K_START, OFF(start), 0, 0, 0, 0, 0, "-", "steady", "steady or rest",
     "initial state: steady (every body on the ideal mechanism's motion) or rest (the crank "
     "at full speed from t = 0, every body not rigidly tied to it at rest: coupler and "
     "follower of the clearance models; the ideal models get the velocities their joints "
     "impose)"},
    {"run", "pin_start", K_PINSTART, OFF(pin_start), FB_RAD_PER_DEG, -INF, INF, 1, 1, "deg",
     "centred", "centred, resting, or a finite eccentricity angle in degrees",
     "pin position in every clearance joint at t = 0: centred in its hole, resting on the "
     "wall along the static gravity load the joint carries, or on the wall at this "
     "eccentricity angle (pin centre - hole centre, counter-clockwise from +x)"},
    {"run", "ensemble", K_INT, OFF(ensemble), 0, 1, 64, 0, 0, "-", "1",
     "an integer from 1 to 64",
     "runs of the clearance models and their references, each with the pins' initial "
     "eccentricity moved by 1e-6 x the radial clearance in another direction (the first run "
     "unmoved); the impact statistics (peak force, coupler and follower alpha spikes per "
     "impact) are pooled over them and their spread reported (docs/chaos.md); not given: "
     "fourbar run adds 5 by itself when a model's verdict is unsettled (it left its "
     "reference, or a reference its check integration)"},
    {"run", "peaks", K_PEAKS, OFF(peaks), 0, 0, 0, 0, 0, "-", "steady", "steady or all",
     "window of the reported peaks: steady (from the second revolution on) or all (from "
     "t = 0, the start-up included); summary.json reports the first revolution alone too"},
    {"run", "series", K_SERIES, OFF(series), 0, 0, 0, 0, 0, "-", "csv", "csv, hdf5 or none",
     "time series written per run: csv (DIR/<model>.csv), hdf5 (DIR/series.h5, one group per "
     "model; needs a build with libhdf5) or none (docs/series.md)"},
    {"run", "series_every", K_INT, OFF(series_every), 0, 1, 1e9, 0, 0, "-", "1",
     "a whole number from 1 to 1000000000",
     "write every N-th sample of the time series, and every sample of each impact episode "
     "(contact state impact, with one sample either side)"},
    {"run", "models", K_MODELS, OFF(models), 0, 0, 0, 0, 0, "-",
     "analytic, analytic-stackup, ode-ideal-nominal, ode-ideal-stackup", "known model names",
     "models to run, comma-separated; a name with * is a pattern that adds every model "
     "of this build it matches (e.g. *-clearance-impact: every engine's); not given: the default list, and for a case with "
     "clearance joints also " FB_CLEARANCE_DEFAULT_MODELS},
};

#define NKEYS ((int)(sizeof keys / sizeof keys[0]))
_Static_assert(sizeof keys / sizeof keys[0] <= FB_CASE_MAX_KEYS,
               "fb_case.given has a slot per key: raise FB_CASE_MAX_KEYS");

int fb_casefile_key_count(void) { return NKEYS; }

int fb_casefile_name_ok(const char *name) {
  size_t n = strlen(name);
  return n > 0 && n < FB_NAME_SIZE && name[0] != '.' &&
         strspn(name, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_.") == n;
}

const char *fb_casefile_key_name(int i, char *buf, size_t size) {
  snprintf(buf, size, "%s.%s", keys[i].section, keys[i].key);
  return buf;
}

void fb_casefile_write_keys(FILE *f) {
  fprintf(f, "| key | unit | default | rule | meaning |\n|---|---|---|---|---|\n");
  const char *section = "";
  for (int i = 0; i < NKEYS; i++) {
    if (strcmp(section, keys[i].section) != 0) section = keys[i].section;
    fprintf(f, "| [%s] %s | %s | %s | %s | %s |\n", keys[i].section, keys[i].key, keys[i].unit,
            keys[i].def, keys[i].rule, keys[i].doc);
  }
}

/* ---- raw entries: what the file and --set said, with where -------------- */

#define MAX_ENTRIES 512

typedef struct {
  char section[64];
  char key[64];
  char value[256];
  char origin[512]; /* "file:line" or "--set" */
  int line;         /* 0 for --set */
} entry;

typedef struct {
  entry e[MAX_ENTRIES];
  int n;
  const char *path;
  fb_ini_lines *lines; /* the line reader: the line it returned last */
  const char *text; /* parse this text instead of the file (fb_casefile_load_text) */
  size_t text_size;
  fb_status status; /* first error seen by the handler */
  fb_diag *diag;
} load_ctx;

static int find_entry(const load_ctx *c, const char *section, const char *key) {
  for (int i = 0; i < c->n; i++)
    if (strcmp(c->e[i].section, section) == 0 && strcmp(c->e[i].key, key) == 0) return i;
  return -1;
}

static fb_status put_entry(load_ctx *c, const char *section, const char *key,
                           const char *value, const char *origin, int line, int replace) {
  if (strlen(section) >= sizeof c->e[0].section || strlen(key) >= sizeof c->e[0].key ||
      strlen(value) >= sizeof c->e[0].value)
    return fb_diag_set(c->diag, FB_ERR_PARSE, "%s: [%s] %s: section, key or value is too long",
                       origin, section, key);
  int i = find_entry(c, section, key);
  if (i >= 0 && !replace)
    return fb_diag_set(c->diag, FB_ERR_PARSE,
                       "%s: duplicate key '%s' in [%s] (first given at %s); give each key once",
                       origin, key, section, c->e[i].origin);
  if (i < 0) {
    if (c->n == MAX_ENTRIES)
      return fb_diag_set(c->diag, FB_ERR_PARSE, "%s: more than %d keys", origin, MAX_ENTRIES);
    i = c->n++;
  }
  entry *e = &c->e[i];
  snprintf(e->section, sizeof e->section, "%s", section);
  snprintf(e->key, sizeof e->key, "%s", key);
  snprintf(e->value, sizeof e->value, "%s", value);
  snprintf(e->origin, sizeof e->origin, "%s", origin);
  e->line = line;
  return FB_OK;
}

static int on_ini_entry(void *user, const char *section, const char *name, const char *value) {
  load_ctx *c = user;
  if (c->status != FB_OK) return 1;
  char origin[512];
  snprintf(origin, sizeof origin, "%s:%d", c->path, c->lines->line);
  c->status = put_entry(c, section, name, value, origin, c->lines->line, 0);
  return 1;
}

/* ---- interpretation --------------------------------------------------------- */

/* 1 when every '_'-separated word of key appears in typed, in order (a word
 * of 4 or more letters also with one typo), with at most two words of typed
 * besides: "crank_lenght_mm" holds crank_mm's words */
static int words_within(const char *typed, const char *key) {
  char t[128], k[128];
  snprintf(t, sizeof t, "%s", typed);
  snprintf(k, sizeof k, "%s", key);
  char *tw[16], *kw[16], *save = NULL;
  int nt = 0, nk = 0;
  for (char *w = strtok_r(t, "_", &save); w && nt < 16; w = strtok_r(NULL, "_", &save)) tw[nt++] = w;
  save = NULL;
  for (char *w = strtok_r(k, "_", &save); w && nk < 16; w = strtok_r(NULL, "_", &save)) kw[nk++] = w;
  if (nk == 0 || nk >= nt || nt - nk > 2) return 0;
  int at = 0;
  for (int i = 0; i < nk; i++) {
    while (at < nt && strcmp(tw[at], kw[i]) != 0 &&
           !(strlen(kw[i]) >= 4 && fb_edit_distance(tw[at], kw[i]) <= 1))
      at++;
    if (at == nt) return 0;
    at++;
  }
  return 1;
}

static const key_spec *find_spec(const char *section, const char *key) {
  for (int i = 0; i < NKEYS; i++)
    if (strcmp(keys[i].section, section) == 0 && strcmp(keys[i].key, key) == 0) return &keys[i];
  return NULL;
}

static int section_known(const char *section) {
  for (int i = 0; i < NKEYS; i++)
    if (strcmp(keys[i].section, section) == 0) return 1;
  return 0;
}

static fb_status unknown_key(const entry *e, fb_diag *diag) {
  const key_spec *best = NULL;
  int bd = 1 << 30;
  const key_spec *words = NULL; /* a key whose words the typed one holds */
  int wd = 1 << 30;
  for (int i = 0; i < NKEYS; i++) {
    /* a key missing its unit suffix ("speed" for "speed_rpm") is a prefix */
    size_t n = strlen(e->key);
    int prefix = n >= 3 && strncmp(keys[i].key, e->key, n) == 0;
    const int other = strcmp(keys[i].section, e->section) ? 3 : 0;
    int d = (prefix ? 1 : fb_edit_distance(e->key, keys[i].key)) + other;
    if (d < bd) bd = d, best = &keys[i];
    /* one with a word too many ("crank_length_mm"): the key's words, in order */
    if (other < wd && words_within(e->key, keys[i].key)) wd = other, words = &keys[i];
  }
  if (!(best && (bd <= 4 || bd <= fb_suggest_bound(e->key))) && words) best = words, bd = 0;
  if (!e->section[0]) {
    /* a key above the first [section] header */
    const key_spec *k = NULL;
    for (int i = 0; i < NKEYS && !k; i++)
      if (strcmp(keys[i].key, e->key) == 0) k = &keys[i];
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: key '%s' comes before any [section] header%s%s%s",
                       e->origin, e->key, k ? "; it belongs under [" : "", k ? k->section : "",
                       k ? "]" : "");
  }
  if (!section_known(e->section)) {
    int sd = 1 << 30;
    const char *bs = NULL;
    for (int i = 0; i < NKEYS; i++) {
      int d = fb_edit_distance(e->section, keys[i].section);
      if (d < sd) sd = d, bs = keys[i].section;
    }
    return fb_diag_set(diag, FB_ERR_PARSE,
                       "%s: unknown section [%s]%s%s%s (sections: case, linkage, tolerance, "
                       "drive, environment, mass, material, pin, clearance, expect, solver, mujoco, bullet, "
                       "simbody, run, published, published.impact, published.restitution, "
                       "variant.<name>)",
                       e->origin, e->section, bs && sd <= 3 ? "; did you mean [" : "",
                       bs && sd <= 3 ? bs : "", bs && sd <= 3 ? "]?" : "");
  }
  if (best && (bd <= 4 || bd <= fb_suggest_bound(e->key)))
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: unknown key '%s' in [%s]; did you mean [%s] %s?",
                       e->origin, e->key, e->section, best->section, best->key);
  return fb_diag_set(diag, FB_ERR_PARSE,
                     "%s: unknown key '%s' in [%s]; see fourbar keys (docs/keys.md) for the keys", e->origin,
                     e->key, e->section);
}

int fb_casefile_underflows(const char *text) {
  errno = 0;
  const double v = strtod(text, NULL);
  return errno == ERANGE && fabs(v) < DBL_MIN;
}

int fb_casefile_decimal(const char *text, double *out) {
  while (*text == ' ' || *text == '\t') text++;
  if (fb_casefile_underflows(text)) return 0;
  char *end;
  const double v = strtod(text, &end);
  /* strtod also reads hexadecimal (0x10, 0x1p3), inf and nan: refused */
  const size_t used = (size_t)(end - text);
  if (used == 0 || strspn(text, "0123456789+-.eE") < used) return 0;
  while (*end == ' ' || *end == '\t') end++;
  if (*end != '\0') return 0;
  *out = v;
  return 1;
}

fb_status fb_casefile_check_range(const char *section, const char *key, double value,
                                  const char *origin, fb_diag *diag) {
  const key_spec *k = find_spec(section, key);
  if (!k) return FB_OK;
  const int bad_lo = k->lo_open ? !(value > k->lo) : !(value >= k->lo);
  const int bad_hi = k->hi_open ? !(value < k->hi) : !(value <= k->hi);
  if (bad_lo || bad_hi || !isfinite(value))
    return fb_diag_set(diag, FB_ERR_RANGE, "%s = %s: %s (as [%s] %s)", origin, FB_NUM(value),
                       k->rule, section, key);
  return FB_OK;
}

static fb_status parse_double(const entry *e, const key_spec *k, double *out, fb_diag *diag) {
  char *end;
  double v = strtod(e->value, &end);
  while (*end == ' ' || *end == '\t') end++;
  if (end == e->value || *end != '\0')
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s = '%s': not a number (%s)", e->origin,
                       e->section, e->key, e->value, k->unit);
  if (!isfinite(v))
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s = '%s': must be a finite number",
                       e->origin, e->section, e->key, e->value);
  if (fb_casefile_underflows(e->value))
    return fb_diag_set(diag, FB_ERR_RANGE, "%s: [%s] %s = '%s': below the smallest normal "
                       "double (2.2e-308), so it would read as %g: give 0 or a larger number (%s)",
                       e->origin, e->section, e->key, e->value, v, k->unit);
  if (!fb_casefile_decimal(e->value, &v))
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s = '%s': numbers are decimal (digits, "
                       "sign, point, exponent), not hexadecimal (%s)", e->origin, e->section,
                       e->key, e->value, k->unit);
  int bad_lo = k->lo_open ? !(v > k->lo) : !(v >= k->lo);
  int bad_hi = k->hi_open ? !(v < k->hi) : !(v <= k->hi);
  if (bad_lo || bad_hi)
    return fb_diag_set(diag, FB_ERR_RANGE, "%s: [%s] %s = %s: %s", e->origin, e->section,
                       e->key, e->value, k->rule);
  *out = v;
  return FB_OK;
}

static fb_status bad_word(const entry *e, const key_spec *k, fb_diag *diag) {
  return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s = '%s': must be %s", e->origin,
                     e->section, e->key, e->value, k->rule);
}

static char *trim(char *s) {
  while (*s == ' ' || *s == '\t') s++;
  size_t n = strlen(s);
  while (n > 0 && (s[n - 1] == ' ' || s[n - 1] == '\t')) s[--n] = '\0';
  return s;
}

/* 1 when a comma-separated list has an empty item ("a,,b", "a,", ",a") */
static int has_empty_item(const char *v) {
  const char *p = v;
  for (;;) {
    const char *q = strchr(p, ',');
    const char *end = q ? q : p + strlen(p);
    int blank = 1;
    for (const char *x = p; x < end; x++)
      if (*x != ' ' && *x != '\t') blank = 0;
    if (blank) return 1;
    if (!q) return 0;
    p = q + 1;
  }
}

static fb_status apply(fb_case *c, const entry *e, fb_diag *diag) {
  const key_spec *k = find_spec(e->section, e->key);
  if (!k) return unknown_key(e, diag);
  void *field = (char *)c + k->offset;
  double v = 0.0;
  fb_status st;
  switch (k->kind) {
    case K_DOUBLE:
      st = parse_double(e, k, &v, diag);
      if (st == FB_OK) *(double *)field = v * k->scale;
      return st;
    case K_UNUSED:
      return parse_double(e, k, &v, diag);
    case K_INT:
    case K_ULONG: {
      char *end;
      errno = 0;
      long long n = strtoll(e->value, &end, 10);
      if (end == e->value || *trim(end) != '\0' || errno)
        return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s = '%s': not an integer", e->origin,
                           e->section, e->key, e->value);
      if (k->kind == K_ULONG) {
        if (n < 0 || (unsigned long long)n > 0xFFFFFFFFull)
          return fb_diag_set(diag, FB_ERR_RANGE, "%s: [%s] %s = %s: %s (at most 4294967295)",
                             e->origin, e->section, e->key, e->value, k->rule);
        *(unsigned long *)field = (unsigned long)n;
        return FB_OK;
      }
      if ((double)n < k->lo || (double)n > k->hi)
        return fb_diag_set(diag, FB_ERR_RANGE, "%s: [%s] %s = %s: %s", e->origin, e->section,
                           e->key, e->value, k->rule);
      if (k->offset == OFF(revolutions))
        *(double *)field = (double)n;
      else
        *(int *)field = (int)n;
      return FB_OK;
    }
    case K_NAME: {
      size_t n = strlen(e->value);
      if (!fb_casefile_name_ok(e->value))
        return fb_diag_set(diag, FB_ERR_PARSE,
                           "%s: [%s] %s = '%s': a name is 1 to %d characters from letters, "
                           "digits, '-', '_' and '.', not starting with '.'",
                           e->origin, e->section, e->key, e->value, FB_NAME_SIZE - 1);
      memcpy(field, e->value, n + 1);
      return FB_OK;
    }
    case K_TEXT:
      return FB_OK;
    case K_STRING: /* the one such key: [published] source */
      if (strlen(e->value) >= sizeof c->published_source)
        return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s: %zu characters, at most %zu",
                           e->origin, e->section, e->key, strlen(e->value),
                           sizeof c->published_source - 1);
      snprintf(field, sizeof c->published_source, "%s", e->value);
      return FB_OK;
    case K_BRANCH:
      if (strcmp(e->value, "open") == 0) *(fb_branch *)field = FB_BRANCH_OPEN;
      else if (strcmp(e->value, "crossed") == 0) *(fb_branch *)field = FB_BRANCH_CROSSED;
      else return bad_word(e, k, diag);
      return FB_OK;
    case K_DIRECTION:
      if (strcmp(e->value, "ccw") == 0) *(int *)field = +1;
      else if (strcmp(e->value, "cw") == 0) *(int *)field = -1;
      else return bad_word(e, k, diag);
      return FB_OK;
    case K_STEP:
      if (strcmp(e->value, "auto") == 0) {
        c->solver.h_mode = FB_STEP_AUTO;
        return FB_OK;
      }
      if (strcmp(e->value, "adaptive") == 0) {
        c->solver.h_mode = FB_STEP_ADAPTIVE;
        return FB_OK;
      }
      st = parse_double(e, k, &v, diag);
      if (st == FB_OK) {
        *(double *)field = v * k->scale;
        /* the key table's own default leaves the choice to the clearance joints */
        c->solver.h_mode =
            strcmp(e->origin, "key table default") == 0 ? FB_STEP_DEFAULT : FB_STEP_FIXED;
      }
      return st;
    case K_STEPPER:
      if (strcmp(e->value, "world") == 0) *(fb_stepper *)field = FB_STEPPER_WORLD;
      else if (strcmp(e->value, "quick") == 0) *(fb_stepper *)field = FB_STEPPER_QUICK;
      else return bad_word(e, k, diag);
      return FB_OK;
    case K_JOINTS: {
      if (has_empty_item(e->value))
        return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s = '%s': an empty item in the list",
                           e->origin, e->section, e->key, e->value);
      char buf[sizeof e->value];
      snprintf(buf, sizeof buf, "%s", e->value);
      int mask = 0;
      char *save = NULL;
      if (strcmp(trim(buf), "none") != 0) {
        for (char *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
          tok = trim(tok);
          int j = -1;
          for (int q = 0; q < 4; q++)
            if (strcmp(tok, fb_joint_name(q)) == 0) j = q;
          if (j < 0)
            return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s: unknown joint '%s' (%s)",
                               e->origin, e->section, e->key, tok, k->rule);
          mask |= 1 << j;
        }
      }
      *(int *)field = mask;
      return FB_OK;
    }
    case K_PENALTY:
      if (strcmp(e->value, "physical") == 0) *(fb_penalty_source *)field = FB_PENALTY_SOURCE_PHYSICAL;
      else if (strcmp(e->value, "paper") == 0) *(fb_penalty_source *)field = FB_PENALTY_SOURCE_PAPER;
      else if (strcmp(e->value, "explicit") == 0) *(fb_penalty_source *)field = FB_PENALTY_SOURCE_EXPLICIT;
      else if (strcmp(e->value, "goldsmith") == 0) *(fb_penalty_source *)field = FB_PENALTY_SOURCE_GOLDSMITH;
      else return bad_word(e, k, diag);
      return FB_OK;
    case K_MJINT:
      if (strcmp(e->value, "euler") == 0) *(int *)field = FB_MUJOCO_EULER;
      else if (strcmp(e->value, "implicit") == 0) *(int *)field = FB_MUJOCO_IMPLICIT;
      else if (strcmp(e->value, "rk4") == 0) *(int *)field = FB_MUJOCO_RK4;
      else if (strcmp(e->value, "auto") == 0) *(int *)field = FB_MUJOCO_AUTO;
      else return bad_word(e, k, diag);
      return FB_OK;
    case K_MJBORE:
      if (strcmp(e->value, "tendon") == 0) *(int *)field = FB_MUJOCO_BORE_TENDON;
      else if (strcmp(e->value, "facets") == 0) *(int *)field = FB_MUJOCO_BORE_FACETS;
      else return bad_word(e, k, diag);
      return FB_OK;
    case K_BTSOLVER:
      if (strcmp(e->value, "sequential-impulse") == 0) *(int *)field = FB_BULLET_SEQUENTIAL_IMPULSE;
      else if (strcmp(e->value, "mlcp-dantzig") == 0) *(int *)field = FB_BULLET_MLCP_DANTZIG;
      else return bad_word(e, k, diag);
      return FB_OK;
    case K_SBINT: {
      int found = -1;
      for (int i = 0; i < FB_SIMBODY_INTEGRATOR_COUNT; i++)
        if (strcmp(e->value, fb_simbody_integrator_name(i)) == 0) found = i;
      if (found < 0) return bad_word(e, k, diag);
      *(int *)field = found;
      return FB_OK;
    }
    case K_COLLIDER:
      if (strcmp(e->value, "exact") == 0) *(fb_case_collider *)field = FB_CASE_COLLIDER_EXACT;
      else if (strcmp(e->value, "faceted") == 0) *(fb_case_collider *)field = FB_CASE_COLLIDER_FACETED;
      else if (strcmp(e->value, "ccd") == 0) *(fb_case_collider *)field = FB_CASE_COLLIDER_CCD;
      else return bad_word(e, k, diag);
      return FB_OK;
    case K_BORE:
      if (strcmp(e->value, "circle") == 0) *(fb_case_bore *)field = FB_CASE_BORE_CIRCLE;
      else if (strcmp(e->value, "ellipse") == 0) *(fb_case_bore *)field = FB_CASE_BORE_ELLIPSE;
      else return bad_word(e, k, diag);
      return FB_OK;
    case K_MAPPING: {
      const fb_mapping m = fb_mapping_parse(e->value);
      if (m == FB_MAPPING_COUNT) return bad_word(e, k, diag);
      *(int *)field = (int)m;
      return FB_OK;
    }
    case K_START:
      if (strcmp(e->value, "steady") == 0) *(fb_start *)field = FB_START_STEADY;
      else if (strcmp(e->value, "rest") == 0) *(fb_start *)field = FB_START_REST;
      else return bad_word(e, k, diag);
      return FB_OK;
    case K_PEAKS:
      if (strcmp(e->value, "steady") == 0) *(fb_peak_window *)field = FB_PEAKS_STEADY;
      else if (strcmp(e->value, "all") == 0) *(fb_peak_window *)field = FB_PEAKS_ALL;
      else return bad_word(e, k, diag);
      return FB_OK;
    case K_SERIES:
      if (strcmp(e->value, "csv") == 0) *(fb_series_format *)field = FB_SERIES_CSV;
      else if (strcmp(e->value, "none") == 0) *(fb_series_format *)field = FB_SERIES_NONE;
      else if (strcmp(e->value, "hdf5") == 0) {
        if (!FB_HAVE_HDF5)
          return fb_diag_set(diag, FB_ERR_ARG,
                             "%s: [%s] %s = hdf5: this fourbar was built without HDF5; install "
                             "libhdf5-dev (Debian) and rebuild (meson setup --reconfigure build "
                             "-Dhdf5=enabled; ninja -C build), or use csv",
                             e->origin, e->section, e->key);
        *(fb_series_format *)field = FB_SERIES_HDF5;
      } else return bad_word(e, k, diag);
      return FB_OK;
    case K_PINSTART:
      if (strcmp(e->value, "centred") == 0) {
        c->pin_start = FB_PIN_CENTRED;
      } else if (strcmp(e->value, "resting") == 0) {
        c->pin_start = FB_PIN_RESTING;
      } else {
        double deg;
        if (!fb_casefile_decimal(e->value, &deg) || !isfinite(deg)) return bad_word(e, k, diag);
        c->pin_start = FB_PIN_ANGLE;
        c->pin_start_angle = deg * k->scale;
      }
      return FB_OK;
    case K_LIMIT:
      if (strcmp(e->value, "none") == 0) {
        c->clearance.penetration_unlimited = 1;
        return FB_OK;
      }
      c->clearance.penetration_unlimited = 0;
      if (strcmp(e->value, "clearance") == 0) {
        *(double *)field = 0.0;
        return FB_OK;
      }
      {
        char *end;
        (void)strtod(e->value, &end);
        if (end == e->value) return bad_word(e, k, diag); /* neither a word nor a number */
      }
      st = parse_double(e, k, &v, diag);
      if (st == FB_OK) *(double *)field = v * k->scale;
      return st;
    case K_CLASS:
      if (strlen(e->value) != 1 || !strchr("fmcv", e->value[0])) return bad_word(e, k, diag);
      *(char *)field = e->value[0];
      return FB_OK;
    case K_DIST:
      if (strcmp(e->value, "normal") == 0) *(int *)field = 0;
      else if (strcmp(e->value, "uniform") == 0) *(int *)field = 1;
      else return bad_word(e, k, diag);
      return FB_OK;
    case K_OUTPUT: {
      int i = fb_tol_output_parse(e->value);
      if (i < 0) {
        char known[1024] = "";
        for (int j = 0; j < FB_TOL_NOUT; j++) {
          strncat(known, j ? ", " : "", sizeof known - strlen(known) - 1);
          strncat(known, fb_tol_output_name(j), sizeof known - strlen(known) - 1);
        }
        return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s = '%s': unknown output (known: %s)",
                           e->origin, e->section, e->key, e->value, known);
      }
      *(int *)field = i;
      return FB_OK;
    }
    case K_FIT:
      if (strlen(e->value) >= sizeof c->fit)
        return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s: too long", e->origin, e->section,
                           e->key);
      snprintf(c->fit, sizeof c->fit, "%s", e->value);
      return FB_OK;
    case K_STACKUP: {
      fb_stackup *s = field;
      int corner = 2;
      if (strcmp(e->value, "worst") == 0) {
        s->worst = 1;
        return FB_OK;
      }
      s->worst = 0;
      if (strcmp(e->value, "nominal") == 0) corner = 0;
      else if (strcmp(e->value, "max") == 0) corner = +1;
      else if (strcmp(e->value, "min") == 0) corner = -1;
      if (corner != 2) {
        for (int i = 0; i < FB_LINK_COUNT; i++) s->corner[i] = corner;
        return FB_OK;
      }
      if (strlen(e->value) != FB_LINK_COUNT) return bad_word(e, k, diag);
      for (int i = 0; i < FB_LINK_COUNT; i++) {
        char ch = e->value[i];
        if (ch != '+' && ch != '-' && ch != '0') return bad_word(e, k, diag);
        s->corner[i] = ch == '+' ? 1 : (ch == '-' ? -1 : 0);
      }
      return FB_OK;
    }
    case K_MODELS: {
      if (has_empty_item(e->value))
        return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s = '%s': an empty item in the list",
                           e->origin, e->section, e->key, e->value);
      char buf[sizeof e->value];
      snprintf(buf, sizeof buf, "%s", e->value);
      c->model_count = 0;
      char *save = NULL;
      for (char *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        tok = trim(tok);
        if (strchr(tok, '*')) {
          /* a pattern: every model of the table it matches that this build
           * has, in table order, each once */
          const int before = c->model_count;
          for (int q = 0; q < fb_model_count; q++) {
            const fb_model *m = &fb_models[q];
            if (fnmatch(tok, m->name, 0) != 0 || !fb_engine_available(m->engine)) continue;
            int dup = 0;
            for (int i = 0; i < c->model_count; i++) dup |= strcmp(c->models[i], m->name) == 0;
            if (dup) continue;
            if (c->model_count == FB_MAX_MODELS)
              return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s: more than %d models", e->origin,
                                 e->section, e->key, FB_MAX_MODELS);
            snprintf(c->models[c->model_count++], FB_NAME_SIZE, "%s", m->name);
          }
          if (c->model_count == before) {
            char known[768];
            fb_model_list(known, sizeof known);
            return fb_diag_set(diag, FB_ERR_PARSE,
                               "%s: [%s] %s: pattern '%s' matches no model of this build "
                               "(known: %s)",
                               e->origin, e->section, e->key, tok, known);
          }
          continue;
        }
        if (!fb_model_find(tok)) {
          char known[768];
          fb_model_list(known, sizeof known);
          return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s: unknown model '%s' (known: %s)",
                             e->origin, e->section, e->key, tok, known);
        }
        if (!fb_engine_available(fb_model_find(tok)->engine))
          return fb_diag_set(diag, FB_ERR_ARG, "%s: [%s] %s: model '%s' is not in this build: %s",
                             e->origin, e->section, e->key, tok,
                             fb_engine_howto(fb_model_find(tok)->engine)[0]
                                 ? fb_engine_howto(fb_model_find(tok)->engine)
                                 : "its engine was left out");
        for (int i = 0; i < c->model_count; i++)
          if (strcmp(c->models[i], tok) == 0)
            return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s: model '%s' listed twice",
                               e->origin, e->section, e->key, tok);
        if (c->model_count == FB_MAX_MODELS)
          return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s: more than %d models", e->origin,
                             e->section, e->key, FB_MAX_MODELS);
        snprintf(c->models[c->model_count++], FB_NAME_SIZE, "%s", tok);
      }
      if (c->model_count == 0)
        return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s is empty: name at least one model",
                           e->origin, e->section, e->key);
      return FB_OK;
    }
  }
  return FB_ERR_ARG;
}

/* 1 when a key's default is a value to apply ("(none)", "-" and "" are not) */
static int has_default(const key_spec *k) {
  return k->kind != K_TEXT && k->kind != K_UNUSED && k->def[0] != '\0' &&
         strcmp(k->def, "(none)") != 0 && strcmp(k->def, DERIVED) != 0 &&
         strcmp(k->def, "-") != 0;
}

/* key i's default as an entry, as if a file had said it */
static void default_entry(entry *e, int i) {
  memset(e, 0, sizeof *e);
  snprintf(e->section, sizeof e->section, "%s", keys[i].section);
  snprintf(e->key, sizeof e->key, "%s", keys[i].key);
  snprintf(e->value, sizeof e->value, "%s", keys[i].def);
  snprintf(e->origin, sizeof e->origin, "key table default");
}

static int key_index(const char *section, const char *key) {
  for (int i = 0; i < NKEYS; i++)
    if (strcmp(keys[i].section, section) == 0 && strcmp(keys[i].key, key) == 0) return i;
  return -1;
}

int fb_casefile_given(const fb_case *c, const char *section, const char *key) {
  const int i = key_index(section, key);
  return i >= 0 && c->given[i];
}

/* each link's mass and inertias the case does not give, from its bar (nominal
 * length, width, thickness) and the density (bar_mass.h); the source of every
 * field recorded for the writers */
static fb_status resolve_masses(fb_case *c, fb_diag *diag) {
  for (int i = 0; i < 3; i++) {
    const char *nm = fb_link_name(i);
    char k_m[64], k_i[64], k_l[64], k_t[64], k_f[64];
    snprintf(k_m, sizeof k_m, "%s_kg", nm);
    snprintf(k_i, sizeof k_i, "%s_inertia_kg_mm2", nm);
    snprintf(k_l, sizeof k_l, "%s_inertia_long_kg_mm2", nm);
    snprintf(k_t, sizeof k_t, "%s_inertia_transverse_kg_mm2", nm);
    snprintf(k_f, sizeof k_f, "%s_com_fraction", nm);
    const fb_bar b = {c->nominal.length[i], c->link_width[i], c->link_thickness[i], c->density};
    fb_link_mass *m = &c->link[i];
    fb_link_mass_source *src = &c->link_source[i];
    const int given_mass = fb_casefile_given(c, "mass", k_m);
    const double mass = given_mass ? m->mass : fb_bar_mass(&b);
    if (!given_mass && !(mass >= FB_MASS_MIN_KG && mass <= FB_MASS_MAX_KG))
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "[mass] %s not given: the %s's bar gives %g kg ([material] "
                         "density_kg_m3 = %g x [mass] %s_width_mm = %g x %s_thickness_mm = %g x "
                         "[linkage] %s_mm = %g): %s; give [mass] %s or change the bar",
                         k_m, nm, mass, c->density, nm, c->link_width[i] * 1e3, nm,
                         c->link_thickness[i] * 1e3, nm, c->nominal.length[i] * 1e3, MASS_RULE,
                         k_m);
    fb_link_mass bar;
    fb_diag inner;
    fb_status st = fb_bar_fill(&bar, &b, mass, &inner);
    if (st != FB_OK) return fb_diag_set(diag, st, "[mass] the %s's bar: %s", nm, inner.msg);
    src->mass = given_mass ? FB_SOURCE_CASE : FB_SOURCE_DERIVED;
    m->mass = mass;
#define FB_TAKE(field, key)                                                 \
  do {                                                                      \
    src->field = fb_casefile_given(c, "mass", key) ? FB_SOURCE_CASE : FB_SOURCE_DERIVED; \
    if (src->field == FB_SOURCE_DERIVED) m->field = bar.field;              \
  } while (0)
    FB_TAKE(inertia, k_i);
    FB_TAKE(inertia_long, k_l);
    FB_TAKE(inertia_transverse, k_t);
#undef FB_TAKE
    /* the key table's 0.5 is a default, not derived from the bar */
    src->com_fraction = fb_casefile_given(c, "mass", k_f) ? FB_SOURCE_CASE : FB_SOURCE_DEFAULT;
  }
  return FB_OK;
}

void fb_case_default(fb_case *c) {
  memset(c, 0, sizeof *c);
  /* what no key sets: where the tolerances and the clearance came from, and
   * the stack-up corner (every link at its maximum) */
  for (int i = 0; i < FB_LINK_COUNT; i++) {
    snprintf(c->tolerance_source[i], sizeof c->tolerance_source[i], "none (0)");
    c->stackup.corner[i] = +1;
  }
  snprintf(c->clearance_source, sizeof c->clearance_source,
           "default (10 H7/g6 maximum, 29 um diametral / 2)");
  /* no published value until a case gives one */
  for (int l = 0; l < FB_PUBLISHED_LAWS; l++) {
    fb_case_body_values *b[2] = {&c->published[l].coupler, &c->published[l].follower};
    for (int q = 0; q < 2; q++) b[q]->omega_max = b[q]->omega_min = b[q]->alpha_max = b[q]->alpha_min = NAN;
  }
  /* every other default is the key table's, read by the same parser as a
   * file (a test checks that each one applies) */
  for (int i = 0; i < NKEYS; i++) {
    if (!has_default(&keys[i])) continue;
    entry e;
    default_entry(&e, i);
    fb_diag d;
    (void)apply(c, &e, &d);
  }
  /* nothing given: every mass and inertia from the default bar (the key
   * table's defaults make a valid bar, test_casefile checks it) */
  fb_diag d;
  (void)resolve_masses(c, &d);
}

int fb_casefile_defaults_check(fb_diag *diag) {
  for (int i = 0; i < NKEYS; i++) {
    if (!has_default(&keys[i])) continue;
    fb_case c;
    memset(&c, 0, sizeof c);
    entry e;
    default_entry(&e, i);
    fb_diag inner;
    if (apply(&c, &e, &inner) != FB_OK)
      return fb_diag_set(diag, FB_ERR_PARSE, "default of [%s] %s = '%s' does not apply: %s",
                         keys[i].section, keys[i].key, keys[i].def, inner.msg);
  }
  return FB_OK;
}

/* origin of an entry ("file:line" or "--set ..."), or NULL if absent */
static const char *entry_origin(const load_ctx *c, const char *section, const char *key) {
  int i = find_entry(c, section, key);
  return i >= 0 ? c->e[i].origin : NULL;
}

/* tolerances from ISO 2768-1 and the clearance from an ISO 286 fit, with
 * the source of each recorded for the report */
static fb_status resolve_standards(fb_case *out, const load_ctx *c, fb_diag *diag) {
  for (int k = 0; k < FB_LINK_COUNT; k++) {
    char key[64];
    snprintf(key, sizeof key, "%s_plus_minus_mm", fb_link_name(k));
    if (entry_origin(c, "tolerance", key)) {
      snprintf(out->tolerance_source[k], sizeof out->tolerance_source[k], "explicit");
    } else if (out->tolerance_class) {
      fb_diag inner;
      fb_status st = fb_iso2768_linear(&out->plus_minus[k], out->tolerance_class,
                                       out->nominal.length[k], out->tolerance_source[k],
                                       sizeof out->tolerance_source[k], &inner);
      if (st != FB_OK)
      {
        char lkey[64];
        snprintf(lkey, sizeof lkey, "%s_mm", fb_link_name(k));
        const char *len_at = entry_origin(c, "linkage", lkey);
        /* a length in the wrong unit shows here first: say so */
        const char *why = fb_casefile_length_implausible(out->nominal.length[k]);
        return fb_diag_set(diag, st, "%s: [tolerance] class = %c for [linkage] %s = %g (%s%s): %s%s%s%s",
                           entry_origin(c, "tolerance", "class"), out->tolerance_class, lkey,
                           out->nominal.length[k] * 1e3, len_at ? "given at " : "the default",
                           len_at ? len_at : "", inner.msg, why ? "; a link length " : "",
                           why ? why : "", why ? " (the key is in millimetres)" : "");
      }
    } else {
      snprintf(out->tolerance_source[k], sizeof out->tolerance_source[k], "none (0)");
    }
  }
  const char *fit_at = entry_origin(c, "pin", "fit");
  if (fit_at && strcmp(out->fit, "none") == 0) { /* cancels a fit inherited from a base */
    fit_at = NULL;
    out->fit[0] = '\0';
  }
  const char *rc_at = entry_origin(c, "pin", "radial_clearance_um");
  if (fit_at) {
    if (rc_at)
      return fb_diag_set(diag, FB_ERR_PARSE,
                         "%s: [pin] radial_clearance_um and fit (%s) both given: give one "
                         "(to replace a base case's fit by an explicit clearance: "
                         "--set pin.fit=none, or fit = none in the case file)",
                         rc_at, fit_at);
    fb_fit f;
    fb_diag inner;
    fb_status st = fb_iso286_fit(&f, out->fit, &inner);
    if (st != FB_OK) return fb_diag_set(diag, st, "%s: [pin] fit = '%s': %s", fit_at, out->fit, inner.msg);
    if (f.kind != FB_FIT_CLEARANCE)
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "%s: [pin] fit = '%s' is a%s %s fit (clearance %+.1f to %+.1f um): %sa "
                         "clearance joint needs a clearance fit (minimum clearance >= 0)",
                         fit_at, out->fit, f.kind == FB_FIT_INTERFERENCE ? "n" : "",
                         fb_fit_kind_name(f.kind), f.clearance_min * 1e6, f.clearance_max * 1e6,
                         f.kind == FB_FIT_INTERFERENCE
                             ? "an interference fit has no clearance (a press fit holds the pin "
                               "fast); "
                             : "");
    const char *d_at = entry_origin(c, "pin", "diameter_mm");
    if (d_at && fabs(out->pin_diameter - f.nominal) > 1e-12)
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "%s: [pin] diameter_mm = %g disagrees with the fit's nominal size %g mm",
                         d_at, out->pin_diameter * 1e3, f.nominal * 1e3);
    out->pin_diameter = f.nominal;
    out->radial_clearance = 0.5 * f.clearance_max;
    snprintf(out->clearance_source, sizeof out->clearance_source,
             "ISO 286-1 %s: maximum clearance %.1f um diametral, / 2", out->fit,
             f.clearance_max * 1e6);
  } else {
    snprintf(out->clearance_source, sizeof out->clearance_source, "%s",
             rc_at ? "explicit" : "default (10 H7/g6 maximum, 29 um diametral / 2)");
  }
  return FB_OK;
}

/* reads line n of path (1-based) for an error message */
static void read_line(const char *path, int n, char *buf, size_t size) {
  buf[0] = '\0';
  int not_regular;
  FILE *f = fb_fopen_regular(path, &not_regular);
  if (!f) return;
  char line[1024];
  for (int i = 1; fgets(line, sizeof line, f); i++)
    if (i == n) {
      line[strcspn(line, "\r\n")] = '\0';
      size_t len = strlen(line);
      if (len >= size) len = size - 1;
      memcpy(buf, line, len);
      buf[len] = '\0';
      break;
    }
  fclose(f);
}

static fb_status parse_override(load_ctx *c, const char *ov, int index) {
  char origin[64];
  snprintf(origin, sizeof origin, "--set #%d '%.40s'", index + 1, ov);
  size_t bad;
  if (!fb_text_utf8_ok(ov, strlen(ov), &bad))
    return fb_diag_set(c->diag, FB_ERR_PARSE, "%s: byte 0x%02x at position %zu is not UTF-8 text "
                       "(its value goes into JSON, which holds UTF-8 only)", origin,
                       (unsigned char)ov[bad], bad + 1);
  const char *eq = strchr(ov, '=');
  /* the key has no dot, a section may ([published.impact]): the last dot before '=' */
  const char *dot = NULL;
  for (const char *q = ov; eq && q < eq; q++)
    if (*q == '.') dot = q;
  if (!eq || !dot || dot == ov || dot + 1 == eq)
    return fb_diag_set(c->diag, FB_ERR_PARSE,
                       "--set '%s': expected section.key=value (for example "
                       "drive.speed_rpm=1500)",
                       ov);
  char section[64], key[64], value[256];
  size_t ls = (size_t)(dot - ov), lk = (size_t)(eq - dot - 1);
  if (ls >= sizeof section || lk >= sizeof key || strlen(eq + 1) >= sizeof value)
    return fb_diag_set(c->diag, FB_ERR_PARSE, "--set '%s': too long", ov);
  memcpy(section, ov, ls);
  section[ls] = '\0';
  memcpy(key, dot + 1, lk);
  key[lk] = '\0';
  snprintf(value, sizeof value, "%s", eq + 1);
  if (strcmp(trim(section), "case") == 0 && strcmp(trim(key), "base") == 0)
    return fb_diag_set(c->diag, FB_ERR_PARSE, "%s: [case] base cannot be set from the command "
                       "line (it would be read after the case file it extends): write a case "
                       "file with base = %s and run that", origin, trim(value));
  return put_entry(c, trim(section), trim(key), trim(value), origin, 0, 1);
}

#define MAX_BASE_DEPTH 4

/* parses one file into ctx entries of its own, then merges: the entries of
 * its [case] base file (resolved relative to it, recursively) first, its own
 * keys replacing them */
static fb_status read_file_entries(load_ctx *top, const char *path, int depth, fb_diag *diag,
                                   const char *text, size_t text_size) {
  load_ctx *c = calloc(1, sizeof *c);
  if (!c) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  c->path = path;
  c->text = text;
  c->text_size = text_size;
  c->diag = diag;
  c->status = FB_OK;
  fb_status st = FB_OK;
  /* a directory opens and reads as empty, a device may never end, a FIFO
   * blocks the open itself: only a regular file is read (fileio.h) */
  int not_regular = 0;
  FILE *f = c->text ? fmemopen((void *)c->text, c->text_size, "r")
                    : fb_fopen_regular(path, &not_regular);
  if (!f) {
    st = not_regular ? fb_diag_set(diag, FB_ERR_IO, "%s: not a regular file (a case file is a "
                                   "text file)", path)
                     : fb_diag_set(diag, FB_ERR_IO, "%s: cannot open case file: %s", path,
                                   strerror(errno));
    goto out;
  }
  fb_ini_lines lines = {0};
  lines.f = f;
  c->lines = &lines;
  int rc = ini_parse_stream(fb_ini_lines_read, &lines, on_ini_entry, c);
  fclose(f);
  if (c->status != FB_OK) {
    st = c->status;
    goto out;
  }
  if (lines.problem != FB_INI_LINE_OK) {
    char msg[FB_DIAG_SIZE];
    st = fb_diag_set(diag, FB_ERR_PARSE, "%s", fb_ini_lines_problem(&lines, path, msg, sizeof msg));
    goto out;
  }
  if (rc != 0) {
    char line[256] = "";
    if (!c->text) read_line(path, rc, line, sizeof line);
    st = fb_diag_set(diag, FB_ERR_PARSE,
                     "%s:%d: malformed line '%s': expected '[section]', 'key = value' or "
                     "a comment starting with ; or #",
                     path, rc, line);
    goto out;
  }
  int b = find_entry(c, "case", "base");
  if (b >= 0) {
    if (depth >= MAX_BASE_DEPTH) {
      st = fb_diag_set(diag, FB_ERR_PARSE, "%s: [case] base = %s: more than %d nested bases "
                       "(a cycle?)", c->e[b].origin, c->e[b].value, MAX_BASE_DEPTH);
      goto out;
    }
    char base[4096];
    const char *slash = strrchr(path, '/');
    if (c->e[b].value[0] == '/' || !slash)
      snprintf(base, sizeof base, "%s", c->e[b].value);
    else
      snprintf(base, sizeof base, "%.*s/%s", (int)(slash - path), path, c->e[b].value);
    fb_diag inner;
    st = read_file_entries(top, base, depth + 1, &inner, NULL, 0);
    if (st != FB_OK) {
      fb_diag_set(diag, st, "%s: [case] base: %s", c->e[b].origin, inner.msg);
      goto out;
    }
  }
  for (int i = 0; i < c->n; i++) {
    const entry *e = &c->e[i];
    if (strcmp(e->section, "case") == 0 && strcmp(e->key, "base") == 0) continue;
    st = put_entry(top, e->section, e->key, e->value, e->origin, e->line, 1);
    if (st != FB_OK) goto out;
  }
out:
  free(c);
  return st;
}

/* the section prefix of a variant ([variant.NAME]) */
#define VARIANT_PREFIX "variant."

/* splits a variant's set ("a.b=1; c.d=2") into items, each checked to be
 * section.key=value with a key of the table; items[] point into buf */
static fb_status variant_items(const fb_case_variant *v, char *buf, size_t size, char **items,
                               int max, int *n, fb_diag *diag) {
  snprintf(buf, size, "%s", v->set);
  *n = 0;
  char *save = NULL;
  for (char *tok = strtok_r(buf, ";", &save); tok; tok = strtok_r(NULL, ";", &save)) {
    tok = trim(tok);
    if (!*tok) continue;
    const char *eq = strchr(tok, '='), *dot = NULL;
    for (const char *q = tok; eq && q < eq; q++)
      if (*q == '.') dot = q; /* the last dot before '=' (sections may hold one) */
    char section[64] = "", key[64] = "";
    if (eq && dot && (size_t)(dot - tok) < sizeof section &&
        (size_t)(eq - dot - 1) < sizeof key) {
      snprintf(section, sizeof section, "%.*s", (int)(dot - tok), tok);
      snprintf(key, sizeof key, "%.*s", (int)(eq - dot - 1), dot + 1);
    }
    if (!find_spec(trim(section), trim(key)) || strcmp(trim(section), "case") == 0)
      return fb_diag_set(diag, FB_ERR_PARSE,
                         "%s: [variant.%s] set: '%s' is not section.key=value with a case key "
                         "(for example clearance.penalty=goldsmith; fourbar keys lists them; "
                         "[case] keys cannot vary)",
                         v->origin, v->name, tok);
    if (*n == max)
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [variant.%s] set: more than %d overrides",
                         v->origin, v->name, max);
    /* one key once, as in a case file: a second value never silently wins */
    for (int q = 0; q < *n; q++) {
      const size_t lq = strcspn(items[q], "=");
      char other[128];
      snprintf(other, sizeof other, "%.*s", (int)lq, items[q]);
      char *ot = trim(other);
      char mine[128];
      snprintf(mine, sizeof mine, "%s.%s", trim(section), trim(key));
      if (strcmp(ot, mine) == 0)
        return fb_diag_set(diag, FB_ERR_PARSE, "%s: [variant.%s] set: duplicate key %s ('%s' "
                           "and '%s'); give each key once", v->origin, v->name, mine, items[q],
                           tok);
    }
    if (v->models[0] && strcmp(trim(section), "run") == 0 && strcmp(trim(key), "models") == 0)
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [variant.%s] set gives run.models and the "
                         "variant has its own models key too: give the models once", v->origin,
                         v->name);
    items[(*n)++] = tok;
  }
  if (*n == 0)
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [variant.%s] set is empty: give at least one "
                       "section.key=value (separated by ;)", v->origin, v->name);
  return FB_OK;
}

/* one key of a [variant.NAME] section into out->variant */
static fb_status take_variant(fb_case *out, const entry *e, fb_diag *diag) {
  const char *name = e->section + strlen(VARIANT_PREFIX);
  /* the INI parser keeps a section name of FB_INI_NAME_MAX characters whole
   * (ini_lines.h), "variant." included */
  const int name_max = FB_INI_NAME_MAX - (int)strlen(VARIANT_PREFIX);
  if (!fb_casefile_name_ok(name) || (int)strlen(name) > name_max)
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s]: a variant name is 1 to %d characters from "
                       "letters, digits, '-', '_' and '.', not starting with '.'",
                       e->origin, e->section, name_max);
  int i = 0;
  while (i < out->variant_count && strcmp(out->variant[i].name, name) != 0) i++;
  if (i == out->variant_count) {
    if (i == FB_MAX_VARIANTS)
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s]: more than %d variants", e->origin,
                         e->section, FB_MAX_VARIANTS);
    memset(&out->variant[i], 0, sizeof out->variant[i]);
    snprintf(out->variant[i].name, sizeof out->variant[i].name, "%s", name);
    out->variant_count++;
  }
  fb_case_variant *v = &out->variant[i];
  char *dst;
  size_t size;
  if (strcmp(e->key, "set") == 0) {
    dst = v->set;
    size = sizeof v->set;
    snprintf(v->origin, sizeof v->origin, "%s", e->origin);
  } else if (strcmp(e->key, "models") == 0) {
    dst = v->models;
    size = sizeof v->models;
  } else if (strcmp(e->key, "description") == 0) {
    dst = v->description;
    size = sizeof v->description;
  } else {
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: unknown key '%s' in [%s] (a variant has set, "
                       "models and description)", e->origin, e->key, e->section);
  }
  if (strlen(e->value) >= size)
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s: %zu characters, at most %zu", e->origin,
                       e->section, e->key, strlen(e->value), size - 1);
  snprintf(dst, size, "%s", e->value);
  return FB_OK;
}

/* every variant has a set whose items name case keys */
static fb_status check_variants(const fb_case *out, fb_diag *diag) {
  for (int i = 0; i < out->variant_count; i++) {
    const fb_case_variant *v = &out->variant[i];
    if (!v->set[0])
      return fb_diag_set(diag, FB_ERR_PARSE, "[variant.%s] has no set: give set = "
                         "section.key=value; ... (the overrides that make the variant)", v->name);
    char buf[sizeof v->set], *items[FB_VARIANT_MAX_SETS];
    int n;
    fb_status st = variant_items(v, buf, sizeof buf, items, FB_VARIANT_MAX_SETS, &n, diag);
    if (st != FB_OK) return st;
  }
  return FB_OK;
}

fb_status fb_casefile_load_variant(fb_case *out, const char *path, const char *const *sets,
                                   int nsets, const fb_case_variant *v, fb_diag *diag) {
  const char *all[FB_CASEFILE_MAX_SETS + FB_VARIANT_MAX_SETS + 1];
  if (nsets > FB_CASEFILE_MAX_SETS)
    return fb_diag_set(diag, FB_ERR_ARG, "more than %d --set", FB_CASEFILE_MAX_SETS);
  char buf[sizeof v->set], *items[FB_VARIANT_MAX_SETS], models[sizeof v->models + 16];
  int n;
  fb_status st = variant_items(v, buf, sizeof buf, items, FB_VARIANT_MAX_SETS, &n, diag);
  if (st != FB_OK) return st;
  int k = 0;
  for (int i = 0; i < nsets; i++) all[k++] = sets[i];
  for (int i = 0; i < n; i++) all[k++] = items[i];
  if (v->models[0]) {
    snprintf(models, sizeof models, "run.models=%s", v->models);
    all[k++] = models;
  }
  fb_diag inner;
  st = fb_casefile_load(out, path, all, k, &inner);
  if (st != FB_OK)
    return fb_diag_set(diag, st, "variant %s (%s): %s", v->name, v->origin, inner.msg);
  out->variant_count = 0; /* a variant runs no variants of its own */
  return FB_OK;
}

static fb_status load(fb_case *out, const char *path, const char *text, size_t text_size,
                      const char *const *overrides, int n_overrides, fb_diag *diag);

fb_status fb_casefile_load(fb_case *out, const char *path, const char *const *overrides,
                           int n_overrides, fb_diag *diag) {
  return load(out, path, NULL, 0, overrides, n_overrides, diag);
}

fb_status fb_casefile_load_text(fb_case *out, const char *name, const char *text, size_t size,
                                fb_diag *diag) {
  if (size == 0) { /* fmemopen refuses an empty buffer: an empty case is the defaults */
    static const char empty[] = "\n";
    text = empty;
    size = 1;
  }
  return load(out, name, text, size, NULL, 0, diag);
}

static fb_status load(fb_case *out, const char *path, const char *text, size_t text_size,
                      const char *const *overrides, int n_overrides, fb_diag *diag) {
  fb_diag_clear(diag);
  load_ctx *c = calloc(1, sizeof *c);
  if (!c) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  c->path = path;
  c->diag = diag;
  c->status = FB_OK;
  fb_status st = FB_OK;

  if (path) {
    st = read_file_entries(c, path, 0, diag, text, text_size);
    if (st != FB_OK) goto done;
  }
  for (int i = 0; i < n_overrides; i++) {
    st = parse_override(c, overrides[i], i);
    if (st != FB_OK) goto done;
  }

  fb_case_default(out);
  for (int i = 0; i < c->n; i++) {
    const entry *e = &c->e[i];
    st = strncmp(e->section, VARIANT_PREFIX, strlen(VARIANT_PREFIX)) == 0
             ? take_variant(out, e, diag)
             : apply(out, e, diag);
    if (st != FB_OK) goto done;
  }
  st = check_variants(out, diag);
  if (st != FB_OK) goto done;
  st = resolve_standards(out, c, diag);
  if (st != FB_OK) goto done;
  for (int i = 0; i < NKEYS; i++)
    out->given[i] = entry_origin(c, keys[i].section, keys[i].key) != NULL;
  if (!fb_casefile_given(out, "run", "models") && out->clearance.mask)
    for (size_t i = 0; i < sizeof clearance_default_models / sizeof clearance_default_models[0] &&
                       out->model_count < FB_MAX_MODELS; i++)
      snprintf(out->models[out->model_count++], FB_NAME_SIZE, "%s", clearance_default_models[i]);
  st = resolve_masses(out, diag);
  if (st != FB_OK) {
    char msg[FB_DIAG_SIZE];
    snprintf(msg, sizeof msg, "%s", diag->msg);
    fb_diag_set(diag, st, "%s: %s", path ? path : "case", msg);
    goto done;
  }
  out->clearance.segments_given = entry_origin(c, "clearance", "segments") != NULL;
  {
    fb_diag inner;
    st = fb_case_check(out, &inner);
    if (st != FB_OK) {
      /* a cross-key rule: where each key it names was given (its last entry) */
      char where[FB_DIAG_SIZE] = "";
      size_t l = 0;
      for (int i = c->n - 1; i >= 0 && l + 1 < sizeof where; i--) {
        const entry *e = &c->e[i];
        char sk[160];
        snprintf(sk, sizeof sk, " %s", e->key);
        const char *at = strstr(inner.msg, sk);
        const int named = at && (at[strlen(sk)] == ' ' || at[strlen(sk)] == '\0' ||
                                 at[strlen(sk)] == ',') &&
                          strstr(inner.msg, e->section) != NULL;
        int later = 0; /* only the entry that counts: the last for its key */
        for (int q = i + 1; q < c->n; q++)
          later |= strcmp(c->e[q].section, e->section) == 0 && strcmp(c->e[q].key, e->key) == 0;
        if (named && !later)
          l += (size_t)snprintf(where + l, sizeof where - l, "%s[%s] %s at %s", l ? "; " : "",
                                e->section, e->key, e->origin);
      }
      fb_diag_set(diag, st, "%s: %s%s%s%s", path ? path : "case", inner.msg, l ? " (given: " : "",
                  where, l ? ")" : "");
    }
  }
done:
  free(c);
  return st;
}

/* ---- plausibility ----------------------------------------------------------- */

const char *fb_casefile_length_implausible(double length_m) {
  if (length_m < FB_PLAUSIBLE_LENGTH_MIN_M) return "below 1 mm";
  if (length_m > FB_PLAUSIBLE_LENGTH_MAX_M) return "above 10 m";
  return NULL;
}

int fb_casefile_plausibility(const fb_case *c, char notes[][FB_DIAG_SIZE], int max) {
  int n = 0;
  /* every length key the case gives, in millimetres */
  for (int i = 0; i < NKEYS && n < max; i++) {
    const key_spec *k = &keys[i];
    if (k->kind != K_DOUBLE || strcmp(k->unit, "mm") != 0 || !c->given[i]) continue;
    if (strcmp(k->section, "tolerance") == 0) continue; /* a tolerance is small by nature */
    double v;
    memcpy(&v, (const char *)c + k->offset, sizeof v);
    const char *why = fb_casefile_length_implausible(v);
    const double mm = v / FB_M_PER_MM;
    if (why)
      snprintf(notes[n++], FB_DIAG_SIZE,
               "[%s] %s = %g: a length %s; the key is in millimetres (if %g is in %s, write "
               "%s = %g)", k->section, k->key, mm, why, mm,
               v < FB_PLAUSIBLE_LENGTH_MIN_M ? "metres" : "micrometres", k->key,
               v < FB_PLAUSIBLE_LENGTH_MIN_M ? mm * 1e3 : mm * 1e-3);
  }
  /* the pin against the bars it passes through: links at a clearance joint */
  static const int link_at[4][2] = {{-1, FB_CRANK}, {FB_CRANK, FB_COUPLER},
                                    {FB_COUPLER, FB_FOLLOWER}, {FB_FOLLOWER, -1}};
  int warned[3] = {0, 0, 0};
  for (int j = 0; j < 4 && n < max; j++) {
    if (!(c->clearance.mask & (1 << j))) continue;
    for (int s = 0; s < 2 && n < max; s++) {
      const int l = link_at[j][s];
      if (l < 0 || warned[l]) continue;
      char wkey[64];
      snprintf(wkey, sizeof wkey, "%s_width_mm", fb_link_name(l));
      const int width_counts = fb_casefile_given(c, "mass", wkey) ||
                               c->link_source[l].mass == FB_SOURCE_DERIVED;
      if (!width_counts || c->pin_diameter < c->link_width[l]) continue;
      warned[l] = 1;
      snprintf(notes[n++], FB_DIAG_SIZE,
               "[pin] diameter_mm = %g is not smaller than [mass] %s = %g: the pin of the %s "
               "joint is as wide as the %s's bar it passes through, or wider",
               c->pin_diameter / FB_M_PER_MM, wkey, c->link_width[l] / FB_M_PER_MM,
               fb_joint_name(j), fb_link_name(l));
    }
  }
  /* (a radial clearance as large as the pin's radius is an error: fb_case_check) */
  return n;
}
