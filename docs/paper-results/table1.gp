# table1.png, drawn by `antcd bench paper`. Redraw with:
#   gnuplot -e "set terminal pngcairo size 1100,620 enhanced font 'DejaVu Sans,10'; set output 'table1.png'" table1.gp
$ours1000 << EOD
20 0.445308
40 0.801492
60 1.44196
80 2.40848
EOD
$paper1000 << EOD
20 5.1
40 8.4
60 10.6
80 13.4
EOD
$ours2000 << EOD
20 1.098
40 2.13689
60 4.33983
80 7.46639
EOD
$paper2000 << EOD
20 7
40 11.1
60 12.9
80 16.4
EOD
$ours3000 << EOD
20 1.89379
40 4.39494
60 6.74741
80 11.5207
EOD
$paper3000 << EOD
20 9.2
40 13.4
60 16.1
80 20.8
EOD
$ours4000 << EOD
20 3.12191
40 5.92697
60 10.9311
80 19.5278
EOD
$paper4000 << EOD
20 12.3
40 15.6
60 18.5
80 22
EOD
$ours5000 << EOD
20 4.70088
40 9.24149
60 15.9201
80 30.1316
EOD
$paper5000 << EOD
20 14.1
40 17.2
60 20.5
80 27.3
EOD
set key outside right
set grid
set xlabel 'detection rate (% of colliding feature pairs found)'
set xrange [15:85]
set xtics 20,20,80
set title 'Table 1: time for MACO to reach each detection rate (solid: ours, dashed: paper)'
set ylabel 'time (ms)'
set logscale y
plot $ours1000 using 1:2 with linespoints lw 2 pt 7 lc rgb '#1f77b4' title 'ours 1000^2', $paper1000 using 1:2 with linespoints dt 2 pt 6 lc rgb '#1f77b4' title 'paper 1000^2', \
     $ours2000 using 1:2 with linespoints lw 2 pt 7 lc rgb '#d62728' title 'ours 2000^2', $paper2000 using 1:2 with linespoints dt 2 pt 6 lc rgb '#d62728' title 'paper 2000^2', \
     $ours3000 using 1:2 with linespoints lw 2 pt 7 lc rgb '#2ca02c' title 'ours 3000^2', $paper3000 using 1:2 with linespoints dt 2 pt 6 lc rgb '#2ca02c' title 'paper 3000^2', \
     $ours4000 using 1:2 with linespoints lw 2 pt 7 lc rgb '#ff7f0e' title 'ours 4000^2', $paper4000 using 1:2 with linespoints dt 2 pt 6 lc rgb '#ff7f0e' title 'paper 4000^2', \
     $ours5000 using 1:2 with linespoints lw 2 pt 7 lc rgb '#9467bd' title 'ours 5000^2', $paper5000 using 1:2 with linespoints dt 2 pt 6 lc rgb '#9467bd' title 'paper 5000^2'
