#!/usr/bin/env bash
# Fails if any C++ source is not formatted with the repository's .clang-format.
# Exit code 77 (ctest: skipped) when clang-format is not installed.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v clang-format > /dev/null; then
  echo "clang-format not installed: format check skipped"
  exit 77
fi
mapfile -t files < <(find core geometry energies integrators solver sim io problems apps tests bench contact examples mesh \
  -name '*.h' -o -name '*.cc' 2> /dev/null | sort)
clang-format --dry-run --Werror "${files[@]}"
echo "${#files[@]} files formatted"
