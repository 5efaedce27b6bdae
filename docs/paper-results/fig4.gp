# fig4.png, drawn by `antcd bench paper`. Redraw with:
#   gnuplot -e "set terminal pngcairo size 1100,620 enhanced font 'DejaVu Sans,10'; set output 'fig4.png'" fig4.gp
$m0 << EOD
0.0117011 1 0.993548
EOD
$m1 << EOD
9.19656 0.489327 0.511663
9.26397 0.917898 0.400993
9.28768 1 0.375186
9.40099 1 0.375186
9.93328 1 0.375186
12.1044 1 0.375186
21.0734 1 0.375186
EOD
$m2 << EOD
9.51944 0.444171 0.512903
9.59454 0.908046 0.407444
9.76686 1 0.375186
10.0717 1 0.375186
11.4399 1 0.375186
16.9071 1 0.375186
38.9154 1 0.375186
EOD
set multiplot layout 1,2 title 'Figure 4: detection against time, Sphere-OBB, ACO and MACO'
set logscale x
set grid
set xlabel 'mean time per candidate pair (ms, log scale)'
set yrange [0:1.05]
set key bottom right
set title 'recall: colliding pairs detected'
set ylabel 'recall'
plot $m0 using 1:2 with points pt 7 ps 2 lc rgb '#1f77b4' title 'sphere-obb', \
     $m1 using 1:2 with linespoints lw 2 pt 7 lc rgb '#d62728' title 'aco', \
     $m2 using 1:2 with linespoints lw 2 pt 7 lc rgb '#2ca02c' title 'maco'
set title 'accuracy: candidate pairs classified as exact does'
set ylabel 'accuracy'
plot $m0 using 1:3 with points pt 7 ps 2 lc rgb '#1f77b4' title 'sphere-obb', \
     $m1 using 1:3 with linespoints lw 2 pt 7 lc rgb '#d62728' title 'aco', \
     $m2 using 1:3 with linespoints lw 2 pt 7 lc rgb '#2ca02c' title 'maco', \
     0.65 with lines dt 3 lw 1.5 lc rgb '#1f77b4' title 'paper sphere-obb 0.65', \
     0.8 with lines dt 3 lw 1.5 lc rgb '#d62728' title 'paper aco 0.8', \
     0.85 with lines dt 3 lw 1.5 lc rgb '#2ca02c' title 'paper maco 0.85'
unset multiplot
