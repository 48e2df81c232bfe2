#!/usr/bin/env bash
# `impactkit diagram` on the paper's system over 0.8..0.9 with a short
# seeding sweep: with no start given, it prints the P(2,1), P(3,2), P(4,2)
# and P(1,1) branches and the period doubling at 0.8372414 in parameter
# order; --json holds nodes (type, param, multipliers) and edges whose
# from/to are node ids; the seeds that did not converge are explained;
# --max-branches stops it with an "incomplete" report.
#
#     check_diagram.sh IMPACTKIT
source "$(dirname "$0")/testlib.sh"
impactkit=$1

args=(diagram --from 0.8 --to 0.9 --sweep-values 41 --sweep-transient 300 --sweep-record 20
      --json "$work/d.json")
"$impactkit" "${args[@]}" >"$work/stdout" 2>"$work/stderr" ||
  fail "impactkit diagram failed: $(cat "$work/stderr")"
for branch in 'P(2,1) from 0.8 to 0.857' 'P(3,2) from 0.8322' 'P(4,2) from 0.8322' \
              'P(1,1) from 0.8564'; do
  grep -qF "$branch" "$work/stdout" || fail "no branch '$branch': $(cat "$work/stdout")"
done
grep -q "period_doubling at omega = 0.83724137" "$work/stdout" || fail "no PD at 0.8372414"
# Seeds that did not converge (6 here: grazings tried on both sides) are
# explained where they are counted.
grep -q " 6 seeds not converged)" "$work/stdout" || fail "no failed seeds: $(cat "$work/stdout")"
grep -q "^ *(6 seeds not converged: starts tried at special points that found no orbit" \
  "$work/stdout" || fail "'seeds not converged' unexplained: $(cat "$work/stdout")"
# Special points in parameter order.
grep -E '^  [a-z_]+ at omega = ' "$work/stdout" | sed -E 's/.* = ([0-9.]+) .*/\1/' >"$work/params"
sort -g -c "$work/params" || fail "special points not in parameter order"
json=$(tr -d ' \n' <"$work/d.json")
for field in '"nodes":[{' '"type":"period_doubling"' '"multipliers":[[' '"edges":[{' \
             '"points":[{' '"range_xN":' '"parameter":"omega"'; do
  [[ $json == *"$field"* ]] || fail "JSON lacks $field"
done
# Every edge's ends are node ids.
nodes=$(grep -o '"id": [0-9]*' "$work/d.json" | wc -l)
while read -r id; do
  ((id < nodes)) || fail "an edge ends at node $id, but there are $nodes nodes"
done < <(grep -oE '"(from|to)": [0-9]+' "$work/d.json" | grep -oE '[0-9]+$')
# A bound on the branches stops the network and says so.
"$impactkit" diagram --from 0.8 --to 0.9 --sweep-values 41 --sweep-transient 300 --sweep-record 20 \
  --max-branches 2 >"$work/bounded" || fail "impactkit diagram --max-branches 2 failed"
grep -q '^diagram: *2 branches, .*incomplete: max_branches (2) reached' "$work/bounded" ||
  fail "no 'incomplete' report: $(cat "$work/bounded")"
# Every grazing predicted and checked by sweeps both ways: the paper's two
# of Fig. 5 jump (P(1,1) to P(3,2) below 0.8564, P(3,2) to P(2,1) below
# 0.8322) as the sweeps find, with hysteresis; the JSON carries each check.
"$impactkit" diagram --from 0.8 --to 0.9 --sweep-values 41 --sweep-transient 300 --sweep-record 20 \
  --grazings "$work/g.json" >"$work/grazings" || fail "impactkit diagram --grazings failed"
for line in 'omega = 0.8322220921, P(3,2) (new contact): predicted P(2,1) (jump), swept P(2,1): agrees; hysteresis' \
            ', P(1,1) (vanishing impact): predicted P(3,2) (jump), swept P(3,2): agrees; hysteresis'; do
  grep -qF "$line" "$work/grazings" || fail "no '$line': $(cat "$work/grazings")"
done
json=$(tr -d ' \n' <"$work/g.json")
for field in '"grazings":[{' '"grazing_orbit":"P(3,2)"' '"contact":"new"' '"local":false' \
             '"agrees":true' '"hysteresis":true' '"toward":["P(2,1)"' '"provenance":{'; do
  [[ $json == *"$field"* ]] || fail "grazings JSON lacks $field"
done
echo ok
