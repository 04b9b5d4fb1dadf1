#!/usr/bin/env bash
# Renders docs/bunny-profiles.png: the Stanford bunny (3 cm) lit from behind and above in six
# Jensen 2001 materials, the paper's dipole (top row) against the calibrated profile (bottom).
# Needs a build (build/bin/sss-render, sss-montage) and the bunny (meshes/stanford-bunny.obj in
# $SSS_DATA_DIR, default ../shared/data). About three minutes on two cores with llvmpipe.
set -euo pipefail
cd "$(dirname "$0")/.."
export SSS_DATA_DIR=${SSS_DATA_DIR:-../shared/data}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
materials=(ketchup potato skin1 marble cream apple)
tiles=() labels=()
for profile in dipole calibrated; do
  for material in "${materials[@]}"; do
    build/bin/sss-render --mesh stanford-bunny.obj --mesh-size 1 --scale 30 --mode sss --material "$material" \
      --profile "$profile" --light-dir 0.35,-0.45,0.85 --light-intensity 2.5 --environment 0.06,0.06,0.06 \
      --size 240x240 --cameras 4 --frames 4 --out "$tmp/$profile-$material.png" >/dev/null
    tiles+=("$tmp/$profile-$material.png")
    labels+=(--label "$profile $material")
  done
done
build/bin/sss-montage --columns 6 --gap 4 "${labels[@]}" "${tiles[@]}" --out docs/bunny-profiles.png
echo "wrote docs/bunny-profiles.png"
