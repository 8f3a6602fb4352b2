#!/usr/bin/env bash
# Regenerates the wang2020 screenshots of README.md and docs/wang2020.md (run from the repository root after a
# build; needs ../shared/assets for the HDR maps). The shader-vs-reference pairs come from the tests
# (Wang2020Render.AverageGlintEnergyMatchesExplicitReference, Wang2020Environment.SnowAndGlitterClothNextToReference)
# and are copied from build/test-output.
set -euo pipefail
glimmer=./build/glimmer
assets=${GLIMMER_ASSETS_DIR:-../shared/assets}
out=screenshots
point=tests/data/wang2020_point.json
sphere=(--scene sphere --method wang2020 --size 256x256 --set wang2020.particles=3e5 --set wang2020.roughness=0.5
        --set material.alpha=0.5)
$glimmer render "${sphere[@]}" --env none --out $out/wang2020_sphere_point.png
$glimmer render "${sphere[@]}" --env none --aov glintscale --out $out/wang2020_sphere_glintscale.png
$glimmer render "${sphere[@]}" --ibl wang2020 --env "$assets/hdri/rooitou_park_1k.hdr" \
    --out $out/wang2020_env_sphere_rooitou.png
$glimmer render --scene sphere --method smooth --size 256x256 --set material.alpha=0.5 \
    --env "$assets/hdri/rooitou_park_1k.hdr" --out $out/wang2020_env_sphere_rooitou_smooth.png
# The tilted view of the golden test across the thresholds (micro/meso at N 2.5e5, meso/macro at N 3.4e6), with
# the paper's hard switch (transition=0) and our default one-octave blend, and the scale AOV.
tilted=(--scene $point --camera tilted --size 256x256 --method wang2020 --set wang2020.gamma=4
        --set wang2020.roughness=0.4 --set material.alpha=0.4 --set exposure=-1)
for case in micro_meso:2.5e5 meso_macro:3.4e6; do
    name=${case%%:*}; n=${case##*:}
    $glimmer render "${tilted[@]}" --set wang2020.particles=$n --out $out/wang2020_seam_${name}.png
    $glimmer render "${tilted[@]}" --set wang2020.particles=$n --set wang2020.transition=0 \
        --out $out/wang2020_seam_${name}_hard.png
    $glimmer render "${tilted[@]}" --set wang2020.particles=$n --aov glintscale \
        --out $out/wang2020_seam_${name}_glintscale.png
done
$glimmer render --scene atrium --method wang2020 --ibl wang2020 --size 640x360 --out $out/wang2020_atrium_ibl.png
for f in wang2020_point_a0.1_shader_vs_reference:wang2020_point_a01_shader_vs_reference \
         wang2020_point_a0.5_shader_vs_reference:wang2020_point_a05_shader_vs_reference \
         wang2020_env_snow_shader_vs_reference:wang2020_env_snow_shader_vs_reference \
         wang2020_env_glitter_cloth_shader_vs_reference:wang2020_env_glitter_cloth_shader_vs_reference; do
    src=build/test-output/${f%%:*}.png
    if [ -f "$src" ]; then cp "$src" $out/${f##*:}.png; else echo "missing $src (run the wang2020 tests)"; fi
done
