#!/usr/bin/env bash
# Renders the README's pictures with `undergrowth render` (no display needed) into docs/images/.
#   scripts/render-gallery.sh [BUILD_DIR]      (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."
bin="${1:-build}/undergrowth"
out=docs/images
mkdir -p "$out"
shot() {  # name scene [render options...]
  local name="$1" scene="$2"
  shift 2
  "$bin" render "assets/scenes/$scene.json" -o "$out/$name.png" --size 960x540 "$@" | tail -1
}
shot rock_pile rock_pile                                     # the opening view
shot rock_pile_close rock_pile --camera 0.2,-0.1,0.25,1.4,-70,38
shot meadow meadow                                           # the opening view
shot meadow_close meadow --camera -8,8,0.35,2.2,-100,22
shot stone_hut stone_hut --camera 0,0,1.6,12,-105,30
shot stone_hut_side stone_hut --camera 0,0,1.8,10,10,10
shot beaver_dam beaver_dam
shot haystack_field haystack_field
shot street_winter street_winter --camera 5,5,0.5,13,-115,32
shot street_winter_close street_winter --camera 6.6,6.5,1,7,-110,18
shot montmartre_winter montmartre_winter --camera 0,-20,0.2,14,-90,20
shot road_winter road_winter --camera 0,6,1,14,-120,22
shot street_autumn street_autumn --camera 5,6.2,0.8,9.5,-80,24
shot street_autumn_bench street_autumn --camera 6.6,7.2,0.4,2.6,-80,12
shot street_autumn_litter street_autumn --camera 8.3,5.6,0.2,2.4,-60,32
shot street_autumn_puddle street_autumn --camera 6.2,2.2,0.05,2.6,-100,32
shot street_autumn_pile street_autumn --camera 7.6,4.9,0.15,2.6,-140,22
shot park_autumn park_autumn                                 # the opening view
shot park_autumn_fountain park_autumn --camera 0,0,0.5,6,-60,20
shot park_autumn_close park_autumn --camera -30,-31,0.3,4,-90,14   # under a tree
shot park_autumn_dry park_autumn --camera 45.5,-33,0.3,7,-90,12    # the warm corner
shot road_autumn road_autumn --camera 0,0,0.5,22,-110,25
shot road_autumn_close road_autumn --camera 7.8,-4.5,0.3,4,-170,10       # along the fence, over the pavers
shot road_autumn_verge road_autumn --camera -8,-13,0.1,2.2,-120,18       # tufts and leaves on the verge
shot meadow_strands meadow_strands --camera -7.2,8.2,0.3,2.6,-100,20
shot bus_stop_vines bus_stop_vines --camera 0,-0.5,1.2,5.5,-120,15
shot bus_stop_vines_side bus_stop_vines --camera -1.3,-0.6,1.6,2.4,-170,25
shot rock_pile_moss rock_pile_moss --camera 0.3,-0.2,0.25,1.1,-60,40
shot rock_pile_moss_side rock_pile_moss --camera 0.6,-0.5,0.2,1.3,-100,8
# The same vines file on the autumn street's shelter (turned round): its seeds and pull are the objects'.
shot particles_vines_street_autumn street_autumn --particles assets/particles/vines_bus_shelter.json \
  --camera 2.4,7.6,1.2,5.5,60,15
# Particle systems (assets/particles/) grown into the default scene, after the paper's figures.
strands() {  # sample camera
  shot "particles_$1" default --particles "assets/particles/$1.json" --camera "$2"
}
strands fig1_four_attractors 0,0,0.5,3.2,-60,20
strands fig5_pulsar 0,0,0.4,2.0,-90,8
strands fig5_exchanging_pulsars 0,0,0.45,2.6,-90,12
strands fig6_split_grass 0,0,0.2,1.4,-60,15
strands fig7_sphere_stop 0,0,0.5,2.2,-60,18
strands fig8_sphere_to_sphere 0,0,0.6,2.0,-60,20
strands fig9_grass_cutter 0,0,0.15,1.8,-60,15
strands fig9_four_attractors_no_collision 0,0,0.5,3.2,-60,20
strands fig9_four_attractors_keep_distance 0,0,0.5,3.2,-60,20
strands fig10_stone_statue 0,0,0.5,3.0,-60,22
strands fig11_sphere_to_statue 0,0,0.4,2.8,-60,35
strands moss_stone 0,0,0.3,1.6,-60,25
strands turning_tendrils 0,0,0.2,0.8,-80,12
