#!/usr/bin/env bash
# The Debian package (issue 24): `cpack -G DEB` in this build directory makes
# bouncer_VERSION_ARCH.deb; unpacked with `dpkg-deb -x` into a temporary directory (not
# installed: no root needed), the packaged bouncer reproduces claims with its own proof
# programs (a subset: the whole --quick run takes minutes; tests/cli/install_reproduce.sh
# runs every proof's claim), its Python module imports from the packaged dist-packages, and
# the package's Depends name the Debian package of every shared library the programs and
# the module load (dpkg-shlibdeps), and python3 and python3-numpy; its Maintainer is
# CITATION.cff's authors and its Suggests and description name the -dev packages a C++
# developer needs (those cmake/bouncerConfig.cmake.in names). Label `package`; exit 77
# (skipped) without dpkg-deb or dpkg-shlibdeps (Debian's dpkg-dev).
# cpack first builds the build directory's default target (its `preinstall`): in CI
# everything is built already and that is a check only.
# Usage: bash package_deb.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
command -v dpkg-deb >/dev/null || skip "dpkg-deb is missing (Debian's dpkg)"
command -v dpkg-shlibdeps >/dev/null || skip "dpkg-shlibdeps is missing (Debian's dpkg-dev)"
command -v cpack >/dev/null || skip "cpack is missing (cmake)"
build=$(cd "$(dirname "$BOUNCER")/.." && pwd)
version=$(sed -n 's/^CMAKE_PROJECT_VERSION:[A-Z]*=//p' "$build/CMakeCache.txt")
arch=$(dpkg --print-architecture)
cpack -G DEB --config "$build/CPackConfig.cmake" -B "$TMP/deb" > "$TMP/cpack.log" 2>&1 ||
  die "cpack -G DEB failed: $(tail -n 5 "$TMP/cpack.log")"
deb="$TMP/deb/bouncer_${version}_${arch}.deb"
[[ -f $deb ]] || die "no $deb: $(ls "$TMP/deb")"

# The Debian package that owns a library file (dpkg knows /lib and /usr/lib apart: try both,
# and the file a symbolic link names).
owner_of() {
  local f real o
  real=$(readlink -f "$1")
  for f in "$1" "$real" "${1#/usr}" "/usr${1#/usr}" "${real#/usr}" "/usr${real#/usr}"; do
    o=$(dpkg -S "$f" 2>/dev/null || true)
    [[ -n $o ]] && { echo "${o%%:*}"; return 0; }
  done
  return 0
}
# Python: when this build has the module (the sanitized build has not).
python_module=false
compgen -G "$build/python/bouncer/_core*.so" >/dev/null && python_module=true

# Depends: python3, python3-numpy, and the owner of every library the ELF files need.
depends=$(dpkg-deb -f "$deb" Depends)
for p in python3 python3-numpy; do
  [[ ", $depends," == *", $p"[\ ,]* ]] || fail depends "$p is not in Depends: $depends"
done
# Maintainer: the authors as CITATION.cff names them. Suggests and the description: every
# -dev package cmake/bouncerConfig.cmake.in says a consumer of the library needs.
maintainer=$(dpkg-deb -f "$deb" Maintainer)
authors=$(sed -n 's/^  - name: "\(.*\)"$/\1/p' "$SRC/CITATION.cff" | head -n 1)
[[ -n $authors && $maintainer == "$authors"* ]] || fail maintainer "Maintainer '$maintainer', CITATION.cff names '$authors'"
suggests=$(dpkg-deb -f "$deb" Suggests)
description=$(dpkg-deb -f "$deb" Description)
devs=$(grep -o '[a-z0-9+.-]*-dev' "$SRC/cmake/bouncerConfig.cmake.in" | sort -u)
[[ $(wc -w <<<"$devs") -ge 8 ]] || die "bouncerConfig.cmake.in names only '$devs'"
for p in $devs; do
  [[ ", $suggests," == *", $p"[\ ,]* ]] || fail suggests "$p is not in Suggests: $suggests"
  grep -qw -- "$p" <<<"$description" || fail description "the description does not name $p"
done
dpkg-deb -x "$deb" "$TMP/root"
root="$TMP/root"
core=$(find "$root/usr/lib/python3/dist-packages/bouncer" -name '_core*.so' 2>/dev/null | head -n 1)
[[ -n $core ]] || ! $python_module || fail layout "no _core*.so in usr/lib/python3/dist-packages/bouncer (where Debian's python3 looks)"
for f in usr/bin/bouncer usr/libexec/bouncer/proof_elastic_period2 usr/share/bouncer/scenes/default.toml \
         usr/share/bouncer/paper/manifest.toml usr/share/doc/bouncer/LICENSE usr/include/bouncer/model/spec.hpp; do
  [[ -e $root/$f ]] || fail layout "the package has no /$f"
done
[[ -n $(find "$root/usr" -name bouncer.pc -path '*/pkgconfig/*') ]] || fail layout "the package has no bouncer.pc"
[[ -n $(find "$root/usr" -name bouncerConfig.cmake) ]] || fail layout "the package has no bouncerConfig.cmake"
libs=$(ldconfig -p)  # the system's libraries: NAME (FLAGS) => PATH
for elf in "$root/usr/bin/bouncer" "$root"/usr/libexec/bouncer/proof_* ${core:+"$core"}; do
  for lib in $(objdump -p "$elf" | awk '$1 == "NEEDED" {print $2}'); do
    path=$(awk -v l="$lib" '$1 == l && !p {p = $NF} END {print p}' <<<"$libs")
    [[ -n $path ]] || { fail depends "$lib (needed by ${elf#"$root"}) is not a system library"; continue; }
    owner=$(owner_of "$path")
    [[ -n $owner ]] || { fail depends "no Debian package owns $path ($lib)"; continue; }
    [[ ", $depends," == *", $owner"[\ ,]* ]] || fail depends "$lib (${elf#"$root"}) is $owner's, not in Depends: $depends"
  done
done

# Run from the unpacked tree, away from the checkout and the build tree.
mkdir "$TMP/elsewhere"
cd "$TMP/elsewhere"
only=elastic-period2,trapping-region,sticking-thresholds
"$root/usr/bin/bouncer" reproduce --quick --only "$only" --out r > run.out 2> run.err ||
  fail reproduce "exit $?: $(tail -n 5 run.err)"
grep -q '3 of 3 claims reproduced' run.err || fail reproduce "$(grep 'claims reproduced' run.err || tail -n 3 run.err)"
grep -q 'build/proofs' r/report.md && fail reproduce "report.md names build/proofs/"
if $python_module; then
  # The python3 the module was built for (Debian's /usr/bin/python3, with python3-numpy).
  python=$(sed -n 's/^Python3_EXECUTABLE:[A-Z]*=//p' "$build/CMakeCache.txt")
  PYTHONPATH="$root/usr/lib/python3/dist-packages" "$python" -c "
import bouncer
assert bouncer.__file__.startswith('$root/usr/lib/python3/dist-packages/'), bouncer.__file__
s = bouncer.step(model='constant', a='24', eps='0.5', theta='0.25', v='12')
assert s['event'] == 'impact', s
" || fail python "import bouncer from the unpacked package failed"
fi
finish
