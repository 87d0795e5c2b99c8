#!/usr/bin/env bash
# Run the benchmarks in full (ctest only smoke-runs them) and collect CSV and
# plots in build/bench. Needs a built `vtk` preset (scripts/test.sh) and the
# scans in ../shared/data/scans.
#
# Usage: scripts/bench.sh [OUTDIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=$(realpath -m "${1:-$root/build/bench}")
build="$root/build/vtk"
site=$(sed -n 's/^POINTSURFACES_PYTHON_SITE_PACKAGES:STRING=//p' "$build/CMakeCache.txt")
export PYTHONPATH="$build/$site"
scans="$root/../shared/data/scans"
mkdir -p "$out"
set -x
"$build/bin/BenchFitPeers" --threads 2 "$scans/bunny.ply" "$scans/igea.xyz" "$scans/horse.ply" \
  | tee "$out/fit_peers.csv"
for b in counts million tradeoff fittime equalquality; do
  /usr/bin/python3 "$root/Testing/Benchmarks/bench_splat_fit.py" "$b" --out "$out"
done
env -u DISPLAY POINTSURFACES_RENDER_WINDOW=egl /usr/bin/python3 \
  "$root/Testing/Benchmarks/bench_splat_render.py" --frames 5 --out "$out/render-bunny"
# A dense scan: 1M points sampled on the Bunny's triangles.
env -u DISPLAY POINTSURFACES_RENDER_WINDOW=egl /usr/bin/python3 \
  "$root/Testing/Benchmarks/bench_splat_render.py" --frames 5 --points 1000000 \
  --out "$out/render-bunny-1M"
env -u DISPLAY POINTSURFACES_RENDER_WINDOW=egl /usr/bin/python3 \
  "$root/Testing/Benchmarks/bench_metaballs.py" --out "$out"
# The SPH density surface of the Gadget snapshot's gas, at four thresholds.
env -u DISPLAY POINTSURFACES_RENDER_WINDOW=egl /usr/bin/python3 \
  "$root/Testing/Benchmarks/bench_sph_density.py" --out "$out"
# Splat image quality against the mesh: Bunny, Horse, Lucy, six views each.
env -u DISPLAY POINTSURFACES_RENDER_WINDOW=egl /usr/bin/python3 \
  "$root/Testing/Benchmarks/bench_splat_quality.py" --data "$scans" --out "$out/quality"
env -u DISPLAY POINTSURFACES_RENDER_WINDOW=egl "$build/bin/BenchComputeTiles" | tee "$out/compute_tiles.csv"
/usr/bin/python3 "$root/Testing/Benchmarks/plot_csv.py" "$out/compute_tiles.csv" "$out/compute_tiles.png" \
  n gpu_ms cpu_ms --logx --logy
