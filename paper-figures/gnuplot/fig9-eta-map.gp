# The eta map: the contours |eta| = 1 of the derived rotation criterion (docs/criterion.md) in
# the plane of skew angle and W/L, with the simulated free-deck impacts. Reads `data`
# (fig9-eta-map.csv: kind 0 contours, 1 simulated points, 2 the benchmark deck), `agree` and
# `total` (points as predicted, of all); set by paper-figures/fig9.cpp.
set title sprintf('eta map: |eta| = 1 (derived criterion) for several mu; points: free-deck impacts at mu = 0.5 (%d of %d as predicted)', agree, total)
set xlabel 'skew angle alpha [deg]'
set ylabel 'W / L [-]'
set key outside right
set yrange [0:1]
plot for [m in '0 0.1 0.3 0.5 0.8'] data using (column('kind') == 0 && abs(column('mu') - m) < 1e-9 ? column('skew_deg') : 1/0):'w_over_l' with lines title '|eta| = 1, mu = '.m, \
  data using (column('kind') == 1 && column('rotating') == 1 ? column('skew_deg') : 1/0):'w_over_l' with points pt 7 ps 1.5 lc rgb 'red' title 'simulated: rotates', \
  data using (column('kind') == 1 && column('rotating') == 0 ? column('skew_deg') : 1/0):'w_over_l' with points pt 6 ps 1.5 lc rgb 'blue' title 'simulated: does not rotate', \
  data using (column('kind') == 2 ? column('skew_deg') : 1/0):'w_over_l' with points pt 9 ps 2 lc rgb 'black' title 'benchmark deck'
