#!/usr/bin/env bash
# Run the benchmarks in full (ctest only smoke-runs them) and collect their CSVs
# and plots in OUTDIR. Needs a built `vtk` preset (scripts/test.sh).
#
# Usage: scripts/bench.sh [--data DIR] [OUTDIR]
#
#   OUTDIR      where the CSVs and plots go (default: Testing/Benchmarks/results,
#               the committed results: a run updates them, git shows the change,
#               and scripts/results.py then rewrites docs/results.md from them).
#   --data DIR  a folder of full-size inputs (its files may also sit one folder
#               below it), passed to the benchmarks that take it. They look for:
#                 scans      bunny.ply igea.xyz horse.ply lucy_50k.ply (with faces:
#                            bunny, horse, lucy_50k)
#                 particles  halo_32k.xyz hyg_stars.vtp gadget4_lcdm_gas_z5.hdf5
#                 molecules  adk_solvated.pdb
#               An input not there is skipped, with one line saying so.
#               Without --data they read the data a clone has: Testing/Data
#               (bunny.vtp, bun000.vtp, halo_2k.xyz, adk_solvated_2k.pdb) and
#               IO/Testing/Data (the Gadget subset, GROMACS and LAMMPS runs).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
results="$root/Testing/Benchmarks/results"
data=""
out=""
while [ $# -gt 0 ]; do
  case "$1" in
    --data) [ $# -ge 2 ] || { echo "bench.sh: --data needs a folder" >&2; exit 2; }
            data=$(realpath -m "$2"); shift 2 ;;
    -h|--help) sed -n '2,19p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "bench.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
    *) [ -z "$out" ] || { echo "bench.sh: one OUTDIR only" >&2; exit 2; }
       out="$1"; shift ;;
  esac
done
[ -z "$data" ] || [ -d "$data" ] || { echo "bench.sh: --data $data: no such folder" >&2; exit 2; }
out=$(realpath -m "${out:-$results}")
build="$root/build/vtk"
bench="$root/Testing/Benchmarks"
site=$(sed -n 's/^POINTSURFACES_PYTHON_SITE_PACKAGES:STRING=//p' "$build/CMakeCache.txt")
export PYTHONPATH="$build/$site"
data_args=()
[ -z "$data" ] || data_args=(--data "$data")
egl=(env -u DISPLAY POINTSURFACES_RENDER_WINDOW=egl)
mkdir -p "$out"

# The scans BenchFitPeers fits: the full-size ones in --data (each one missing
# skipped), else the committed Bunny and its raw range scan.
peer_scans=()
if [ -n "$data" ]; then
  for name in bunny.ply igea.xyz horse.ply; do
    found=$(find "$data" -maxdepth 2 -name "$name" -type f | sort | head -n 1)
    if [ -n "$found" ]; then
      peer_scans+=("$found")
    else
      echo "bench.sh: skipped $name in BenchFitPeers: no $name in $data" >&2
    fi
  done
else
  peer_scans=("$root/Testing/Data/bunny.vtp" "$root/Testing/Data/bun000.vtp")
fi

# bench_splat_render.py DIR writes splat_render*.{csv,png}: into OUTDIR as
# splat_render_NAME*.
render() {
  local name=$1 tmp
  shift
  tmp=$(mktemp -d)
  "${egl[@]}" /usr/bin/python3 "$bench/bench_splat_render.py" --frames 5 --out "$tmp" "$@"
  for f in "$tmp"/splat_render*; do
    [ -e "$f" ] || continue
    base=$(basename "$f")
    mv "$f" "$out/splat_render_$name${base#splat_render}"
  done
  rm -rf "$tmp"
}

set -x
if [ ! -x "$build/bin/BenchFitPeers" ]; then
  echo "bench.sh: skipped BenchFitPeers: not built (it needs PCL and CGAL)" >&2
elif [ ${#peer_scans[@]} -gt 0 ]; then
  "$build/bin/BenchFitPeers" --threads 2 "${peer_scans[@]}" | tee "$out/fit_peers.csv"
fi
for b in counts million tradeoff fittime equalquality levels; do
  /usr/bin/python3 "$bench/bench_splat_fit.py" "$b" "${data_args[@]}" --out "$out"
done
render bunny
# A dense scan: 1M points sampled on the Bunny's triangles.
render bunny_1M --points 1000000
"${egl[@]}" /usr/bin/python3 "$bench/bench_metaballs.py" "${data_args[@]}" --out "$out"
# Metaballs over a time series (the vortex of Examples/Python/particle_animation.py).
"${egl[@]}" /usr/bin/python3 "$bench/bench_metaball_series.py" --out "$out"
# A soak: 10 000 LAMMPS snapshots through the reader and the CPU metaball
# caster, 1 000 changing point sets through the splat fitter and mapper.
"${egl[@]}" /usr/bin/python3 "$bench/bench_soak.py" --out "$out"
# The SPH density surface of the Gadget snapshot's gas, at four thresholds.
"${egl[@]}" /usr/bin/python3 "$bench/bench_sph_density.py" "${data_args[@]}" --out "$out"
# Splat image quality against the mesh, six views each.
"${egl[@]}" /usr/bin/python3 "$bench/bench_splat_quality.py" "${data_args[@]}" --out "$out"
# What a change of colouring costs the splat mapper, against vtkPointGaussianMapper.
"${egl[@]}" /usr/bin/python3 "$bench/bench_splat_recolor.py" --out "$out"
# What pages arriving cost the streaming mapper: uploading them alone, or the resident set.
"${egl[@]}" /usr/bin/python3 "$bench/bench_splat_page_upload.py" --out "$out"
"${egl[@]}" "$build/bin/BenchComputeTiles" | tee "$out/compute_tiles.csv"
/usr/bin/python3 "$bench/plot_csv.py" "$out/compute_tiles.csv" "$out/compute_tiles.png" \
  n gpu_ms cpu_ms --logx --logy
if [ "$out" = "$(realpath -m "$results")" ]; then
  # The committed results changed: docs/results.md follows them.
  /usr/bin/python3 "$root/scripts/results.py" --results "$out"
fi
