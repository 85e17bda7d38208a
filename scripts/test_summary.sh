#!/usr/bin/env bash
# Sums the per-binary results ("NAME: P passed, F failed") into one closing line.
dir=$1
p=0; f=0; crashed=0
for r in "$dir"/*.result; do
  [ -e "$r" ] || continue
  line=$(cat "$r")
  rc=$(cat "${r%.result}.result.rc" 2>/dev/null || echo 1)
  if [[ "$line" =~ ([0-9]+)\ passed,\ ([0-9]+)\ failed ]]; then
    p=$((p + BASH_REMATCH[1])); f=$((f + BASH_REMATCH[2]))
    if [ "$rc" != 0 ] && [ "${BASH_REMATCH[2]}" = 0 ]; then f=$((f + 1)); crashed=$((crashed + 1)); fi
  else
    f=$((f + 1)); crashed=$((crashed + 1))
    echo "$(basename "${r%.result}"): no summary (crashed?), see ${r}.log"
  fi
done
n=$(ls "$dir"/*.result 2>/dev/null | wc -l)
slow=$(for t in "$dir"/*.result.seconds; do [ -e "$t" ] && printf '%s %s\n' "$(cat "$t")" "$(basename "${t%.result.seconds}")"; done |
       sort -rn | head -n 5 | awk '{printf "%s%s %s s", (NR > 1 ? ", " : ""), $2, $1}')
[ -n "$slow" ] && echo "slowest test binaries (wall seconds): $slow"
echo "test binaries: $n, crashed: $crashed"
echo "$p passed, $f failed"
[ "$f" = 0 ]
