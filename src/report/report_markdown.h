/* report.md: the human-readable report of a run, with its figures. */
#ifndef FB_REPORT_MARKDOWN_H
#define FB_REPORT_MARKDOWN_H

#include "run.h"

/* Writes DIR/report.md atomically: the command line, the summary table (as
 * printed), the stack-up and contact parameters used, and each figure in
 * figures (n names, may be 0) embedded. Errors: FB_ERR_IO. */
fb_status fb_report_write_markdown(const char *dir, const fb_run *r, const char *case_path,
                                   const char *command, char figures[][128], int n,
                                   const char *figure_note, fb_diag *diag);

#endif
