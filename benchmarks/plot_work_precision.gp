# Work–precision plot of work_precision_bench's CSV (log–log: error against wall time).
# gnuplot -e "csv='out/work_precision/work_precision.csv'; png='docs/benchmarks/work-precision.png'" \
#         benchmarks/plot_work_precision.gp
if (!exists("csv")) csv = 'out/work_precision/work_precision.csv'
if (!exists("png")) png = 'docs/benchmarks/work-precision.png'
set terminal pngcairo size 1400,1000 font ",11" noenhanced
set output png
set datafile separator ","
set logscale xy
set format x "%.0e"
set format y "%.0e"
set grid
set key top right
set xlabel "wall time [s]"
set multiplot layout 2,2 title "Work–precision: event-driven (tolerance 1e-3..1e-9), Moreau–Jean (h 1e-2..1e-5), compliance (k 1e-4..1e2 k0); reference = event-driven at 1e-10"
# Errors below 1e-16 (round-off, or exactly 0 where the scheme is exact) are drawn at 1e-16.
floor16(v) = v > 1e-16 ? v : 1e-16
sel(scene, method, col) = (strcol(1) eq scene && strcol(2) eq method && strcol(3) ne "1e-10") ? floor16(column(col)) : NaN
set ylabel "max |theta - theta_ref| [rad]"
set title "bridge, excitation 5: theta(t) history"
plot csv skip 1 using 4:(sel("bridge-exc5","event_driven",7)) with linespoints pt 7 title "event-driven", \
     csv skip 1 using 4:(sel("bridge-exc5","moreau",7)) with linespoints pt 5 title "Moreau–Jean", \
     csv skip 1 using 4:(sel("bridge-exc5","compliance",7)) with linespoints pt 9 title "compliance (k 1e-4..1e2 k0)"
set ylabel "|peak |theta| - reference| [rad]"
set title "bridge, excitation 5: peak rotation"
plot csv skip 1 using 4:(sel("bridge-exc5","event_driven",6)) with linespoints pt 7 title "event-driven", \
     csv skip 1 using 4:(sel("bridge-exc5","moreau",6)) with linespoints pt 5 title "Moreau–Jean", \
     csv skip 1 using 4:(sel("bridge-exc5","compliance",6)) with linespoints pt 9 title "compliance (k 1e-4..1e2 k0)"
set ylabel "max |y - y_ref| [m]"
set title "bouncing ball (e = 0.8): y(t) history"
plot csv skip 1 using 4:(sel("bouncing-ball","event_driven",7)) with linespoints pt 7 title "event-driven", \
     csv skip 1 using 4:(sel("bouncing-ball","moreau",7)) with linespoints pt 5 title "Moreau–Jean", \
     csv skip 1 using 4:(sel("bouncing-ball","compliance",7)) with linespoints pt 9 title "compliance (k 1e-4..1e2 k0)"
set ylabel "|peak y - reference| [m]"
set title "bouncing ball: peak height"
plot csv skip 1 using 4:(sel("bouncing-ball","event_driven",6)) with linespoints pt 7 title "event-driven", \
     csv skip 1 using 4:(sel("bouncing-ball","moreau",6)) with linespoints pt 5 title "Moreau–Jean", \
     csv skip 1 using 4:(sel("bouncing-ball","compliance",6)) with linespoints pt 9 title "compliance (k 1e-4..1e2 k0)"
unset multiplot
