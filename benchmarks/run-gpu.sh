#!/usr/bin/env bash
# Records every benchmark table on a GPU, with GL timer queries, after checking that the EGL
# device libsss gets is that GPU (not Mesa's llvmpipe, which EGL also offers).
#
# Usage: benchmarks/run-gpu.sh [options]
#   --expect TEXT   the GL vendor or renderer must contain TEXT (default: NVIDIA)
#   --name NAME     file-name tag of the results (default: from the renderer, e.g. "h100" for
#                   "NVIDIA H100 80GB HBM3/PCIe/SSE2")
#   --out DIR       where the results go (default: benchmarks/results)
#   --build         build first (scripts/install-deps.sh + CMake, Release, build/), as
#                   scripts/test.sh does; without it an existing build/bin/sss-bench is used, so
#                   a build made elsewhere can be carried to a machine without compilers
#   --sweeps        also the time-against-error sweeps and the volume accuracy (CPU references:
#                   minutes on many cores)
#   --tests         also the test suite under ctest (the GL tests then run on this GPU; the
#                   golden images still use llvmpipe, see tests/README or the H100 report);
#                   with --bundle, the GL test program without the golden cases
#   --data-dir DIR  data sets (default: $SSS_DATA_DIR, else ../shared/data)
#   --bundle FILE   use the programs, libraries and data packed by benchmarks/gpu-bundle.sh
#                   (for a machine with no compilers or packages); NVIDIA's EGL vendor file under
#                   /usr/local/nvidia is then used when the system has none
# Environment: SSS_BUILD_DIR (default build), as scripts/test.sh.
# Writes <table>-<name>.{json,md} per table (baseline, 5.3, 5.4, 5.5, casters, light-sweep, scaling, and the
# per-pass passes-5.4 and passes-5.3), and with --sweeps
# error-sweep-{mesh,volume}-<name>.* and accuracy-volume-<name>.*; with --tests
# test-suite-<name>.log. Exit status: 0 done, 2 usage, 3 wrong device, else the failing step's.
set -euo pipefail
cd "$(dirname "$0")/.."

expect=NVIDIA name="" out=benchmarks/results build=0 sweeps=0 tests=0 data=() bundle=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --expect) expect=${2:?--expect needs TEXT}; shift 2 ;;
    --name) name=${2:?--name needs NAME}; shift 2 ;;
    --out) out=${2:?--out needs DIR}; shift 2 ;;
    --data-dir) data=(--data-dir "${2:?--data-dir needs DIR}"); shift 2 ;;
    --bundle) bundle=${2:?--bundle needs FILE}; shift 2 ;;
    --build) build=1; shift ;;
    --sweeps) sweeps=1; shift ;;
    --tests) tests=1; shift ;;
    -h|--help) sed -n '2,25p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "run-gpu.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done

builddir=${SSS_BUILD_DIR:-build}
if [[ -n $bundle ]]; then
  builddir=$(mktemp -d)
  tar -C "$builddir" -xzf "$bundle"
  export LD_LIBRARY_PATH="$builddir/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  data=(--data-dir "$builddir/data")
  for d in /usr/local/nvidia/lib64 /usr/local/nvidia/lib; do
    [[ -d $d ]] && export LD_LIBRARY_PATH="$LD_LIBRARY_PATH:$d"
  done
  vendor_file=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
  if [[ -z ${__EGL_VENDOR_LIBRARY_FILENAMES:-} && ! -d /usr/share/glvnd/egl_vendor.d && -f $vendor_file ]]; then
    export __EGL_VENDOR_LIBRARY_FILENAMES=$vendor_file
  fi
fi
bench=$builddir/bin/sss-bench
if [[ $build -eq 1 ]]; then
  scripts/install-deps.sh
  cmake -S . -B "$builddir" -DCMAKE_BUILD_TYPE=Release -DSSS_BUILD_TESTS=ON -DSSS_BUILD_EXAMPLES=ON -DSSS_BUILD_BENCH=ON
  cmake --build "$builddir" -j "$(nproc)"
