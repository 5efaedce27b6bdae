# fig4.png, drawn by `antcd bench paper`. Redraw with:
#   gnuplot -e "set terminal pngcairo size 1100,620 enhanced font 'DejaVu Sans,10'; set output 'fig4.png'" fig4.gp
$m0 << EOD
0.00112459 1 0.993548
EOD
$m1 << EOD
0.02881 0.995895 0.998759
0.0255441 1 1
0.0265055 1 1
0.0322457 1 1
0.0526076 1 1
0.133338 1 1
0.452427 1 1
EOD
$m2 << EOD
0.0340804 0.993432 0.998015
0.0265176 1 1
0.0268413 1 1
0.0318296 1 1
0.0498566 1 1
0.123575 1 1
0.423035 1 1
EOD
$m3 << EOD
0.0229938 1 0.993548
0.0229309 1 0.993548
0.0228054 1 0.993548
0.0230202 1 0.993548
0.0228207 1 0.993548
0.0229598 1 0.993548
0.0227733 1 0.993548
EOD
$m4 << EOD
0.0234404 1 0.993548
0.0231384 1 0.993548
0.0229857 1 0.993548
0.0229745 1 0.993548
0.022811 1 0.993548
0.0231585 1 0.993548
0.0229304 1 0.993548
EOD
$m5 << EOD
0.00328914 1 1
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
