#!/usr/bin/env bash
# Installs what is missing, builds libsss, and renders the demo images into out/: what the
# library is for (translucent meshes lit from behind, materials, volume shadows, a hybrid
# Cornell box), each next to its baseline where there is one. Writes a contact sheet too:
# out/index.html (every image, its caption and the command that made it) and out/index.png.
# Uses the real data sets in $SSS_DATA_DIR (default ../shared/data) when present, and
# procedural stand-ins otherwise (it says which). Rendering takes about 1-2 minutes on 2 cores
# with llvmpipe (half a minute without the data). SSS_JOBS sets the build's parallel jobs.
set -euo pipefail
cd "$(dirname "$0")/.."
started=$SECONDS

scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DSSS_BUILD_EXAMPLES=ON
cmake --build build -j "${SSS_JOBS:-$(nproc)}" --target sss-render sss-montage textured-model
mkdir -p out

# Every image is recorded with a short label (drawn into index.png), a caption and its command.
files=() labels=() captions=() commands=()
record() { files+=("$1"); labels+=("$2"); captions+=("$3"); commands+=("$4"); }
# A command line to copy: arguments with characters other than these in single quotes.
quoted() {
  local a out=()
  for a; do
    if [[ $a =~ ^[A-Za-z0-9_./:,=+%-]+$ ]]; then out+=("$a"); else out+=("'${a//\'/\'\\\'\'}'"); fi
  done
  printf '%s' "${out[*]}"
}

# render FILE LABEL CAPTION SSS-RENDER-ARGS...
render() {
  local file=$1 label=$2 caption=$3 t=$SECONDS
  shift 3
  local command
  command="build/bin/sss-render $(quoted "$@" --out "out/$file")"
  echo "+ $command"
  local log
  log=$(build/bin/sss-render "$@" --out "out/$file")
  echo "  $(grep '^wrote' <<<"$log") ($((SECONDS - t)) s)"
  record "$file" "$label" "$caption" "$command"
}

# montage FILE LABEL CAPTION SSS-MONTAGE-ARGS... (input images and --label options)
montage() {
  local file=$1 label=$2 caption=$3
  shift 3
  local command
  command="build/bin/sss-montage $(quoted "$@" --out "out/$file")"
  echo "+ $command"
  build/bin/sss-montage "$@" --out "out/$file"
  record "$file" "$label" "$caption" "$command"
}

data=${SSS_DATA_DIR:-../shared/data}
have() { [[ -f "$data/$1" ]]; }
if [[ -d "$data" ]]; then export SSS_DATA_DIR=$data; else
  echo "(no data directory at $data: procedural stand-ins replace the dragon, the bunny and the bonsai)"
fi
missing() { echo "($data/$1 not found: $2)"; }

# 1. Light from behind, towards the camera: thin parts of a translucent object glow, thick parts
#    stay dark; the Blinn-Phong baseline under the same light shows only a dark silhouette.
#    --mesh-size 1 --scale 40: the object is 4 cm on its longest side (the scale decides how
#    translucent a material looks).
if have meshes/dragon_50k.obj; then
  subject=dragon; size="4 cm"; mesh=(--mesh dragon_50k.obj --pitch 10 --scale 40 --light-dir 0.2,-0.4,0.9)
else
  missing meshes/dragon_50k.obj "the back-lit scene shows the procedural torus"
  subject=torus; size="1.5 cm"; mesh=(--mesh procedural:torus --pitch 15 --scale 15 --light-dir 0.2,-0.3,0.95)
fi
backlit=("${mesh[@]}" --yaw 20 --mesh-size 1 --light-intensity 3 --environment 0.03,0.03,0.03 --size 600x400)
render "${subject}_backlit_sss_skin1.png" "$subject, skin1, back-lit" \
  "The $subject in skin (Jensen 2001 skin1), $size long, lit from behind towards the camera: light scattered through the thin parts (horns, spines, claws, tail) makes them glow, the thick body stays darker." \
  "${backlit[@]}" --mode sss --material skin1
