# docs/slider_guide_reference.svg from scripts/slider_guide_reference.sh's both.dat
# (columns 1-3 ours: time [s], crank angle, slider angle [rad]; 4-38 the
# example's .ref: 4 time, 5 crank revolutions, 6 rod angle, 7 tilt):
# gnuplot -e "dat='both.dat'; out='slider_guide_reference.svg'" scripts/slider_guide_reference.gp
set terminal svg size 1200,430 dynamic enhanced font 'sans,12' background '#ffffff'
set output out
set grid
set xlabel 't [ms]'
set xrange [0:200]
ours = 'lc rgb "#2166ac" lw 2'
theirs = 'lc rgb "#b2182b" lw 1 dt 2'
set multiplot layout 1,3 title "Slider in its guide (c = 1 mm), undriven from 150 rad/s: the harness's penalty reference (p = 1e9 N/m, e = 0.4, frictionless) over Siconos's .ref (h = 1e-4 s, mu = 0.01)"

set title 'crank angle'
set ylabel 'theta1 [rad]'
set key top left box opaque
plot dat using ($1*1e3):2 with lines @ours title 'ours', \
     '' using ($4*1e3):($5*2*pi) with lines @theirs title 'Siconos .ref'

set title 'crank angle: ours - .ref'
set ylabel 'difference [rad]'
unset key
plot dat using ($1*1e3):($2 - $5*2*pi) with lines @ours notitle

set title 'slider tilt (both strike flat)'
set ylabel 'theta3 [rad]'
set key top left box opaque
set format y '%.0e'
plot dat using ($1*1e3):3 with lines @ours title 'ours', \
     '' using ($4*1e3):7 with lines @theirs title 'Siconos .ref'
unset multiplot
