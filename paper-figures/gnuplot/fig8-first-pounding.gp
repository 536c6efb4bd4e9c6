# Fig. 8 of Shi & Dimitrakopoulos (2017): the first pounding of excitation 5 under the
# compliance method, one row of panels per damping law of eq. (9). Reads `data`
# (fig8-first-pounding.csv: factor, law, e_eff, t, gap, lambda_n; law is the 1-based position
# in `laws`, 0 the nonsmooth run; e_eff the law's effective restitution), `contact` (1-based),
# `t_first` [s], `factors` (every factor, as '0.0001 0.01 1 100'), `loop_factors` (those whose
# force-penetration loop is drawn, as in the paper 1e0 k and 1e2 k; may be empty), `laws`
# ('hertzdamp hunt_crossley_exact') and `eps` (the nonsmooth runs' restitution); set by
# paper-figures/fig8.cpp.
set multiplot layout words(laws),2 title sprintf('Fig. 8: first pounding of excitation 5 (contact %d, t = %.4f s; nonsmooth eps = %g)', contact, t_first, eps)
do for [j = 1:words(laws)] {
  # The law's effective restitution, read from its rows of the table.
  stats data using (column('law') == j ? column('e_eff') : 1/0) nooutput
  e_eff = STATS_max
  set title sprintf('%s (effective restitution %.3g): gap (factor 0: nonsmooth)', word(laws, j), e_eff) noenhanced
  set xlabel 't [s]'
  set ylabel sprintf('g_{N%d} [m]', contact)
  set xrange [t_first - 0.02:t_first + 0.1]
  plot for [f in factors] data using 't':(column('law') == j && column('factor') == f + 0 ? column('gap') : 1/0) with lines title f.' k', \
       data using 't':(column('law') == 0 ? column('gap') : 1/0) with lines lw 2 lc rgb 'black' title 'nonsmooth'
  set autoscale x
  set title sprintf('%s (effective restitution %.3g): force-penetration loop', word(laws, j), e_eff) noenhanced
  set xlabel 'penetration -g_N [m]'
  set ylabel 'lambda_N [kN]'
  if (words(loop_factors) == 0) {
    plot 0 notitle
  } else {
    plot for [f in loop_factors] data using (column('law') == j && column('factor') == f + 0 && column('gap') < 0 ? -column('gap') : 1/0):'lambda_n' with lines title f.' k'
  }
}
unset multiplot
