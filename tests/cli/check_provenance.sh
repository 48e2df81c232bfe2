# Usage: check_provenance.sh IMPACTKIT SYSTEM_FILE
# Every output file of every subcommand says what produced it (docs/cli.md,
# "Output files"): CSV comment lines "impactkit VERSION", "command: " (the
# command as typed), "system: " (the file with its CRC-32, or the
# built-in system), "parameters: ", "run: "; a JSON's "provenance" object with
# the same. The hash is recomputed here, independently, with Python.
source "$(dirname "$0")/testlib.sh"
impactkit=$1
system_file=$2
version=$("$impactkit" --version | awk '{ print $2 }')
crc=$(python3 -c '
import sys, zlib
data = open(sys.argv[1], "rb").read()
print("%08x" % zlib.crc32(data))' "$system_file")

# check_csv FILE COMMAND-WORDS [SYSTEM]: the header of FILE, written by the
# run `impactkit COMMAND-WORDS`, with SYSTEM the --system file if any.
check_csv() {
  local file=$1 command=$2 system=${3:-}
  local want_system="the paper's system (built in)"
  [[ -n $system ]] && want_system="$system (CRC-32 $crc)"
  mapfile -t head < <(grep '^#' "$file")
  [[ ${#head[@]} == 5 ]] || fail "$file: ${#head[@]} comment lines, want 5"
  [[ ${head[0]} == "# impactkit $version" ]] || fail "$file: version line '${head[0]}'"
  [[ ${head[1]} == "# command: impactkit $command" ]] || fail "$file: command line '${head[1]}'"
  [[ ${head[2]} == "# system: $want_system" ]] || fail "$file: system line '${head[2]}'"
  [[ ${head[3]} == "# parameters: "*omega=*xs=*r=* ]] || fail "$file: parameters line '${head[3]}'"
  [[ ${head[4]} == "# run: "?* ]] || fail "$file: run line '${head[4]}'"
}

# check_json FILE COMMAND-WORDS [SYSTEM]: the same in FILE's "provenance".
check_json() {
  python3 - "$1" "impactkit $2" "${3:-}" "$version" "$crc" <<'PY' || fail "$1: bad provenance"
import json, sys
path, command, system, version, crc = sys.argv[1:]
p = json.load(open(path))["provenance"]
want = {"impactkit_version": version, "command": command,
        "system_file": system or None, "system_crc32": crc if system else None}
for key, value in want.items():
    if p.get(key) != value:
        sys.exit(f"{path}: provenance {key} = {p.get(key)!r}, want {value!r}")
if "omega=" not in p["parameters"] or not p["run"]:
    sys.exit(f"{path}: provenance parameters/run: {p}")
PY
}

# run WORDS...: impactkit WORDS, in $work, its stdout kept out of the way.
run() {
  (cd "$work" && "$impactkit" "$@" >stdout 2>stderr) || fail "impactkit $*: $(cat "$work/stderr")"
}

cp "$system_file" "$work/system.toml"
run simulate --system system.toml --periods 2 --transient 2 --series s.csv --impacts i.csv --json s.json
for f in s.csv i.csv; do
  check_csv "$work/$f" "simulate --system system.toml --periods 2 --transient 2 --series s.csv --impacts i.csv --json s.json" system.toml
done
check_json "$work/s.json" "simulate --system system.toml --periods 2 --transient 2 --series s.csv --impacts i.csv --json s.json" system.toml

run orbit --omega 1.2 --json o.json
check_json "$work/o.json" "orbit --omega 1.2 --json o.json"
run orbit --omega 0.2 --json os.json
check_json "$work/os.json" "orbit --omega 0.2 --json os.json"

run continue --from 1.0 --to 1.1 --out c.csv --json c.json
check_csv "$work/c.csv" "continue --from 1.0 --to 1.1 --out c.csv --json c.json"
check_json "$work/c.json" "continue --from 1.0 --to 1.1 --out c.csv --json c.json"
run continue --from 0.2 --to 0.19 --out cs.csv --json cs.json
check_csv "$work/cs.csv" "continue --from 0.2 --to 0.19 --out cs.csv --json cs.json"
check_json "$work/cs.json" "continue --from 0.2 --to 0.19 --out cs.csv --json cs.json"

curve=(curve --type period_doubling --p 1 --q 1 --omega 1.6 --param omega --param2 r --from2 0.69 --to2 0.71 --out k.csv --json k.json)
run "${curve[@]}"
check_csv "$work/k.csv" "${curve[*]}"
check_json "$work/k.json" "${curve[*]}"

run diagram --from 1.0 --to 1.1 --start 1.05 --sweep-values 0 --json d.json
check_json "$work/d.json" "diagram --from 1.0 --to 1.1 --start 1.05 --sweep-values 0 --json d.json"

sweep=(sweep --from 0.6 --to 0.7 --steps 2 --transient 10 --record 5 --out w.csv --summary ws.csv)
run "${sweep[@]}"
check_csv "$work/w.csv" "${sweep[*]}"
check_csv "$work/ws.csv" "${sweep[*]}"

run impactmap --omega 1.72 --transient 10 --periods 20 --out im.csv
check_csv "$work/im.csv" "impactmap --omega 1.72 --transient 10 --periods 20 --out im.csv"
returnmap=(returnmap --omega 1.72 --periods 1000 --bound 0.3 --fit --out rm.csv --json rm.json)
run "${returnmap[@]}"
check_csv "$work/rm.csv" "${returnmap[*]}"
check_json "$work/rm.json" "${returnmap[*]}"
run lyapunov --omega 1.2 --impacts 50 --json l.json
check_json "$work/l.json" "lyapunov --omega 1.2 --impacts 50 --json l.json"
run resonance --steps 3 --out res.csv
check_csv "$work/res.csv" "resonance --steps 3 --out res.csv"

map=(map --from 0.6 --to 0.7 --steps 2 --param2 r --from2 0.6 --to2 0.7 --steps2 2 --transient 10 --record 5 --threads 1 --out m.csv --json m.json)
run "${map[@]}"
check_csv "$work/m.csv" "${map[*]}"
check_json "$work/m.json" "${map[*]}"
basins=(basins --omega 2 --coord x2 --from -1 --to 0.1 --steps 2 --coord2 v2 --from2 -1 --to2 1 --steps2 2 --transient 10 --record 5 --threads 1 --out b.csv --json b.json)
run "${basins[@]}"
check_csv "$work/b.csv" "${basins[*]}"
check_json "$work/b.json" "${basins[*]}"

# A figure records the version and the command in an iTXt chunk; the chunks
# are read here by their layout (PNG 1.2), each CRC checked with zlib's.
if command -v gnuplot >/dev/null; then
  run simulate --periods 2 --plot p.png
  python3 - "$work/p.png" "impactkit $version" "command: impactkit simulate --periods 2 --plot p.png" <<'PY' ||
import struct, sys, zlib
path, version, command = sys.argv[1:]
data = open(path, "rb").read()
assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
at, texts = 8, {}
while at < len(data):
    (length,) = struct.unpack(">I", data[at:at + 4])
    kind, body = data[at + 4:at + 8], data[at + 8:at + 8 + length]
    (crc,) = struct.unpack(">I", data[at + 8 + length:at + 12 + length])
    assert zlib.crc32(kind + body) == crc, f"bad CRC in {kind}"
    if kind == b"iTXt":
        keyword, rest = body.split(b"\0", 1)
        texts[keyword.decode()] = rest[2:].split(b"\0", 2)[2].decode()
    at += 12 + length
assert texts.get("Description") == version + "\n" + command, texts
PY
    fail "p.png: no provenance text chunk"
fi

# A word with characters a shell treats specially is quoted so that the
# command line can be pasted back.
run resonance --steps 3 --out 'a b.csv'
check_csv "$work/a b.csv" "resonance --steps 3 --out 'a b.csv'"
echo "ok: provenance"
