#!/usr/bin/env bash
# The README's main job on the [GZ] 2016 powder (600 316L particles, diameters N(27, 4.25) um,
# 1 mm x 0.5 mm floor): a geometric layer with packgen, a DEM-settled layer with deposit from the
# paper's scene, both compared side by side with bedstat and drawn; then the paper's laser track
# with sinter on the deposited bed, its melt pool beside the paper's. Last, a [KE] bed of 1 mm
# steel spheres poured into a box, and its effective conductivity with keff between the box's
# side walls.
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p out
# The Python the build found importing numpy (python/CMakeLists.txt records it), so a pyenv or
# conda python3 first on PATH without Debian's numpy/h5py/matplotlib does not break the plots.
python=$(cat build/python/interpreter 2>/dev/null || command -v python3)
psd="gauss:mean=27e-6,sd=4.25e-6,min=10e-6,max=50e-6,on=diameter"
echo "== packgen: 600 particles grown from the floor (3-contact, lowest site first)"
build/apps/packgen --dim 3 --domain 1e-3,0.5e-3,60e-6 --psd "$psd" --count 600 --approach 3 \
  --seed 1 --out out/packgen.h5
# --until-rest: the bed is at rest at t = 0.045 s of the scene's 0.1 s (every speed under
# rest.speed for rest.window); the rest of the 0.1 s only moved it by creep (layer density 0.4373
# against 0.4375), at twice the time.
echo "== deposit: the paper's drop and settle until at rest (data/scenes/gz2016-deposit.ini, 12 s on 2 idle cores)"
build/apps/deposit --config data/scenes/gz2016-deposit.ini --seed 1 --until-rest --out out/deposit.h5
echo "== bedstat: side by side; the paper reports about 0.45 in the bottom 30 um"
build/apps/bedstat out/packgen.h5 out/deposit.h5 --layer 0,30e-6 --psd "$psd"
"$python" scripts/plot_bed.py out/packgen.h5 out/packgen.png --title "packgen, [GZ] powder"
"$python" scripts/plot_bed.py out/deposit.h5 out/deposit.png --title "deposit, [GZ] scene"
echo "== sinter: 200 W at 2 m/s over the deposited bed (data/scenes/gz2016-sinter.ini, 15 s on 2 idle cores)"
build/apps/sinter --config data/scenes/gz2016-sinter.ini --bed out/deposit.h5 --out out/sinter.h5
"$python" - out/sinter.h5 <<'PY'
import sys, h5py
m = h5py.File(sys.argv[1], "r")["melt"].attrs
print("melt pool on x = Lx/2 (um)     height  width  depth")
print("  sinter, this bed          %8.1f %6.1f %6.1f" % tuple(m[k] * 1e6 for k in ("height", "width", "depth")))
print("  [GZ] 2016 model               30.0   85.0   20.0")
print("  [GZ] 2016 experiment          26.0   75.0   30.0")
PY
"$python" scripts/plot_sinter.py out/sinter.h5 out/sinter --title "sinter, [GZ] scene, 200 W, 2 m/s"
echo "== deposit + keff: the [KE] steel 1 mm bed (~1,000 spheres inserted from the top of a 10 D cube until full, linear contact as MFiX; 14 s on 2 idle cores)"
build/apps/deposit --config data/scenes/ke2016-steel-1mm-bed.ini --seed 1 --out out/ke-steel-1mm.h5
echo "   its conductivity between the box's two x faces (the side walls it was poured against):"
echo "   at room temperature (air; contact, gas lens and radiation), then at 1000 K"
echo "   [KE]'s quantity: fixed temperatures at two opposite walls of the filled domain, k = flux"
echo "   over the gradient of the bin-averaged profile, which is about linear (R^2 near 1); keff"
echo "   prints k_eff wall to wall (Q H / (A dT)), k_core (flux over the core's mean gradient,"
echo "   over two diameters from both walls), the profile's R^2 and each wall's share of dT"
build/apps/keff --config data/scenes/ke2016-steel-1mm.ini --bed out/ke-steel-1mm.h5 \
  --out out/keff-300K.h5
build/apps/keff --config data/scenes/ke2016-steel-1mm.ini --bed out/ke-steel-1mm.h5 \
  --temperature 1000 --gas.model air --out out/keff-1000K.h5
"$python" scripts/plot_keff_profile.py out/keff-300K-profile.csv out/keff-1000K-profile.csv \
  out/keff-profile.png --label "300 K" --label "1000 K"
echo "beds: out/packgen.h5, out/deposit.h5, out/ke-steel-1mm.h5; laser run: out/sinter.h5" \
  "(ParaView: open the .xmf, see docs/bed-format.md); pictures: out/packgen.png," \
  "out/deposit.png, out/sinter-top.png, out/sinter-section.png, out/keff-profile.png"
