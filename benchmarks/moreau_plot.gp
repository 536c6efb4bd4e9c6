# Plots moreau_bench's CSV: speed-up over real time and peak rotation per excitation.
#   gnuplot -e "csv='out/moreau_bench.csv'; out='moreau_bench.png'" benchmarks/moreau_plot.gp
if (!exists("csv")) csv = 'out/moreau_bench.csv'
if (!exists("out")) out = 'moreau_bench.png'
set terminal pngcairo size 1000,420
set output out
set datafile separator ','
set multiplot layout 1,2
set xlabel 'excitation'
set ylabel 'simulated time / wall time'
set logscale y
set key top right
plot csv every ::1 using ($2 < 5e-4 ? $1 : 1/0):10 with linespoints title 'h = 1e-4', \
     csv every ::1 using ($2 > 5e-4 ? $1 : 1/0):10 with linespoints title 'h = 1e-3', \
     300 with lines dashtype 2 title 'target 300x (h = 1e-4)'
unset logscale y
set ylabel 'peak |theta| [rad]'
plot csv every ::1 using ($2 < 5e-4 ? $1 : 1/0):13 with linespoints title 'h = 1e-4', \
     csv every ::1 using ($2 > 5e-4 ? $1 : 1/0):13 with linespoints title 'h = 1e-3'
unset multiplot
