#!/usr/bin/env bash
# A short run of the bad-input fuzzer (tools/fuzz_input.py): 200 random mutations of valid
# command lines and scenes, seed 1 (deterministic). Every run must exit 0, 1 or 2 (no
# signal, sanitizer report or internal error), an exit 2 must print exactly one stderr line
# starting with "bouncer" and leave no output behind, and every run must finish in 60 s.
# Usage: bash fuzz_input.sh <bouncer-binary> <source-dir>
set -euo pipefail
BOUNCER=${1:?usage: bash fuzz_input.sh <bouncer-binary> <source-dir>}
SRC=${2:?usage: bash fuzz_input.sh <bouncer-binary> <source-dir>}
exec python3 "$SRC/tools/fuzz_input.py" --bouncer "$BOUNCER" --cases 200 --seed 1 --jobs 2 --timeout 60
