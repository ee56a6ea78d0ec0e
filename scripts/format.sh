#!/usr/bin/env bash
# Apply .clang-format to fsai's C++ sources; with --check, only report
# (exit 1 if any file would change).
set -euo pipefail
cd "$(dirname "$0")/.."
mapfile -t files < <(git ls-files 'src/*.h' 'src/*.cpp' 'demos/*.cpp' \
  'tests/*.cpp' 'tests/*.h' 'forms/*.h' 2>/dev/null || true)
if [ ${#files[@]} -eq 0 ]; then
  mapfile -t files < <(find src demos tests forms -name '*.h' -o -name '*.cpp')
fi
if [ "${1:-}" = "--check" ]; then
  clang-format --dry-run --Werror "${files[@]}"
  echo "format: ${#files[@]} files clean"
else
  clang-format -i "${files[@]}"
fi
