/* summary.json: a run's every number as JSON (jansson; its wall times:
 * report_timing.h). Keys carry their SI unit; NaN and infinity are never
 * written (JSON null stands for "not measured"). docs/outputs.md gives the
 * keys. */
#ifndef FB_REPORT_SUMMARY_H
#define FB_REPORT_SUMMARY_H

#include "contact.h"
#include "report_common.h"
#include "run.h"

/* The summary of a run as documented in docs/outputs.md (new reference):
 * {"case", "models": [{"name", "kind", "status", "h_s", "steps",
 *  "coupler", "follower", "error_vs_analytic", ...}], ...}. It holds no
 * wall time, so two runs of the same case give byte-identical summaries. */
json_t *fb_report_summary_json(const fb_run *r, const char *case_path);

/* The law-and-mapping part of one clearance joint's `contact` object (the
 * keys fourbar run's summary.json and fourbar penalty --json share):
 * {"joint" (the joint's name, joint), "law", "mapping", "stiffness" (N/m^n), "exponent", then for the
 * impact law "damping_n_s_m" (c_max) and "damping_depth_m" (d_max), for the
 * restitution law "restitution" and "damping_ratio" (zeta: the damper is
 * 2 zeta sqrt(p m_eff) at each step's effective mass), for other laws
 * "damping_n_s_m" (linear) or "restitution"}. */
json_t *fb_report_contact_law_json(const char *joint, const fb_contact_law *law,
                                   fb_mapping mapping);

#endif
