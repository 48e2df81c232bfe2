#!/usr/bin/env bash
# The main job in its reduced mode: `impactkit paper --quick` writes every
# promised file, non-empty, names each in its closing list (branch tables
# only for the paper's three branches without --all-branches), and prints
# the same special points of the main branches as the library computes
# directly (paper_points); its connected diagram holds the P(2,2) branch born
# at the P(1,1) period doubling.
#
#     check_paper.sh IMPACTKIT PAPER_POINTS
source "$(dirname "$0")/testlib.sh"
impactkit=$1
points=$2

"$impactkit" paper --quick --out "$work/paper" >"$work/stdout" 2>"$work/stderr" ||
  fail "impactkit paper failed: $(cat "$work/stderr")"
for file in summary.json fig2-resonance.png fig3-sweep.csv fig3-bifurcation.png diagram.png \
            diagram.json branch-main.csv branch-seed2.csv branch-seed3.csv; do
  [[ -s "$work/paper/$file" ]] || fail "missing or empty: $file"
done
# The branch tables are the paper's three branches' unless --all-branches
# asks for every one (diagram.json holds them all), and the closing list says
# what each file in the folder is.
tables=$(find "$work/paper" -name 'branch-*.csv' | wc -l)
((tables == 3)) || fail "$tables branch tables without --all-branches, expected 3"
sed -n '/^wrote into/,$p' "$work/stdout" >"$work/where"
for file in "$work"/paper/*; do
  grep -qF "$(basename "$file")" "$work/where" || fail "the closing list does not name $(basename "$file")"
done
grep -q "^  branch-\*.csv  *3 branch tables: .*(every branch's with --all-branches)" "$work/where" ||
  fail "the closing list does not say where the other branches are: $(cat "$work/where")"
for section in "modal data:" "resonance:" "orbits (" "branches (" "brute-force diagram" "wrote into"; do
  grep -q "^$section" "$work/stdout" || fail "the summary lacks '$section'"
done
grep -q "omega = 0.6   P(2,1) stable" "$work/stdout" || fail "no stable P(2,1) at 0.6"
# One schema for motion kinds (docs/cli.md, "Motion kinds"): names, and p =
# 0 for sticking, as `sweep --summary` writes them.
columns_of "$work/paper/fig3-sweep.csv" | grep -qx "omega,range_xN_max,impacts,kind,p,q" ||
  fail "fig3-sweep.csv columns: $(columns_of "$work/paper/fig3-sweep.csv")"
awk -F, '!/^#/ && ++row > 1 && $4 !~ /^(periodic|sticking|chaotic|non_impacting|unresolved)$/ {exit 1}'   "$work/paper/fig3-sweep.csv" || fail "fig3-sweep.csv has a kind that is not a name"
awk -F, '!/^#/ && ++row > 1 && $4 == "sticking" && $5 != "0" {exit 1}' "$work/paper/fig3-sweep.csv" ||
  fail "fig3-sweep.csv: a sticking row whose p is not 0"
# Provenance (docs/cli.md, "Output files"): every table names the run and
# what it holds; summary.json has the same object as every JSON output.
for table in fig3-sweep.csv branch-main.csv; do
  grep -qx "# command: impactkit paper --quick --out $work/paper" "$work/paper/$table" ||
    fail "$table: no command line"
  run_line_of "$work/paper/$table" | grep -q "^paper --out $work/paper --quick; " ||
    fail "$table: run line '$(run_line_of "$work/paper/$table")'"
done
python3 -c 'import json, sys; p = json.load(open(sys.argv[1]))["provenance"]; sys.exit(p["run"] != sys.argv[2])' \
  "$work/paper/summary.json" "paper --out $work/paper --quick" || fail "summary.json: no provenance"
"$points" >"$work/expected" || fail "paper_points failed"
(($(wc -l <"$work/expected") >= 8)) || fail "too few special points from the library"
while read -r line; do
  grep -qF -- "$line" "$work/stdout" || fail "impactkit paper does not print: $line"
done <"$work/expected"
json=$(tr -d ' \n' <"$work/paper/summary.json")
for field in '"modes":[' '"resonance_peaks":[' '"orbits":[' '"branches":[' '"regimes":[' \
             '"special_points":['; do
  [[ $json == *"$field"* ]] || fail "summary.json lacks $field"
done
grep -q '^\[3/5\] brute-force' "$work/stderr" || fail "no stage display on stderr"
grep -q '^  [a-z0-9]* *P(2,2) from 1.613045' "$work/stdout" ||
  fail "no P(2,2) branch from the P(1,1) period doubling at 1.613045"
echo ok
