/* The kit's adaptive step ([solver] h_s = adaptive), private to
 * src/engines/kit: each engine step's size chosen from every clearance
 * joint's contact at the step's start by step_control.h's rules, as a
 * whole number of grid steps h_min (the series' h), so that every step
 * lands on the output grid; the binding takes it whole (kit.h step_by)
 * and the kit samples inside it. One rule for every engine: the engine's
 * part is its binding's persistent_rule and whether it takes contact rows
 * (the hold inside an impact, step_control.h fb_step_hold_in_impact). */
#ifndef FB_KIT_ADAPTIVE_H
#define FB_KIT_ADAPTIVE_H

#include "kit_contact.h"

/* An adaptive run's state between steps. */
typedef struct {
  int on;              /* 1: [solver] h_s = adaptive */
  int m_max;           /* the longest step, h_max, in grid steps [-] */
  int m_prev;          /* the last step's grid steps (1 before the first) [-] */
  double accuracy;     /* [solver] accuracy: largest h omega_c in an impact or free flight [-] */
  double rocking_h_omega; /* [solver] rocking_h_omega with clearance joints, else 0 [-] */
  double h_grid;       /* the grid's step h_min [s] */
  double h_max;        /* the longest step [s] */
  double h_prev;       /* the last step [s] (0 before the first) */
  double ddot_prev[FB_PLANAR_SPEC_MAX_JOINTS]; /* each joint's penetration rate at the last
                          step's start (FB_PERSIST_DEPTH_CHANGE's dddot) [m/s] */
} fb_kit_adapt;

/* Sets a up for a run of description m in b's engine with world settings
 * o (o->solver's h_mode, h_min, h_max, accuracy, rocking_h_omega; the
 * grid's step o->h) and clearance joints cl (NULL: none); p->rocking is
 * set when the rocking bound applies. A fixed step leaves a->on 0.
 * Errors (FB_ERR_ARG, naming the engine and what to change): an adaptive
 * step with a binding without step_by; a faceted or libccd collider, or
 * the engine's native contact (cl->collider: the rules follow the exact
 * pin under the project's law); a clearance joint at a prismatic
 * joint (the rules follow a pin in its hole); a binding whose
 * persistent_rule is FB_PERSIST_LOAD_SCHEDULE with clearance joints and no
 * cl->load. */
fb_status fb_kit_adapt_open(fb_kit_adapt *a, fb_kit_pipe *p, const fb_kit_binding *b,
                            const fb_planar *m, const fb_kit_world *o,
                            const fb_kit_clearance *cl, fb_diag *diag);

/* The longest step a run with world settings o takes, in grid steps of
 * o->h: floor(h_max / h) for [solver] h_s = adaptive (at least 1), 1 for
 * a fixed step [-]. */
int fb_kit_adapt_m_max(const fb_kit_world *o);

/* The coming step's grid steps (>= 1, at most a->m_max) from every
 * clearance joint's contact at the state p last read (step_control.h:
 * the shortest step any joint asks for, held inside an impact, ramped);
 * records it as the last step's. Errors: those of the effective mass. */
fb_status fb_kit_adapt_multiple(int *mult, fb_kit_adapt *a, fb_kit_pipe *p,
                                const fb_kit_binding *b, const fb_planar *m,
                                const fb_kit_clearance *cl, fb_diag *diag);

#endif
