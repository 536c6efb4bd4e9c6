# Fig. 4 of Shi & Dimitrakopoulos (2017): the deck's angular velocity under excitation 5.
# Reads `data` (fig4-omega.csv) and the longest sliding contact of the Moreau-Jean run:
# `contact` (1-based), `slide_start` and `slide_end` [s]; set by paper-figures/fig4.cpp.
set title sprintf('Fig. 4: angular velocity of the deck under excitation 5; shaded: the longest sliding contact (contact %d, %g - %g s)', contact, slide_start, slide_end)
set xlabel 't [s]'
set ylabel 'omega_d [rad/s]'
set object 1 rect from slide_start, graph 0 to slide_end, graph 1 fc rgb '#dddddd' fs solid noborder behind
plot data using 't':'omega' with lines title 'Moreau-Jean', data using 't':'omega_event' with lines dt 2 title 'event-driven'
