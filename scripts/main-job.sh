#!/usr/bin/env bash
# The README's main job: pack a 3D powder layer (1.0 x 0.5 x 0.1 mm, 316L-like truncated
# Gaussian diameters 30 +- 5 um in [20, 40] um) with packgen, print its statistics and draw it.
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p out
psd="gauss:mean=30e-6,sd=5e-6,min=20e-6,max=40e-6"
build/apps/packgen --dim 3 --domain 1e-3,0.5e-3,0.1e-3 --psd "$psd" --approach 3 --size-sampling stratified \
  --seed 1 --out out/layer.h5
build/apps/bedstat out/layer.h5 --layer 0,30e-6 --psd "$psd"
/usr/bin/python3 scripts/plot_bed.py out/layer.h5 out/layer.png --title "packgen powder layer"
echo "bed: out/layer.h5 (ParaView: open out/layer.xmf, see docs/bed-format.md); picture: out/layer.png"
