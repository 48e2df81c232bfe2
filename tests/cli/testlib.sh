# Sourced by the CLI test scripts: strict mode, a scratch directory removed
# on exit, and a failure report that `ctest --output-on-failure` shows.
set -euo pipefail
work=$(mktemp -d "${TMPDIR:-/tmp}/impactkit-cli-test.XXXXXX")
trap 'rm -rf "$work"' EXIT

fail() {
  echo "FAIL: $*" >&2
  exit 1
}
