#!/usr/bin/env bash
# Runs inside the GPU bundle that scripts/gpu-bundle.sh makes: the EGL render
# tests (ctest -L egl) and the benchmarks at 1080p, with nothing but the
# bundle and the host's GL driver (its EGL vendor library, found by the
# bundle's glvnd loader). Writes the CSVs, images and a log to OUTDIR.
#
# Usage: gpu-run.sh [--smoke] OUTDIR
#   --smoke  tiny sizes (what the bundle's own test runs on Mesa's llvmpipe)
#
# On the GPU host: tar xf pointsurfaces-gpu.tar.xz && pointsurfaces-gpu/gpu-run.sh results
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
smoke=0
if [ "${1:-}" = --smoke ]; then
  smoke=1
  shift
fi
if [ $# -ne 1 ]; then
  sed -n '2,10p' "$0"
  exit 2
fi
mkdir -p "$1"
out=$(cd "$1" && pwd)
exec > >(tee "$out/gpu-run.log") 2>&1
tee_pid=$!

export LD_LIBRARY_PATH="$here/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export POINTSURFACES_RENDER_WINDOW=egl
unset DISPLAY

echo "== host"
uname -srm
if command -v nvidia-smi > /dev/null 2>&1; then
  nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv
fi
echo "bundle: $here ($(cat "$here/VERSION" 2> /dev/null))"

echo "== EGL render tests (ctest -L egl)"
mkdir -p "$out/ctest" "$out/ctest/Testing/Temporary" "$out/ctest/work"
sed -e "s#@BUNDLE@#$here#g" -e "s#@OUT@#$out/ctest#g" \
  "$here/tests/CTestTestfile.cmake.in" > "$out/ctest/CTestTestfile.cmake"
# --smoke runs one test of each kind (a splat, a metaball and a compute-shader
# scene and the EGL window itself): the build tree has run them all already.
smoke_tests=()
if [ "$smoke" = 1 ]; then
  smoke_tests=(-R 'egl-Test(AlgebraicSplatMapperBunny|MetaballMapperShadows|ComputeTileHistogram|EGLHeadlessRenderWindow)$')
fi
"$here/bin/ctest" --test-dir "$out/ctest" -L egl ${smoke_tests[@]+"${smoke_tests[@]}"} --no-tests=error --output-on-failure --timeout 180
tests=$?

echo "== benchmarks"
mkdir -p "$out/bench"
if [ "$smoke" = 1 ]; then
  render_args=(--smoke)
  tiles_args=(--smoke)
else
  # --paging 100: the 1M-point Bunny's splats tiled 100 times, 10^8 points,
  # as a splat file drawn within 4 GB, against vtkPointGaussianMapper.
  render_args=(--size 1920x1080 --frames 20 --points 1000000 --balls 100000,1000000,10000000,100000000
    --paging 100 --budget 4096)
  tiles_args=()
fi
"$here/bin/BenchRender" "${render_args[@]}" --out "$out/bench" \
  "$here/data/Testing/Data/bunny.vtp" | tee "$out/bench/render-stdout.csv"
render=${PIPESTATUS[0]}
"$here/bin/BenchComputeTiles" "${tiles_args[@]}" > "$out/bench/compute_tiles.csv"
tiles=$?
cat "$out/bench/compute_tiles.csv"

passed=0
failed=0
for rc in "$tests" "$render" "$tiles"; do
  if [ "$rc" = 0 ]; then passed=$((passed + 1)); else failed=$((failed + 1)); fi
done
echo "== results in $out"
echo "gpu-run: $passed passed, $failed failed (ctest -L egl: $tests, BenchRender: $render, BenchComputeTiles: $tiles)"
# The log is complete once tee has drained it.
exec 1>&- 2>&-
wait "$tee_pid" 2> /dev/null
[ "$failed" = 0 ]
