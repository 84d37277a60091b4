# docs/siconos_kit_guide.svg from scripts/siconos_kit_guide.sh's DIR/TAG.dat
# (columns 1-2 ours: time [s], crank angle [rad]; 3-37 the example's .ref:
# 3 time, 4 crank revolutions):
# gnuplot -e "dir='results/siconos_kit_guide'; out='docs/siconos_kit_guide.svg'" scripts/siconos_kit_guide.gp
set terminal svg size 900,480 dynamic enhanced font 'sans,12' background '#ffffff'
set output out
set grid
set xlabel 't [ms]'
set xrange [0:200]
set ylabel '|crank angle - .ref| [rad]'
set logscale y
set yrange [1e-16:1e8]
set format y '10^{%L}'
set key top right box opaque
set title "The harness's Siconos model (built from the description) against Siconos's .ref, h = 1e-4 s: the example's settings, then one changed"
d(tag) = sprintf('%s/%s.dat', dir, tag)
f(x) = abs(x) > 1e-16 ? abs(x) : 1e-16
plot d('example') using ($1*1e3):(f($2 - $4*2*pi)) with lines lw 2 lc rgb '#000000' title "the example's (angles, combined projection, its Newton loop, mu 0.01)", \
     d('friction0') using ($1*1e3):(f($2 - $4*2*pi)) with lines lw 1.5 lc rgb '#1b9e77' title 'friction 0', \
     d('newton') using ($1*1e3):(f($2 - $4*2*pi)) with lines lw 1.5 lc rgb '#d95f02' title 'Newton converged to 1e-12', \
     d('moreau') using ($1*1e3):(f($2 - $4*2*pi)) with lines lw 1.5 lc rgb '#7570b3' title 'Moreau-Jean, no projection', \
     d('absolute') using ($1*1e3):(f($2 - $4*2*pi)) with lines lw 1.5 lc rgb '#e7298a' title 'absolute coordinates, friction 0'
