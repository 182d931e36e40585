#!/bin/sh
# The bad-input corpus (tests/data/bad/MANIFEST): every malformed, hostile
# or impossible input ends with its expected exit code and a one-line error
# naming it, within a time limit (a hang fails), never with a crash, an
# abort or an uncaught exception.  Cases run four at a time (each is mostly
# the executable's start-up, about half a second).
demvv="$1"; dir="$2"; out=$(mktemp -d); limit=30; batch=4
field() { printf '%s\n' "$1" | awk -F ' [|] ' -v k="$2" '{ print $k }' | sed 's/^ *//; s/ *$//'; }

# Run every case: case N leaves its line, exit code and stderr in $out/N.*.
n=0
while IFS= read -r line; do
  case "$line" in '' | '#'*) continue ;; esac
  n=$((n + 1))
  printf '%s\n' "$line" > "$out/$n.case"
  args=$(field "$line" 2 | sed "s|@|$dir|g; s|OUT|$out/$n.run|g")
  (
    eval "set -- $args"
    # One thread: the corpus is about input, and the machine may be shared.
    [ "$1" = run ] && set -- "$@" --threads 1 --quiet
    timeout "$limit" "$demvv" "$@" > /dev/null 2> "$out/$n.err" < /dev/null
    echo $? > "$out/$n.rc"
  ) &
  [ $((n % batch)) -eq 0 ] && wait
done < "$dir/MANIFEST"
wait

# Check them in the manifest's order.
failures=0
k=0
while [ "$k" -lt "$n" ]; do
  k=$((k + 1))
  line=$(cat "$out/$k.case")
  file=$(field "$line" 1); code=$(field "$line" 3); words=$(field "$line" 4)
  rc=$(cat "$out/$k.rc"); err="$out/$k.err"
  problems=""
  [ -e "$dir/$file" ] || [ -e "$file" ] || problems="$problems; no input file '$file'"
  if [ "$rc" -eq 124 ]; then
    problems="$problems; no end within $limit s (a hang)"
  else
    [ "$rc" -gt 128 ] && problems="$problems; killed by signal $((rc - 128))"
    grep -Eq "terminate called|Aborted|Segmentation|core dumped|AddressSanitizer|what\(\)" "$err" &&
      problems="$problems; crashed or aborted"
    [ "$rc" -eq "$code" ] || problems="$problems; exit code $rc, expected $code"
    lines=$(grep -cv "^demvv: warning:" "$err")
    [ "$lines" -eq 1 ] || problems="$problems; $lines lines on stderr besides warnings, expected one"
    last=$(tail -n 1 "$err")
    missing=$(printf '%s\n' "$words" | tr ';' '\n' | while IFS= read -r word; do
      word=$(printf '%s' "$word" | sed 's/^ *//; s/ *$//')
      [ -z "$word" ] || printf '%s' "$last" | grep -qF -- "$word" || printf " '%s'" "$word"
    done)
    [ -z "$missing" ] || problems="$problems; the error lacks$missing"
  fi
  if [ -n "$problems" ]; then
    failures=$((failures + 1))
    echo "FAIL [$line]${problems}"
    head -c 600 "$err"
  fi
done

rm -rf "$out"
[ "$n" -gt 0 ] || { echo "FAIL: no cases in $dir/MANIFEST"; exit 1; }
[ "$failures" -eq 0 ] || { echo "bad inputs: $failures of $n cases failed"; exit 1; }
echo "bad inputs: $n cases ok"
