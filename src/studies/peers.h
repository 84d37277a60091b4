/* The harness beside bare programs (`fourbar bench --grid peers`): for each
 * engine of the build, a minimal program of its own (tests/peers/peer_*,
 * built with the tests: the engine's API only) simulates the ideal four-bar
 * of the case with the settings the harness's ideal nominal model runs
 * with, on the same output grid, keeping the same samples (angles, angular
 * velocities and accelerations, drive torque, joint reactions), and the
 * harness runs that model as `fourbar run` does. Each is timed on its own
 * stepping and sampling loop (the harness: the model's wall time without
 * its set-up; the peer: its loop), in FB_PEER_ROUNDS rounds that alternate
 * harness and peer, so that a slow phase of the machine hits both; the
 * cost ratio is the median of the rounds' ratios. The two runs' omega peaks
 * are compared, so that the peer is known to simulate the same thing. */
#ifndef FB_PEERS_H
#define FB_PEERS_H

#include "case.h"
#include "model_table.h"
#include "status.h"

/* Rounds of the timing: harness then peer, per engine. */
#define FB_PEER_ROUNDS 3

/* The bare programs are looked for in this folder of the build tree by
 * default (meson.build: FB_PEERS_DIR); $FOURBAR_PEERS_DIR overrides it. */
#define FB_PEERS_ENV "FOURBAR_PEERS_DIR"

typedef struct {
  char engine[16];          /* fb_engine_name: "ode", "mujoco", "bullet", "simbody", "dart" */
  const fb_model *model;    /* the harness's model: the engine's ideal nominal model */
  char peer[64];            /* the bare program's file name (peer_<engine>) */
  int ran;                  /* 1: both ran every round; else why in status */
  char status[512];         /* "ok", or what failed */
  double h;                 /* the output step both sampled [s] */
  long samples;             /* samples each kept [-] */
  long peer_steps;          /* the peer's engine steps (Simbody: its integrator's) [-] */
  int rounds;
  double harness_s[FB_PEER_ROUNDS]; /* the harness's model: wall time without set-up [s] */
  double bare_s[FB_PEER_ROUNDS];    /* the peer: its loop [s] */
  double harness_per_rev;   /* medians per simulated revolution [s] */
  double bare_per_rev;
  double harness_over_bare; /* median of the rounds' harness_s / bare_s [-] */
  double peak_rel;          /* largest |peer - harness| / |harness| of the coupler and
                               follower omega peaks over the peak window [-] */
} fb_peer_row;

/* 1 when the bare programs (tests/peers) build mechanism t (its
 * description's peers_build: the four-bar only). */
int fb_peers_build(fb_mech_type t);

/* The most rows fb_peers_run gives: one per engine. */
#define FB_PEERS_MAX FB_ENGINE_COUNT

/* Runs the peers of the engines this build has (at most FB_PEERS_MAX rows) on case c
 * (2 revolutions, the case's step; the case's engine settings). dir: the
 * folder of the peer programs (NULL: $FOURBAR_PEERS_DIR, else
 * FB_PEERS_DIR). progress (may be NULL) gets the fraction done. A peer that
 * is missing or fails gives a row with ran = 0 and the reason, not an
 * error. Errors: those of fb_run_case; FB_ERR_NOMEM. */
fb_status fb_peers_run(fb_peer_row *rows, int *n, const fb_case *c, const char *dir,
                       void (*progress)(double fraction, void *user), void *user, fb_diag *diag);

/* The CPU time [s] fb_peers_run(c, dir) would take, estimated before it
 * runs: each engine's harness case (its ideal nominal model, 2
 * revolutions) by its pilot (pilot.h), counted twice per round (the bare
 * program does no more than the model); *pilot_s (may be NULL) what the
 * pilots cost. Errors: those of fb_run_case. */
fb_status fb_peers_estimate(double *cpu_s, double *pilot_s, const fb_case *c, const char *dir,
                            fb_diag *diag);

#endif
