# fig3.png, drawn by `antcd bench paper`. Redraw with:
#   gnuplot -e "set terminal pngcairo size 1100,620 enhanced font 'DejaVu Sans,10'; set output 'fig3.png'" fig3.gp
$f1000 << EOD
10 0.156482
20 0.28871
30 0.396402
40 0.48543
50 0.527269
60 0.63412
70 0.658145
80 0.71549
90 0.771886
100 0.803389
EOD
$f2000 << EOD
10 0.0649483
20 0.145156
30 0.178983
40 0.254041
50 0.311527
60 0.350148
70 0.388023
80 0.448332
90 0.46096
100 0.502197
EOD
$f3000 << EOD
10 0.0620039
20 0.108406
30 0.143988
40 0.198148
50 0.252125
60 0.284356
70 0.322388
80 0.349446
90 0.409894
100 0.426923
EOD
$f4000 << EOD
10 0.0482444
20 0.0988852
30 0.142178
40 0.188515
50 0.213732
60 0.266523
70 0.292801
80 0.317159
90 0.357103
100 0.386226
EOD
$f5000 << EOD
10 0.0441216
20 0.0895281
30 0.128174
40 0.174785
50 0.212261
60 0.241551
70 0.283237
80 0.326115
90 0.345765
100 0.385565
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
