#!/usr/bin/env bash
# A fuzz campaign of the readers: each libFuzzer target (the `fuzz` preset)
# runs for a given time, or until a given number of inputs, over a corpus
# that it grows and keeps between campaigns, and a summary row per target
# is written (inputs run, coverage, corpus, crashes, out-of-memory inputs,
# timeouts). Fork mode restarts its child processes, so memory that a
# reader leaks does not pile up here: a plain long run of one target
# (Testing/Fuzz/README.md) is the way to see that.
#
# Usage: scripts/fuzz-campaign.sh [--jobs J] [--runs N] [TARGET|all] [MINUTES]
#        scripts/fuzz-campaign.sh --minimize [TARGET|all]
#   TARGET   a reader as the fuzz targets name it (PCD, OpenMesh,
#            OpenVDBPoints, LAMMPSDump, GromacsGro, GromacsXtc, GadgetHDF5,
#            PLYScan); default all, one after the other
#   MINUTES  the time per target (default 30)
#   --runs N stop a target once N inputs have run (before MINUTES is up)
#   --jobs J child processes per target (libFuzzer's -fork; default: the
#            number of cores)
#   --minimize  instead of a campaign: the smallest set of grown inputs that
#            adds coverage beyond the seeds (libFuzzer's -merge=1), into
#            Testing/Fuzz/Campaign/<target> (committed; a campaign starts
#            from it too, the CI smoke run does not)
#
# Out: build/fuzz-campaign/<target>/{corpus,artifacts,log.txt} and
# build/fuzz-campaign/summary.csv (one row per target and campaign,
# appended). A crash, leak, timeout or out-of-memory input does not stop
# the campaign: libFuzzer keeps going (-ignore_crashes and friends) and
# writes the input under artifacts/ (reproduce: build/fuzz/bin/Fuzz<target>Reader
# <artifact>). The seeds in Testing/Fuzz/Corpus are read, never written.
# Testing/Fuzz/README.md has the figures of the last campaign.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
jobs=$(nproc)
runs=0
minimize=0
args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --jobs) jobs=$2; shift 2 ;;
    --runs) runs=$2; shift 2 ;;
    --minimize) minimize=1; shift ;;
    -h | --help) sed -n '2,28p' "$0"; exit 0 ;;
    *) args+=("$1"); shift ;;
  esac
done
target=${args[0]:-all}
minutes=${args[1]:-30}
all=(PCD OpenMesh OpenVDBPoints LAMMPSDump GromacsGro GromacsXtc GadgetHDF5 PLYScan)
if [ "$target" = all ]; then
  targets=("${all[@]}")
else
  [[ " ${all[*]} " == *" $target "* ]] || { echo "fuzz-campaign.sh: unknown target '$target' (${all[*]})" >&2; exit 2; }
  targets=("$target")
fi

if [ ! -f "$root/build/fuzz/build.ninja" ]; then
  (cd "$root" && cmake --preset fuzz) >&2
fi
cmake --build --preset fuzz >&2

