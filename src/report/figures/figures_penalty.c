/* penalty_<mode>.<ext> (fourbar penalty --out): force, contact stiffness,
 * penalty and approach against crank speed for every joint (named by the
 * caller: the mechanism's). */
#include "figures_internal.h"

#include <stdio.h>
#include <string.h>

fb_status fb_figures_penalty(const char *path, fb_figure_format fmt, const char *mode,
                             const char *speed, int n, const double *rpm, int njoints, const double *const *force,
                             const double *const *stiffness, const double *const *penalty,
                             const double *const *approach_um, const char *const *joint,
                             fb_diag *diag) {
  char dir[4096], name[256];
  fig_split_path(path, dir, sizeof dir, name, sizeof name);
  plot pl;
  fb_status st = fig_plot_open(&pl, dir, name, fmt, 1100, 850, diag);
  if (st != FB_OK) return st;
  const double *const *cols[4] = {force, stiffness, penalty, approach_um};
  /* P = Kc C^1.5: the paper's Table II unit in paper mode, SI otherwise */
  const char *labels[4] = {"force [N]", "contact stiffness Kc [N/m]",
                           strcmp(mode, "paper") == 0 ? "penalty P [N mm^{0.5}]" : "penalty P [N m^{0.5}]",
                           "approach [um]"};
  for (int q = 0; q < 4; q++)
    for (int j = 0; j < njoints; j++) {
      fprintf(pl.p, "$d%d_%d << EOD\n", q, j);
      for (int i = 0; i < n; i++) fprintf(pl.p, "%.6g %.9g\n", rpm[i], cols[q][j][i]);
      fprintf(pl.p, "EOD\n");
    }
  char en[160], sn[160];
  fig_esc(speed, sn, sizeof sn);
  fprintf(pl.p, "set multiplot layout 2,2 title 'penalty estimate against %s (%s mode)'\n", sn,
          fig_esc(mode, en, sizeof en));
  /* inside the panel, where the rising curves leave room (outside, the
   * legends of the right column sat on the left column's plots) */
  fprintf(pl.p, "set xlabel '%s [rpm]'\nset key inside top left box opaque\n", sn);
  /* a point type per joint, in the order given (gnuplot's 7, 5, 9, 11, ...) */
  static const int pt[] = {7, 5, 9, 11, 13, 4, 6, 8, 10, 12};
  for (int q = 0; q < 4; q++) {
    fprintf(pl.p, "set title '%s'\nset ylabel '%s'\nplot ", labels[q], labels[q]);
    for (int j = 0; j < njoints; j++) {
      char jn[160];
      fprintf(pl.p, "%s$d%d_%d using 1:2 with linespoints pt %d title '%s'", j ? ", " : "", q, j,
              pt[j % (int)(sizeof pt / sizeof pt[0])], fig_esc(joint[j], jn, sizeof jn));
    }
    fprintf(pl.p, "\n");
  }
  fprintf(pl.p, "unset multiplot\n");
  return fig_plot_close(&pl, diag);
}
