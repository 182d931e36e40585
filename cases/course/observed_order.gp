# Your own convergence plot and observed order, from the convergence.csv of
# a demvv mms run (exercise 8 of the course).
#
#   gnuplot -e "run='DIR'; error='stress_l2'; levels=3" cases/course/observed_order.gp
#
# Fits ln(error) = p ln(h) + c by least squares over the finest `levels`
# rows of DIR/convergence.csv (h: the column named by `abscissa`,
# cell_size_m unless set; time_step_s for a study in time), writes the
# order to DIR/own_order_ERROR.csv and draws DIR/own_order_ERROR.svg: the
# errors of every level, and the fitted line over the levels it used.
# Change it: fit other levels, add the line of the order theory expects.
if (!exists("run") || !exists("error")) {
  print "usage: gnuplot -e \"run='DIR'; error='stress_l2'; levels=3\" observed_order.gp"
  exit status 2
}
if (!exists("levels")) levels = 3
if (!exists("abscissa")) abscissa = 'cell_size_m'
data = run.'/convergence.csv'
set datafile separator ','
set datafile columnheaders

stats data using (column(abscissa)) nooutput
first = STATS_records - levels
if (first < 0) {
  print sprintf("%s holds %d levels, fewer than levels = %d", data, STATS_records, levels)
  exit status 2
}

line(x) = p * x + c
p = 1
c = 1
set fit quiet
set fit logfile '/dev/null'
fit line(x) data every ::first using (log(column(abscissa))):(log(column(error))) via p, c

set print run.'/own_order_'.error.'.csv'
print 'error,abscissa,levels,observed_order'
print sprintf('%s,%s,%d,%.6f', error, abscissa, levels, p)
unset print

set terminal svg size 760,460 noenhanced font 'Sans,12' background rgb 'white'
set output run.'/own_order_'.error.'.svg'
set title sprintf('%s against %s: observed order %.3f over the finest %d levels', error, abscissa, p, levels)
set xlabel abscissa.((abscissa eq 'time_step_s') ? ' [s]' : ' [m]')
set ylabel error.' (relative) [-]'
set logscale xy
set format xy '%g'
set grid
set key top left box opaque
stats data every ::first using (column(abscissa)) name 'FIT' nooutput
set samples 2
plot data using (column(abscissa)):(column(error)) with linespoints lw 2 pt 7 lc 1 title error, \
     [FIT_min:FIT_max] exp(c) * x**p with lines lw 2 dt 2 lc 2 title sprintf('least-squares fit, order %.3f', p)
