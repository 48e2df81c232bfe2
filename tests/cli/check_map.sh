#!/usr/bin/env bash
# `impactkit map` and `impactkit basins` as a user meets them.
#
#     check_map.sh IMPACTKIT row
#         the map's r = 0.7 row is `impactkit sweep --set r=0.7 --summary`
#         over the same omega values (kind, p, q, largest impact speed,
#         range of x_N, exponent), number for number
#     check_map.sh IMPACTKIT threads
#         CSV and JSON are byte-identical for --threads 1 and 2
#     check_map.sh IMPACTKIT mpi MPIRUN
#         `MPIRUN -np 2 impactkit map` writes the CSV of --threads 1
#     check_map.sh IMPACTKIT resume
#         a checkpointed run killed (SIGKILL) midway and rerun gives the CSV
#         of an uninterrupted run, computing only the cells not on record
#         (their count is the report's); a checkpoint of another grid is
#         refused with exit 2 and one line
#     check_map.sh IMPACTKIT interrupt
#         a checkpointed run stopped by SIGTERM (a batch system's time limit;
#         Ctrl-C's SIGINT takes the same path) says on stderr, in one line,
#         that the finished units are saved and that rerunning resumes, and
#         dies of the signal (status 143); the rerun resumes
#     check_map.sh IMPACTKIT damaged
#         a finished checkpoint with one unit edited (periodic -> chaotic),
#         one cut short and one emptied: the rerun computes those three
#         again, with one warning line naming each, and writes the CSV of
#         an uninterrupted run; a run.txt edited by a byte is refused with
#         exit 2 and one line saying it is damaged
#     check_map.sh IMPACTKIT plot
#         --plot with --curves (one curve in (omega, r), drawn; one in
#         (omega, xs), skipped) writes a PNG; a curves file without
#         "curves" is refused with exit 2 and one line naming it (skipped,
#         77, without gnuplot)
#     check_map.sh IMPACTKIT full
#         map, basins and sweep each with --full-transient (listed by their
#         --help, named in their provenance line) class every cell as the
#         default does, whose transients end early at confirmed orbits
#     check_map.sh IMPACTKIT basins
#         at omega = 2 (the paper's P(1,2)) the basins of a grid of starts
#         hold one attractor, P(1,2), whose orbit is the fixed point that
#         `impactkit orbit --p 1 --q 2` solves for: its impact phase and
#         speed to 1e-6
source "$(dirname "$0")/testlib.sh"
impactkit=$1
mode=$2
shift 2

# A 13 x 5 (omega, r) grid with a row at r = 0.7, 200 + 40 periods a cell,
# rows in chunks of 5 values: 15 work units.
grid=(map --from 0.6 --to 2.4 --steps 13 --param2 r --from2 0.5 --to2 0.9 --steps2 5
      --transient 200 --record 40 --chunk 5)

