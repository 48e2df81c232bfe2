#!/usr/bin/env bash
# One schema for motion kinds (docs/cli.md, "Motion kinds"): the sticking
# motion at omega = 0.2 is p = 0, q = 1 in `simulate --json`, `sweep
# --summary` and `map --out` (and Python's sweep: test_analysis.py), as
# the library's GridCell has it; the periodic P(1,1) at omega = 1.0 is p = 1.
#
#     check_kind_schema.sh IMPACTKIT
source "$(dirname "$0")/testlib.sh"
impactkit=$1

for case in "0.2 sticking 0" "1.0 periodic 1"; do
  read -r omega kind p <<<"$case"
  "$impactkit" simulate --omega "$omega" --transient 300 --periods 20 --json "$work/s.json" \
    >/dev/null || fail "simulate failed"
  json=$(tr -d ' \n' <"$work/s.json")
  want="\"p\":$p,\"q\":1"
  [[ $json == *"$want"* ]] || fail "simulate --json at $omega lacks $want"
  "$impactkit" sweep --from "$omega" --to "$omega" --steps 1 --transient 300 --record 20 \
    --summary "$work/w.csv" >/dev/null || fail "sweep failed"
  row=$(grep -v '^#' "$work/w.csv" | sed -n 2p | cut -d, -f2-4)
  [[ $row == "$kind,$p,1" ]] || fail "sweep --summary at $omega: $row, expected $kind,$p,1"
  "$impactkit" map --from "$omega" --to "$omega" --steps 1 --param2 r --from2 0.7 --to2 0.7 \
    --steps2 1 --transient 300 --record 20 --threads 1 --out "$work/m.csv" >/dev/null ||
    fail "map failed"
  row=$(grep -v '^#' "$work/m.csv" | sed -n 2p | cut -d, -f3-5)
  [[ $row == "$kind,$p,1" ]] || fail "map --out at $omega: $row, expected $kind,$p,1"
done
echo "ok"
