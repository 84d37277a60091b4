/* The case-file key table: one row per key a case file may hold, with its
 * section, name, kind, the fb_case field it fills, the factor from its file
 * unit to SI, its range, unit, default (as a file would write it), rule and
 * meaning. Every other part of the reader works from these rows: the parser
 * (casefile.c), the values (casefile_values.c), the defaults (fb_case_default
 * and each engine's options default read the rows' defaults) and
 * docs/keys.md (fourbar keys writes the rows; scripts/keys_doc.sh). */
#include "casefile.h"
#include "casefile_internal.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "bar_mass.h"
#include "contact.h"
#include "units.h"

#define INF HUGE_VAL
/* honest physical ranges (issue 13): outside them ODE's closed-loop solve
 * degenerates (dxNormalize4 aborts were measured at CFM 1e-18 and at
 * extreme mass ratios) and the mechanism is no four-bar this program models */
/* (LEN_RULE, FB_LINK_MM_MIN and _MAX: casefile_internal.h; a planar case's
 * links follow them too) */
#define TOL_RULE "a tolerance must be >= 0"
/* (MASS_RULE: casefile_internal.h, the mass resolution says it too) */
#define INERTIA_RULE "a moment of inertia must be positive, from 1e-6 to 1e12 kg mm^2"
#define COM_RULE "the centre of mass lies between the link's joints (0 to 1)"

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

/* one row of an engine's own section (model/opts_<name>.h: ROW(section,
 * kind, key, field, words, scale, lo, hi, lo_open, hi_open, unit, default,
 * rule, meaning)); its words, if any, go to engine_words below */
