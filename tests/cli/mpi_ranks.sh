#!/usr/bin/env bash
# End-to-end: under mpirun the ranks are the shards. Two ranks split a basin's tiles and rank
# 0 writes the outputs, whose rows are those of the same basin computed by one process.
# Exit 77 (ctest: skipped) when the binary was built without MPI or mpirun is missing;
# tools/setup installs Open MPI, so in CI it runs.
# Usage: bash mpi_ranks.sh <bouncer-binary> <source-dir>
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
if ! command -v mpirun >/dev/null || [[ $(ldd "$BOUNCER" 2>/dev/null) != *libmpi* ]]; then
  skip "the binary is not built with MPI, or mpirun is missing (apt-get install libopenmpi-dev openmpi-bin)"
fi
BA=(basin --model constant --a 24 --eps 0.5 --theta-range 0:1 --v-range 2:20 --transient 200 --steps 100 --grid 8x6 --quiet)
"$BOUNCER" "${BA[@]}" --threads 1 --out "$TMP/one" || die "the one-process basin: exit $?"
# Under AddressSanitizer (build-sanitize/, `tools/setup sanitize`), LeakSanitizer reports
# Open MPI's own allocations (MPI_Init/MPI_Finalize and its dlopen'ed components) as leaks,
# with no bouncer frame; the components are unloaded before the report, so their frames
# cannot even be named in a suppression file. The leak check is off for this one run only.
mpi_env=()
if asan_build; then
  echo "mpi_ranks: AddressSanitizer build: leak check off for the mpirun run (Open MPI's own allocations)"
  mpi_env=(env "ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0")
fi
if ! "${mpi_env[@]}" mpirun --allow-run-as-root --oversubscribe -n 2 "$BOUNCER" "${BA[@]}" --threads 1 --out "$TMP/mpi" \
    >"$TMP/mpi.stdout" 2>"$TMP/mpi.stderr"; then
  die "mpirun -n 2 failed: $(head -c 400 "$TMP/mpi.stderr")"
fi
outputs mpi "$TMP/mpi"
cmp -s <(data "$TMP/mpi.csv") <(data "$TMP/one.csv") || fail mpi "2 MPI ranks differ from one process"
finish "mpi_ranks: 2 ranks give the one-process rows"
