# Fig. 6 of Shi & Dimitrakopoulos (2017): peak deck rotation against the transverse PGA.
# Reads `data` (fig6-peak-rotation.csv); set by paper-figures/fig6.cpp.
set title 'Fig. 6: peak deck rotation against the transverse PGA (runs 1-7, RSN 988, Moreau-Jean)'
set xlabel 'transverse PGA of the input [g]'
set ylabel 'peak |theta_d| [rad]'
set key top left
plot data using 'pga_transverse_g':'peak_theta_pounding' with linespoints pt 7 title 'with pounding, mu = 0.5', \
     data using 'pga_transverse_g':'peak_theta_mu0' with linespoints pt 6 dt 3 title 'with pounding, mu = 0', \
     data using 'pga_transverse_g':'peak_theta_no_pounding' with linespoints pt 5 dt 2 title 'without pounding (gaps never close)'
