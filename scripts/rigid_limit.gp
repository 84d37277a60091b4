# docs/rigid_limit.svg from the rigid-limit study's points.csv (scripts/rigid_limit.sh):
# gnuplot -e "csv='points.csv'; cr=0.9; out='rigid_limit.svg'" scripts/rigid_limit.gp
set terminal svg size 1200,860 dynamic enhanced font 'sans,12' background '#ffffff'
set output out
set datafile separator comma
set datafile columnheaders
set datafile missing NaN
set logscale x
set xrange [0.6:1700]
set xtics (1, 10, 100, 1000)
set xlabel 'penalty stiffness / the case''s (clearance.stiffness\_scale)'
set grid
set key top left box opaque
R = 'reference-restitution.'
S = 'siconos-clearance-newton.'
ref = 'lc rgb "#8c8c00" pt 7 ps 1.2 lw 2'
sic = 'lc rgb "#cb181d" pt 5 ps 1.2 lw 2 dt 2'
amax(a, b) = abs(a) > abs(b) ? abs(a) : abs(b)
set multiplot layout 2,2 title "The rigid limit on the paper's case: the restitution law's reference as its stiffness grows, and Siconos's Newton-impact model (each at that stiffness's automatic step)"

set title 'first impact: rebound ratio (separation / approach speed at the clearance crossings)'
set ylabel 'rebound ratio [-]'
set yrange [0.6:1.0]
plot csv using 2:(column(R.'first_impact.rebound_ratio')) with linespoints @ref title 'reference-restitution', \
     '' using 2:(column(S.'first_impact.rebound_ratio')) with linespoints @sic title 'siconos-clearance-newton (speeds up to 2 steps apart)', \
     cr with lines lc rgb '#000000' dt 3 lw 1.5 title sprintf('Newton''s e_N = %g', cr)
set autoscale y

set title 'first impact: contact duration, entry to exit crossing (1 x: pressed, no bounce)'
set ylabel 'contact duration [s]'
set key bottom left
set yrange [1e-8:1e-3]
set logscale y
set format y '%.0e'
plot csv using 2:(column(R.'first_impact.contact_duration_s')) with linespoints @ref title 'reference-restitution', \
     '' using 2:(column(S.'first_impact.contact_duration_s')) with linespoints @sic title 'siconos-clearance-newton', \
     3.99e-5 / sqrt(x) with lines lc rgb '#000000' dt 3 lw 1.5 title 'k^{-1/2} (through 10 x)'
unset logscale y
set format y '% h'
set autoscale y

set title 'revolution 2: impacts (approach >= 1e-3 m/s)'
set ylabel 'impacts in revolution 2 [-]'
set key bottom right
set yrange [0:*]
plot csv using 2:(column(R.'spikes.impacts')) with linespoints @ref title 'reference-restitution', \
     '' using 2:(column(S.'spikes.impacts')) with linespoints @sic title 'siconos-clearance-newton'
set autoscale y

set title 'revolution 2: largest coupler |alpha| (no limit: the rigid impact is an impulse)'
set ylabel '|alpha| peak [rad/s^2]'
set key top left
set logscale y
set format y '%.0e'
plot csv using 2:(amax(column(R.'coupler.alpha_max_rad_s2'), column(R.'coupler.alpha_min_rad_s2'))) with linespoints @ref title 'reference-restitution', \
     '' using 2:(amax(column(S.'coupler.alpha_max_rad_s2'), column(S.'coupler.alpha_min_rad_s2'))) with linespoints @sic title 'siconos-clearance-newton (grows as 1 / h)', \
     7.52e4 * sqrt(x) with lines lc rgb '#000000' dt 3 lw 1.5 title 'k^{1/2} (through 1 x)'
unset multiplot
