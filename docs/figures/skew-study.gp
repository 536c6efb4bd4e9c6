# Skew study (docs/skew-study.md): the full-scale bridge of scenes/bridge-full-scale-skew.toml
# with its skew from 0 to 60 degrees, event-driven, with and without its shear keys. Input:
# skew-study.csv, one row per skew angle from the sweep's results.csv (peak_theta, the smaller
# of unseating_left_margin and unseating_right_margin, residual_theta) and the frictionless
# rotation criterion eta0 = sin(2 alpha) / (2 W / L) of eq. (1) (docs/criterion.md). Made by
# (from the repository root):
#   build/app/nsbridge sweep scenes/sweeps/skew.toml --out out/skew
#   /usr/bin/python3 docs/figures/skew-study.py out/skew/results.csv > docs/figures/skew-study.csv
#   cd docs/figures && gnuplot skew-study.gp
set datafile separator ","
set terminal pngcairo size 1000,760 font ",11"
set output "skew-study.png"
set multiplot layout 2,1 title "Full-scale bridge (W/L = 0.133, μ = 0.3), RSN 988 at 0.6 g: response against the skew angle"
set key top left
set grid
set xrange [0:60]
set xtics 10
set ylabel "peak |θ| [mrad]"
set y2label "η₀ = sin 2α / (2 W/L)"
set y2range [0:4]
set y2tics 1
plot "skew-study.csv" using 1:($3*1000) skip 1 with linespoints lw 2 pt 7 title "no shear keys", \
     "" using 1:($2*1000) skip 1 with linespoints lw 2 pt 5 title "shear keys, 50 mm", \
     "" using 1:7 skip 1 axes x1y2 with lines dt 2 lc rgb "gray40" title "η₀ (right axis)", \
     1 axes x1y2 with lines dt 3 lc rgb "gray60" title "η₀ = 1"
unset y2label
unset y2tics
set xlabel "skew angle α [deg]"
set ylabel "smallest seat overlap [m]"
set yrange [0.35:0.6]
plot "skew-study.csv" using 1:5 skip 1 with linespoints lw 2 pt 7 title "no shear keys", \
     "" using 1:4 skip 1 with linespoints lw 2 pt 5 title "shear keys, 50 mm", \
     0.6 - 0.05 * cos(x * pi / 180) with lines dt 2 lc rgb "gray40" title "at rest, N − gap cos α", \
     0.6 - 0.1 * cos(x * pi / 180) with lines dt 3 lc rgb "gray40" title "other joint closed, N − 2 gap cos α"
unset multiplot
