# fig3.png, drawn by `antcd bench paper`. Redraw with:
#   gnuplot -e "set terminal pngcairo size 1100,620 enhanced font 'DejaVu Sans,10'; set output 'fig3.png'" fig3.gp
$f1000 << EOD
10 0.861538
20 0.947436
30 0.966667
40 1
50 1
60 1
70 1
80 1
90 1
100 1
EOD
$f2000 << EOD
10 0.49186
20 0.759902
30 0.870815
40 0.87281
50 0.928809
60 0.97973
70 0.97101
80 0.968764
90 0.992857
100 0.98491
EOD
$f3000 << EOD
10 0.32824
20 0.477019
30 0.597803
40 0.806896
50 0.855104
60 0.839756
70 0.899873
80 0.942712
90 0.953953
100 0.929663
EOD
$f4000 << EOD
10 0.264481
20 0.425379
30 0.543287
40 0.671743
50 0.704897
60 0.719494
70 0.787262
80 0.851347
90 0.859663
100 0.911384
EOD
$f5000 << EOD
10 0.178913
20 0.320758
30 0.437682
40 0.515707
50 0.603648
60 0.633972
70 0.728822
80 0.76678
90 0.7971
100 0.816888
EOD
set title 'Figure 3: MACO detection rate against ant colony size (N = 100 iterations)'
set xlabel 'ant colony size m'
set ylabel 'share of colliding feature pairs found'
set yrange [0:*]
set grid
set key outside right title 'feature pairs'
plot $f1000 using 1:2 with linespoints lw 2 pt 7 lc rgb '#1f77b4' title '1000^2', \
     $f2000 using 1:2 with linespoints lw 2 pt 7 lc rgb '#d62728' title '2000^2', \
     $f3000 using 1:2 with linespoints lw 2 pt 7 lc rgb '#2ca02c' title '3000^2', \
     $f4000 using 1:2 with linespoints lw 2 pt 7 lc rgb '#ff7f0e' title '4000^2', \
     $f5000 using 1:2 with linespoints lw 2 pt 7 lc rgb '#9467bd' title '5000^2'