#define ENGINE_ROW(sec, kind, key, field, words, scale, lo, hi, lo_open, hi_open, unit, def,  \
                   rule, doc)                                                                  \
  {#sec, key, K_##kind, OFF(sec.field), scale, lo, hi, lo_open, hi_open, unit, def, rule, doc},

static const key_spec keys[] = {
    {"case", "name", K_NAME, OFF(name), 0, 0, 0, 0, 0, "-", "case", "letters, digits, - _ .",
     "case name; run output goes to results/<name>/"},
    {"case", "base", K_TEXT, 0, 0, 0, 0, 0, 0, "-", "(none)", "a case file path",
     "case file read first (relative to this one); this file's keys override it"},
    {"case", "description", K_TEXT, 0, 0, 0, 0, 0, 0, "-", "", "free text",
     "one line describing the case (not used by the solver)"},

    {"linkage", "type", K_MECH, OFF(mechanism), 0, 0, 0, 0, 0, "-", "four-bar",
     "four-bar, slider-crank or planar",
     "the mechanism: the four-bar (crank, coupler, follower, ground) or the offset slider-crank "
     "(crank, coupler as the connecting rod, a slider on a guide along +x; keys crank_mm, "
     "coupler_mm, offset_mm and [mass] slider_kg), or planar: any planar mechanism of one "
     "degree of freedom given by [joint.NAME] and [body.NAME] sections and [drive] joint "
     "(docs/planar.md; their keys at the end of this table)"},
    {"linkage", "crank_mm", K_DOUBLE, OFF(nominal.length[FB_CRANK]), FB_M_PER_MM, FB_LINK_MM_MIN,
     FB_LINK_MM_MAX, 0, 0, "mm", "108", LEN_RULE, "basic crank length, A to B"},
    {"linkage", "coupler_mm", K_DOUBLE, OFF(nominal.length[FB_COUPLER]), FB_M_PER_MM, FB_LINK_MM_MIN,
     FB_LINK_MM_MAX, 0, 0, "mm", "279.4", LEN_RULE, "basic coupler length, B to C"},
    {"linkage", "follower_mm", K_DOUBLE, OFF(nominal.length[FB_FOLLOWER]), FB_M_PER_MM, FB_LINK_MM_MIN,
     FB_LINK_MM_MAX, 0, 0, "mm", "270.5", LEN_RULE, "basic follower (rocker) length, D to C"},
    {"linkage", "ground_mm", K_DOUBLE, OFF(nominal.length[FB_GROUND]), FB_M_PER_MM, FB_LINK_MM_MIN,
     FB_LINK_MM_MAX, 0, 0, "mm", "254", LEN_RULE, "basic ground length, A to D along +x"},
    {"linkage", "offset_mm", K_DOUBLE, OFF(nominal.length[FB_LENGTH_OFFSET]), FB_M_PER_MM, -1e5,
     1e5, 0, 0, "mm", "(none)", "an offset from -1e5 mm to 1e5 mm",
     "slider-crank: the guide line's distance from the crank pivot A along +y (either sign; "
     "default 0); the guide runs along +x and the slider sits at +x of A"},
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
    {"tolerance", "offset_plus_minus_mm", K_DOUBLE, OFF(plus_minus[FB_LENGTH_OFFSET]), FB_M_PER_MM,
     0, INF, 0, 1, "mm", "(none)", TOL_RULE,
     "slider-crank: symmetric tolerance of the guide offset (default 0, or the class's for an "
     "offset of 0.5 mm or more)"},
    {"tolerance", "class", K_CLASS, OFF(tolerance_class), 0, 0, 0, 0, 0, "-", "(none)",
     "f, m, c or v",
     "ISO 2768-1 general tolerance class for every link without an explicit "
     "<link>_plus_minus_mm"},
    {"tolerance", "stackup", K_STACKUP, OFF(stackup), 0, 0, 0, 0, 0, "-", "max",
     "nominal, max, min, worst, or 4 characters from + - 0; a planar case: nominal, max, "
     "min, or one of + - 0 per dimension",
     "stack-up corner for the *-stackup models: every link at max or min, one "
     "character per link in the order crank, coupler, follower, ground (e.g. +-+-), or "
     "worst: the corner that maximises |worst_output|; a planar case: one character per "
     "dimension of its description in the order fourbar stackup lists them (with "
     "[tolerance] class)"},
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
    {"mass", "slider_kg", K_DOUBLE, OFF(link[2].mass), 1.0, FB_MASS_MIN_KG, FB_MASS_MAX_KG, 0, 0,
     "kg", "(none)", MASS_RULE,
     "slider-crank: mass of the slider (with its piston pin), required: it has no bar to derive "
     "it from; its inertia does not enter the planar motion"},

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
     "joint names, each once: ground-crank, crank-coupler, coupler-follower, follower-ground, "
     "or none (a slider-crank: coupler-slider or none; a planar case: its own joints)",
     "joints modelled as a pin in a hole (the *-clearance-* models); the others stay ideal "
     "hinges and get no contact geometry; a clearance model takes every one, each with its "
     "own law (a planar case: up to 8, a prismatic one as a slider in its guide; the "
     "four-bar's references with [run] start = steady and pin_start = centred beyond "
     "crank-coupler alone); a slider-crank's default is its piston pin, coupler-slider"},
    {"clearance", "penalty", K_PENALTY, OFF(clearance.penalty), 0, 0, 0, 0, 0, "-", "physical",
     "physical, paper, explicit or goldsmith",
     "stiffness source: physical (Johnson line contact at the inverse-dynamics reaction), "
     "paper (the paper's Kc and P read in N and mm), explicit (the stiffness keys), goldsmith "
     "(paper Eq. 3-5: K = 4 / (3 (s1 + s2)) sqrt(R_pin R_hole / c), s = (1 - nu^2)/E, n = 1.5; "
     "the restitution law's p is its tangent at the joint's largest ideal reaction)"},
    {"clearance", "restitution", K_DOUBLE, OFF(clearance.restitution), 1.0, FB_RESTITUTION_MIN,
     1, 1, 0, "-", "0.9", "cr must lie in (0.1353, 1] (the restitution law's range)",
     "coefficient of restitution of the restitution model"},
    {"clearance", "guide_clearance_mm", K_DOUBLE, OFF(clearance.guide_clearance), FB_M_PER_MM, 0,
     1e5, 1, 0, "mm", "(none)", "a guide clearance must be positive, at most 1e5 mm",
     "planar case: the gap c on each side between the centred slider's face and its guide's "
     "wall at a prismatic joint [clearance] joints names (the slider's size: slider_half_length_mm "
     "and slider_half_height_mm in its [joint.NAME]; docs/planar.md); required there"},
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
     "-", "1", "a scale must lie in (0, 1e6]", "multiplies the contact stiffness from any penalty source"},
    {"clearance", "engine_stiffness_scale", K_DOUBLE, OFF(clearance.engine_stiffness_scale), 1.0,
     0, 1e6, 1, 0, "-", "1", "a scale must lie in (0, 1e6]",
     "an injected error: multiplies, after stiffness_scale, the contact stiffness every engine "
     "model gets, not the references' (would the verdict notice? docs/verdicts.md); the "
     "restitution law's damper follows the scaled stiffness unless engine_damping_scale is "
     "given; a rigid model (siconos-clearance-newton) has no stiffness to scale"},
    {"clearance", "engine_damping_scale", K_DOUBLE, OFF(clearance.engine_damping_scale), 1.0, 0,
     1e6, 1, 0, "-", "1", "a scale must lie in (0, 1e6]",
     "an injected error: multiplies the damper every engine model gets, not the references' "
     "(the impact law's c_max; when given, the restitution law's damper 2 zeta sqrt(p m_eff) of "
     "the case's stiffness); a rigid model's Newton restitution is not a damper and is kept"},
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
     "step size h of the ODE models; auto: the largest with h x rate <= 0.5 at the fastest "
     "contact (rate: omega_c or the damper's c / m_eff), at most one revolution / 6000; "
     "adaptive: from h_min_s to h_max_s following the contact (docs/step-size.md; the ODE "
     "and MuJoCo models); not given: "
     "auto for a case with clearance joints (a driven one, for a planar case), else the "
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
    {"solver", "builder", K_WORDS, OFF(solver.builder), 0, 0, 0, 0, 0, "-", "auto",
     "auto, hand or kit",
     "who builds a four-bar or slider-crank model of an engine that has both: hand (the "
     "engine's own world), kit (its engine-kit binding, through the kit adapter: the "
     "colliders, native contacts and friction its binding builds, ODE's all; a fixed or auto "
     "step; docs/architecture.md) or auto: the kit for the models whose every feature of the "
     "engine's own world its binding builds within the committed baselines, at about its cost "
     "(every ODE model; MuJoCo's clearance models, about half on the four-bar), but with "
     "clearance at the driven joint, which the kit does not drive (the engine's own world), "
     "else the engine's own world "
     "(MuJoCo's ideal models, Bullet's, Simbody's, Siconos's; but Simbody's and Siconos's "
     "clearance models through the kit when [clearance] joints looses a pin other than "
     "crank-coupler, which their own worlds do not take); an engine with a binding alone "
     "(DART) always builds through the kit"},

    /* each engine's own section, in engine order (model/opts_<name>.h) */
