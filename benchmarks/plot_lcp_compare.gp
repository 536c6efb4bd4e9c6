# Plots the performance profiles written by lcp_compare_bench (Dolan & Moré 2002):
#   gnuplot -e "csv='out/lcp_compare_profiles.csv'; group='bridge'; out='lcp-compare-bridge.png'" \
#           benchmarks/plot_lcp_compare.gp
# group: bridge (the harvested problems of excitations 1..7) or siconos (Siconos's collection).
# Four panels: the profile of the CPU time to a solution and of the residual reached, at the
# tolerances 1e-8 and 1e-12. rho_s(tau) is the share of the problems on which solver s is
# within a factor tau of the best. With Siconos linked, add its solvers:
#   -e "solvers='lemke pgs nfb enum siconos_lexicolemke siconos_pgs siconos_newton_fb'"
if (!exists("csv")) csv = 'out/lcp_compare_profiles.csv'
if (!exists("group")) group = 'bridge'
if (!exists("out")) out = 'lcp-compare-'.group.'.png'
if (!exists("solvers")) solvers = "lemke pgs nfb enum"
set terminal pngcairo size 1200,900 font ",10"
set output out
set datafile separator ","
set logscale x
set xlabel "tau (ratio to the best solver on the problem)"
set ylabel "rho(tau): share of the problems"
set yrange [-0.02:1.02]
set grid
set key center right noenhanced
set multiplot layout 2,2 title "performance profiles, ".group." collection"
do for [m in "time residual"] {
  do for [tol in "1e-08 1e-12"] {
    set title m." profile, tolerance ".tol noenhanced
    plot for [s in solvers] csv using (strcol(1) eq group && strcol(2) eq m && \
         strcol(3) eq tol && strcol(4) eq s ? $5 : 1/0):6 with steps lw 2 title s
  }
}
unset multiplot
