#!/usr/bin/env bash
# `cmake --install` the library, then build and run a separate project that uses it
# through find_package(bouncer) (tests/consumer); LICENSE, CITATION.cff and CHANGELOG.md are
# installed in share/doc/bouncer.
# Usage: bash install_consumer.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
build=$(cd "$(dirname "$BOUNCER")/.." && pwd)
cmake --install "$build" --prefix "$TMP/prefix" >/dev/null
# The licence, the citation and the changelog go with it, as in the source.
for f in LICENSE CITATION.cff CHANGELOG.md; do
  cmp -s "$SRC/$f" "$TMP/prefix/share/doc/bouncer/$f" || die "cmake --install did not install $f in share/doc/bouncer"
done
cmake -S "$SRC/tests/consumer" -B "$TMP/consumer" -DCMAKE_PREFIX_PATH="$TMP/prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$TMP/consumer" >/dev/null
"$TMP/consumer/consumer"  # prints the certified step; exits 1 if it is not a narrow enclosure of the fixed point
# A sanitized install (BOUNCER_SANITIZE=ON, build-sanitize/): the consumer has no sanitizer
# flags of its own; the exported target must carry -fsanitize to its compile and link lines,
# or the sanitized libbouncer.a would not link. The consumer built, linked and ran above;
# here: the flags came from the target, and the consumer runs with the ASan runtime.
targets=$(cat "$TMP/prefix"/lib*/cmake/bouncer/bouncer*Targets.cmake)
if [[ $targets == *-fsanitize=address,undefined* ]]; then
  [[ $targets == *INTERFACE_LINK_OPTIONS*-fsanitize=address,undefined* ]] ||
    die "the sanitized bouncer::numerics has no -fsanitize link option for consumers"
  grep -q fsanitize "$SRC/tests/consumer/CMakeLists.txt" && die "tests/consumer sets sanitizer flags itself"
  [[ $(ldd "$TMP/consumer/consumer") == *libasan* ]] ||
    die "the consumer of the sanitized install is not linked with the ASan runtime"
  echo "install_consumer: a consumer without sanitizer flags links and runs against the sanitized install"
fi
echo "install_consumer: find_package(bouncer COMPONENTS numerics) works"
# The whole library (both components, the I/O layer with Cairo): a scene read and its
# provenance written through bouncer::bouncer.
cmake -S "$SRC/tests/consumer/io" -B "$TMP/consumer-io" -DCMAKE_PREFIX_PATH="$TMP/prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$TMP/consumer-io" >/dev/null
"$TMP/consumer-io/consumer_io" "$SRC/data/scenes/default.toml" | grep -q '^# bouncer ' ||
  die "the consumer of bouncer::bouncer did not write the provenance of a scene"
echo "install_consumer: find_package(bouncer) and bouncer::bouncer work"
# pkg-config, beside the CMake package (lib/pkgconfig/bouncer.pc): the same consumer
# compiled and linked with nothing but `pkg-config --cflags --libs bouncer`, its prefix
# found from the .pc file's own place (the install was made to a temporary prefix).
pc=$(find "$TMP/prefix" -name bouncer.pc -path '*/pkgconfig/*' | head -n 1)
[[ -n $pc ]] || die "cmake --install did not install bouncer.pc"
flags=$(PKG_CONFIG_PATH=$(dirname "$pc") pkg-config --cflags --libs bouncer) || die "pkg-config --cflags --libs bouncer failed"
[[ $flags == *"-I$TMP/prefix/"*include* ]] || die "pkg-config's include directory is not the prefix's: $flags"
compiler=$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' "$build/CMakeCache.txt")
# shellcheck disable=SC2086  # the flags are words
"$compiler" -o "$TMP/consumer-pc" "$SRC/tests/consumer/io/main.cpp" $flags || die "the pkg-config consumer did not build"
"$TMP/consumer-pc" "$SRC/data/scenes/default.toml" | grep -q '^# bouncer ' ||
  die "the pkg-config consumer did not write the provenance of a scene"
echo "install_consumer: pkg-config --cflags --libs bouncer works"
# The Python module (when this build has it) is installed into the prefix's Python directory
# and imports from there alone, away from the source and build trees.
if compgen -G "$build/python/bouncer/_core*.so" >/dev/null; then
  python=$(sed -n 's/^Python3_EXECUTABLE:[A-Z]*=//p' "$build/CMakeCache.txt")
  core=$(find "$TMP/prefix" -name '_core*.so' -path '*/bouncer/*' | head -n 1)
  [[ -n $core ]] || die "cmake --install did not install the Python module"
  site=$(dirname "$(dirname "$core")")
  [[ $site == "$TMP/prefix"/lib/python3*/*-packages ]] || die "the module went to $site"
  (cd "$TMP" && PYTHONPATH="$site" "$python" -c "
import bouncer
assert bouncer.__file__.startswith('$site'), bouncer.__file__
s = bouncer.step(model='constant', a='24', eps='0.5', theta='0.25', v='12')
assert s['event'] == 'impact', s
print('install_consumer: import bouncer works from', '$site'.replace('$TMP', '<prefix>'))
")
fi