#define X(name) FB_OPTS_KEYS_##name(ENGINE_ROW)
    FB_ENGINE_OPTS_LIST
#undef X

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
    {"run", "duration_s", K_DOUBLE, OFF(duration_s), 1.0, 0, 1e6, 1, 0, "s", "(none)",
     "a duration must be positive, at most 1e6 s",
     "simulated time, instead of revolutions at the drive's speed; required by an undriven "
     "planar case ([drive] joint = none, docs/planar.md), which has no revolution"},
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
     "eccentricity moved by 1e-2 x the radial clearance in another direction (the first run "
     "unmoved); each model's members are tested against its reference's once (docs/verdicts.md) "
     "and their impact statistics pooled and their spread reported (docs/chaos.md); not given: "
     "fourbar run tests members sequentially by itself, 4 to 32, when a model's verdict is "
     "unsettled (it left its reference, or a reference its check integration)"},
    {"run", "peaks", K_PEAKS, OFF(peaks), 0, 0, 0, 0, 0, "-", "steady", "steady or all",
     "window of the reported peaks: steady (from the second revolution on) or all (from "
     "t = 0, the start-up included); summary.json reports the first revolution alone too"},
    {"run", "series", K_SERIES, OFF(series), 0, 0, 0, 0, 0, "-", "csv", "csv, hdf5 or none",
     "time series written per run: csv (DIR/<model>.csv), hdf5 (DIR/series.h5, one group per "
     "model; needs a build with libhdf5) or none (docs/series.md)"},
    {"run", "series_every", K_INT, OFF(series_every), 0, 1, 1e9, 0, 0, "-", "1",
     "a whole number from 1 to 1000000000",
     "write every N-th sample of the time series, the last, and every sample of each impact "
     "episode (contact state impact, with one sample either side; a planar case likewise, "
     "its impacts told from continuous contact by its penetration column)"},
    {"run", "models", K_MODELS, OFF(models), 0, 0, 0, 0, 0, "-",
     "analytic, analytic-stackup, ode-ideal-nominal, ode-ideal-stackup", "known model names",
     "models to run, comma-separated; a name with * is a pattern that adds every model "
     "of this build it matches (e.g. *-clearance-impact: every engine's); not given: the default list, and for a case with "
     "clearance joints also " FB_CLEARANCE_DEFAULT_MODELS "; a planar case: analytic and "
     "ode-ideal-nominal (undriven: reference), analytic-stackup and ode-ideal-stackup with "
     "[tolerance] class, and the same clearance models"},
};

