#!/bin/sh
# Two builds of demvv side by side in one sitting: `demvv bench` on the
# prepared 6000-ball sample (p01) and on the sc lattice with each contact
# law, one build then the other, three rounds, and the best of the three
# per build and configuration (the machine is shared: the best run is the
# least disturbed one).  Prints the load before and after.
#
# usage: bench/compare.sh BEFORE_DEMVV AFTER_DEMVV [THREADS...]   (from the repository root)
#   THREADS default "1 2".  The sample is prepared (and cached) on first use.
set -eu
before=$1 after=$2
shift 2
threads=${*:-1 2}
log=$(mktemp)
trap 'rm -f "$log"' EXIT
echo "# $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
rate() { sed -n 's/.*particle-steps\/s \([0-9.e+]*\),.*/\1/p'; }
for round in 1 2 3; do
  for t in $threads; do
    for build in before after; do
      eval bin=\$$build
      echo "sample-p01 $t $build $("$bin" bench --sample cases/p01_thesis_6000/case.prm --threads "$t" --steps 2000 --repeat 1 | rate)" >> "$log"
      for law in linear burgers modified_burgers; do
        [ "$t" = 1 ] || [ "$law" = linear ] || continue
        echo "lattice-$law $t $build $("$bin" bench --threads "$t" --steps 1000 --repeat 1 --law "$law" | rate)" >> "$log"
      done
    done
  done
done
echo "# load after $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%-26s %-8s %-12s %-12s %s\n' work threads before after after/before
awk '{ k = $1 " " $2; if (!($3 in seen)) seen[$3] = 1
       if ($4 + 0 > best[k, $3] + 0) best[k, $3] = $4; keys[k] = 1 }
     END { for (k in keys) { split(k, p, " ")
             printf "%-26s %-8s %-12s %-12s %.2f\n", p[1], p[2], best[k, "before"], best[k, "after"],
                    best[k, "after"] / best[k, "before"] } }' "$log" | sort
