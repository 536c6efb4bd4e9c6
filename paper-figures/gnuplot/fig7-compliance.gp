# Fig. 7 of Shi & Dimitrakopoulos (2017): the rotation under excitation 5, nonsmooth against
# the compliance method. Reads `data` (fig7-compliance.csv, a column theta_k<f> per factor) and
# `factors`, the stiffness factors as the column names spell them ('0.0001 0.01 100');
# set by paper-figures/fig7.cpp.
set title 'Fig. 7: rotation under excitation 5, nonsmooth (Moreau-Jean) against the compliance method at c k'
set xlabel 't [s]'
set ylabel 'theta_d [rad]'
plot data using 't':'theta_nonsmooth' with lines lw 2 lc rgb 'black' title 'nonsmooth', \
     for [f in factors] data using 't':'theta_k'.f with lines title 'compliance '.f.' k'