#define NKEYS ((int)(sizeof keys / sizeof keys[0]))
_Static_assert(sizeof keys / sizeof keys[0] <= FB_CASE_MAX_KEYS,
               "fb_case.given has a slot per key: raise FB_CASE_MAX_KEYS");

int fb_casefile_key_count(void) { return NKEYS; }

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

const key_spec *fb_casefile_spec(int i) { return i >= 0 && i < NKEYS ? &keys[i] : NULL; }

const key_spec *fb_casefile_spec_find(const char *section, const char *key) {
  return fb_casefile_spec(fb_casefile_spec_index(section, key));
}

/* the words of every K_WORDS row of the engines' sections, by section and key */
typedef struct {
  const char *section, *key;
  const char *const *words;
} engine_words_row;
#define ENGINE_WORDS(sec, kind, key, field, words, ...) {#sec, key, words},
static const char *const builder_words[] = {"hand", "kit", "auto", NULL}; /* fb_builder */
static const engine_words_row engine_words[] = {
#define X(name) FB_OPTS_KEYS_##name(ENGINE_WORDS)
    FB_ENGINE_OPTS_LIST
#undef X
    {"solver", "builder", builder_words},
    {NULL, NULL, NULL}};

const char *const *fb_casefile_spec_words(const key_spec *k) {
  if (k->kind != K_WORDS) return NULL;
  for (const engine_words_row *w = engine_words; w->section; w++)
    if (strcmp(w->section, k->section) == 0 && strcmp(w->key, k->key) == 0) return w->words;
  return NULL;
}

int fb_casefile_section_known(const char *section) {
  for (int i = 0; i < NKEYS; i++)
    if (strcmp(keys[i].section, section) == 0) return 1;
  return 0;
}

int fb_casefile_spec_has_default(const key_spec *k) {
  return k->kind != K_TEXT && k->kind != K_UNUSED && k->def[0] != '\0' &&
         strcmp(k->def, "(none)") != 0 && strcmp(k->def, DERIVED) != 0 &&
         strcmp(k->def, "-") != 0;
}

int fb_casefile_spec_index(const char *section, const char *key) {
  for (int i = 0; i < NKEYS; i++)
    if (strcmp(keys[i].section, section) == 0 && strcmp(keys[i].key, key) == 0) return i;
  return -1;
}

int fb_casefile_given(const fb_case *c, const char *section, const char *key) {
  const int i = fb_casefile_spec_index(section, key);
  return i >= 0 && c->given[i];
}
