#!/usr/bin/env bash
# Links and FIFOs planted at every output and staging path of every command that writes
# files: never followed, never a hang (tests/cli/planted_paths.py says what is checked).
# Usage: bash planted_paths.sh <bouncer-binary> <source-dir>
set -euo pipefail
BOUNCER=${1:?usage: bash planted_paths.sh <bouncer-binary> <source-dir>}
SRC=${2:?usage: bash planted_paths.sh <bouncer-binary> <source-dir>}
exec python3 "$SRC/tests/cli/planted_paths.py" "$BOUNCER"
