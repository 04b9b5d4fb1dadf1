#!/usr/bin/env bash
# Times libsss against VTK's vtkGPUVolumeRayCastMapper on the same volume, transfer function,
# viewport, camera and step (benchmarks/vtk_peer.py), and writes
# benchmarks/results/peer-vtk-<renderer>.{json,md}. Debian's VTK renders through GLX only, so
# VTK runs under Xvfb (Mesa llvmpipe there, like libsss's EGL here without a GPU).
#
# Usage: benchmarks/vtk-peer.sh [--paraview] [--volume FILE] [--tf NAME] [--size WxH] [--step S] [--tag NAME]
#   --paraview   use ParaView 5.11's pvpython (VTK 9.2, with volumetric scattering) instead of
#                python3-vtk9 (VTK 9.1: emission-absorption and gradient shading only);
#                installs python3-paraview (about 450 MB) if missing. Debian's ParaView conflicts
#                with libvtk9-dev, which libsss builds against: apt removes it, and this script
#                puts it (and python3-vtk9) back when the run ends
# Defaults: the bonsai (256^3) from the data directory, tf bonsai, 1200x680, step 0.5 voxel.
set -euo pipefail
cd "$(dirname "$0")/.."

paraview=0 volume="" tf=bonsai size=1200x680 step=0.5 tag=llvmpipe
while [[ $# -gt 0 ]]; do
  case "$1" in
    --paraview) paraview=1 ;;
    --volume) volume=$2; shift ;;
    --tf) tf=$2; shift ;;
    --size) size=$2; shift ;;
    --step) step=$2; shift ;;
    --tag) tag=$2; shift ;;
    -h|--help) sed -n '2,12p' "$0"; exit 0 ;;
    *) echo "vtk-peer: unknown option $1" >&2; exit 2 ;;
  esac
  shift
done
data=${SSS_DATA_DIR:-../shared/data}
volume=${volume:-$data/volumes/bonsai_256x256x256_uint8.raw}
[[ -f "$volume" ]] || { echo "vtk-peer: no volume at $volume (--volume FILE or SSS_DATA_DIR)" >&2; exit 1; }

packages=(xvfb xauth python3-numpy)
if [[ $paraview -eq 1 ]]; then packages+=(python3-paraview); else packages+=(python3-vtk9); fi
installed() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"; }
sudo=(); [[ $(id -u) -ne 0 ]] && sudo=(sudo)
restore=()
if [[ $paraview -eq 1 ]]; then
  for p in libvtk9-dev python3-vtk9; do installed "$p" && restore+=("$p"); done
  if [[ ${#restore[@]} -gt 0 ]]; then
    echo "vtk-peer: python3-paraview conflicts with ${restore[*]}; they are reinstalled when the run ends" >&2
    trap 'DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq --no-install-recommends "${restore[@]}" >/dev/null' EXIT
  fi
fi
missing=()
for p in "${packages[@]}"; do
  installed "$p" || missing+=("$p")
done
if [[ ${#missing[@]} -gt 0 ]]; then
  "${sudo[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
[[ -x build/bin/sss-render ]] || { echo "vtk-peer: build libsss first (scripts/test.sh or cmake --build build)" >&2; exit 1; }

python=/usr/bin/python3  # Debian's, which has the vtk modules (not a pyenv or venv interpreter)
suffix=vtk9.1
if [[ $paraview -eq 1 ]]; then python=pvpython; suffix=vtk9.2; fi
mkdir -p benchmarks/results
out=benchmarks/results/peer-$suffix-$tag
xvfb-run -a -s "-screen 0 ${size%x*}x${size#*x}x24" "$python" benchmarks/vtk_peer.py \
  --sss-render build/bin/sss-render --volume "$volume" --tf "$tf" --size "$size" --step "$step" \
  --json "$out.json" --markdown "$out.md"
echo "vtk-peer: wrote $out.json and $out.md"
