#!/usr/bin/env bash
# Packs what benchmarks/run-gpu.sh needs (and the GL test program) on a GPU machine that has no compilers and no Debian
# packages (a rented or lent machine, a container): the benchmark programs built here, the shared
# libraries they load that such a machine may lack (everything but the C and C++ runtimes, which a
# newer system has in newer versions), GLVND's libEGL, and the data sets the tables read,
# compressed. There: `benchmarks/run-gpu.sh --bundle FILE`.
#
# Usage: benchmarks/gpu-bundle.sh [--out FILE] [--data-dir DIR] [--no-data]
#   --out FILE      the tarball (default .gpu/sss-gpu.tar.gz; .gpu/ is meant to be git-ignored)
#   --data-dir DIR  data sets (default: $SSS_DATA_DIR, else ../shared/data)
#   --no-data       programs and libraries only
# Environment: SSS_BUILD_DIR (default build), a Release build with the benchmark.
set -euo pipefail
cd "$(dirname "$0")/.."

out=.gpu/sss-gpu.tar.gz data=${SSS_DATA_DIR:-../shared/data} with_data=1
while [[ $# -gt 0 ]]; do
  case "$1" in
    --out) out=${2:?--out needs FILE}; shift 2 ;;
    --data-dir) data=${2:?--data-dir needs DIR}; shift 2 ;;
    --no-data) with_data=0; shift ;;
    -h|--help) sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "gpu-bundle.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done

builddir=${SSS_BUILD_DIR:-build}
programs=(sss-bench sss-render sss_gl_tests)
for p in "${programs[@]}"; do
  [[ -x $builddir/bin/$p ]] || { echo "gpu-bundle.sh: $builddir/bin/$p not found: build first" >&2; exit 2; }
done

stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
mkdir -p "$stage/bin" "$stage/lib" "$stage/data"
for p in "${programs[@]}"; do cp "$builddir/bin/$p" "$stage/bin/"; done

# The runtime every Linux system has, newer than ours on a newer system: not carried.
system='^(linux-vdso|ld-linux|libc|libm|libpthread|libdl|librt|libstdc\+\+|libgcc_s)\.'
for p in "${programs[@]}"; do ldd "$builddir/bin/$p"; done |
  awk '$2 == "=>" && $3 ~ /^\// { print $1, $3 }' | sort -u |
  while read -r soname path; do
    [[ $soname =~ $system ]] || cp -L "$path" "$stage/lib/$soname"
  done

if [[ $with_data -eq 1 ]]; then
  for f in meshes/stanford-bunny.obj meshes/dragon_50k.obj meshes/happy_buddha_50k.obj \
           volumes/bucky_32x32x32_uint8.raw volumes/bonsai_256x256x256_uint8.raw \
           volumes/engine_256x256x256_uint8.raw; do
    [[ -f $data/$f ]] || { echo "gpu-bundle.sh: $data/$f not found (--data-dir)" >&2; exit 2; }
    mkdir -p "$stage/data/$(dirname "$f")"
    cp "$data/$f" "$stage/data/$f"
  done
fi

mkdir -p "$(dirname "$out")"
tar -C "$stage" -czf "$out" bin lib data
echo "gpu-bundle.sh: $out ($(du -h "$out" | cut -f1); $(ls "$stage/lib" | wc -l) libraries)"
