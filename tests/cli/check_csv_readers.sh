# Usage: check_csv_readers.sh IMPACTKIT PYTHON3
# Every kind of CSV the tool writes opens with the recipes docs/cli.md
# gives ("Output files"): pandas.read_csv(f, comment="#"),
# numpy.genfromtxt(f, delimiter=",", names=True, comments="#") and gnuplot
# (separator ",", `every ::1`). PYTHON3 has numpy and pandas (Debian's).
# Each table is read by both Python recipes; they must find the header's
# columns, every row, and the same numbers. gnuplot plots one table, and the
# points it draws must be that table's.
source "$(dirname "$0")/testlib.sh"
impactkit=$1
python=$2

# run WORDS...: impactkit WORDS, in $work.
run() {
  (cd "$work" && "$impactkit" "$@" >stdout 2>stderr) || fail "impactkit $*: $(cat "$work/stderr")"
}

run simulate --periods 20 --transient 2 --series series.csv --impacts impacts.csv
# The main branch and the period-doubled one's FILE.<label>.csv.
run continue --from 1.8 --to 2.0 --start 1.9 --switch-pd --out branch.csv
run continue --from 0.2 --to 0.19 --out sticking.csv
run curve --type period_doubling --p 1 --q 1 --omega 1.6 --param omega --param2 r \
  --from2 0.69 --to2 0.71 --out curve.csv
run sweep --from 0.6 --to 0.7 --steps 2 --transient 10 --record 5 --out sweep.csv \
  --summary sweep-summary.csv
run impactmap --omega 1.72 --transient 10 --periods 20 --out impactmap.csv
run returnmap --omega 1.72 --periods 1000 --bound 0.3 --fit --out returnmap.csv
run resonance --steps 3 --out resonance.csv
run map --from 0.6 --to 0.7 --steps 2 --param2 r --from2 0.6 --to2 0.7 --steps2 2 \
  --transient 10 --record 5 --threads 1 --out map.csv
run basins --omega 2 --coord x2 --from -1 --to 0.1 --steps 2 --coord2 v2 --from2 -1 --to2 1 \
  --steps2 2 --transient 10 --record 5 --threads 1 --out basins.csv
# The main job's own tables: its Fig. 3 sweep, and a branch as `continue` writes it.
run paper --quick --out paper

kinds=(series impacts branch branch.pd1 sticking curve sweep sweep-summary impactmap returnmap
  resonance map basins)
for kind in "${kinds[@]}"; do
  [[ -s $work/$kind.csv ]] || fail "$kind.csv was not written"
done
[[ $(ls "$work"/*.csv | wc -l) -eq ${#kinds[@]} ]] || fail "CSVs not in the list: $(ls "$work")"
tables=("$work"/*.csv "$work/paper/fig3-sweep.csv" "$work/paper/branch-main.csv")

"$python" - "${tables[@]}" <<'PY' || fail "a reader's recipe failed (above)"
import sys
import warnings

import numpy as np
import pandas as pd

warnings.simplefilter("error")  # a reader that complains has not read the table as it is
for path in sys.argv[1:]:
    with open(path) as f:
        lines = f.read().splitlines()
    header = lines[0].split(",")
    rows = [line.split(",") for line in lines[1:] if not line.startswith("#")]
    assert rows, f"{path}: no rows"
    table = pd.read_csv(path, comment="#")
    exact = pd.read_csv(path, comment="#", float_precision="round_trip")
    assert list(table.columns) == header, f"{path}: pandas columns {list(table.columns)}"
    assert len(table) == len(rows), f"{path}: pandas read {len(table)} rows of {len(rows)}"
    array = np.genfromtxt(path, delimiter=",", names=True, comments="#")
    assert list(array.dtype.names) == header, f"{path}: numpy names {array.dtype.names}"
    assert array.size == len(rows), f"{path}: numpy read {array.size} rows of {len(rows)}"
    numeric = [c for c in header if pd.api.types.is_numeric_dtype(table[c])]
    assert numeric, f"{path}: pandas found no numeric column"
    for i, column in enumerate(header):
        if column not in numeric:
            continue
        # numpy reads every bit of the shortest round-trip text written, and
        # so does pandas with float_precision="round_trip"; its default, fast
        # parser is off in the last digits (seen: 4e-13 relative), as
        # docs/cli.md says.
        written = np.array([float(r[i]) if r[i] else np.nan for r in rows])
        np.testing.assert_array_equal(array[column], written, err_msg=f"{path}: {column}")
        np.testing.assert_array_equal(exact[column].to_numpy(float), written,
                                      err_msg=f"{path}: {column}")
        np.testing.assert_allclose(table[column].to_numpy(float), written, rtol=1e-11, atol=0,
                                   err_msg=f"{path}: {column}")
print(f"ok: pandas and numpy read {len(sys.argv) - 1} tables")
PY

# gnuplot draws the impact table's phase against speed; its table of the
# points drawn must be every row, in order.
if ! command -v gnuplot >/dev/null; then fail "gnuplot is not installed"; fi
(cd "$work" && gnuplot -e "set datafile separator ','; set table 'drawn.txt';
  plot 'impacts.csv' every ::1 using 2:3 with points") 2>"$work/gnuplot.log" ||
  fail "gnuplot: $(cat "$work/gnuplot.log")"
"$python" - "$work/impacts.csv" "$work/drawn.txt" <<'PY' || fail "gnuplot did not draw the table"
import sys

import numpy as np
import pandas as pd

table = pd.read_csv(sys.argv[1], comment="#")
with open(sys.argv[2]) as f:
    drawn = np.array([[float(v) for v in line.split()[:2]] for line in f
                      if line.strip() and not line.startswith("#")])
assert drawn.shape == (len(table), 2), f"gnuplot drew {drawn.shape[0]} points of {len(table)}"
np.testing.assert_allclose(drawn, table[["phase", "velocity"]].to_numpy(), rtol=1e-5)
print(f"ok: gnuplot drew the {len(table)} impacts")
PY
echo "ok: every kind of CSV reads with pandas, numpy and gnuplot"
