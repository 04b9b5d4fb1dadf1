#!/usr/bin/env bash
# Installs what is missing, builds libsss, and renders the demo images into out/.
# Uses the real data sets in $SSS_DATA_DIR (default ../shared/data) when present, and the
# procedural assets otherwise.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DSSS_BUILD_EXAMPLES=ON
cmake --build build -j "$(nproc)" --target sss-render
mkdir -p out
render() { echo "+ sss-render $*"; build/bin/sss-render "$@"; }

# Procedural assets: always available.
render --mesh procedural:sphere --mode blinn-phong --size 600x340 --out out/sphere_blinn_phong.png
render --mesh procedural:torus --mode blinn-phong --size 600x340 --yaw -25 --pitch 40 --out out/torus_blinn_phong.png
render --volume procedural:blobs --mode emission-absorption --tf bucky --size 600x340 --out out/blobs_emission_absorption.png
render --volume procedural:shell --mode gradient --tf ct-bone --size 600x340 --out out/shell_gradient.png
render --mesh procedural:torus --mode sss --material marble --scale 40 --size 600x340 --out out/torus_sss_marble.png
render --volume procedural:bucky --mode scattering --tf bucky --size 600x340 --out out/bucky_scattering.png
render --mesh procedural:torus --volume procedural:bucky --mode hybrid --tf bucky --cornell-box --scale 40 \
  --mesh-offset -0.7,-0.4,0 --volume-offset 0.6,0.3,0 --size 600x450 --out out/hybrid_cornell_box.png

data=${SSS_DATA_DIR:-../shared/data}
if [[ -d "$data" ]]; then
  export SSS_DATA_DIR=$data
  [[ -f $data/meshes/stanford-bunny.obj ]] &&
    render --mesh stanford-bunny.obj --mode blinn-phong --out out/bunny_blinn_phong.png &&
    render --mesh stanford-bunny.obj --mode sss --material cream --zoom 0.8 --out out/bunny_sss_cream.png
  [[ -f $data/volumes/bonsai_256x256x256_uint8.raw ]] &&
    render --volume bonsai_256x256x256_uint8.raw --mode gradient --tf bonsai --out out/bonsai_gradient.png &&
    render --volume bonsai_256x256x256_uint8.raw --mode scattering --tf bonsai --light-dir -1,-1,-0.3 \
      --out out/bonsai_scattering.png
  [[ -f $data/volumes/bucky_32x32x32_uint8.raw ]] &&
    render --volume bucky_32x32x32_uint8.raw --mode emission-absorption --tf bucky --step 0.5 --out out/bucky_emission_absorption.png
else
  echo "(no data directory at $data: skipped the Stanford bunny and the bonsai)"
fi
echo
echo "Demo images are in $(pwd)/out/:"
ls -1 out/*.png
