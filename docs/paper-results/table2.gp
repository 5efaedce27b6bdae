# table2.png, drawn by `antcd bench paper`. Redraw with:
#   gnuplot -e "set terminal pngcairo size 1100,620 enhanced font 'DejaVu Sans,10'; set output 'table2.png'" table2.gp
$ours1000 << EOD
20 0.248016
40 0.446429
60 0.644841
80 0.843254
EOD
$paper1000 << EOD
20 7.3
40 15.2
60 22.1
80 30.2
EOD
$ours2000 << EOD
20 0.744048
40 1.43849
60 2.13294
80 2.82738
EOD
$paper2000 << EOD
20 10
40 21.2
60 34.3
80 45.6
EOD
$ours3000 << EOD
20 1.6369
40 3.1746
60 4.7123
80 6.25
EOD
$paper3000 << EOD
20 13.3
40 27.8
60 39.6
80 51.2
EOD
$ours4000 << EOD
20 2.82738
40 5.60516
60 8.38294
80 11.1607
EOD
$paper4000 << EOD
20 16.2
40 35.9
60 55.1
80 62.7
EOD
$ours5000 << EOD
20 4.46429
40 8.87897
60 13.3433
80 17.7579
EOD
$paper5000 << EOD
20 20
40 44.1
60 65.4
80 85.3
EOD
set key outside right
set grid
set xlabel 'detection rate (% of colliding feature pairs found)'
set xrange [15:85]
set xtics 20,20,80
set title 'Table 2: A/B at each detection rate (solid: ours, dashed: paper)'
set ylabel 'A/B (%)'
set yrange [0:100]
plot $ours1000 using 1:2 with linespoints lw 2 pt 7 lc rgb '#1f77b4' title 'ours 1000^2', $paper1000 using 1:2 with linespoints dt 2 pt 6 lc rgb '#1f77b4' title 'paper 1000^2', \
     $ours2000 using 1:2 with linespoints lw 2 pt 7 lc rgb '#d62728' title 'ours 2000^2', $paper2000 using 1:2 with linespoints dt 2 pt 6 lc rgb '#d62728' title 'paper 2000^2', \
     $ours3000 using 1:2 with linespoints lw 2 pt 7 lc rgb '#2ca02c' title 'ours 3000^2', $paper3000 using 1:2 with linespoints dt 2 pt 6 lc rgb '#2ca02c' title 'paper 3000^2', \
     $ours4000 using 1:2 with linespoints lw 2 pt 7 lc rgb '#ff7f0e' title 'ours 4000^2', $paper4000 using 1:2 with linespoints dt 2 pt 6 lc rgb '#ff7f0e' title 'paper 4000^2', \
     $ours5000 using 1:2 with linespoints lw 2 pt 7 lc rgb '#9467bd' title 'ours 5000^2', $paper5000 using 1:2 with linespoints dt 2 pt 6 lc rgb '#9467bd' title 'paper 5000^2'