render "${subject}_backlit_blinn_phong.png" "$subject, Blinn-Phong" \
  "The same $subject under the same light with the Blinn-Phong baseline (no scattering): light that does not reach a surface directly is lost, so only a flat silhouette (the ambient term) with a few rim highlights remains." \
  "${backlit[@]}" --mode blinn-phong
montage "${subject}_backlit_pair.png" "back-lit pair" \
  "Side by side: subsurface scattering (left) and the Blinn-Phong baseline (right) under the same back light." \
  --gap 6 --label "subsurface scattering, skin1" --label "Blinn-Phong, same light" \
  "out/${subject}_backlit_sss_skin1.png" "out/${subject}_backlit_blinn_phong.png"

# 2. One object in five materials at the same size (3 cm) and light (from behind, above):
#    how far light travels inside decides how much the thin parts glow and the colour.
if have meshes/stanford-bunny.obj; then
  subject=bunny; mesh=(--mesh stanford-bunny.obj)
else
  missing meshes/stanford-bunny.obj "the material row shows the procedural torus"
  subject=torus; mesh=(--mesh procedural:torus --pitch 35)
fi
row=() row_labels=()
for material in marble skin1 skimmilk ketchup potato; do
  render "${subject}_${material}.png" "$subject, $material" \
    "The $subject, 3 cm tall, in $material (measured coefficients of Jensen 2001), lit from behind and above." \
    "${mesh[@]}" --mesh-size 1 --scale 30 --mode sss --material "$material" --light-dir 0.35,-0.45,0.85 \
    --light-intensity 2.5 --environment 0.06,0.06,0.06 --size 320x320 --cameras 4 --frames 4
  row+=("out/${subject}_${material}.png")
  row_labels+=(--label "$material")
done
montage "${subject}_materials.png" "materials row" \
  "The same $subject in marble, skin1, skim milk, ketchup and potato (left to right), same size and light: the more light travels inside (skim milk, ketchup in red), the more the ears and feet glow." \
  --gap 4 --tile 240x240 "${row_labels[@]}" "${row[@]}"

# 3. A volume with and without the light volume: gradient shading lights each sample locally
#    (no shadows); scattering propagates the light through the data, so the tree and the pot
#    cast shadows on the plate.
if have volumes/bonsai_256x256x256_uint8.raw; then
  subject=bonsai; volume=(--volume bonsai_256x256x256_uint8.raw --tf bonsai --pitch 25)
else
  missing volumes/bonsai_256x256x256_uint8.raw "the volume pair shows the procedural bucky ball"
  subject=bucky; volume=(--volume procedural:bucky --tf bucky --pitch 25 --zoom 0.75)
fi
light=(--light-dir 1,-0.45,0.35 --light-intensity 1.6 --size 600x450)
render "${subject}_gradient.png" "$subject, gradient" \
  "The $subject CT with gradient (Phong) shading: every sample is lit as if nothing stood between it and the light." \
  "${volume[@]}" --mode gradient "${light[@]}"
render "${subject}_scattering.png" "$subject, light volume" \
  "The same $subject and light with the light volume (Ropinski 2010): light is attenuated on its way through the data, so the pot and the tree shadow the plate and the leaves shadow each other." \
  "${volume[@]}" --mode scattering "${light[@]}"
montage "${subject}_shadows_pair.png" "volume shadows pair" \
  "Side by side: gradient shading (left) and light-volume scattering with shadows (right), same light from the left." \
  --gap 6 --label "gradient shading" --label "light volume: shadows" \
  "out/${subject}_gradient.png" "out/${subject}_scattering.png"

