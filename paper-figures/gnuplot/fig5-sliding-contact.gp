# Fig. 5 of Shi & Dimitrakopoulos (2017): the deck at the start of the longest sliding contact
# of excitation 5, with the contact forces. Reads `data` (fig5-sliding-contact.csv: kind 0
# deck outline, 1 seat faces, 2 normal force, 3 tangential force; x, y, dx, dy [m], forces at
# 1 m per 200 kN), `contact` (1-based), `slide_start`, `slide_end`, `t` [s], `lambda_n`,
# `lambda_t` [kN], `omega` [rad/s] and the contact point `px`, `py` [m]; set by
# paper-figures/fig5.cpp.
set multiplot layout 2,1 title sprintf('Fig. 5: excitation 5 at t = %.4f s, start of the longest sliding contact (contact %d, %.4g - %.4g s): lambda_N = %.1f kN, lambda_T = %.1f kN, omega = %.2e rad/s', t, contact, slide_start, slide_end, lambda_n, lambda_t, omega)
set title 'plan (y exaggerated); forces at 1 m per 200 kN'
set xlabel 'x [m]'
set ylabel 'y [m]'
set key outside right
plan = "plot data using (column('kind') == 0 ? column('x') : 1/0):'y' with lines lw 2 title 'deck', \
  data using (column('kind') == 1 ? column('x') : 1/0):'y':'dx':'dy' with vectors nohead lw 3 lc rgb 'gray30' title 'seat faces', \
  data using (column('kind') == 2 ? column('x') : 1/0):'y':'dx':'dy' with vectors lw 2 lc rgb 'red' title 'lambda_N n', \
  data using (column('kind') == 3 ? column('x') : 1/0):'y':'dx':'dy' with vectors lw 2 lc rgb 'blue' title 'lambda_T t'"
eval plan
set title sprintf('close-up of contact %d (equal axes)', contact)
set size ratio -1
set xrange [px - 1.2:px + 1.2]
set yrange [py - 0.8:py + 0.8]
eval plan
unset multiplot
