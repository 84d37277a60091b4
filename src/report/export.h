/* fourbar export: a case's mechanism in a user's own model format (MJCF for
 * MuJoCo, SDFormat 1.9 for Gazebo), with the contact the project verified
 * (docs/contact-params.md, "Your mechanism in your engine"). */
#ifndef FB_EXPORT_H
#define FB_EXPORT_H

#include <stddef.h>

#include "case.h"
#include "scene.h"
#include "status.h"

/* Writes case c's mechanism as MJCF into buf (size bytes, NUL terminated):
 * with ideal = 1, or when c has no clearance joint, model
 * mujoco-ideal-nominal; else mujoco-clearance-native with its bore as a
 * limited tendon (fb_mujoco_export). Errors: those of
 * fb_scene_from_case and fb_mujoco_export; FB_ERR_ARG in a build
 * without MuJoCo (the MJCF is checked by compiling it), or when the model
 * does not build the case's mechanism (fb_model.mechanisms: the
 * slider-crank today). On FB_OK,
 * diag->msg is empty, or a note that a clearance contact is beyond the
 * run's resolution rule at the case's step (h omega_c > 0.5): the file is
 * written, the command prints the note as a warning. */
fb_status fb_export_mjcf(char *buf, size_t size, const fb_case *c, int ideal, fb_diag *diag);

/* Writes planar case c's ([linkage] type = planar) mechanism as MJCF into
 * buf (size bytes, NUL terminated): a leading comment, then the text
 * MuJoCo's binding of the engine kit composes and runs at the case's step
 * (fb_planar_run_step; fb_planar_kit_model_text), bodies and joints by the
 * case's names, keyframe "start" (the assembly and the drive's velocities
 * there): with ideal = 1 or no clearance joint model mujoco-ideal-nominal's
 * mechanism, else mujoco-clearance-native's with its bore as a limited
 * tendon (its law as a run takes it: joint_law.h at the joint's largest
 * ideal reaction). fb_export_mjcf's route for a planar case. Errors:
 * FB_ERR_ARG for a case with springs or loads, a prismatic clearance joint
 * without ideal (MuJoCo's bore is a pin's), or in a build without MuJoCo;
 * those of fb_planar_kit_model_text. On FB_OK diag->msg is empty, or the
 * note that a clearance joint's contact is beyond the planar run's
 * resolution rule at the written step (planar_resolution.h: h x rate >
 * FB_H_OMEGA_C_BOUND), naming the step that resolves it. */
fb_status fb_export_planar_mjcf(char *buf, size_t size, const fb_case *c, int ideal,
                                fb_diag *diag);

/* Writes case c's mechanism as an SDFormat 1.9 world for Gazebo's ODE
 * physics into buf (size bytes, NUL terminated): with ideal = 1, or when c
 * has no clearance joint, model ode-ideal-nominal's mechanism, else
 * ode-clearance-restitution's (fb_export_sdf_model). Errors: those of
 * fb_scene_from_case and fb_export_sdf_model; FB_ERR_ARG for a mechanism
 * whose description has no SDF export (fb_mech_desc.sdf_export: all but the
 * four-bar; fb_export_sdf_refusal). On FB_OK, diag->msg as
 * fb_export_mjcf's. */
fb_status fb_export_sdf(char *buf, size_t size, const fb_case *c, int ideal, fb_diag *diag);
/* (A planar case: FB_ERR_ARG naming the format and the case type: no SDF
 * of a planar case is written.) */

/* The SDFormat 1.9 world of model sm (export_sdf.c): world "fourbar" with
 * the case's gravity along -y and a physics "case_step" (ODE, world solver,
 * max_step_size = the case's h, the case's world ERP and CFM, contact
 * surface layer 0); model "fourbar" with link ground welded to the world
 * (joint ground_weld), links crank, coupler, follower at the start with
 * their masses and inertias (ixx the long axis, izz the hinge axis, about
 * the centre of mass), a revolute joint per ideal joint (named after the
 * joint; the loop is closed by the fourth), frames <joint>_pin and
 * <joint>_hole at each joint's pin and hole centre, and per clearance joint
 * a cylinder collision <joint>_pin in a ring of boxes <joint>_hole_<k>
 * whose surface/contact/ode carries the restitution law's spring and damper
 * as the project's matched row at h in Gazebo's kp, kd (fb_cp_rows_make),
 * max_vel, min_depth 0; the crank driven by Gazebo Sim's JointController at
 * the case's speed. Errors: those of fb_scene_check and
 * fb_cp_rows_make; FB_ERR_ARG for a clearance ground-crank joint (the drive
 * needs its revolute); FB_ERR_RANGE when buf is too small; FB_ERR_ARG
 * (fb_export_sdf_refusal) for a scene of a mechanism without SDF export
 * (fb_mech_desc.sdf_export): the world written is the four-bar's. */
fb_status fb_export_sdf_model(char *buf, size_t size, const fb_model_scene *sm, fb_diag *diag);

/* Refuses the SDF export of a mechanism of type t (not the four-bar):
 * FB_ERR_ARG saying the SDF world written is the four-bar's and a t's
 * (a slider on a prismatic joint) is not written. */
fb_status fb_export_sdf_refusal(fb_mech_type t, fb_diag *diag);

#endif
