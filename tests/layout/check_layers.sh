#!/usr/bin/env bash
# Fails when a library area includes an area above it. The layers, bottom
# up (docs/architecture.md): core; solvers, dynamics and model (each on core
# only: a system is data); hybrid; orbits; continuation; analysis; io. An
# area may include itself and any lower layer; solvers, dynamics and model
# may not include one another.
set -euo pipefail
root=${1:-$(dirname "$0")/../..}
cd "$root/lib"

declare -A rank=([core]=0 [solvers]=1 [dynamics]=1 [model]=1 [hybrid]=3 [orbits]=4
                 [continuation]=5 [analysis]=6 [io]=7)
# A data header declares values and functions of them on core alone, and
# includes no library header but core's (checked below): any area may
# include it. So a stop's parameters are declared beside the law that reads
# them while the model holds their values, and a contact law is one folder.
data_headers=(hybrid/stop_parameters.hpp)
failures=0
checked=0
for header in "${data_headers[@]}"; do
  for file in "include/impactkit/$header" "src/${header%.hpp}.cpp"; do
    [[ -f $file ]] || continue
    while IFS= read -r target; do
      [[ $target == "$header" || $target == core/* ]] && continue
      echo "FAIL: data header $header: $file includes \"$target\" (only core's)"
      failures=$((failures + 1))
    done < <(sed -nE 's#^\#include "(impactkit/)?([a-z_]+/[^"]+)".*#\2#p' "$file")
  done
done
while IFS= read -r file; do
  area=$(sed -E 's#^(include/impactkit|src)/([^/]+)/.*#\2#' <<<"$file")
  if [[ -z ${rank[$area]+x} ]]; then
    echo "FAIL: $file is in no known area ($area)"; failures=$((failures + 1)); continue
  fi
  while IFS= read -r target; do
    checked=$((checked + 1))
    target_area=${target%%/*}
    if [[ -z ${rank[$target_area]+x} ]]; then
      echo "FAIL: $file includes \"$target\", in no known area"; failures=$((failures + 1))
    elif [[ " ${data_headers[*]} " == *" $target "* ]]; then
      continue
    elif [[ $target_area != "$area" && ${rank[$target_area]} -ge ${rank[$area]} ]]; then
      echo "FAIL: $file ($area) includes \"$target\" ($target_area, not a lower layer)"
      failures=$((failures + 1))
    fi
  done < <(sed -nE 's#^\#include "(impactkit/)?([a-z_]+/[^"]+)".*#\2#p' "$file")
done < <(find include/impactkit src -mindepth 2 -name '*.[ch]pp' | sort)

if ((checked == 0)); then echo "FAIL: no include checked"; exit 1; fi
echo "$checked includes checked, $failures across layers the wrong way"
((failures == 0))
