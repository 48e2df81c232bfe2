#!/usr/bin/env bash
# Output files under bad paths and interruptions: all of a run's files or
# none, checked before any work, and no temporary left behind.
#
#     check_outputs.sh empty-path  IMPACTKIT   an empty output (or system) path is bad input
#     check_outputs.sh long-name   IMPACTKIT   a file name of NAME_MAX (255) bytes is written
#     check_outputs.sh early-check IMPACTKIT   a bad output path fails before the work, and
#                                              no other output of the run appears
#     check_outputs.sh all-or-none IMPACTKIT   continue: a branch file that cannot be written
#                                              leaves an existing main CSV as it was
#     check_outputs.sh signals     IMPACTKIT   a sweep ended by SIGINT or SIGTERM leaves no
#                                              temporary and an existing file as it was
#     check_outputs.sh stale       IMPACTKIT   the temporaries of a sweep killed by SIGKILL
#                                              are removed by the next run in that directory
source "$(dirname "$0")/testlib.sh"
check=$1
impactkit=$2

# The hidden temporaries the program names .impactkit.PID.SERIAL.HOST.tmp.
temporaries() { find "$1" -maxdepth 1 -name '.impactkit.*.tmp' | sort; }

# expect_empty FLAG ARGS...: `impactkit ARGS... FLAG ''` exits 2 with one
# line on stderr saying FLAG's empty path names nothing, and writes nothing.
expect_empty() {
  local flag=$1 status=0
  shift
  (cd "$work" && "$impactkit" "$@" "$flag" '') >"$work/stdout" 2>"$work/stderr" || status=$?
  [[ $status -eq 2 && $(wc -l <"$work/stderr") -eq 1 ]] ||
    fail "$* $flag '': exit $status, stderr: $(cat "$work/stderr")"
  grep -q -- "^impactkit: error: $flag: an empty path names no " "$work/stderr" ||
    fail "$* $flag '': $(cat "$work/stderr")"
  [[ ! -s $work/stdout && -z $(ls -A "$work" | grep -v -x -e stdout -e stderr) ]] ||
    fail "$* $flag '': output or files: $(cat "$work/stdout") $(ls -A "$work")"
}

run_empty_path() {
  local flag
  for flag in --series --impacts --plot --json; do expect_empty $flag simulate; done
  for flag in --out --summary --plot; do expect_empty $flag sweep --from 1 --to 2 --steps 3; done
  for flag in --out --json --plot; do expect_empty $flag continue --from 1 --to 2; done
  for flag in --out --plot; do
    expect_empty $flag resonance
    expect_empty $flag impactmap
  done
  for flag in --out --plot --json; do expect_empty $flag returnmap --fit; done
  expect_empty --json orbit
  expect_empty --json lyapunov
  expect_empty --out paper
  expect_empty --system simulate
}

run_long_name() {
  local name
  name=$(printf 'a%.0s' $(seq 251)).csv  # 255 bytes
  "$impactkit" simulate --transient 1 --periods 1 --series "$work/$name" >"$work/stdout" ||
    fail "a 255-byte file name was refused"
  [[ -s $work/$name ]] || fail "the series was not written"
  [[ -z $(temporaries "$work") ]] || fail "temporaries left: $(temporaries "$work")"
}

# expect_early MESSAGE LEFTOVER ARGS...: exit 1, one line on stderr naming
# MESSAGE, nothing on stdout (no work was done), and no file LEFTOVER.
expect_early() {
  local expected=$1 leftover=$2 status=0
  shift 2
  (cd "$work" && "$impactkit" "$@") >"$work/stdout" 2>"$work/stderr" || status=$?
  [[ $status -eq 1 && $(wc -l <"$work/stderr") -eq 1 ]] ||
    fail "$*: exit $status, stderr: $(cat "$work/stderr")"
  grep -qF -- "$expected" "$work/stderr" || fail "$*: stderr lacks '$expected': $(cat "$work/stderr")"
  [[ ! -s $work/stdout ]] || fail "$*: work was done first: $(cat "$work/stdout")"
  [[ ! -e $work/$leftover ]] || fail "$*: left $leftover behind"
  [[ -z $(temporaries "$work") ]] || fail "$*: temporaries left: $(temporaries "$work")"
}

