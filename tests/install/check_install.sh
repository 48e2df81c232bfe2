#!/usr/bin/env bash
# The C++ user's path: `cmake --install` the build tree into a fresh prefix,
# configure and build tests/install/consumer against it with find_package
# (nothing but the prefix on CMAKE_PREFIX_PATH), run the consumer on the
# shipped examples/systems/paper.json, and check that it finds the paper's
# stable P(2,1) at Ω = 0.6 with the impacts the installed `impactkit orbit`
# finds; the license is installed in share/doc/impactkit.
#
#     check_install.sh CMAKE BUILD_DIR SOURCE_DIR CXX_COMPILER CONFIG
source "$(dirname "$0")/../cli/testlib.sh"
cmake=$1 build=$2 source=$3 cxx=$4 config=${5:-Release}
prefix=$work/prefix

"$cmake" --install "$build" --config "$config" --prefix "$prefix" >"$work/install.log" 2>&1 ||
  fail "cmake --install $build failed: $(cat "$work/install.log")"
for file in include/impactkit/impactkit.hpp include/impactkit/io/system_file.hpp include/impactkit/core/errors.hpp; do
  [[ -f $prefix/$file ]] || fail "not installed: $file"
done
# The license travels with the package (and the citation beside it).
cmp -s "$source/LICENSE" "$prefix/share/doc/impactkit/LICENSE" ||
  fail "not installed, or not the source's: share/doc/impactkit/LICENSE"
[[ -f $prefix/share/doc/impactkit/CITATION.cff ]] || fail "not installed: share/doc/impactkit/CITATION.cff"
package_config=$(find "$prefix" -name impactkitConfig.cmake -print -quit)
[[ -n $package_config ]] || fail "no impactkitConfig.cmake under $prefix"

# The package registry off, so that only the prefix can provide impactkit.
"$cmake" -S "$source/tests/install/consumer" -B "$work/consumer" \
  -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE="$config" \
  -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF >"$work/configure.log" 2>&1 ||
  fail "configuring the consumer failed: $(cat "$work/configure.log")"
found=$(sed -n 's/^impactkit_DIR:PATH=//p' "$work/consumer/CMakeCache.txt")
[[ $found == "$prefix"/* ]] || fail "find_package found impactkit in '$found', not in $prefix"
"$cmake" --build "$work/consumer" --config "$config" >"$work/build.log" 2>&1 ||
  fail "building the consumer failed: $(cat "$work/build.log")"

"$work/consumer/consumer" "$source/examples/systems/paper.json" >"$work/stdout" ||
  fail "the consumer failed: $(cat "$work/stdout")"
grep -qx 'P(2,1) at omega = 0.6, stable' "$work/stdout" || fail "consumer printed: $(cat "$work/stdout")"
[[ $(grep -c '^impact ' "$work/stdout") -eq 2 ]] || fail "expected 2 impacts: $(cat "$work/stdout")"

# The same orbit from the installed program (when the apps are built).
if [[ -x $prefix/bin/impactkit ]]; then
  "$prefix/bin/impactkit" orbit --omega 0.6 --json "$work/orbit.json" >/dev/null ||
    fail "the installed impactkit orbit failed"
  # Each impact is an object {"phase": ..., "t": ..., "velocity": ...} (any key order).
  tr -d ' \n' <"$work/orbit.json" | grep -o '{[^{}]*"phase"[^{}]*}' >"$work/impacts"
  sed 's/.*"phase":\([^,}]*\).*/\1/' "$work/impacts" >"$work/phases"
  sed 's/.*"velocity":\([^,}]*\).*/\1/' "$work/impacts" >"$work/speeds"
  paste -d' ' "$work/phases" "$work/speeds" >"$work/expected"
  awk '$1 == "impact" { print $2, $3 }' "$work/stdout" >"$work/actual"
  paste -d' ' "$work/expected" "$work/actual" | awk '
    NF != 4 { print "row " NR ": " $0; bad = 1; next }
    { for (i = 1; i <= 2; i++) { d = $i - $(i + 2); if (d < 0) d = -d
        if (d > 1e-8) { print "impact " NR ": " $i " vs " $(i + 2); bad = 1 } } }
    END { if (NR != 2) { print NR " impacts"; bad = 1 }; exit bad }' ||
    fail "the consumer's orbit differs from impactkit orbit's"
fi
echo "ok: consumer built against $prefix"
