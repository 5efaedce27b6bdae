# fig4.png, drawn by `antcd bench paper`. Redraw with:
#   gnuplot -e "set terminal pngcairo size 1100,620 enhanced font 'DejaVu Sans,10'; set output 'fig4.png'" fig4.gp
$m0 << EOD
0.00115861 1 0.993548
EOD
$m1 << EOD
0.0279441 0.995895 0.998759
0.0254346 1 1
0.0268864 1 1
0.0344995 1 1
0.0645913 1 1
0.182941 1 1
0.649512 1 1
EOD
$m2 << EOD
0.0328059 0.990969 0.99727
0.0260406 1 1
0.0272176 1 1
0.0344415 1 1
0.0612311 1 1
0.172633 1 1
0.631678 1 1
EOD
$m3 << EOD
0.0224413 1 0.993548
0.0223545 1 0.993548
0.0225671 1 0.993548
0.0223763 1 0.993548
0.0225225 1 0.993548
0.0225928 1 0.993548
0.0222814 1 0.993548
EOD
$m4 << EOD
0.0231348 1 0.993548
0.0224462 1 0.993548
0.0225581 1 0.993548
0.0223751 1 0.993548
0.0226047 1 0.993548
0.0226667 1 0.993548
0.0224381 1 0.993548
EOD
$m5 << EOD
0.00277417 1 1
EOD
set multiplot layout 1,2 title 'Figure 4: detection against time, Sphere-OBB, ACO and MACO'
set logscale x
set grid
set xlabel 'mean time per candidate pair (ms, log scale)'
set yrange [0:1.05]
set key bottom right
set title 'recall: colliding object pairs detected'
set ylabel 'recall'
plot $m0 using 1:2 with points pt 7 ps 2 lc rgb '#1f77b4' title 'sphere-obb', \
     $m1 using 1:2 with linespoints lw 2 pt 7 lc rgb '#d62728' title 'aco', \
     $m2 using 1:2 with linespoints lw 2 pt 7 lc rgb '#2ca02c' title 'maco', \
     $m3 using 1:2 with linespoints lw 2 dt 2 pt 6 lc rgb '#d62728' title 'aco (paper centroid)', \
     $m4 using 1:2 with linespoints lw 2 dt 2 pt 6 lc rgb '#2ca02c' title 'maco (paper centroid)', \
     $m5 using 1:2 with points pt 7 ps 2 lc rgb '#8c564b' title 'exact'
set title 'accuracy: candidate pairs decided as exact does (vs the paper)'
set ylabel 'accuracy'
plot $m0 using 1:3 with points pt 7 ps 2 lc rgb '#1f77b4' title 'sphere-obb', \
     $m1 using 1:3 with linespoints lw 2 pt 7 lc rgb '#d62728' title 'aco', \
     $m2 using 1:3 with linespoints lw 2 pt 7 lc rgb '#2ca02c' title 'maco', \
     $m3 using 1:3 with linespoints lw 2 dt 2 pt 6 lc rgb '#d62728' title 'aco (paper centroid)', \
     $m4 using 1:3 with linespoints lw 2 dt 2 pt 6 lc rgb '#2ca02c' title 'maco (paper centroid)', \
     $m5 using 1:3 with points pt 7 ps 2 lc rgb '#8c564b' title 'exact', \
     0.65 with lines dt 3 lw 1.5 lc rgb '#1f77b4' title 'paper sphere-obb 0.65', \
     0.8 with lines dt 3 lw 1.5 lc rgb '#d62728' title 'paper aco 0.8', \
     0.85 with lines dt 3 lw 1.5 lc rgb '#2ca02c' title 'paper maco 0.85'
unset multiplot
