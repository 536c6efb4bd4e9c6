# Fig. 3 of Shi & Dimitrakopoulos (2017): the deck's response and gaps under excitation 5.
# Reads `data` (fig3-response.csv); set by nsbridge figures (paper-figures/fig3.cpp).
set multiplot layout 3,2 title 'Fig. 3: response under excitation 5 (Moreau-Jean h = 1e-4 s and event-driven)'
set xlabel 't [s]'
set ylabel 'x_d [m]'
plot data using 't':'x' with lines title 'Moreau-Jean', data using 't':'x_event' with lines dt 2 title 'event-driven'
set ylabel 'g_{N1} [m]'
plot data using 't':'gN1' with lines notitle
set ylabel 'y_d [m]'
plot data using 't':'y' with lines title 'Moreau-Jean', data using 't':'y_event' with lines dt 2 title 'event-driven'
set ylabel 'g_{N2} [m]'
plot data using 't':'gN2' with lines notitle
set ylabel 'theta_d [rad]'
plot data using 't':'theta' with lines title 'Moreau-Jean', data using 't':'theta_event' with lines dt 2 title 'event-driven'
set ylabel 'g_{N3}, g_{N4} [m]'
plot data using 't':'gN3' with lines title 'g_{N3}', data using 't':'gN4' with lines title 'g_{N4}'
unset multiplot