case $mode in
  row)
    "$impactkit" "${grid[@]}" --out "$work/map.csv" >/dev/null || fail "map failed"
    "$impactkit" sweep --set r=0.7 --from 0.6 --to 2.4 --steps 13 --transient 200 --record 40 \
      --chunk 5 --summary "$work/sweep.csv" >/dev/null || fail "sweep failed"
    # map: omega,r,kind,p,q,max_velocity,range_xN,lyapunov; sweep summary:
    # omega,kind,p,q,range_xN,...,velocity_max (11),lyapunov (12).
    awk -F, '!/^#/ && ++row > 1 && $2 == "0.7" { print $1","$3","$4","$5","$6","$7","$8 }' "$work/map.csv" \
      >"$work/map-row"
    awk -F, '!/^#/ && ++row > 1 { print $1","$2","$3","$4","$11","$5","$12 }' "$work/sweep.csv" \
      >"$work/sweep-row"
    [[ $(wc -l <"$work/map-row") -eq 13 ]] || fail "map has no row of 13 cells at r = 0.7"
    diff "$work/map-row" "$work/sweep-row" || fail "the map's r = 0.7 row differs from the sweep"
    echo ok
    ;;
  threads)
    for threads in 1 2; do
      "$impactkit" "${grid[@]}" --threads $threads --out "$work/map$threads.csv" \
        --json "$work/map$threads.json" >"$work/stdout" || fail "map failed"
    done
    same_but_command "$work/map1.csv" "$work/map2.csv" || fail "CSV differs between 1 and 2 threads"
    same_but_command "$work/map1.json" "$work/map2.json" || fail "JSON differs between 1 and 2 threads"
    [[ $(columns_of "$work/map1.csv") == omega,r,kind,p,q,max_velocity,range_xN,lyapunov ]] ||
      fail "columns: $(columns_of "$work/map1.csv")"
    grep -q '"cells": 65' "$work/map1.json" || fail "JSON lacks the cell count"
    echo ok
    ;;
  mpi)
    mpirun=$1
    "$impactkit" "${grid[@]}" --threads 1 --out "$work/one.csv" >/dev/null || fail "map failed"
    "$mpirun" --allow-run-as-root --oversubscribe -np 2 "$impactkit" "${grid[@]}" \
      --out "$work/mpi.csv" >"$work/stdout" 2>"$work/stderr" ||
      fail "mpirun failed: $(cat "$work/stderr")"
    grep -q "x 2 ranks" "$work/stdout" || fail "not run on 2 ranks: $(cat "$work/stdout")"
    same_but_command "$work/one.csv" "$work/mpi.csv" || fail "CSV differs between 1 process and 2 ranks"
    echo ok
    ;;
  interrupt)
    long=(map --from 0.6 --to 2.4 --steps 30 --param2 r --from2 0.3 --to2 0.95 --steps2 20
          --transient 300 --record 40 --chunk 10 --threads 1)
    "$impactkit" "${long[@]}" --checkpoint "$work/cp" --out "$work/resumed.csv" \
      >/dev/null 2>"$work/stderr" &
    pid=$!
    for _ in $(seq 200); do
      (($(find "$work/cp" -name 'unit-*.txt' 2>/dev/null | wc -l) >= 2)) && break
      sleep 0.02
    done
    kill -TERM $pid 2>/dev/null || fail "the run ended before it could be stopped"
    status=0
    wait $pid || status=$?
    ((status == 143)) || fail "exit status $status after SIGTERM, expected 143"
    [[ $(wc -l <"$work/stderr") -eq 1 ]] || fail "stderr: $(cat "$work/stderr")"
    grep -qF "interrupted; the units finished so far are saved in $work/cp: run the same command again to resume" \
      "$work/stderr" || fail "no resume hint: $(cat "$work/stderr")"
    "$impactkit" "${long[@]}" --checkpoint "$work/cp" --out "$work/resumed.csv" \
      >"$work/stdout" || fail "the resumed run failed"
    grep -q "[1-9][0-9]* resumed from the checkpoint" "$work/stdout" ||
      fail "nothing resumed: $(cat "$work/stdout")"
    echo ok
    ;;
  resume)
    # 20 rows of 30 cells in units of 10: long enough (~1 s) to be killed midway.
    long=(map --from 0.6 --to 2.4 --steps 30 --param2 r --from2 0.3 --to2 0.95 --steps2 20
          --transient 300 --record 40 --chunk 10 --threads 1)
    "$impactkit" "${long[@]}" --out "$work/whole.csv" >/dev/null || fail "map failed"
    "$impactkit" "${long[@]}" --checkpoint "$work/cp" --out "$work/resumed.csv" >/dev/null &
    pid=$!
    for _ in $(seq 200); do
      (($(find "$work/cp" -name 'unit-*.txt' 2>/dev/null | wc -l) >= 3)) && break
      sleep 0.02
    done
    kill -9 $pid 2>/dev/null || fail "the run ended before it could be killed"
    wait $pid 2>/dev/null || true
    [[ ! -e $work/resumed.csv ]] || fail "a killed run wrote its CSV"
    finished=$(find "$work/cp" -name 'unit-*.txt' | wc -l)
    ((finished >= 3 && finished < 60)) || fail "$finished units on record, expected 3 to 59"
    "$impactkit" "${long[@]}" --checkpoint "$work/cp" --out "$work/resumed.csv" \
      >"$work/stdout" || fail "the resumed run failed"
    expected="($((600 - 10 * finished)) computed, $((10 * finished)) resumed from the checkpoint)"
    grep -qF "$expected" "$work/stdout" || fail "expected '$expected': $(cat "$work/stdout")"
    same_but_command "$work/whole.csv" "$work/resumed.csv" || fail "the resumed CSV differs"
    # The same directory for another grid is refused, and left as it was.
    refused "belongs to another run" "$impactkit" "${grid[@]}" --checkpoint "$work/cp"
    echo ok
    ;;
  damaged)
    "$impactkit" "${grid[@]}" --out "$work/whole.csv" >/dev/null || fail "map failed"
    "$impactkit" "${grid[@]}" --checkpoint "$work/cp" >/dev/null || fail "the checkpointed map failed"
    edited=$(grep -l ' periodic ' "$work"/cp/unit-*.txt | head -1)
    [[ -n $edited ]] || fail "no unit holds a periodic cell"
    sed -i '0,/ periodic /s// chaotic /' "$edited"
    others=($(ls "$work"/cp/unit-*.txt | grep -vx "$edited" | head -2))
    # Their cells: every line but the checksum line of each.
    recomputed=$(($(cat "$edited" "${others[@]}" | wc -l) - 3))
    truncate -s 20 "${others[0]}"
    : >"${others[1]}"
    unit_of() { basename "$1" .txt | sed 's/unit-//'; }
    damaged=$(for f in "$edited" "${others[@]}"; do unit_of "$f"; done | sort -n)
    "$impactkit" "${grid[@]}" --checkpoint "$work/cp" --out "$work/resumed.csv" \
      >"$work/stdout" 2>"$work/stderr" || fail "the resumed run failed: $(cat "$work/stderr")"
    warned=$(sed -n 's/^impactkit: warning: checkpoint unit \([0-9]*\) is damaged (.*); computing it again$/\1/p' \
      "$work/stderr")
    [[ $warned == "$damaged" && $(wc -l <"$work/stderr") -eq 3 ]] ||
      fail "expected a warning for each of units $(echo $damaged), got: $(cat "$work/stderr")"
    expected="($recomputed computed, $((65 - recomputed)) resumed from the checkpoint)"
    grep -qF "$expected" "$work/stdout" || fail "expected '$expected': $(cat "$work/stdout")"
    same_but_command "$work/whole.csv" "$work/resumed.csv" || fail "the resumed CSV differs"
    # The units computed again are on record, whole.
    "$impactkit" "${grid[@]}" --checkpoint "$work/cp" >"$work/stdout" 2>"$work/stderr" ||
      fail "the second resume failed"
    [[ ! -s $work/stderr ]] || fail "warned again: $(cat "$work/stderr")"
    grep -qF "(0 computed, 65 resumed" "$work/stdout" || fail "not all resumed: $(cat "$work/stdout")"
    # A damaged run.txt says whose units these are: refused, as damaged.
    sed -i 's/units=15/units=16/' "$work/cp/run.txt"
    refused "run.txt is damaged" "$impactkit" "${grid[@]}" --checkpoint "$work/cp"
    echo ok
    ;;
  plot)
    command -v gnuplot >/dev/null || { echo "gnuplot not installed: skipped"; exit 77; }
    cat >"$work/curves.json" <<'JSON'
{"curves": [
  {"type": "period_doubling", "p": 1, "q": 1, "params": ["omega", "r"],
   "points": [{"omega": 1.61, "r": 0.5}, {"omega": 1.62, "r": 0.9}]},
  {"type": "fold", "p": 1, "q": 2, "params": ["omega", "xs"],
   "points": [{"omega": 1.8, "xs": 0.1}, {"omega": 1.9, "xs": 0.2}]}]}
