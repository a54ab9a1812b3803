# The suite's plots (run by bench/run.sh): the quality frontier (error against triangle count for
# every contender), how cost grows (retrieval time against output size per terrain size, node
# erase time against input size) and the flight's per-frame update time against the nodes it
# changed and against the TIN size. Reads the series bench_suite and bench_fly wrote into `tmp`,
# writes PNGs into `out`. usage: gnuplot -e "tmp='DIR'; out='DIR'" bench/plot.gp
set terminal pngcairo size 900,560 font ",10" noenhanced
set grid
# Twelve distinct colours, so no two contenders share one (gnuplot cycles through eight).
colours = '#1f77b4 #d62728 #2ca02c #ff7f0e #9467bd #8c564b #e377c2 #7f7f7f #bcbd22 #17becf #000000 #aec7e8'
do for [i=1:12] { set linetype i linecolor rgb word(colours, i) linewidth 1.5 pointtype i }
set linetype cycle 12
set key outside right top
set logscale xy

frontier = system('cat '.tmp.'/frontier_input.txt')
set output out.'/frontier.png'
set title 'Quality frontier: '.frontier.', low oblique view'
set xlabel 'output triangles'
set ylabel 'max screen-space error (px, exhaustive over the DEM)'
stats tmp.'/frontier.dat' using 1 nooutput # one column: the title lines are no data
plot for [i=0:STATS_blocks-1] tmp.'/frontier.dat' index i using 1:2 with linespoints \
     pointsize 0.8 title columnheader(1)

set output out.'/scaling.png'
set multiplot layout 1,2 title 'Cost against size'
set key inside left top
set title 'retrieval (τ = 0.5 … 4 px, low oblique view)'
set xlabel 'output triangles'
set ylabel 'CPU ms per view'
stats tmp.'/scaling_retrieve.dat' using 1 nooutput
plot for [i=0:STATS_blocks-1] tmp.'/scaling_retrieve.dat' index i using 1:2 with linespoints \
     title columnheader(1)
set title 'node erase of the whole grid TIN (τ = 1 px)'
set xlabel 'input triangles'
set ylabel 'CPU ms'
plot tmp.'/scaling_erase.dat' index 0 using 1:2 with linespoints title columnheader(1)
unset multiplot

set output out.'/flight.png'
set multiplot layout 1,2 title 'Flight: Refiner::update per frame (CPU ms), one point per frame'
unset logscale
set yrange [0:*]
set format x '%.1s%c'
set key inside right bottom
set title 'against the nodes the frame changed'
set xlabel 'nodes changed (erased + recovered)'
set ylabel 'update CPU ms'
stats tmp.'/flight.dat' using 1 nooutput # one column: the title lines are no data
plot for [i=0:STATS_blocks-1] tmp.'/flight.dat' index i using 1:3 with points pointsize 0.8 \
     title columnheader(1)
set title 'against the TIN size'
set xlabel 'live TIN nodes'
plot for [i=0:STATS_blocks-1] tmp.'/flight.dat' index i using 2:3 with points pointsize 0.8 \
     title columnheader(1)
unset multiplot
