#!/bin/sh
# Fresh-clone build times: for each git revision given, a clean clone, the
# README's configure and build (Release, every target, -j the cores), timed
# from configure to the last link; one after another in one sitting, so
# that two revisions are compared on the same machine in the same state.
# No ccache (a fresh machine has none).  Run from the repository.
#
# usage: bench/build_time.sh REV [REV...]     (JOBS=N to set -j; GENERATOR=Ninja to compare)
# prints: revision, commit, seconds, and the machine's load at the start.
set -eu
repo=$(git rev-parse --show-toplevel)
jobs=${JOBS:-$(nproc)}
for rev in "$@"; do
  work=$(mktemp -d)
  git clone -q --no-local "$repo" "$work/src"
  git -C "$work/src" checkout -q --detach "$rev"
  load=$(cut -d' ' -f1 /proc/loadavg)
  start=$(date +%s.%N)
  cmake -S "$work/src" -B "$work/src/build" -G "${GENERATOR:-Unix Makefiles}" -DCMAKE_BUILD_TYPE=Release > "$work/configure.log" 2>&1
  cmake --build "$work/src/build" -j"$jobs" > "$work/build.log" 2>&1 || {
    echo "$rev: the build failed ($work/build.log)"; exit 1; }
  end=$(date +%s.%N)
  awk -v rev="$rev" -v sha="$(git -C "$work/src" rev-parse --short HEAD)" -v s="$start" -v e="$end" -v j="$jobs" \
    -v load="$load" -v gen="${GENERATOR:-Unix Makefiles}" \
    'BEGIN { printf "%s %s %.0f s (-j%s, %s, load %s at the start)\n", rev, sha, e - s, j, gen, load }'
  rm -rf "$work"
done
