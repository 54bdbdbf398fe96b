#!/usr/bin/env bash
# `cmake --install` the library, then build and run a separate project that uses it
# through find_package(bouncer) (tests/consumer).
set -euo pipefail
bouncer=$1
src=$2
build=$(cd "$(dirname "$bouncer")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" >/dev/null
cmake -S "$src/tests/consumer" -B "$tmp/consumer" -DCMAKE_PREFIX_PATH="$tmp/prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$tmp/consumer" >/dev/null
"$tmp/consumer/consumer"  # prints the certified step; exits 1 if it is not a narrow enclosure of the fixed point
# A sanitized install (BOUNCER_SANITIZE=ON, build-sanitize/): the consumer has no sanitizer
# flags of its own; the exported target must carry -fsanitize to its compile and link lines,
# or the sanitized libbouncer.a would not link. The consumer built, linked and ran above;
# here: the flags came from the target, and the consumer runs with the ASan runtime.
targets=$(cat "$tmp/prefix"/lib*/cmake/bouncer/bouncerTargets.cmake)
if [[ $targets == *-fsanitize=address,undefined* ]]; then
  [[ $targets == *INTERFACE_LINK_OPTIONS*-fsanitize=address,undefined* ]] || {
    echo "FAIL: the sanitized bouncer::bouncer has no -fsanitize link option for consumers" >&2; exit 1; }
  grep -q fsanitize "$src/tests/consumer/CMakeLists.txt" && {
    echo "FAIL: tests/consumer sets sanitizer flags itself" >&2; exit 1; }
  [[ $(ldd "$tmp/consumer/consumer") == *libasan* ]] || {
    echo "FAIL: the consumer of the sanitized install is not linked with the ASan runtime" >&2; exit 1; }
  echo "install_consumer: a consumer without sanitizer flags links and runs against the sanitized install"
fi
echo "install_consumer: find_package(bouncer) works"
# The Python module (when this build has it) is installed into the prefix's Python directory
# and imports from there alone, away from the source and build trees.
if compgen -G "$build/python/bouncer/_core*.so" >/dev/null; then
  python=$(sed -n 's/^Python3_EXECUTABLE:[A-Z]*=//p' "$build/CMakeCache.txt")
  core=$(find "$tmp/prefix" -name '_core*.so' -path '*/bouncer/*' | head -n 1)
  [[ -n $core ]] || { echo "FAIL: cmake --install did not install the Python module" >&2; exit 1; }
  site=$(dirname "$(dirname "$core")")
  [[ $site == "$tmp/prefix"/lib/python3*/*-packages ]] || { echo "FAIL: the module went to $site" >&2; exit 1; }
  (cd "$tmp" && PYTHONPATH="$site" "$python" -c "
import bouncer
assert bouncer.__file__.startswith('$site'), bouncer.__file__
s = bouncer.step(model='constant', a='24', eps='0.5', theta='0.25', v='12')
assert s['event'] == 'impact', s
print('install_consumer: import bouncer works from', '$site'.replace('$tmp', '<prefix>'))
")
fi
