#!/usr/bin/env bash
# Renders docs/presets-calibrated.png: the Stanford bunny (3 cm) in every material preset
# (Jensen et al. 2001 and Narasimhan et al. 2006), calibrated profile, lit from the front left
# and above, to check by eye that each renders with a plausible colour. Needs a build
# (build/bin/sss-render, sss-montage) and meshes/stanford-bunny.obj in $SSS_DATA_DIR (default
# ../shared/data). About five minutes on two cores with llvmpipe.
set -euo pipefail
cd "$(dirname "$0")/.."
export SSS_DATA_DIR=${SSS_DATA_DIR:-../shared/data}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
tiles=() labels=()
while read -r material; do
  build/bin/sss-render --mesh stanford-bunny.obj --mesh-size 1 --scale 30 --mode sss --material "$material" \
    --light-dir 0.5,-0.6,-0.6 --light-intensity 2 --environment 0.06,0.06,0.06 --no-specular \
    --size 200x200 --cameras 4 --frames 4 --out "$tmp/$material.png" >/dev/null
  tiles+=("$tmp/$material.png")
  labels+=(--label "$material")
done < <(build/bin/sss-render --list-materials)
build/bin/sss-montage --columns 8 --tile 140x140 --gap 4 "${labels[@]}" "${tiles[@]}" --out docs/presets-calibrated.png
echo "wrote docs/presets-calibrated.png"
