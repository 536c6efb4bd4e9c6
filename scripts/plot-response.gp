# Plots a bridge or deck run's history.csv (docs/outputs.md): x and y, theta, and the four
# normal gaps gN1..gN4 against t, to a PNG.
#   gnuplot -e "history='out/bridge-exc7/history.csv'; out='out/bridge-exc7/response.png'; \
#               name='bridge-exc7'" scripts/plot-response.gp
if (!exists("history")) history = 'out/bridge-exc7/history.csv'
if (!exists("out")) out = 'out/bridge-exc7/response.png'
if (!exists("name")) name = 'bridge-exc7'

set terminal pngcairo size 1200,900 font ',10'
set output out
set datafile separator ','
set datafile columnheaders
set key top right
set grid
set xlabel 't [s]'
set multiplot layout 3,1 title sprintf('%s: Moreau-Jean response of the deck', name)

set ylabel 'displacement [m]'
plot history using (column("t")):(column("x")) with lines lw 1.2 title 'x (longitudinal)', \
     history using (column("t")):(column("y")) with lines lw 1.2 title 'y (transverse)'

set ylabel 'rotation [rad]'
plot history using (column("t")):(column("theta")) with lines lw 1.2 lc rgb '#a0302a' title 'theta'

set ylabel 'normal gap [m]'
plot history using (column("t")):(column("gN1")) with lines title 'gN1 (left, +W/2)', \
     history using (column("t")):(column("gN2")) with lines title 'gN2 (left, -W/2)', \
     history using (column("t")):(column("gN3")) with lines title 'gN3 (right, +W/2)', \
     history using (column("t")):(column("gN4")) with lines title 'gN4 (right, -W/2)', \
     0 with lines dashtype 2 lc rgb 'black' notitle
unset multiplot