out="$root/build/fuzz-campaign"
if [ "$minimize" = 1 ]; then
  for t in "${targets[@]}"; do
    bin="$root/build/fuzz/bin/Fuzz${t}Reader"
    [ -x "$bin" ] && [ -d "$out/$t/corpus" ] || continue
    keep="$root/Testing/Fuzz/Campaign/$t"
    work="$out/$t/merge"
    rm -rf "$work" && mkdir -p "$work/out" "$work/tmp"
    # The seeds go in first, so that only inputs adding coverage beyond
    # them are merged; they are taken out again after.
    cp "$root/Testing/Fuzz/Corpus/$t"/* "$work/out/"
    seeds=$(ls "$work/out")
    TMPDIR="$work/tmp" ASAN_OPTIONS=detect_container_overflow=0:detect_leaks=0 \
      "$bin" -merge=1 -max_len=65536 -timeout=20 -rss_limit_mb=4096 -malloc_limit_mb=4096 \
      "$work/out" "$out/$t/corpus" ${keep:+$( [ -d "$keep" ] && echo "$keep")} \
      >"$work/log.txt" 2>&1 || { echo "== $t: merge failed (see $work/log.txt)" >&2; continue; }
    (cd "$work/out" && rm -f $seeds)
    rm -rf "$keep" && mkdir -p "$keep" && cp "$work/out"/* "$keep/" 2>/dev/null || true
    echo "== $t: $(ls "$keep" | wc -l) inputs, $(( $(du -sb "$keep" | cut -f1) / 1024 )) KB in ${keep#$root/}" >&2
  done
  exit 0
fi
summary="$out/summary.csv"
mkdir -p "$out"
[ -f "$summary" ] || echo "date,target,minutes,jobs,inputs,inputs_per_s,coverage,features,corpus_files,corpus_kb,crashes,ooms,timeouts,artifacts" >"$summary"

for t in "${targets[@]}"; do
  bin="$root/build/fuzz/bin/Fuzz${t}Reader"
  if [ ! -x "$bin" ]; then
    echo "fuzz-campaign.sh: $t: no $bin (its module was not built: is its library installed?)" >&2
    continue
  fi
  dir="$out/$t"
  mkdir -p "$dir/corpus" "$dir/artifacts" "$dir/tmp"
  limit=()
  [ "$runs" -gt 0 ] && limit=(-runs="$runs")
  echo "== $t: $minutes min on $jobs processes${limit[*]:+, ${limit[*]}}" >&2
  start=$SECONDS
  # The smoke run's options (Testing/Fuzz/CMakeLists.txt), in fork mode so
  # that a crash is written and the campaign goes on.
  TMPDIR="$dir/tmp" \
    ASAN_OPTIONS=detect_container_overflow=0 \
    LSAN_OPTIONS="suppressions=$root/Testing/Fuzz/lsan.supp" \
    "$bin" -fork="$jobs" -ignore_crashes=1 -ignore_ooms=1 -ignore_timeouts=1 \
    -max_total_time=$((minutes * 60)) "${limit[@]}" -max_len=65536 -timeout=20 \
    -rss_limit_mb=4096 -malloc_limit_mb=4096 -artifact_prefix="$dir/artifacts/" \
    "$dir/corpus" "$root/Testing/Fuzz/Corpus/$t" \
    $( [ -d "$root/Testing/Fuzz/Campaign/$t" ] && echo "$root/Testing/Fuzz/Campaign/$t") \
    >"$dir/log.txt" 2>&1 || true
  elapsed=$((SECONDS - start))
  # libFuzzer's fork mode reports "#INPUTS: cov: C ft: F corp: N exec/s E
  # oom/timeout/crash: O/T/X time: Ss job: J ...".
  last=$(grep -E '^#[0-9]+: cov:' "$dir/log.txt" | tail -1 || true)
  inputs=$(sed -E 's/^#([0-9]+):.*/\1/' <<<"$last")
  cov=$(sed -nE 's/.* cov: ([0-9]+).*/\1/p' <<<"$last")
  ft=$(sed -nE 's/.* ft: ([0-9]+).*/\1/p' <<<"$last")
  IFS=' ' read -r oom timeouts crashes \
    < <(sed -nE 's#.*oom/timeout/crash: ([0-9]+)/([0-9]+)/([0-9]+).*#\1 \2 \3#p' <<<"$last") || true
  files=$(find "$dir/corpus" -type f | wc -l)
  kb=$(du -sk "$dir/corpus" | cut -f1)
  rate=$(( ${inputs:-0} / (elapsed > 0 ? elapsed : 1) ))
  row="$(date +%F),$t,$minutes,$jobs,${inputs:-0},$rate,${cov:-},${ft:-},$files,$kb,${crashes:-0},${oom:-0},${timeouts:-0},$(find "$dir/artifacts" -type f | wc -l)"
  echo "$row" >>"$summary"
  echo "== $t: $row" >&2
done
column -s, -t <"$summary" >&2
