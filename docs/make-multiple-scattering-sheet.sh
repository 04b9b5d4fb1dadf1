#!/usr/bin/env bash
# Renders docs/multiple-scattering.png: the bonsai and the engine with the physical model, one
# directional light, g = 0.5: single scattering from the light volume, the same plus the
# multiple-scattering cache (refined to its default 2^21 photons), and the GPU path tracer's
# full transport (all orders, 136 paths per pixel for the bonsai, 40 for the engine). Needs a
# build (build/bin/sss-render, sss-montage) and the volumes in $SSS_DATA_DIR (default
# ../shared/data). About five minutes on two cores with llvmpipe, most of it path tracing.
set -euo pipefail
cd "$(dirname "$0")/.."
export SSS_DATA_DIR=${SSS_DATA_DIR:-../shared/data}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
tiles=() labels=()
for scene in bonsai engine; do
  if [ "$scene" = bonsai ]; then
    args=(--volume bonsai_256x256x256_uint8.raw --tf bonsai --light-intensity 12 --exposure 1.5)
    paths=(--samples 8 --frames 16)
  else
    args=(--volume engine_256x256x256_uint8.raw --tf engine --light-intensity 6)
    paths=(--samples 8 --frames 4)
  fi
  common=(--mode scattering --volume-model physical --light-dir -0.6,-0.7,-0.4 --pitch 20 --size 300x225 --aa 1)
  build/bin/sss-render "${args[@]}" "${common[@]}" --out "$tmp/$scene-single.png" >/dev/null
  build/bin/sss-render "${args[@]}" "${common[@]}" --multiple-scattering-cache --cache-resolution 64 --out "$tmp/$scene-cache.png" >/dev/null
  build/bin/sss-render "${args[@]}" "${common[@]}" --multiple-scattering "${paths[@]}" --out "$tmp/$scene-path.png" >/dev/null
  tiles+=("$tmp/$scene-single.png" "$tmp/$scene-cache.png" "$tmp/$scene-path.png")
  labels+=(--label "$scene: single" --label "+ cache" --label "GPU path tracer")  # tiles fit 24 characters
done
build/bin/sss-montage --columns 3 --gap 4 "${labels[@]}" "${tiles[@]}" --out docs/multiple-scattering.png
echo "wrote docs/multiple-scattering.png"
