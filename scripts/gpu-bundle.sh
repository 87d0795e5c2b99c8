#!/usr/bin/env bash
# Packs everything a bare NVIDIA host needs to run the GPU tests and
# benchmarks into one tarball: OUTDIR/pointsurfaces-gpu.tar.xz (at most
# 60 MiB). The host needs a driver with its EGL vendor library and bash;
# nothing from Debian, no VTK, no Python, no network.
#
# Usage: scripts/gpu-bundle.sh OUTDIR
#
# Builds the `vtk` preset, then stages:
#   bin/   the EGL render test driver (PointSurfacesRenderingCxxTests), the
#          C++ benchmarks (BenchRender: splats, metaballs and a paged
#          splat file against their peers; BenchComputeTiles) and ctest;
#   lib/   the project's libraries and the ldd closure of all of them: the
#          Debian libraries they load, without glibc and without any GL
#          vendor library, plus the glvnd loaders (libEGL.so.1, libGL.so.1,
#          libGLX.so.0, libOpenGL.so.0, libGLdispatch.so.0) that pick the
#          host's driver;
#   data/  the test data and the render tests' baseline images;
#   tests/ the EGL tests as a CTestTestfile template (paths filled in by
#          gpu-run.sh);
#   gpu-run.sh, README.txt, VERSION.
# Then: tar xf pointsurfaces-gpu.tar.xz && pointsurfaces-gpu/gpu-run.sh RESULTS
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
if [ $# -ne 1 ]; then
  sed -n '2,7p' "$0"
  exit 2
fi
mkdir -p "$1"
out=$(cd "$1" && pwd)
build="$root/build/vtk"
limit=$((60 * 1024 * 1024))

"$root/scripts/install-deps.sh"
if [ ! -f "$build/CMakeCache.txt" ]; then
  (cd "$root" && cmake --preset vtk > "$out/configure.log")
fi
cmake --build "$build" --target PointSurfacesRenderingCxxTests BenchRender BenchComputeTiles

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
stage="$work/pointsurfaces-gpu"
mkdir -p "$stage/bin" "$stage/lib" "$stage/data" "$stage/tests"

bins=(PointSurfacesRenderingCxxTests BenchRender BenchComputeTiles)
for b in "${bins[@]}"; do
  cp "$build/bin/$b" "$stage/bin/"
done
cp "$(command -v ctest)" "$stage/bin/ctest"

# The project's libraries, under their sonames.
for lib in "$build"/lib/libPointSurfaces*.so.*; do
  soname=$(objdump -p "$lib" | awk '/SONAME/ {print $2}')
  [ -n "$soname" ] && [ ! -e "$stage/lib/$soname" ] && cp -L "$lib" "$stage/lib/$soname"
done

# The ldd closure of every binary and library, less glibc and GL vendor
# libraries (the host's driver brings its own, and its glibc).
skip='^(linux-vdso|ld-linux|libc|libm|libmvec|libpthread|libdl|librt|libutil|libresolv|libnsl|libanl|libcrypt|libBrokenLocale)\.so|^lib(EGL|GLX|GLESv1_CM|GLESv2)_|^libnvidia|^libcuda'
# Copies into lib/ what the files given load and lib/ lacks (ldd resolves
# the whole closure, through lib/ first).
copy_closure() {
  for f in "$@"; do
    LD_LIBRARY_PATH="$stage/lib" ldd "$f" | awk '/=>/ && $3 ~ /^\// {print $1, $3}'
  done | sort -u | while read -r name path; do
    if [[ "$name" =~ $skip ]] || [ -e "$stage/lib/$name" ]; then
      continue
    fi
    cp -L "$path" "$stage/lib/$name"
  done
}
copy_closure "$stage"/bin/* "$stage"/lib/*
# The glvnd loaders, whether or not a binary links them directly, and what
# they load.
for name in libEGL.so.1 libGL.so.1 libGLX.so.0 libOpenGL.so.0 libGLdispatch.so.0; do
  if [ ! -e "$stage/lib/$name" ]; then
    path=$(ldconfig -p | awk -v n="$name" '$1 == n && /x86-64/ {print $NF; exit}')
    [ -n "$path" ] && cp -L "$path" "$stage/lib/$name"
  fi
done
copy_closure "$stage"/lib/*
strip --strip-unneeded "$stage"/bin/* "$stage"/lib/* 2> /dev/null || true

# Data and baselines, at their paths relative to the repository.
mkdir -p "$stage/data/Testing" "$stage/data/Rendering/Testing/Data"
cp -r "$root/Testing/Data" "$stage/data/Testing/"
cp -r "$root/Rendering/Testing/Data/Baseline" "$stage/data/Rendering/Testing/Data/"

# The EGL tests that the bundled binaries run, with the build's and the
# repository's paths turned into placeholders.
ctest --test-dir "$build" -L egl --show-only=json-v1 > "$work/tests.json"
python3 - "$work/tests.json" "$root" "$build" "${bins[*]}" > "$stage/tests/CTestTestfile.cmake.in" << 'EOF'
import json, sys
tests, root, build, bins = json.load(open(sys.argv[1]))["tests"], sys.argv[2], sys.argv[3], sys.argv[4].split()

def path(arg):
    if arg.startswith(build + "/bin/") and arg[len(build) + 5:] in bins:
        return "@BUNDLE@/bin/" + arg[len(build) + 5:]
    if arg.startswith(build + "/Testing/Temporary"):
        return "@OUT@/Testing/Temporary" + arg[len(build) + 18:]
    if arg.startswith(build):
        return "@OUT@/work" + arg[len(build):]
    if arg.startswith(root + "/"):
        return "@BUNDLE@/data/" + arg[len(root) + 1:]
    return arg

def quote(s):
    return '"' + s.replace("\\", "\\\\").replace('"', '\\"') + '"'

print("# The EGL render tests of PointSurfaces, for the GPU bundle (made by gpu-bundle.sh).")
for t in tests:
    command = t.get("command") or []
    if not command or not path(command[0]).startswith("@BUNDLE@/bin/"):
        continue  # Python, MPI and CMake-script tests need what the bundle does not carry
    props = {p["name"]: p["value"] for p in t.get("properties", [])}
    print("add_test(%s %s)" % (quote(t["name"]), " ".join(quote(path(a)) for a in command)))
    settings = ["WORKING_DIRECTORY", quote("@OUT@/work")]
    for key in ("LABELS", "ENVIRONMENT", "ENVIRONMENT_MODIFICATION", "FAIL_REGULAR_EXPRESSION",
                "PASS_REGULAR_EXPRESSION", "WILL_FAIL"):
        if key in props:
            value = props[key] if isinstance(props[key], list) else [props[key]]
            settings += [key, quote(";".join(str(v) for v in value))]
    print("set_tests_properties(%s PROPERTIES %s)" % (quote(t["name"]), " ".join(settings)))
EOF
if ! grep -q add_test "$stage/tests/CTestTestfile.cmake.in"; then
  echo "gpu-bundle.sh: no EGL test found in $build" >&2
  exit 1
fi

cp "$root/scripts/gpu-run.sh" "$stage/gpu-run.sh"
chmod +x "$stage/gpu-run.sh"
(cd "$root" && git describe --always --dirty 2> /dev/null || echo unknown) > "$stage/VERSION"
cat > "$stage/README.txt" << 'EOF'
PointSurfaces GPU bundle: the EGL render tests and the benchmarks, with the
libraries they load (not glibc, not the GL driver: the host's EGL vendor
library is found through the bundled glvnd loader).

  ./gpu-run.sh RESULTS            # ctest -L egl, then the benchmarks at 1080p
  ./gpu-run.sh --smoke RESULTS    # tiny sizes

RESULTS/gpu-run.log has everything printed (EGL platform and GL renderer
first), RESULTS/bench/*.csv and *.png the benchmarks, and
RESULTS/ctest/Testing/Temporary the test images.
EOF

# POINTSURFACES_BUNDLE_XZ_LEVEL: xz's preset, 6 by default (bookworm: 47 MiB
# in 56 s on 2 cores on 2026-11-28). The bundle's own test uses 1 (bookworm:
# 54 MiB in 12 s; forky, whose libraries are larger: 65 MiB), where the size
# limit below is not checked: it holds for the default preset only.
level=${POINTSURFACES_BUNDLE_XZ_LEVEL:-6}
tar -C "$work" -cf - pointsurfaces-gpu | xz -T2 "-$level" > "$out/pointsurfaces-gpu.tar.xz"
size=$(stat -c %s "$out/pointsurfaces-gpu.tar.xz")
echo "gpu-bundle.sh: $out/pointsurfaces-gpu.tar.xz, $((size / 1024 / 1024)) MiB" \
  "($(ls "$stage/lib" | wc -l) libraries, $(grep -c add_test "$stage/tests/CTestTestfile.cmake.in") tests," \
  "xz -$level)"
if [ "$level" -lt 6 ]; then
  echo "gpu-bundle.sh: xz -$level: the 60 MiB limit is checked at the default preset (6) only"
elif [ "$size" -gt "$limit" ]; then
  echo "gpu-bundle.sh: the bundle is over 60 MiB" >&2
  exit 1
fi
