# Plots the paper's figures from the runs of make-figures.sh. Variables: runs, out, contact
# (the contact of the first pounding), t_first (its time [s]).
set terminal pngcairo size 1200,800 font ',10'
set datafile separator ','
set datafile columnheaders
set grid
set key top right
gcol = sprintf('gN%d', contact)
lcol = sprintf('lambdaN%d', contact)
mj = runs.'/exc5-moreau/history.csv'
ed = runs.'/exc5-event/history.csv'

# Fig. 3
set output out.'/fig3-response.png'
set multiplot layout 3,2 title 'Fig. 3: response under excitation 5 (nonsmooth: Moreau-Jean h = 1e-4 and event-driven)'
set xlabel 't [s]'
set ylabel 'x_d [m]'
plot mj using (column('t')):(column('x')) with lines title 'Moreau-Jean', \
     ed using (column('t')):(column('x')) with lines dashtype 2 title 'event-driven'
set ylabel 'g_{N1} [m]'
plot mj using (column('t')):(column('gN1')) with lines notitle
set ylabel 'y_d [m]'
plot mj using (column('t')):(column('y')) with lines title 'Moreau-Jean', \
     ed using (column('t')):(column('y')) with lines dashtype 2 title 'event-driven'
set ylabel 'g_{N2} [m]'
plot mj using (column('t')):(column('gN2')) with lines notitle
set ylabel 'theta_d [rad]'
plot mj using (column('t')):(column('theta')) with lines title 'Moreau-Jean', \
     ed using (column('t')):(column('theta')) with lines dashtype 2 title 'event-driven'
set ylabel 'g_{N3}, g_{N4} [m]'
plot mj using (column('t')):(column('gN3')) with lines title 'g_{N3}', \
     mj using (column('t')):(column('gN4')) with lines title 'g_{N4}'
unset multiplot

# Fig. 4
set terminal pngcairo size 1200,500 font ',10'
set output out.'/fig4-omega.png'
set title 'Fig. 4: angular velocity of the deck under excitation 5'
set ylabel 'omega_d [rad/s]'
plot mj using (column('t')):(column('omega')) with lines title 'Moreau-Jean', \
     ed using (column('t')):(column('omega')) with lines dashtype 2 title 'event-driven'

# Fig. 6
set datafile separator whitespace
set datafile separator whitespace
set output out.'/fig6-peak-rotation.png'
set title 'Fig. 6: peak deck rotation against the target transverse PGA'
set xlabel 'target transverse PGA [g]'
set ylabel 'peak |theta_d| [rad]'
set key top left
plot out.'/fig6.dat' using 1:2 with linespoints pt 7 title 'with deck-abutment pounding', \
     out.'/fig6.dat' using 1:3 with linespoints pt 5 dashtype 2 title 'without pounding'

# Fig. 7
set datafile separator ','
set datafile columnheaders
set terminal pngcairo size 1200,500 font ',10'
set output out.'/fig7-compliance.png'
set title 'Fig. 7: rotation under excitation 5, nonsmooth against compliance (gap element)'
set xlabel 't [s]'
set ylabel 'theta_d [rad]'
set key top right
plot mj using (column('t')):(column('theta')) with lines lw 2 lc rgb 'black' title 'nonsmooth', \
     for [f in '1e-4 1e-2 1e0 1e2'] runs.'/exc5-k'.f.'/history.csv' \
       using (column('t')):(column('theta')) with lines title 'compliance '.f.' k'

# Fig. 8
set terminal pngcairo size 1200,500 font ',10'
set output out.'/fig8-first-pounding.png'
set multiplot layout 1,2 title sprintf('Fig. 8: first pounding (contact %d, t = %.3f s)', contact, t_first)
set title 'gap at the first pounding'
set xlabel 't [s]'
set ylabel sprintf('g_{N%d} [m]', contact)
set xrange [t_first - 0.02:t_first + 0.1]
plot for [f in '1e-4 1e-2 1e0 1e2'] runs.'/exc5-k'.f.'-first/history.csv' \
       using (column('t')):(column(gcol)) with lines title f.' k', \
     mj using (column('t')):(column(gcol)) with lines lw 2 lc rgb 'black' title 'nonsmooth'
set autoscale x
set title 'force-penetration loop of the gap element'
set xlabel 'penetration -g_N [m]'
set ylabel 'lambda_N [kN]'
plot for [f in '1e0 1e2'] runs.'/exc5-k'.f.'-first/history.csv' \
       using (column(gcol) < 0 ? -column(gcol) : 1/0):(column(lcol)) with lines title f.' k'
unset multiplot
