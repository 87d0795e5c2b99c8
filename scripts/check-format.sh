#!/usr/bin/env bash
# Check C/C++ formatting against .clang-format (VTK's style).
#
# Usage: scripts/check-format.sh [--fix] [--changed BASE] [FILE...]
#   no arguments     check every tracked C/C++ file (what CI runs)
#   --changed BASE   check the C/C++ files changed since git revision BASE
#   --fix            rewrite the files instead of reporting
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
fix=0
base=""
files=()
while [ $# -gt 0 ]; do
  case "$1" in
    --fix) fix=1; shift ;;
    --changed) base="$2"; shift 2 ;;
    -h|--help) sed -n '2,8p' "$0"; exit 0 ;;
    *) files+=("$1"); shift ;;
  esac
done
clang_format=$(command -v clang-format-14 || command -v clang-format || true)
[ -n "$clang_format" ] || { echo "check-format.sh: clang-format not found: run scripts/install-deps.sh" >&2; exit 2; }
if [ "${#files[@]}" -eq 0 ]; then
  if [ -n "$base" ]; then
    mapfile -t files < <(git diff --name-only --diff-filter=ACMR "$base" -- '*.h' '*.cxx' '*.cpp' '*.hpp')
  else
    mapfile -t files < <(git ls-files -co --exclude-standard -- '*.h' '*.cxx' '*.cpp' '*.hpp')
  fi
fi
[ "${#files[@]}" -gt 0 ] || { echo "check-format.sh: no C/C++ files to check"; exit 0; }
if [ "$fix" = 1 ]; then
  "$clang_format" -i "${files[@]}"
  echo "check-format.sh: formatted ${#files[@]} files"
  exit 0
fi
if ! "$clang_format" --dry-run -Werror "${files[@]}"; then
  echo "check-format.sh: formatting differs from .clang-format; run scripts/check-format.sh --fix" >&2
  exit 1
fi
echo "check-format.sh: ${#files[@]} files formatted as .clang-format asks"
