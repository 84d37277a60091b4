/* A case run whole: its models (run.h, fb_run_models), then its ensemble
 * (ensemble.h) and the verdicts (verdict.h) that settle on it. The
 * ensemble sits above the models: run.c never calls it, the ensemble runs
 * its members with fb_run_models, and run_case.c calls both. run.h
 * includes this header, so its includers reach fb_run_case. */
#ifndef FB_RUN_CASE_H
#define FB_RUN_CASE_H

#include "run.h"

/* Runs case c: its models (fb_run_models), then, unless c is an
 * ensemble's member, its ensemble and the verdicts. A model that stops on
 * numerical trouble keeps its status and the others still run. Refused
 * before any model runs (FB_ERR_RANGE, with the estimate) when the
 * estimated memory exceeds FB_COST_MEMORY_FRACTION of physical memory or
 * the estimated wall time exceeds [run] max_wall_s; a model still running
 * [run] max_wall_s after the start (an estimate is only an estimate) stops
 * there with FB_STOP_WALL_TIME, and an ensemble whose member stopped so is
 * an error (FB_ERR_RANGE).
 * Errors: FB_ERR_ASSEMBLY, FB_ERR_NOMEM, FB_ERR_ARG, FB_ERR_RANGE;
 * on error *r holds nothing that needs freeing. */
fb_status fb_run_case(fb_run *r, const fb_case *c, fb_progress_fn progress, void *user,
                      fb_diag *diag);

#endif
