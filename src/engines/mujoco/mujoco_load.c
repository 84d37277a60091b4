/* Loading an MJCF text from memory (mujoco_load.h), with fourbar's MuJoCo
 * error and warning handlers installed. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mujoco_load.h"

static void on_error(const char *msg) {
  fprintf(stderr, "fourbar: MuJoCo error: %s (MuJoCo cannot continue; exiting)\n", msg);
  exit(1);
}

static void on_warning(const char *msg) { fprintf(stderr, "fourbar: MuJoCo warning: %s\n", msg); }

mjModel *fb_mujoco_load_mjcf(const char *mjcf, fb_diag *diag) {
  mju_user_error = on_error;
  mju_user_warning = on_warning;
  mjVFS *vfs = calloc(1, sizeof *vfs); /* ~2 MB of file-name slots: not on the stack */
  if (!vfs) {
    fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for MuJoCo's virtual file system");
    return NULL;
  }
  mj_defaultVFS(vfs);
  const char *name = "fourbar.xml";
  const int len = (int)strlen(mjcf);
  if (mj_makeEmptyFileVFS(vfs, name, len) != 0) {
    free(vfs);
    fb_diag_set(diag, FB_ERR_NOMEM, "MuJoCo's virtual file system refused a %d-byte file", len);
    return NULL;
  }
  memcpy(vfs->filedata[mj_findFileVFS(vfs, name)], mjcf, (size_t)len);
  char err[1024] = "";
  mjModel *m = mj_loadXML(name, vfs, err, (int)sizeof err);
  mj_deleteVFS(vfs);
  free(vfs);
  if (!m) fb_diag_set(diag, FB_ERR_ARG, "MuJoCo rejected the generated model: %s", err);
  return m;
}
