# fig5.png, drawn by `antcd bench paper`. Redraw with:
#   gnuplot -e "set terminal pngcairo size 1100,620 enhanced font 'DejaVu Sans,10'; set output 'fig5.png'" fig5.gp
$m0 << EOD
9.51944 0.444171 0.512903
9.59454 0.908046 0.407444
9.76686 1 0.375186
10.0717 1 0.375186
11.4399 1 0.375186
16.9071 1 0.375186
38.9154 1 0.375186
EOD
$m1 << EOD
9.14394 1 0.376923
9.17454 1 0.375434
9.2429 1 0.375186
9.58131 1 0.375186
10.6516 1 0.375186
15.3693 1 0.375186
33.9169 1 0.375186
EOD
$m2 << EOD
9.20355 1 0.375931
9.20608 1 0.375186
9.33203 1 0.375186
9.89928 1 0.375186
12.1595 1 0.375186
21.2178 1 0.375186
57.686 1 0.375186
EOD
$m3 << EOD
0.0584447 1 1
EOD
set multiplot layout 1,2 title 'Figure 5: detection against time, MACO, PSO, GA and exact'
set logscale x
set grid
set xlabel 'mean time per candidate pair (ms, log scale)'
set yrange [0:1.05]
set key bottom right
set title 'recall: colliding pairs detected'
set ylabel 'recall'
plot $m0 using 1:2 with linespoints lw 2 pt 7 lc rgb '#1f77b4' title 'maco', \
     $m1 using 1:2 with linespoints lw 2 pt 7 lc rgb '#d62728' title 'pso', \
     $m2 using 1:2 with linespoints lw 2 pt 7 lc rgb '#2ca02c' title 'ga', \
     $m3 using 1:2 with points pt 7 ps 2 lc rgb '#ff7f0e' title 'exact'
set title 'accuracy: candidate pairs classified as exact does'
set ylabel 'accuracy'
plot $m0 using 1:3 with linespoints lw 2 pt 7 lc rgb '#1f77b4' title 'maco', \
     $m1 using 1:3 with linespoints lw 2 pt 7 lc rgb '#d62728' title 'pso', \
     $m2 using 1:3 with linespoints lw 2 pt 7 lc rgb '#2ca02c' title 'ga', \
     $m3 using 1:3 with points pt 7 ps 2 lc rgb '#ff7f0e' title 'exact', \
     0.85 with lines dt 3 lw 1.5 lc rgb '#1f77b4' title 'paper maco 0.85', \
     0.8 with lines dt 3 lw 1.5 lc rgb '#d62728' title 'paper pso 0.8'
unset multiplot
