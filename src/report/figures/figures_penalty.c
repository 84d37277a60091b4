/* penalty_<mode>.<ext> (fourbar penalty --out): force, contact stiffness,
 * penalty and approach against crank speed for both joints (named by the
 * caller: the mechanism's). */
#include "figures_internal.h"

#include <stdio.h>
#include <string.h>

fb_status fb_figures_penalty(const char *path, fb_figure_format fmt, const char *mode, int n,
                             const double *rpm, const double *force[2], const double *stiffness[2],
                             const double *penalty[2], const double *approach_um[2],
                             const char *const joint[2], fb_diag *diag) {
  char dir[4096], name[256];
  fig_split_path(path, dir, sizeof dir, name, sizeof name);
  plot pl;
  fb_status st = fig_plot_open(&pl, dir, name, fmt, 1100, 850, diag);
  if (st != FB_OK) return st;
  const double **cols[4] = {force, stiffness, penalty, approach_um};
  /* P = Kc C^1.5: the paper's Table II unit in paper mode, SI otherwise */
  const char *labels[4] = {"force [N]", "contact stiffness Kc [N/m]",
                           strcmp(mode, "paper") == 0 ? "penalty P [N mm^{0.5}]" : "penalty P [N m^{0.5}]",
                           "approach [um]"};
  for (int q = 0; q < 4; q++)
    for (int j = 0; j < 2; j++) {
      fprintf(pl.p, "$d%d_%d << EOD\n", q, j);
      for (int i = 0; i < n; i++) fprintf(pl.p, "%.6g %.9g\n", rpm[i], cols[q][j][i]);
      fprintf(pl.p, "EOD\n");
    }
  char en[160];
  fprintf(pl.p, "set multiplot layout 2,2 title 'penalty estimate against crank speed (%s mode)'\n",
          fig_esc(mode, en, sizeof en));
  /* inside the panel, where the rising curves leave room (outside, the
   * legends of the right column sat on the left column's plots) */
  fprintf(pl.p, "set xlabel 'crank speed [rpm]'\nset key inside top left box opaque\n");
  char j0[160], j1[160];
  fig_esc(joint[0], j0, sizeof j0);
  fig_esc(joint[1], j1, sizeof j1);
  for (int q = 0; q < 4; q++)
    fprintf(pl.p, "set title '%s'\nset ylabel '%s'\nplot $d%d_0 using 1:2 with linespoints pt 7 "
                  "title '%s', $d%d_1 using 1:2 with linespoints pt 5 title '%s'\n",
            labels[q], labels[q], q, j0, q, j1);
  fprintf(pl.p, "unset multiplot\n");
  return fig_plot_close(&pl, diag);
}