# 4. A hybrid scene: a translucent mesh in front of a volume in a Cornell box, lit by one point
#    light from the front left: the mesh's shadow falls onto the volume and the back wall, the
#    volume's shadow (tinted by its colours) onto the walls.
light=(--point-light -1.3,0.5,1.6 --light-intensity 9)
if have meshes/stanford-bunny.obj && have volumes/bonsai_256x256x256_uint8.raw; then
  subject=bunny_bonsai
  scene=(--mesh stanford-bunny.obj --volume bonsai_256x256x256_uint8.raw --tf bonsai)
else
  missing "meshes/stanford-bunny.obj or volumes/bonsai_256x256x256_uint8.raw" "the Cornell box holds a sphere and the bucky ball"
  subject=sphere_bucky
  scene=(--mesh procedural:sphere --volume procedural:bucky --tf bucky)
fi
render "cornell_box_${subject}.png" "Cornell box, hybrid" \
  "A hybrid scene in a Cornell box: a translucent marble mesh in front of a scattering volume, one point light at the front left. The mesh's shadow falls onto the volume's pot and plate (the light volume darkens there) and the back wall, the volume's (tinted by its colours) onto the back and right walls." \
  "${scene[@]}" --mesh-size 1 --mesh-offset -0.4,-0.1,0.55 --volume-offset 0.35,0,-0.45 --material marble --scale 40 \
  --mode hybrid --cornell-box --pitch 8 "${light[@]}" --cameras 4 --frames 4 --size 500x450

# 5. A CT head: cut open by a clip plane (the cut face lit by the light the removed half no longer
#    holds back), and its skin as a translucent skin1 mesh at life size (the isosurface, 24 cm).
if have volumes/invesalius_cthead_256x256x108_uint16.raw; then
  render "ct_head_clipped.png" "CT head, clip plane" \
    "The InVesalius CT head cut sagittally by a clip plane; the cut matter casts no shadow, so the cut face (skull, sinuses, soft tissue) is lit like the inside it exposes." \
    --scene examples/scenes/ct_head_skin_clipped.json
  render "ct_head_skin_life_size.png" "CT head skin, life size" \
    "The same head's skin (the -500 HU isosurface) as a translucent skin1 mesh at its real size: its triangles are many diffusion lengths wide, the regime of life-size objects (docs/near-field.md)." \
    --scene examples/scenes/ct_head_skin_isosurface.json
else
  missing volumes/invesalius_cthead_256x256x108_uint16.raw "the clip plane cuts the procedural blobs"
  render "blobs_clipped.png" "blobs, clip plane" \
    "The procedural blobs cut by a clip plane, showing their dense cores; the cut matter casts no shadow, so the cut face is lit like the inside it exposes." \
    --volume procedural:blobs --tf bucky --mode scattering --clip-plane=0,0,0,-1,0,-1 --size 500x400
fi

# 6. Multiple scattering in a volume: physical single scattering from the light volume, and the
#    same with the multiple-scattering cache (light scattered more than once, photon-traced into
#    a view-independent grid): the shadowed pot and plate fill with light bounced off the rest.
if have volumes/bonsai_256x256x256_uint8.raw; then
  subject=bonsai; volume=(--volume bonsai_256x256x256_uint8.raw --tf bonsai --pitch 25)
else
  subject=bucky; volume=(--volume procedural:bucky --tf bucky --pitch 25 --zoom 0.75)
fi
physical=(--mode scattering --volume-model physical --light-dir 1,-0.45,0.35 --light-intensity 12 --size 600x450)
render "${subject}_single_scattering.png" "$subject, single scattering" \
  "The $subject with physical single scattering (TF colour as albedo, Henyey-Greenstein g = 0.5): only light that scattered once reaches the eye, so shadowed parts are black." \
  "${volume[@]}" "${physical[@]}"
render "${subject}_multiple_scattering_cache.png" "$subject, multiple-scattering cache" \
  "The same with the multiple-scattering cache: 512k photons from the light fill a view-independent grid with the light scattered more than once, which every sample scatters towards the eye; camera moves reuse it (docs/multiple-scattering.md)." \
  "${volume[@]}" "${physical[@]}" --multiple-scattering-cache --cache-photons 524288
