# fig5.png, drawn by `antcd bench paper`. Redraw with:
#   gnuplot -e "set terminal pngcairo size 1100,620 enhanced font 'DejaVu Sans,10'; set output 'fig5.png'" fig5.gp
$m0 << EOD
0.0340804 0.993432 0.998015
0.0265176 1 1
0.0268413 1 1
0.0318296 1 1
0.0498566 1 1
0.123575 1 1
0.423035 1 1
EOD
$m1 << EOD
0.0234404 1 0.993548
0.0231384 1 0.993548
0.0229857 1 0.993548
0.0229745 1 0.993548
0.022811 1 0.993548
0.0231585 1 0.993548
0.0229304 1 0.993548
EOD
$m2 << EOD
0.0266829 0.993432 0.998015
0.0251462 1 1
0.0273156 1 1
0.036824 1 1
0.0732772 1 1
0.216785 1 1
0.795481 1 1
EOD
$m3 << EOD
0.0262271 0.997537 0.999256
0.0255235 0.999179 0.999752
0.029472 1 1
0.0472513 1 1
0.115609 1 1
0.38792 1 1
1.47648 1 1
EOD
$m4 << EOD
0.0231351 1 0.997022
EOD
$m5 << EOD
0.0999723 0.99179 0.996774
EOD
$m6 << EOD
0.00328914 1 1
EOD
set multiplot layout 1,2 title 'Figure 5: detection against time, MACO, PSO, GA, BOX-DNN, BOX-LSTM and exact'
set logscale x
set grid
set xlabel 'mean time per candidate pair (ms, log scale)'
set yrange [0:1.05]
set key bottom right
set title 'recall: colliding object pairs detected'
set ylabel 'recall'
plot $m0 using 1:2 with linespoints lw 2 pt 7 lc rgb '#1f77b4' title 'maco', \
     $m1 using 1:2 with linespoints lw 2 dt 2 pt 6 lc rgb '#1f77b4' title 'maco (paper centroid)', \
     $m2 using 1:2 with linespoints lw 2 pt 7 lc rgb '#2ca02c' title 'pso', \
     $m3 using 1:2 with linespoints lw 2 pt 7 lc rgb '#ff7f0e' title 'ga', \
     $m4 using 1:2 with points pt 7 ps 2 lc rgb '#9467bd' title 'box-dnn', \
     $m5 using 1:2 with points pt 7 ps 2 lc rgb '#8c564b' title 'box-lstm', \
     $m6 using 1:2 with points pt 7 ps 2 lc rgb '#e377c2' title 'exact'
set title 'accuracy: candidate pairs decided as exact does (vs the paper)'
set ylabel 'accuracy'
plot $m0 using 1:3 with linespoints lw 2 pt 7 lc rgb '#1f77b4' title 'maco', \
     $m1 using 1:3 with linespoints lw 2 dt 2 pt 6 lc rgb '#1f77b4' title 'maco (paper centroid)', \
     $m2 using 1:3 with linespoints lw 2 pt 7 lc rgb '#2ca02c' title 'pso', \
     $m3 using 1:3 with linespoints lw 2 pt 7 lc rgb '#ff7f0e' title 'ga', \
     $m4 using 1:3 with points pt 7 ps 2 lc rgb '#9467bd' title 'box-dnn', \
     $m5 using 1:3 with points pt 7 ps 2 lc rgb '#8c564b' title 'box-lstm', \
     $m6 using 1:3 with points pt 7 ps 2 lc rgb '#e377c2' title 'exact', \
     0.85 with lines dt 3 lw 1.5 lc rgb '#1f77b4' title 'paper maco 0.85', \
     0.8 with lines dt 3 lw 1.5 lc rgb '#2ca02c' title 'paper pso 0.8', \
     0.82 with lines dt 3 lw 1.5 lc rgb '#9467bd' title 'paper box-dnn 0.82', \
     0.76 with lines dt 3 lw 1.5 lc rgb '#8c564b' title 'paper box-lstm 0.76'
unset multiplot
