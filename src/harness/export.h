/* fourbar export: a case's mechanism in a user's own model format (MJCF for
 * MuJoCo, SDFormat 1.9 for Gazebo), with the contact the project verified
 * (docs/contact-params.md, "Your mechanism in your engine"). */
#ifndef FB_EXPORT_H
#define FB_EXPORT_H

#include <stddef.h>

#include "case.h"
#include "status.h"

/* Writes case c's mechanism as MJCF into buf (size bytes, NUL terminated):
 * with ideal = 1, or when c has no clearance joint, model
 * mujoco-ideal-nominal; else mujoco-clearance-native with its bore as a
 * limited tendon (fb_mujoco_export). Errors: those of
 * fb_scene_def_from_case and fb_mujoco_export; FB_ERR_ARG in a build
 * without MuJoCo (the MJCF is checked by compiling it). */
fb_status fb_export_mjcf(char *buf, size_t size, const fb_case *c, int ideal, fb_diag *diag);

#endif
