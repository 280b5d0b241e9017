# The block-size study (seed Figs. 15-16): point 1's maximum lateral distance and peak
# lateral velocity against block count, degraded state, sections I-X, with Hendron &
# Patton's field estimates as bands. Input: the sections.csv of scripts/vajont_sections.sh.
#   gnuplot -e "csv='results/vajont-sections/sections.csv'; out='docs/figures/vajont_block_size.png'" scripts/vajont_block_size.gp
if (!exists("csv")) csv = 'results/vajont-sections/sections.csv'
if (!exists("out")) out = 'docs/figures/vajont_block_size.png'
set datafile separator ','
set terminal pngcairo size 1400,560 font ',12'
set output out
set multiplot layout 1,2 title 'Vajont stand-in, point 1, 45 s, reference and degraded (25 %) states: ddafit substep solver'
set logscale x
set xrange [150:8000]
set xlabel 'free blocks (sections I-X)'
set grid
set key bottom right
# Columns: 1 section, 2 state, 3 blocks, 4 solver, 5 status, 6 simulated_s, 7 lateral, 8 total, 9 peak v.
ok(state, c) = (strcol(2) eq state && strcol(5) eq 'completed') ? column(c) : NaN
set ylabel 'maximum lateral distance (m)'
set yrange [0:600]
set object 1 rect from graph 0, first 400 to graph 1, first 500 fc rgb '#cfe3f5' fs solid 0.6 noborder behind
set label 1 'Hendron and Patton 400-500 m' at graph 0.03, first 520
plot csv using 3:(ok('degraded', 7)) skip 1 with points pt 7 ps 1.5 lw 2 lc rgb '#b2182b' title 'degraded', \
     csv using 3:(ok('reference', 7)) skip 1 with points pt 5 ps 1.5 lw 2 lc rgb '#2166ac' title 'reference'
unset object 1
unset label 1
set ylabel 'peak lateral velocity (m/s)'
set yrange [0:30]
set object 2 rect from graph 0, first 20 to graph 1, first 25 fc rgb '#cfe3f5' fs solid 0.6 noborder behind
set label 2 'Hendron and Patton 20-25 m/s' at graph 0.03, first 26
plot csv using 3:(ok('degraded', 9)) skip 1 with points pt 7 ps 1.5 lw 2 lc rgb '#b2182b' title 'degraded', \
     csv using 3:(ok('reference', 9)) skip 1 with points pt 5 ps 1.5 lw 2 lc rgb '#2166ac' title 'reference'
unset multiplot
