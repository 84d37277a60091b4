/* Loading an MJCF text from memory (MuJoCo's virtual file system), with
 * fourbar's MuJoCo error and warning handlers installed. For files inside
 * src/engines/mujoco only: it includes MuJoCo's header. */
#ifndef FB_MUJOCO_LOAD_H
#define FB_MUJOCO_LOAD_H

#include <mujoco/mujoco.h>

#include "status.h"

/* The compiled model of mjcf, or NULL with the reason in diag (FB_ERR_NOMEM,
 * or FB_ERR_ARG with MuJoCo's own message). */
mjModel *fb_mujoco_load_mjcf(const char *mjcf, fb_diag *diag);

#endif
