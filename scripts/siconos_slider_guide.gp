# docs/siconos_slider_guide.svg from scripts/siconos_slider_guide.sh's both.dat
# (columns 1-35 ours, 36-70 the example's .ref, the example's column order):
# gnuplot -e "dat='both.dat'; out='siconos_slider_guide.svg'" scripts/siconos_slider_guide.gp
# The .ref's own values are not drawn (they stay out of the repository): the
# first three panels are the reproduction's, the fourth its differences from
# the .ref, which at 1e-11 and below carry none of its values.
set terminal svg size 1200,860 dynamic enhanced font 'sans,12' background '#ffffff'
set output out
set grid
set xlabel 't [ms]'
set xrange [0:200]
ours = 'lc rgb "#2166ac" lw 2'
ours2 = 'lc rgb "#b2182b" lw 2'
# a difference of exactly 0 drawn at 1e-17 on the log axis
atleast(x) = x > 1e-17 ? x : 1e-17
set multiplot layout 2,2 title "Siconos's slider-crank example, slider in a guide with 1 mm clearance: our reproduction, and its difference from the example's .ref"

set title 'crank and rod angles'
set ylabel 'angle [rad]'
set key bottom left box opaque
plot dat using ($1*1e3):($2*2*pi) every 4 with lines @ours title 'crank theta1', \
     '' using ($1*1e3):3 every 4 with lines @ours2 title 'rod theta2'

set title 'angular velocities'
set ylabel 'omega [rad/s]'
plot dat using ($1*1e3):5 every 4 with lines @ours title 'crank', \
     '' using ($1*1e3):6 every 4 with lines @ours2 title 'rod'

set title "slider centre between the walls (+-1: a face on a wall; tilt below 2.3e-15 rad)"
set ylabel 'y / c [-]'
set yrange [-1.1:1.1]
unset key
plot dat using ($1*1e3):13 every 4 with lines @ours notitle
set autoscale y
set key

set title '|ours - the .ref|, every 10th row (1e-17: equal)'
set ylabel 'absolute difference'
set logscale y
set format y '10^{%L}'
set yrange [1e-18:1e-8]
set key top left box opaque
plot dat using ($1*1e3):(atleast(abs($2-$37)*2*pi)) every 10 with points pt 7 ps 0.3 lc rgb '#2166ac' title 'crank angle [rad]', \
     '' using ($1*1e3):(atleast(abs($3-$38))) every 10 with points pt 7 ps 0.3 lc rgb '#b2182b' title 'rod angle [rad]', \
     '' using ($1*1e3):(atleast(abs($5-$40))) every 10 with points pt 7 ps 0.3 lc rgb '#1b7837' title 'crank omega [rad/s]', \
     '' using ($1*1e3):(atleast(abs($14-$49))) every 10 with points pt 7 ps 0.3 lc rgb '#762a83' title 'gap g1 [m]', \
     1e-8 with lines lc rgb '#000000' dt 2 lw 1.5 title 'the bound, 1e-8'
unset multiplot
