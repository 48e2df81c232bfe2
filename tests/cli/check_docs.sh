#!/usr/bin/env bash
# Docs examples must not rot: runs every command line (`$ ...`) of the
# ```console blocks of each DOC, in order, with `impactkit` (or
# `./build/apps/impactkit`) standing for the built binary, and fails naming
# the first command that does not do what the doc shows:
#
# - a command whose shown output starts with `impactkit: error:` must exit
#   with status 2 and print exactly that line on stderr;
# - every other command must exit with status 0.
#
# Other output is not compared (run times differ). The commands run in a
# scratch directory holding `out/` and a copy of examples/systems/, so that
# the paths the docs use resolve and nothing is written into the source tree.
#
#     check_docs.sh IMPACTKIT SOURCE_DIR DOC...
source "$(dirname "$0")/testlib.sh"
impactkit=$(realpath "$1")
source_dir=$(realpath "$2")
shift 2

run=$work/run
mkdir -p "$run/out" "$run/examples"
cp -r "$source_dir/examples/systems" "$run/examples/"
# A command runs as `bash -c`, with `impactkit` the built binary.
mkdir "$work/bin"
ln -s "$impactkit" "$work/bin/impactkit"

# Prints "LINE<TAB>COMMAND<TAB>ERROR" for each command of the console blocks
# of a Markdown file: backslash-continued lines joined, ./build/apps/impactkit
# shortened to impactkit, ERROR the first shown output line if it is an
# `impactkit: error:` line (else empty).
extract() {
  awk '
    function flush() { if (command != "") print start "\t" command "\t" error; command = "" }
    /^```console[[:space:]]*$/ { inside = 1; next }
    /^```/ { if (inside) flush(); inside = 0; next }
    !inside { next }
    continued {
      line = $0; sub(/^[[:space:]]+/, "", line); command = command " " line
      continued = sub(/[[:space:]]*\\$/, "", command); next
    }
    /^\$ / {
      flush()
      command = substr($0, 3); sub(/^\.\/build\/apps\/impactkit( |$)/, "impactkit ", command)
      start = NR; error = ""; first_output = 1
      continued = sub(/[[:space:]]*\\$/, "", command); next
    }
    first_output { if ($0 ~ /^impactkit: error:/) error = $0; first_output = 0 }
  ' "$1"
}

total=0
for doc in "$@"; do
  name=${doc#"$source_dir"/}
  commands=$(extract "$doc")
  grep -q $'\timpactkit ' <<<"$commands" || fail "$name: no \`\$ impactkit\` command in a console block"
  while IFS=$'\t' read -r line command error; do
    status=0
    (cd "$run" && PATH="$work/bin:$PATH" bash -c "$command") >"$work/stdout" 2>"$work/stderr" \
      </dev/null || status=$?
    if [[ -n $error ]]; then
      ((status == 2)) || fail "$name:$line: \`$command\` exited with $status, the doc shows an error (2)"
      [[ $(cat "$work/stderr") == "$error" ]] ||
        fail "$name:$line: \`$command\` printed '$(cat "$work/stderr")', the doc shows '$error'"
    else
      ((status == 0)) ||
        fail "$name:$line: \`$command\` exited with status $status: $(head -c 2000 "$work/stderr")"
    fi
    total=$((total + 1))
  done <<<"$commands"
done
echo "ok: $total commands of $* ran as shown"
