# The two-frame bridge (scenes/bridge-two-frame.toml, excitation 5, Moreau–Jean h = 2.5e-5 s):
# the rotations of both frames and the normal gaps of the hinge's two corner contacts
# (contacts 3 and 4, docs/outputs.md) against time. Input: two-frame-hinge.csv, the columns
# t, theta1, theta2, gN3, gN4 of the run's history.csv. Made by (from the repository root):
#   build/app/nsbridge run scenes/bridge-two-frame.toml --out out/bridge-two-frame
#   awk -F, -v OFS=, 'NR == 1 {for (i = 1; i <= NF; ++i) c[$i] = i; print "t,theta1,theta2,gN3,gN4"; next}
#     {printf "%.6g,%.6g,%.6g,%.6g,%.6g\n", $c["t"], $c["theta1"], $c["theta2"], $c["gN3"], $c["gN4"]}' \
#     out/bridge-two-frame/history.csv > docs/figures/two-frame-hinge.csv
#   cd docs/figures && gnuplot two-frame-hinge.gp
set datafile separator ","
set terminal pngcairo size 1000,700 font ",11"
set output "two-frame-hinge.png"
set multiplot layout 2,1 title "Two-frame bridge, excitation 5: frame rotations and hinge gaps"
set key top right
set grid
set xrange [0:40]
set ylabel "rotation θ [mrad]"
plot "two-frame-hinge.csv" using 1:($2*1000) skip 1 with lines lw 1 title "frame 1 (θ1)", \
     "" using 1:($3*1000) skip 1 with lines lw 1 title "frame 2 (θ2)"
set xlabel "t [s]"
set ylabel "hinge gap g_N [mm]"
plot "two-frame-hinge.csv" using 1:($4*1000) skip 1 with lines lw 1 title "corner y = +W/2 (gN3)", \
     "" using 1:($5*1000) skip 1 with lines lw 1 title "corner y = −W/2 (gN4)"
unset multiplot
