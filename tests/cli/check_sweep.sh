#!/usr/bin/env bash
# `impactkit sweep` as a user meets it.
#
#     check_sweep.sh IMPACTKIT bad EXPECTED ARGS...
#         exits 2 with one line on stderr containing EXPECTED, nothing on
#         stdout, and no file left behind (all three outputs requested)
#     check_sweep.sh IMPACTKIT outputs
#         a short omega sweep over the paper's P(2,1) and P(1,1) orbits:
#         files start with the provenance line, have the documented
#         columns, the kinds and periods the paper gives, one impact row per
#         recorded impact, and are byte-identical for --threads 1 and 2
source "$(dirname "$0")/testlib.sh"
impactkit=$1
mode=$2
shift 2

case $mode in
  bad)
    expected=$1
    shift
    mkdir "$work/out"
    status=0
    "$impactkit" sweep "$@" --out "$work/out/impacts.csv" --summary "$work/out/summary.csv" \
      --plot "$work/out/plot.png" >"$work/stdout" 2>"$work/stderr" || status=$?
    message=$(cat "$work/stderr")
    [[ $status -eq 2 ]] || fail "exit status $status, expected 2; stderr: $message"
    [[ $(wc -l <"$work/stderr") -eq 1 ]] || fail "stderr is not one line: $message"
    [[ $message == "impactkit: error: "*"$expected"* ]] || fail "stderr lacks '$expected': $message"
    [[ ! -s $work/stdout ]] || fail "unexpected output on stdout: $(cat "$work/stdout")"
    [[ -z $(ls -A "$work/out") ]] || fail "files left behind: $(ls -A "$work/out")"
    echo "ok: $message"
    ;;
  outputs)
    # Ω = 0.6 and 0.9: P(2,1) and P(1,1) (the paper's Fig. 4 (d), (e)).
    for threads in 1 2; do
      "$impactkit" sweep --from 0.6 --to 0.9 --steps 2 --transient 300 --record 20 \
        --threads $threads --out "$work/impacts$threads.csv" \
        --summary "$work/summary$threads.csv" >"$work/stdout" ||
        fail "sweep failed: $(cat "$work/stdout")"
    done
    grep -q "2 values in 1 chunks" "$work/stdout" || fail "unexpected report: $(cat "$work/stdout")"
    same_but_command "$work/impacts1.csv" "$work/impacts2.csv" || fail "--out differs between 1 and 2 threads"
    same_but_command "$work/summary1.csv" "$work/summary2.csv" || fail "--summary differs between 1 and 2 threads"
    for file in impacts1 summary1; do
      run_line_of "$work/$file.csv" | grep -q "^sweep param=omega from=0.6 to=0.9 steps=2 transient=300 record=20 start=previous" ||
        fail "$file.csv: bad provenance line: $(run_line_of "$work/$file.csv")"
    done
    [[ $(columns_of "$work/impacts1.csv") == "omega,t,phase,velocity,stop" ]] || fail "impact columns: $(columns_of "$work/impacts1.csv")"
    [[ $(columns_of "$work/summary1.csv") == omega,kind,p,q,range_xN,range_x1,* ]] ||
      fail "summary columns: $(columns_of "$work/summary1.csv")"
    # 20 periods: 40 impacts of P(2,1) at 0.6, 20 of P(1,1) at 0.9.
    [[ $(grep -c '^0\.6,' "$work/impacts1.csv") -eq 40 ]] || fail "expected 40 impacts at 0.6"
    [[ $(grep -c '^0\.9,' "$work/impacts1.csv") -eq 20 ]] || fail "expected 20 impacts at 0.9"
    grep -q '^0\.6,periodic,2,1,' "$work/summary1.csv" || fail "0.6 is not P(2,1): $(cat "$work/summary1.csv")"
    grep -q '^0\.9,periodic,1,1,' "$work/summary1.csv" || fail "0.9 is not P(1,1): $(cat "$work/summary1.csv")"
    echo ok
    ;;
  *) fail "unknown mode $mode" ;;
esac
