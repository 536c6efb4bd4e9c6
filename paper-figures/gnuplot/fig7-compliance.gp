# Fig. 7 of Shi & Dimitrakopoulos (2017): the rotation under excitation 5, nonsmooth against
# the compliance method, one panel per damping law of eq. (9). Reads `data`
# (fig7-compliance.csv, a column theta_k<f>_<law> per factor and law), `factors` (the stiffness
# factors as the column names spell them, '0.0001 0.01 100'), `laws` ('hertzdamp
# hunt_crossley_exact'), per law e_eff_<law> (its effective restitution) and chi_<law>, and
# `eps` (the nonsmooth runs' restitution); set by paper-figures/fig7.cpp.
set multiplot layout words(laws),1 title sprintf('Fig. 7: rotation under excitation 5, nonsmooth (Moreau-Jean, eps = %g) against the compliance method at c k', eps)
set xlabel 't [s]'
set ylabel 'theta_d [rad]'
do for [law in laws] {
  set title sprintf('damping law %s: chi = %.4g, effective restitution %.3g', law, value('chi_'.law), value('e_eff_'.law)) noenhanced
  plot data using 't':'theta_nonsmooth' with lines lw 2 lc rgb 'black' title 'nonsmooth', \
       for [f in factors] data using 't':'theta_k'.f.'_'.law with lines title 'compliance '.f.' k'
}
unset multiplot