elif [[ ! -x $bench ]]; then
  echo "run-gpu.sh: $bench not found: build first (--build) or carry a build here" >&2
  exit 2
fi

# The device check: what the benchmark itself will get.
info=$("$bench" --gl-info)
field() { sed -n "s/^$1: //p" <<<"$info"; }
vendor=$(field vendor) renderer=$(field renderer) software=$(field software) timing=$(field timing)
echo "run-gpu.sh: GL device: $renderer ($vendor), timing: $timing"
if [[ "$software" == yes || ( "$vendor" != *"$expect"* && "$renderer" != *"$expect"* ) ]]; then
  echo "run-gpu.sh: the EGL device is '$renderer' ($vendor), not a '$expect' GPU: nothing measured." >&2
  echo "run-gpu.sh: check the driver's EGL vendor file (__EGL_VENDOR_LIBRARY_FILENAMES) and that" \
       "SSS_EGL_SOFTWARE is unset" >&2
  exit 3
fi
if [[ -z $name ]]; then
  # "NVIDIA H100 80GB HBM3/PCIe/SSE2" -> h100; "NVIDIA GeForce RTX 4090/PCIe/SSE2" -> rtx-4090.
  name=$(sed -E 's#/.*##; s/^(NVIDIA|AMD|Intel\(R\))[[:space:]]+//I; s/^(GeForce|Quadro|Tesla|Radeon)[[:space:]]+//I' \
           <<<"$renderer" | awk '{ if ($1 ~ /^[A-Za-z]+$/ && $2 ~ /^[0-9]/) print $1 "-" $2; else print $1 }' |
           tr '[:upper:]' '[:lower:]' | tr -c 'a-z0-9-\n' '-')
fi
mkdir -p "$out"
note="$renderer, $(date -u +%Y-%m-%d), benchmarks/run-gpu.sh"

run() {  # run LABEL SSS-BENCH-ARGS...
  local label=$1; shift
  echo "run-gpu.sh: $label"
  "$bench" "${data[@]}" --note "$note" "$@"
}
for table in baseline 5.3 5.4 5.5; do
  run "table $table" --table "$table" --json "$out/$( [[ $table == baseline ]] && echo baseline || echo "table-$table")-$name.json"
done
# Fragment against compute ray casting side by side, time against viewport and step, and where
# each frame's time goes (GPU timestamps per pass).
run "ray casters" --table casters --json "$out/casters-$name.json"
run "light sweep" --table light-sweep --json "$out/light-sweep-$name.json"
run "scaling" --table scaling --json "$out/scaling-$name.json"
run "passes 5.4" --passes --table 5.4 --only bonsai,engine --json "$out/passes-5.4-$name.json"
run "passes 5.3" --passes --table 5.3 --only bunny --json "$out/passes-5.3-$name.json"
if [[ $sweeps -eq 1 ]]; then
  run "error sweep mesh" --error-sweep mesh --json "$out/error-sweep-mesh-$name.json"
  run "error sweep volume" --error-sweep volume --json "$out/error-sweep-volume-$name.json"
  run "accuracy volume" --accuracy volume --json "$out/accuracy-volume-$name.json"
fi
if [[ $tests -eq 1 ]]; then
  echo "run-gpu.sh: test suite"
  if [[ -n $bundle ]]; then
    # No ctest files travel in a bundle: the GL tests' own program, golden cases left out (their
    # images are llvmpipe's). Their data and golden paths are this checkout's, as built.
    SSS_REQUIRE_GL=1 "$builddir/bin/sss_gl_tests" "~[golden]" 2>&1 | tee "$out/test-suite-$name.log"
  else
    SSS_REQUIRE_GL=1 ctest --test-dir "$builddir" -j "$(nproc)" -E "install|fuzz|viewer|glfw" --output-on-failure \
      2>&1 | tee "$out/test-suite-$name.log"
  fi
fi
echo "run-gpu.sh: results in $out (tag $name)"
