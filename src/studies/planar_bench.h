/* fourbar bench on a planar case ([linkage] type = planar, docs/planar.md):
 * the default grid of every engine with a binding of the engine kit
 * (src/engines/kit/kit.h), each model run through the planar run path as
 * `fourbar run` runs it (planar_run.h: fb_planar_run_case, one model a run).
 *
 * The grid: per engine of the build with a kit binding (in the order of
 * their ids), its ideal nominal model (the first model of the engine's
 * table with ideal joints and nominal lengths that fb_planar_kit_of builds)
 * and, when the case has a [clearance] joint, its clearance-impact model
 * (the first with the impact law that fb_planar_kit_of builds; an engine
 * without the impact law has no clearance rows: Siconos's rigid Newton-law
 * model puts an impulse where the reference has a compliant force, whose
 * peaks it cannot match, and its reference, reference-restitution, failed
 * after 5 minutes on the six-bar), at the engine's recommended
 * settings: the points of the four-bar's default grid (engine_bench.h,
 * FB_BENCH_SET_DEFAULT: ODE's dWorldStep at 1e-5 s, MuJoCo at 1e-5 and
 * 3e-6 s, Bullet's MLCP at 1e-5 s, Simbody rkmerson at accuracy 1e-4 and
 * 1e-6 and cpodes at 1e-6, Siconos at the case's step), each at a fixed h
 * (an auto point at the case's h, the kit's own step; an adaptive point,
 * the contact's step that the kit does not take, left out; a point that
 * repeats an earlier one's h and stepper left out), the first also at h/2
 * (the order of the engine's error shows there), FB_PLANAR_BENCH_POINTS
 * at most; an engine without default points at the case's h and h/2.
 * Every run 2 revolutions (the case's [run] revolutions when fewer), the
 * peaks over the window after the first (fb_case_peak_window_from; all of
 * it with [run] peaks = all), as the four-bar's bench.
 *
 * Error (the four-bar bench's definitions, bench.h, carried to any body):
 *   ideal model: the largest |relative error| of the omega window peaks
 *     (max and min) of every moving body against the analytic model's
 *     exact extremes, each relative to the larger magnitude of that body's
 *     two analytic extremes (planar_verdict.h's normalisation: a peak near
 *     zero has no relative error of its own; the four-bar's bench divides
 *     each peak by itself), a body whose extremes are below
 *     FB_PLANAR_PEAK_FLOOR_REL of the largest left out (a slider turns not);
 *   clearance model: the largest of the |relative errors| of its clearance
 *     joint's peak contact force and peak penetration and of every moving
 *     body's alpha spike (max |alpha| over the window) against the
 *     reference of its law (fb_model_reference_of: "reference" for the
 *     impact law, run once on the case's h), a body whose reference spike is
 *     below FB_PLANAR_PEAK_FLOOR_REL of the largest left out (the driven
 *     crank's, which turns at constant speed).
 * Cost: wall time per simulated revolution, the set-up (the law, the
 * engine's world built through the kit: planar_run.h setup_s) apart; a
 * row's run is repeated in FB_BENCH_ROUNDS - 1 further rounds over the
 * whole grid when it took at most FB_BENCH_REPEAT_BELOW_S (bench.h), its
 * cost the median. Each engine's model's Pareto front (fb_bench_mark_pareto)
 * and the cheapest row per error target (1e-2, 1e-3, 1e-4) per model and
 * across engines, as the four-bar's. */
#ifndef FB_PLANAR_BENCH_H
#define FB_PLANAR_BENCH_H

#include "bench_study.h"

/* Rows a planar bench holds at most: 7 engines x 2 models x
 * FB_PLANAR_BENCH_POINTS = 42, with room to spare; beyond it the run stops with an error. */
#define FB_PLANAR_BENCH_MAX_ROWS 160

/* Configurations (steps and settings) per engine at most: its default
 * grid's first point at h and h/2 and the next one (MuJoCo's
 * 3e-6 s, Simbody's accuracy 1e-6), which keeps the grid to about a minute
 * of CPU on the planar four-bar. */
#define FB_PLANAR_BENCH_POINTS 3

/* Bodies whose errors a row keeps by name (bench.json error_by_body); a
 * description with more keeps the worst only. */
#define FB_PLANAR_BENCH_BODIES 32

/* Runs the planar default grid o asks for (o->c a driven planar case;
 * o->grids FB_BENCH_DEFAULT), writes o->dir/bench.csv, bench.json and
 * bench.svg (o->draw) and prints the table (or, with o->json, bench.json)
 * on stdout. Returns the exit status: 0 ok, 1 failed, 2 bad input (an
 * undriven case), having said why on stderr ("fourbar bench: ..."). */
int fb_bench_planar(const fb_bench_opts *o);

#endif