JSON
    "$impactkit" "${grid[@]}" --plot "$work/map.png" --curves "$work/curves.json" >/dev/null ||
      fail "map --plot --curves failed"
    [[ $(head -c 8 "$work/map.png" | od -An -tx1 | tr -d ' \n') == 89504e470d0a1a0a ]] ||
      fail "map.png is not a PNG"
    echo '{"lines": []}' >"$work/bad.json"
    status=0
    "$impactkit" "${grid[@]}" --plot "$work/bad.png" --curves "$work/bad.json" \
      >"$work/stdout" 2>"$work/stderr" || status=$?
    [[ $status -eq 2 && $(wc -l <"$work/stderr") -eq 1 && ! -e $work/bad.png ]] ||
      fail "bad curves: status $status, stderr $(cat "$work/stderr")"
    grep -q "curves file .*bad.json" "$work/stderr" || fail "message: $(cat "$work/stderr")"
    echo ok
    ;;
  full)
    # The class columns: map omega,r,kind,p,q; basins x2,v2,attractor,kind,p,q;
    # sweep summary omega,kind,p,q.
    basins=(basins --omega 1.7 --coord x1 --from -2 --to 2 --steps 4 --coord2 v1 --from2 -2
            --to2 2 --steps2 4 --transient 300 --record 40)
    sweep=(sweep --from 0.1 --to 2.5 --steps 25 --transient 300 --record 40 --chunk 5)
    declare -A outs=([grid]=--out [basins]=--out [sweep]=--summary)
    declare -A class_columns=([grid]='$1","$2","$3","$4","$5' [basins]='$1","$2","$3","$4","$5","$6'
                              [sweep]='$1","$2","$3","$4')
    for run in grid basins sweep; do
      declare -n command=$run
      out=${outs[$run]} columns=${class_columns[$run]}
      # Not `| grep -q`: with pipefail, grep's early exit would fail the pipe.
      [[ $("$impactkit" "${command[0]}" --help) == *--full-transient* ]] ||
        fail "$run --help does not list --full-transient"
      "$impactkit" "${command[@]}" "$out" "$work/$run-early.csv" >/dev/null || fail "$run failed"
      "$impactkit" "${command[@]}" --full-transient "$out" "$work/$run-full.csv" >/dev/null ||
        fail "$run --full-transient failed"
      grep -q '^# run: .* full_transient' "$work/$run-full.csv" ||
        fail "$run --full-transient is not in its provenance"
      ! grep -q 'full_transient' "$work/$run-early.csv" ||
        fail "$run without --full-transient says full_transient"
      diff <(awk -F, "!/^#/ { print $columns }" "$work/$run-early.csv") \
        <(awk -F, "!/^#/ { print $columns }" "$work/$run-full.csv") ||
        fail "$run classes cells differently with --full-transient"
      unset -n command
    done
    echo ok
    ;;
  basins)
    "$impactkit" basins --omega 2 --coord x2 --from -1 --to 0.1 --steps 6 --coord2 v2 \
      --from2 -1.5 --to2 1.5 --steps2 6 --transient 300 --record 40 --json "$work/basins.json" \
      --out "$work/basins.csv" >/dev/null || fail "basins failed"
    "$impactkit" orbit --omega 2 --p 1 --q 2 --json "$work/orbit.json" >/dev/null ||
      fail "orbit failed"
    # Every start reaches attractor 1, periodic P(1,2).
    [[ $(awk -F, '!/^#/ && ++row > 1 && $3 == 1 && $4 == "periodic" && $5 == 1 && $6 == 2' \
      "$work/basins.csv" | wc -l) -eq 36 ]] || fail "not all 36 starts reach P(1,2)"
    grep -q '"share": 1.0' "$work/basins.json" || fail "the share of P(1,2) is not 1"
    [[ $(grep -c '"id":' "$work/basins.json") -eq 1 ]] || fail "more than one attractor"
    # JSON values "key": number, one per line, as both commands write them.
    value() { awk -F': ' -v key="\"$2\"" '$1 ~ key"$" { gsub(/,/, "", $2); print $2; exit }' "$1"; }
    awk -v a="$(value "$work/basins.json" phase)" -v b="$(value "$work/orbit.json" phase)" \
      -v c="$(value "$work/basins.json" velocity)" -v d="$(value "$work/orbit.json" velocity)" \
      'BEGIN { e1 = a - b; e2 = c - d; exit !(a != "" && c != "" && e1 * e1 < 1e-12 && e2 * e2 < 1e-12) }' ||
      fail "orbit of the attractor differs from the orbit's fixed point by more than 1e-6"
    echo ok
    ;;
  *) fail "unknown mode $mode" ;;
esac
