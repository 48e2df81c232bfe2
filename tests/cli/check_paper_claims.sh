# Usage: check_paper_claims.sh IMPACTKIT SOURCE_DIR
# The claims table of docs/paper-reproduction.md is the one a fresh run
# gives: `impactkit paper` at full resolution and examples/fig3_bifurcation.sh,
# as scripts/run.sh runs them, then scripts/paper_claims.py; the table between
# the doc's marker lines must be its output, line for line.
source "$(dirname "$0")/testlib.sh"
impactkit=$(realpath "$1")
source_dir=$(realpath "$2")
cd "$source_dir"

"$impactkit" paper --out "$work/paper" >"$work/log" 2>&1 || fail "impactkit paper: $(tail -3 "$work/log")"
bash examples/fig3_bifurcation.sh "$impactkit" "$work/figures" "$work/paper/data" >"$work/log" 2>&1 ||
  fail "fig3_bifurcation.sh: $(tail -3 "$work/log")"
python3 scripts/paper_claims.py "$work/paper" >"$work/generated" || fail "paper_claims.py failed"
sed -n '/^<!-- claims: generated/,/^<!-- end of claims -->/p' docs/paper-reproduction.md |
  sed '1d;$d' >"$work/documented"
[[ -s $work/documented ]] || fail "docs/paper-reproduction.md has no generated claims table"
diff "$work/documented" "$work/generated" >"$work/diff" ||
  fail "the claims table differs from a fresh run (scripts/paper_claims.py DIR --update):
$(cat "$work/diff")"
echo "ok: the claims table is the run's"
