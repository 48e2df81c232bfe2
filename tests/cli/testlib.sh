# Sourced by the CLI test scripts: strict mode, a scratch directory removed
# on exit, and a failure report that `ctest --output-on-failure` shows.
set -euo pipefail
work=$(mktemp -d "${TMPDIR:-/tmp}/impactkit-cli-test.XXXXXX")
trap 'rm -rf "$work"' EXIT

fail() {
  echo "FAIL: $*" >&2
  exit 1
}

# A CSV's header row: its first line that is not a comment.
columns_of() {
  grep -m1 -v '^#' "$1"
}

# What follows "# run: " in a CSV's provenance (docs/cli.md, "Output files").
run_line_of() {
  sed -n 's/^# run: //p' "$1" | head -1
}

# Whether two outputs agree but for the command line in their provenance
# (runs that differ only in threads, ranks or output paths).
same_but_command() {
  cmp -s <(grep -v -e '^# command: ' -e '^ *"command": ' "$1") \
    <(grep -v -e '^# command: ' -e '^ *"command": ' "$2")
}

# The command "$@" is refused for the reason `pattern`: status 2 and one
# line on stderr that says it.
refused() {
  local pattern=$1 status=0
  shift
  "$@" >"$work/refused.stdout" 2>"$work/refused.stderr" || status=$?
  [[ $status -eq 2 && $(wc -l <"$work/refused.stderr") -eq 1 ]] ||
    fail "expected a refusal ($pattern): status $status, stderr $(cat "$work/refused.stderr")"
  grep -q "$pattern" "$work/refused.stderr" || fail "message: $(cat "$work/refused.stderr")"
}
