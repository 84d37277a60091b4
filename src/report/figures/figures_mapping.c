/* mapping.<ext> (fourbar mapping --out): the ERP map over contact stiffness
 * and step size with the h omega = 1 and ERP = 0.1, 0.99 contours. */
#include "figures_internal.h"

#include <math.h>
#include <stdio.h>

fb_status fb_figures_mapping(const char *path, fb_figure_format fmt, const char *title, int nk,
                             const double *k, int nh, const double *h, const double *erp,
                             const double *h_omega, fb_diag *diag) {
  char dir[4096], name[256];
  fig_split_path(path, dir, sizeof dir, name, sizeof name);
  plot pl;
  char en[512];
  fb_status st = fig_plot_open(&pl, dir, name, fmt, 1000, 760, diag);
  if (st != FB_OK) return st;
  fprintf(pl.p, "$map << EOD\n");
  for (int i = 0; i < nk; i++) {
    for (int j = 0; j < nh; j++)
      fprintf(pl.p, "%.6f %.6f %.9g %.9g\n", log10(k[i]), log10(h[j]), erp[i * nh + j],
              log10(h_omega[i * nh + j]));
    fprintf(pl.p, "\n");
  }
  fprintf(pl.p, "EOD\n");
  /* contours first (tabulated without pm3d), then the map */
  fprintf(pl.p, "set view map\nset contour base\nunset surface\nset cntrparam levels discrete 0\n"
                "set table $hw\nsplot $map using 1:2:4\nunset table\n"
                "set cntrparam levels discrete 0.1, 0.99\nset table $erpc\n"
                "splot $map using 1:2:3\nunset table\nunset contour\nset surface\n");
  fprintf(pl.p, "set title '%s' noenhanced\nset xlabel 'log10 stiffness k [N/m]'\n"
                "set ylabel 'log10 step size h [s]'\nset cblabel 'ERP'\nset cbrange [0:1]\n"
                "set pm3d map interpolate 4,4\nset palette rgb 33,13,10\n"
                "set key outside top center horizontal\n"
                "splot $map using 1:2:3 with pm3d notitle, "
                "$hw using 1:2:(1) with lines lw 3 lc rgb 'white' title 'h omega = 1 (above: under-resolved)', "
                "$erpc using 1:2:(1) with lines lw 2 dt 2 lc rgb 'black' title 'ERP = 0.1 and 0.99'\n",
          fig_gp_text(title, 0, en, sizeof en));
  return fig_plot_close(&pl, diag);
}
