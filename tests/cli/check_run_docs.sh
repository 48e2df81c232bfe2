#!/usr/bin/env bash
# The README's promise about the main job must match the scripts that keep
# it. Checked by reading them, not by running scripts/run.sh (minutes):
#
# - every command of the README's "Two commands" block names a file that exists;
# - the folder the README says everything lands in is the one scripts/run.sh
#   writes into (and the one docs/paper-reproduction.md names);
# - scripts/run.sh runs `impactkit paper` into that folder and every
#   examples/fig*.sh, each with the figure and data folders inside it;
# - every examples/fig*.sh takes the arguments run.sh passes
#   ([impactkit binary] [figure folder] [data folder]), and the figures the
#   README says they regenerate are the ones there are;
# - .ci/run runs scripts/test.sh, as the README says.
#
#     check_run_docs.sh SOURCE_DIR
source "$(dirname "$0")/testlib.sh"
cd "$1"
readme=README.md
run=scripts/run.sh

# The fenced block under "## Two commands": `bash FILE  # ...` lines.
block=$(awk '/^## Two commands/ { heading = 1; next }
             heading && /^```/ { if (inside) exit; inside = 1; next }
             inside { print }' "$readme")
[[ -n $block ]] || fail "$readme: no code block under '## Two commands'"
while read -r shell file _; do
  [[ $shell == bash ]] || fail "$readme: '$shell $file' in 'Two commands' is not 'bash FILE'"
  [[ -f $file ]] || fail "$readme: 'bash $file' in 'Two commands', but $file does not exist"
done <<<"$block"
grep -q 'bash scripts/run.sh' <<<"$block" || fail "$readme: 'Two commands' does not run scripts/run.sh"

# The output folder: README's "Everything lands in `DIR/`" against run.sh's out=DIR.
readme_out=$(tr '\n' ' ' <"$readme" | sed -n 's/.*Everything lands in *`\([^`]*\)`.*/\1/p')
readme_out=${readme_out%/}
[[ -n $readme_out ]] || fail "$readme: no 'Everything lands in \`DIR/\`'"
run_out=$(sed -n 's/^out=\([^ #]*\).*/\1/p' "$run")
[[ -n $run_out ]] || fail "$run: no 'out=DIR' line"
[[ $readme_out == "$run_out" ]] ||
  fail "$readme says everything lands in $readme_out/, but $run writes into $run_out/"
reproduction_out=$(sed -n 's/.*impactkit paper --out \([^ ]*\).*/\1/p' docs/paper-reproduction.md | head -1)
[[ $reproduction_out == "$run_out" ]] ||
  fail "docs/paper-reproduction.md says 'impactkit paper --out $reproduction_out', $run uses $run_out"

# run.sh runs `impactkit paper` into the folder, then every figure script.
grep -Eq '"\$impactkit" paper --out "\$out"' "$run" || fail "$run does not run 'impactkit paper --out \"\$out\"'"
grep -q 'bash scripts/setup.sh' "$run" || fail "$run does not run scripts/setup.sh first"
# The scripts run.sh runs: those it names, or all of them through a loop over the glob.
if grep -Eq '^for script in .*examples/fig\*\.sh' "$run" &&
  grep -Eq '^  bash "\$script" "\$impactkit" "\$out/figures" "\$out/data"$' "$run"; then
  all=1
else
  all=0
fi
scripts=(examples/fig*.sh)
((${#scripts[@]} > 0)) || fail "no examples/fig*.sh"
numbers=()
for script in "${scripts[@]}"; do
  name=$(basename "$script")
  if ((all == 0)); then
    grep -Eq "bash (\./)?$script \"\\\$impactkit\" \"\\\$out/figures\" \"\\\$out/data\"" "$run" ||
      fail "$run does not run $script (with \"\$impactkit\" \"\$out/figures\" \"\$out/data\")"
  fi
  grep -Eq "^#   examples/$name \[impactkit binary\] \[figure folder\] \[data folder\]$" "$script" ||
    fail "$script: its usage line is not '#   examples/$name [impactkit binary] [figure folder] [data folder]'"
  number=${name#fig}
  numbers+=("${number%%_*}")
done

# "regenerates the paper's Figs. A–B": the scripts are figs A..B, one each.
range=$(tr '\n' ' ' <"$readme" | sed -n "s/.*regenerates the paper's Figs\. \([0-9]*\)–\([0-9]*\).*/\1 \2/p")
read -r first last <<<"$range"
[[ -n $first && -n $last ]] || fail "$readme: no \"regenerates the paper's Figs. A–B\""
expected=$(seq "$first" "$last" | tr '\n' ' ')
found=$(printf '%s\n' "${numbers[@]}" | sort -n | tr '\n' ' ')
[[ $expected == "$found" ]] ||
  fail "$readme says Figs. $first–$last; examples/fig*.sh are figs $found"

grep -q 'scripts/test.sh' .ci/run || fail ".ci/run does not run scripts/test.sh, as $readme says"
echo "ok: $readme, $run, ${#scripts[@]} figure scripts and .ci/run agree"
