#!/usr/bin/env bash
# Installs libdepo for C, C++ and Fortran solvers:
#   PREFIX/lib/libdepo.{so,a}, PREFIX/lib/pkgconfig/depo.pc,
#   PREFIX/include/depo.h, depo.hpp, PREFIX/share/depo/fortran/depo.f90
# Usage: crates/capi/install.sh PREFIX [LIBDIR]
#   LIBDIR holds libdepo.so and libdepo.a already built (default: builds them with
#   `cargo build --release -p depo-capi` and takes target/release).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
prefix="${1:?usage: install.sh PREFIX [LIBDIR]}"
libdir="${2:-}"
if [ -z "$libdir" ]; then
  (cd "$here/../.." && cargo build --release -p depo-capi)
  libdir="$here/../../target/release"
fi
version="$(sed -n 's/^version = "\(.*\)"/\1/p' "$here/../../Cargo.toml" | head -n 1)"
mkdir -p "$prefix/lib/pkgconfig" "$prefix/include" "$prefix/share/depo/fortran"
cp "$libdir/libdepo.so" "$libdir/libdepo.a" "$prefix/lib/"
cp "$here/include/depo.h" "$here/include/depo.hpp" "$prefix/include/"
cp "$here/fortran/depo.f90" "$prefix/share/depo/fortran/"
sed -e "s|@PREFIX@|$prefix|" -e "s|@VERSION@|$version|" "$here/depo.pc.in" > "$prefix/lib/pkgconfig/depo.pc"
echo "installed depo $version in $prefix"
