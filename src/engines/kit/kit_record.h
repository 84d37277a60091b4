/* What a step leaves in the harness's records, written once for the
 * kit's pipeline (kit_contact.c) and the hand-built four-bar and
 * slider-crank worlds (ODE, MuJoCo, Bullet): the step statistics of an
 * adaptive run, the matched mapping's aliasing stop, and a sample's body
 * and contact columns. Each function does the arithmetic the engines did
 * in their own copies, in the same order, so their results are the same
 * numbers (`fourbar check`'s baselines). SI throughout. */
#ifndef FB_KIT_RECORD_H
#define FB_KIT_RECORD_H

#include <stddef.h>

#include "engine.h"
#include "episode.h"
#include "outcome.h"
#include "series.h"
#include "status.h"

/* Two steps whose sizes differ by at most this share of the step are the
 * same size [-]: an adaptive step is a whole multiple of the grid's h
 * (step_control.h), so sizes that differ at all differ by a whole h;
 * 1e-9 is far above the rounding of m h and far below one h in m. */
#define FB_KIT_SAME_STEP_REL 1e-9

/* Counts one engine step of size h [s] (> 0) into t: the steps, the
 * shortest and longest size so far and how many steps had each (sizes
 * within FB_KIT_SAME_STEP_REL of one another count as one). Start from
 * a zeroed t. */
void fb_kit_stats_add(fb_step_stats *t, double h);

/* The statistics of steps fixed steps of h [s]: every one the shortest
 * and the longest. */
void fb_kit_stats_fixed(fb_step_stats *out, size_t steps, double h);

/* The matched mapping's aliasing stop (contact.h, FB_MATCHED_ALIAS_BOUND):
 * FB_ERR_NUMERIC with "aliased: omega_d h = ... at the JOINT joint (bound
 * ...); largest usable step ... s" in diag, the largest usable step
 * h FB_MATCHED_ALIAS_BOUND / wdh. wdh: the row's omega_d h [-] (> the
 * bound), h the step it was made for [s], joint the joint's name. */
fb_status fb_kit_alias_diag(fb_diag *diag, double wdh, const char *joint, double h);

/* 1 when a row of mapping with omega_d h = wdh [-] stops the run: the
 * mapping matched (fb_mapping_is_matched) and wdh past the bound (NaN
 * does not stop). */
int fb_kit_aliased(fb_mapping mapping, double wdh);

/* The aliasing stop of a hand-built world about to take step steps + 1
 * of h [s] from t = steps h: stop filled (FB_STOP_ALIASED at joint, a
 * fb_joint, with wdh, the bound and the largest usable step), and
 * fb_kit_alias_diag's error with the four-bar's name of the joint. */
fb_status fb_kit_alias_stop(fb_stop *stop, int joint, double wdh, double h, size_t steps,
                            fb_diag *diag);

/* The four-bar's or slider-crank's sample columns of a hand-built world:
 * time t [s], the crank's angle, the coupler's and follower's angle,
 * omega and alpha (a slider-crank's slider: x, v, a), each array indexed
 * by link (links.h: FB_CRANK, FB_COUPLER, FB_FOLLOWER). */
void fb_kit_sample_bodies(fb_sample *x, double t, const double angle[3], const double omega[3],
                          const double alpha[3]);

/* One clearance joint's contact columns (series.h FB_C_*): force [N],
 * penetration [m], eccentricity pin - hole ex, ey [m], and the contact
 * state: the episode's (ep, episode.h) while the force is positive, else
 * FB_STATE_FREE. */
void fb_kit_sample_contact(double col[FB_CONTACT_COLS], double force, double pen, double ex,
                           double ey, const fb_episode *ep);

#endif
