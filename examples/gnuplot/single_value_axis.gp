# Sets one axis of the next plot from a data column, like autoscale, except
# when every value is the same to 1e-9 of its size (a periodic orbit's impacts
# land on one point): autoscale would then spread rounding noise over the
# axis, every tick reading the same digits. Such an axis is centred on the
# value and a label on the figure says so.
#
#   call 'examples/gnuplot/single_value_axis.gp' 'x|y' 'file.csv' 'using-expression'
#
# Comment lines are not data and the header row is skipped (every ::1); values the expression maps
# to 1/0 are left out, as in `plot`; with no values at all the axis autoscales.
tag = (ARG1 eq 'x') ? 11 : 12
eval sprintf("unset label %d", tag)
# Explicit [*:*] ranges: stats would filter by the previous panel's ranges.
undefine STATS_*
stats [*:*] [*:*] ARG2 every ::1 using @ARG3 nooutput
if (!exists("STATS_max")) {
  eval sprintf("set autoscale %s", ARG1)
} else {
  size = abs(STATS_max) > abs(STATS_min) ? abs(STATS_max) : abs(STATS_min)
}
if (!exists("STATS_max") || STATS_max - STATS_min > 1e-9 * size) {
  eval sprintf("set autoscale %s", ARG1)
} else {
  half = 0.05 * size > 1e-3 ? 0.05 * size : 1e-3
  eval sprintf("set %srange [%.15g:%.15g]", ARG1, STATS_mean - half, STATS_mean + half)
  eval sprintf("set label %d 'every %s value is %.10g (spread %.1e)' at graph 0.02, graph %g front", \
               tag, ARG1, STATS_mean, STATS_max - STATS_min, (ARG1 eq 'x') ? 0.08 : 0.95)
}