run_early_check() {
  expect_early "cannot create nodir/c.csv" - continue --from 1 --to 2 --out nodir/c.csv
  expect_early "cannot create nodir/c.png" c.json continue --from 1 --to 2 --plot nodir/c.png \
    --json c.json
  expect_early "cannot create nodir/r.png" r.csv resonance --plot nodir/r.png --out r.csv
  expect_early "cannot create nodir/m.png" m.csv impactmap --plot nodir/m.png --out m.csv
  expect_early "cannot create nodir/m.png" m.csv returnmap --plot nodir/m.png --out m.csv
  expect_early "cannot create nodir/s.csv" o.csv sweep --from 1 --to 2 --steps 3 --out o.csv \
    --summary nodir/s.csv
  expect_early "cannot create nodir/s.json" s.csv simulate --series s.csv --json nodir/s.json
  expect_early "cannot create nodir/o.json" - orbit --json nodir/o.json
  expect_early "cannot create nodir/l.json" - lyapunov --json nodir/l.json
  mkdir "$work/dir.json"
  expect_early "it names a directory" - orbit --json dir.json
  rmdir "$work/dir.json"
}

run_all_or_none() {
  # The P(1,1) branch from 1.5 has a period doubling near 1.613: with
  # --switch-pd its P(2,2) branch goes to keep.pd1.csv, here a directory.
  echo "an older table" >"$work/keep.csv"
  mkdir "$work/keep.pd1.csv"
  local status=0
  "$impactkit" continue --from 1.5 --to 1.7 --switch-pd --max-points 400 --out "$work/keep.csv" \
    --json "$work/keep.json" >"$work/stdout" 2>"$work/stderr" || status=$?
  [[ $status -eq 1 ]] || fail "exit status $status, expected 1: $(cat "$work/stderr")"
  grep -q "keep.pd1.csv" "$work/stderr" || fail "the failing file is not named: $(cat "$work/stderr")"
  grep -q "^branch pd1:" "$work/stdout" || fail "no period-doubled branch: $(cat "$work/stdout")"
  [[ $(cat "$work/keep.csv") == "an older table" ]] || fail "keep.csv was changed"
  [[ ! -e $work/keep.json ]] || fail "keep.json was written"
  [[ -z $(temporaries "$work") ]] || fail "temporaries left: $(temporaries "$work")"
}

# start_sweep: a sweep long enough to be interrupted, writing over keep.csv;
# returns once its temporary exists. Job control (set -m) leaves SIGINT at
# its default in the background job, as in a terminal.
start_sweep() {
  echo "an older table" >"$work/keep.csv"
  set -m
  "$impactkit" sweep --from 1 --to 2 --steps 100000 --threads 1 --out "$work/keep.csv" \
    >/dev/null 2>&1 &
  sweep=$!
  set +m
  for _ in $(seq 100); do
    [[ -n $(temporaries "$work") ]] && return
    sleep 0.05
  done
  fail "the sweep created no temporary"
}

run_signals() {
  local signal status
  for signal in INT TERM; do
    start_sweep
    sleep 0.2
    kill -s "$signal" "$sweep"
    status=0
    wait "$sweep" || status=$?
    ((status > 128)) || fail "SIG$signal: exit status $status, expected death by the signal"
    [[ -z $(temporaries "$work") ]] || fail "SIG$signal left $(temporaries "$work")"
    [[ $(cat "$work/keep.csv") == "an older table" ]] || fail "SIG$signal: keep.csv was changed"
  done
}

run_stale() {
  start_sweep
  kill -s KILL "$sweep"
  wait "$sweep" || true
  [[ -n $(temporaries "$work") ]] || fail "SIGKILL left no temporary: nothing to test"
  "$impactkit" simulate --transient 1 --periods 1 --series "$work/other.csv" >/dev/null ||
    fail "the next run failed"
  [[ -z $(temporaries "$work") ]] || fail "stale temporaries remain: $(temporaries "$work")"
  [[ $(cat "$work/keep.csv") == "an older table" ]] || fail "keep.csv was changed"
}

case $check in
  empty-path) run_empty_path ;;
  long-name) run_long_name ;;
  early-check) run_early_check ;;
  all-or-none) run_all_or_none ;;
  signals) run_signals ;;
  stale) run_stale ;;
  *) fail "unknown check '$check'" ;;
esac
echo "ok: $check"
