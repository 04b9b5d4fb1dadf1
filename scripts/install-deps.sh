#!/usr/bin/env bash
# Installs the Debian 12 packages libsss needs to build, test and run headless.
# Idempotent: only packages that are not installed yet are passed to apt-get.
# Usage: scripts/install-deps.sh [--viewer]   (--viewer adds GLFW, Dear ImGui, Xvfb, xdotool)
set -euo pipefail

packages=(
  # toolchain
  cmake g++ make pkg-config
  # GL loader generator (glad 2, run offline at build time)
  python3-glad python3-jinja2
  # EGL + GL headers and the Mesa llvmpipe driver. libgl1-mesa-dri holds llvmpipe
  # (swrast_dri.so); nothing pulls it in under --no-install-recommends, so list it.
  libegl-dev libgl-dev libopengl-dev libegl-mesa0 libgl1-mesa-dri
  # libraries
  libglm-dev libtinyobjloader-dev libstb-dev nlohmann-json3-dev catch2 libopenexr-dev
  # CLI11: the one option table of sss-render, sss-viewer and sss-bench (apps/common/cli_options.h)
  libcli11-dev
  # Assimp: the PLY, STL, glTF 2.0 and OFF mesh readers (Mesh::load; OBJ stays on tinyobjloader)
  libassimp-dev
  # Volume::load: VTK 9.1 reads NIfTI, .vti, DICOM series and (bundled MetaIO) MetaImage; teem
  # reads NRRD with its orientation. VTK is the only Debian library with a .vti reader; it is
  # large (156 MB download, 775 MB installed with its -dev closure; see README "Volume formats").
  libvtk9-dev libteem-dev
  # zlib: NIfTI headers (.nii, .nii.gz) are checked before VTK reads them
  zlib1g-dev
  # the Python module (python/, pybind11) and its tests (pytest with NumPy)
  pybind11-dev python3-dev python3-numpy python3-pytest
  # clang with libFuzzer and the sanitizer runtimes: the loader fuzz targets (tests/fuzz)
  clang-14 libclang-rt-14-dev
)
viewer_packages=(libglfw3-dev libimgui-dev xvfb xauth xdotool)

if [[ "${1:-}" == "--viewer" ]]; then packages+=("${viewer_packages[@]}"); fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [[ ${#missing[@]} -eq 0 ]]; then
  echo "install-deps: all ${#packages[@]} packages already installed"
  exit 0
fi

if [[ $(id -u) -eq 0 ]]; then sudo=(); elif command -v sudo >/dev/null; then sudo=(sudo); else
  echo "install-deps: missing packages (${missing[*]}) and neither root nor sudo available" >&2
  exit 1
fi

echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