montage "${subject}_multiple_scattering_pair.png" "multiple scattering pair" \
  "Side by side: single scattering (left) and single plus the multiple-scattering cache (right), same light." \
  --gap 6 --label "single scattering" --label "+ multiple-scattering cache" \
  "out/${subject}_single_scattering.png" "out/${subject}_multiple_scattering_cache.png"

# 7. A textured translucent model made by the project (examples/textured_model: a painted ball,
#    OBJ + MTL map_Kd + PNG): the texture gives each point its reflectance, skin1 its mean free
#    path. At 20 cm the seams and dots stay sharp; at 2 cm (--scale 100) light crosses them under
#    the surface and the colours bleed into each other (docs/textured-materials.md).
build/bin/textured-model out/textured_model > /dev/null
ball=(--mesh out/textured_model/painted_ball.obj --mode sss --material skin1 --pitch 10 --yaw 15
      --light-dir -0.3,-0.5,-1 --size 600x450)
render "painted_ball_20cm.png" "textured ball, 20 cm" \
  "The project's painted ball (a 2048 x 1024 base-colour texture read from the OBJ's map_Kd) as a textured translucent material: each texel's colour becomes skin1-like coefficients with that reflectance." \
  "${ball[@]}"
render "painted_ball_2cm.png" "textured ball, 2 cm" \
  "The same ball at 2 cm (--scale 100): the mean free path is now large against the seams and dots, so light entering one colour leaves through its neighbours." \
  "${ball[@]}" --scale 100
montage "painted_ball_pair.png" "textured ball pair" \
  "Side by side: the textured ball at 20 cm (left) and at 2 cm (right), same light." \
  --gap 6 --label "20 cm" --label "2 cm" out/painted_ball_20cm.png out/painted_ball_2cm.png

# The contact sheet: out/index.png (every image above, in a grid) and out/index.html.
sheet=() sheet_labels=()
for i in "${!files[@]}"; do
  sheet+=("out/${files[$i]}")
  sheet_labels+=(--label "${labels[$i]}")
done
build/bin/sss-montage --columns 4 --tile 300x225 --gap 6 "${sheet_labels[@]}" "${sheet[@]}" --out out/index.png

escape() { local s=${1//&/&amp;}; s=${s//</&lt;}; s=${s//>/&gt;}; printf '%s' "${s//\"/&quot;}"; }
{
  cat <<'EOF'
<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>libsss demo images</title>
<style>
body { background: #1a1a1f; color: #ddd; font: 15px/1.4 sans-serif; margin: 2em; }
figure { display: inline-block; vertical-align: top; width: 620px; margin: 0 1.5em 2em 0; }
img { max-width: 100%; } code { color: #9cf; font-size: 12px; word-break: break-all; }
</style></head><body>
<h1>libsss demo images</h1>
<p>Made by <code>scripts/demo.sh</code>; every command runs from the repository root.
EOF
  if [[ -n "${SSS_DATA_DIR:-}" ]]; then echo "Data files are found in <code>SSS_DATA_DIR=$(escape "$SSS_DATA_DIR")</code>."; fi
  echo "Contact sheet: <a href=\"index.png\">index.png</a>.</p>"
  for i in "${!files[@]}"; do
    echo "<figure><a href=\"$(escape "${files[$i]}")\"><img src=\"$(escape "${files[$i]}")\" alt=\"$(escape "${labels[$i]}")\"></a>"
    echo "<figcaption><b>$(escape "${files[$i]}")</b>: $(escape "${captions[$i]}")<br><code>$(escape "${commands[$i]}")</code></figcaption></figure>"
  done
  echo "</body></html>"
} > out/index.html

echo
echo "Demo images ($((SECONDS - started)) s) are in $(pwd)/out/; contact sheet: out/index.html, out/index.png"
printf '  %s\n' "${files[@]}"
