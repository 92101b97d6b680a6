#!/usr/bin/env bash
# Installs libdepo for C, C++ and Fortran solvers:
#   PREFIX/lib/libdepo.so.VERSION, with the links libdepo.so.SOVERSION (the SONAME) and
#   libdepo.so, PREFIX/lib/libdepo.a, PREFIX/lib/pkgconfig/depo.pc,
#   PREFIX/lib/cmake/depo/depoConfig.cmake and depoConfigVersion.cmake (target depo::depo),
#   PREFIX/include/depo.h, depo.hpp, PREFIX/share/depo/fortran/depo.f90
# Usage: crates/capi/install.sh PREFIX [LIBDIR]
#   LIBDIR holds libdepo.so and libdepo.a already built. By default they are taken from
#   target/release after `cargo build --release --workspace --lib --bins --examples`: the README's one build
#   for the CLI, the examples and libdepo, so after it this is a no-op. (Cargo unifies
#   dependency features per command: `cargo build --release -p depo-capi` would compile the
#   library's dependencies a second time.)
# depo.pc puts PREFIX/lib on the program's run path (-Wl,-rpath), so programs linked with
# `pkg-config --libs depo` start without LD_LIBRARY_PATH.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
prefix="${1:?usage: install.sh PREFIX [LIBDIR]}"
libdir="${2:-}"
if [ -z "$libdir" ]; then
  root="$(cd "$here/../.." && pwd)"
  (cd "$root" && cargo build --release --workspace --lib --bins --examples)
  target="${CARGO_TARGET_DIR:-target}"
  case "$target" in /*) ;; *) target="$root/$target" ;; esac
  libdir="$target/release"
fi
mkdir -p "$prefix"
prefix="$(cd "$prefix" && pwd)"
version="$(sed -n 's/^version = "\(.*\)"/\1/p' "$here/../../Cargo.toml" | head -n 1)"
# The SONAME's version, as crates/capi/build.rs sets it: the major version, or 0.MINOR before 1.0.
major="${version%%.*}"
minor="$(echo "$version" | cut -d. -f2)"
if [ "$major" = 0 ]; then soversion="0.$minor"; else soversion="$major"; fi
mkdir -p "$prefix/lib/pkgconfig" "$prefix/lib/cmake/depo" "$prefix/include" "$prefix/share/depo/fortran"
rm -f "$prefix/lib/libdepo.so" "$prefix/lib/libdepo.so.$soversion"
install -m 0755 "$libdir/libdepo.so" "$prefix/lib/libdepo.so.$version"
ln -s "libdepo.so.$version" "$prefix/lib/libdepo.so.$soversion"
ln -s "libdepo.so.$soversion" "$prefix/lib/libdepo.so"
cp "$libdir/libdepo.a" "$prefix/lib/"
cp "$here/include/depo.h" "$here/include/depo.hpp" "$prefix/include/"
cp "$here/fortran/depo.f90" "$prefix/share/depo/fortran/"
sed -e "s|@PREFIX@|$prefix|" -e "s|@VERSION@|$version|" "$here/depo.pc.in" > "$prefix/lib/pkgconfig/depo.pc"
for f in depoConfig.cmake depoConfigVersion.cmake; do
  sed -e "s|@VERSION@|$version|g" -e "s|@SONAME@|libdepo.so.$soversion|g" "$here/cmake/$f.in" > "$prefix/lib/cmake/depo/$f"
done
echo "installed depo $version in $prefix"
