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
echo "install_consumer: find_package(bouncer) works"
