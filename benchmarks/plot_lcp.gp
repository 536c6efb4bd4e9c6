# Plots the CSV written by lcp_bench (median solve times, log scale).
#   gnuplot -e "csv='out/lcp_bench.csv'; out='lcp_bench.png'" benchmarks/plot_lcp.gp
# Two panels: eq. (6) problems by number of contacts, and dense SPD problems by size.
if (!exists("csv")) csv = 'out/lcp_bench.csv'
if (!exists("out")) out = 'lcp_bench.png'
set terminal pngcairo size 1200,500 font ",10"
set output out
set datafile separator ","
set logscale y
set grid ytics
set key top left noenhanced
set multiplot layout 1,2

set title "eq. (6) problems (eps = 0, mu = 0.5): median time per solve"
set xlabel "contacts (n = 3 x contacts)"
set ylabel "median time [us]"
set xrange [0.5:4.5]
set xtics 1
plot for [s in "frictional_lemke frictional_pgs frictional_nfb lemke_core_eq6 siconos_lexicolemke"] \
     csv using (strcol(1) eq "eq6" && strcol(4) eq s ? $3 / 3 : 1/0):5 with points pointsize 1.5 title s

set title "dense SPD problems, cond 100: median time per solve"
set xlabel "n"
set logscale x
set xrange [40:600]
set xtics (50, 200, 500)
plot for [s in "lemke pgs nfb siconos_lexicolemke siconos_pgs siconos_newton_fb"] \
     csv using (strcol(1) eq "spd" && strcol(4) eq s ? $3 : 1/0):5 with points pointsize 1.5 title s
unset multiplot
