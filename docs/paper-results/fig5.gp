# fig5.png, drawn by `antcd bench paper`. Redraw with:
#   gnuplot -e "set terminal pngcairo size 1100,620 enhanced font 'DejaVu Sans,10'; set output 'fig5.png'" fig5.gp
$m0 << EOD
0.0328059 0.990969 0.99727
0.0260406 1 1
0.0272176 1 1
0.0344415 1 1
0.0612311 1 1
0.172633 1 1
0.631678 1 1
EOD
$m1 << EOD
0.0231348 1 0.993548
0.0224462 1 0.993548
0.0225581 1 0.993548
0.0223751 1 0.993548
0.0226047 1 0.993548
0.0226667 1 0.993548
0.0224381 1 0.993548
EOD
$m2 << EOD
0.0264362 0.992611 0.997767
0.0251622 0.999179 0.999752
0.02729 1 1
0.0358273 1 1
0.0696985 1 1
0.205938 1 1
0.754182 1 1
EOD
$m3 << EOD
0.0256518 0.997537 0.999256
0.0253744 1 1
0.029541 1 1
0.046483 1 1
0.112633 1 1
0.375083 1 1
1.42947 1 1
EOD
$m4 << EOD
0.00937168 0.995895 0.996774
EOD
$m5 << EOD
0.087006 0.992611 0.996526
EOD
$m6 << EOD
0.00277417 1 1
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
