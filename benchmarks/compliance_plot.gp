# Plots of compliance_bench output. Usage (in the folder holding the CSV files):
#   gnuplot -e "csv='out/compliance_bench.csv'; hist='hist'" benchmarks/compliance_plot.gp
# Writes compliance_cost.png (CPU time and steps against k / k0), compliance_error.png
# (theta error against k / k0, and against CPU time beside Moreau–Jean), compliance_fig8.png
# (first pounding: penetration and duration against k / k0) and, if hist is set,
# compliance_theta.png (theta(t) of each stiffness beside the nonsmooth reference).
if (!exists("csv")) csv = 'out/compliance_bench.csv'
set datafile separator ','
set terminal pngcairo size 900,600 noenhanced
set key autotitle columnhead
set logscale x
set grid

set output 'compliance_cost.png'
set xlabel 'stiffness factor k / k0'
set ylabel 'CPU time [s]'
set y2label 'accepted steps'
set y2tics
plot csv using ($5>0 ? $5 : 1/0):8 with linespoints title 'CPU time (median)', \
     csv using ($5>0 ? $5 : 1/0):9 axes x1y2 with linespoints title 'steps'
unset y2tics
unset y2label

set output 'compliance_error.png'
set multiplot layout 1,2
set logscale y
set xlabel 'stiffness factor k / k0'
set ylabel 'theta error / peak |theta_ref|'
plot csv using ($5>0 ? $5 : 1/0):12 with linespoints title 'RMS', \
     csv using ($5>0 ? $5 : 1/0):13 with linespoints title 'max', \
     csv using ($5>0 ? $5 : 1/0):(abs($15)) with linespoints title '|peak error|'
set xlabel 'CPU time [s]'
set ylabel '|peak rotation error| / peak |theta_ref|'
plot csv using (strcol(1) eq 'compliance' ? $8 : 1/0):(abs($15)) with linespoints title 'compliance (k varies)', \
     csv using (strcol(1) ne 'compliance' && strcol(1) ne 'moreau' ? $8 : 1/0):(abs($15)+1e-6) with points pt 7 title 'nonsmooth, coarser h'
unset multiplot

set output 'compliance_fig8.png'
set multiplot layout 1,2
set xlabel 'stiffness factor k / k0'
set ylabel 'first pounding: max penetration [m]'
plot csv using ($5>0 ? $5 : 1/0):19 with linespoints title 'penetration'
set ylabel 'first pounding: contact duration [s]'
plot csv using ($5>0 ? $5 : 1/0):18 with linespoints title 'duration'
unset multiplot
unset logscale

if (exists("hist")) {
  set output 'compliance_theta.png'
  set xlabel 't [s]'
  set ylabel 'theta [rad]'
  plot hist.'/moreau.csv' using 1:2 with lines lw 2 title 'Moreau-Jean, eps = e_eff', \
       for [f in "0.0001 0.01 1 100"] hist.'/compliance_'.f.'.csv' using 1:2 with lines title 'compliance k = '.f.' k0'
}
