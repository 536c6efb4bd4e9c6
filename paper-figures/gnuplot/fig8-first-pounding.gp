# Fig. 8 of Shi & Dimitrakopoulos (2017): the first pounding of excitation 5 under the
# compliance method. Reads `data` (fig8-first-pounding.csv: factor, t, gap, lambda_n; factor 0
# is the nonsmooth run), `contact` (1-based), `t_first` [s], `factors` (every factor, as
# '0.0001 0.01 1 100') and `loop_factors` (those whose force-penetration loop is drawn, as in
# the paper 1e0 k and 1e2 k; may be empty); set by paper-figures/fig8.cpp.
set multiplot layout 1,2 title sprintf('Fig. 8: first pounding of excitation 5 (contact %d, t = %.4f s)', contact, t_first)
set title 'gap at the first pounding (factor 0: nonsmooth)'
set xlabel 't [s]'
set ylabel sprintf('g_{N%d} [m]', contact)
set xrange [t_first - 0.02:t_first + 0.1]
plot for [f in factors] data using 't':(column('factor') == f + 0 ? column('gap') : 1/0) with lines title f.' k', \
     data using 't':(column('factor') == 0 ? column('gap') : 1/0) with lines lw 2 lc rgb 'black' title 'nonsmooth'
set autoscale x
set title 'force-penetration loop of the gap element'
set xlabel 'penetration -g_N [m]'
set ylabel 'lambda_N [kN]'
if (words(loop_factors) == 0) {
  plot 0 notitle
} else {
  plot for [f in loop_factors] data using (column('factor') == f + 0 && column('gap') < 0 ? -column('gap') : 1/0):'lambda_n' with lines title f.' k'
}
unset multiplot
