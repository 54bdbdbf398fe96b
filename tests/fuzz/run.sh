#!/usr/bin/env bash
# Runs one libFuzzer target of tests/fuzz/ for a bounded time from its corpus in the tree.
#   bash tests/fuzz/run.sh TARGET SECONDS CORPUS WORKDIR [LIBFUZZER-OPTIONS...]
# New inputs libFuzzer finds go to WORKDIR/corpus (the corpus in the tree is only read), a
# crashing input to WORKDIR/crashes/ (its path is printed). Exit status: libFuzzer's, so 0
# when no input crashed within SECONDS. ctest runs it (tests/fuzz/CMakeLists.txt); by hand,
# e.g. ten minutes of fuzz_toml:
#   bash tests/fuzz/run.sh build-sanitize/tests/fuzz/fuzz_toml 600 tests/fuzz/corpus/fuzz_toml /tmp/ft
set -euo pipefail
target=$1 seconds=$2 corpus=$3 work=$4
shift 4
mkdir -p "$work/corpus" "$work/crashes"
# -timeout: one input taking longer is a crash, a hang (every command is cancelled at its first long
# step, so none should take long). -rss_limit_mb: two targets run at once beside the suite.
# Leaks are checked (LeakSanitizer) as in the rest of the sanitized suite.
exec "$target" -max_total_time="$seconds" -timeout=120 -rss_limit_mb=4096 -print_final_stats=1 \
  -artifact_prefix="$work/crashes/" "$@" "$work/corpus" "$corpus"
