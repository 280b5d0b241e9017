# Charts of scripts/speed_accuracy.sh: error against wall time, log-log. Call with -e "out='DIR'".
set terminal pngcairo size 900,600 font ",11"
set datafile separator ","
set logscale xy
set grid
set key outside right
set output out.'/incline.png'
set title "Seed incline (phi 25, i 5): error against cost"
set xlabel "wall time of a 2 s run (s)"
set ylabel "worst relative displacement error"
plot out.'/incline.csv' using (strcol(1) eq "implicit" ? $4 : 1/0):5 every ::1 with points pt 7 ps 1.5 title "implicit (time.step 0.5-10 ms)", \
     '' using ((strcol(1) eq "substep" && $3 == 1) ? $4 : 1/0):5 every ::1 with points pt 5 title "substep, 1 substep", \
     '' using ((strcol(1) eq "substep" && $3 == 4) ? $4 : 1/0):5 every ::1 with points pt 9 title "substep, 4 substeps", \
     '' using ((strcol(1) eq "substep" && $3 == 16) ? $4 : 1/0):5 every ::1 with points pt 13 title "substep, 16 substeps"
set output out.'/vajont.png'
set title "Vajont degraded, point 1 runout: change from the finest substep run"
set xlabel "wall time of a 45 s run (s)"
set ylabel "relative change of point-1 runout"
plot out.'/vajont.csv' using ($1 == 34.3 && strcol(2) eq "substep" ? $5 : 1/0):($8 > 0 ? $8 : 1e-4) every ::1 with points pt 7 title "section I, substep", \
     '' using ($1 == 34.3 && strcol(2) eq "implicit" ? $5 : 1/0):($8 > 0 ? $8 : 1e-4) every ::1 with points pt 9 ps 2 title "section I, implicit", \
     '' using ($1 == 23.1 && strcol(2) eq "substep" ? $5 : 1/0):($8 > 0 ? $8 : 1e-4) every ::1 with points pt 5 title "section II, substep", \
     '' using ($1 == 23.1 && strcol(2) eq "implicit" ? $5 : 1/0):($8 > 0 ? $8 : 1e-4) every ::1 with points pt 13 ps 2 title "section II, implicit", \
     '' using ($1 == 16 && strcol(2) eq "substep" ? $5 : 1/0):($8 > 0 ? $8 : 1e-4) every ::1 with points pt 11 title "section III, substep"
