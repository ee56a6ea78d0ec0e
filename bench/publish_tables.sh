#!/usr/bin/env bash
# Copy the tables and charts that docs/ quotes from bench/results/ (where
# the bench scripts write them, not in git) to bench/tables/ (in git).
# Run after a bench script has regenerated its results; files a script has
# not (re)made are left as they are.
set -euo pipefail
cd "$(dirname "$0")"
mkdir -p tables
n=0
for f in tables/*; do
  src="results/$(basename "$f")"
  if [ -f "$src" ] && ! cmp -s "$src" "$f"; then
    cp "$src" "$f"
    n=$((n + 1))
  fi
done
echo "bench/tables: $n file(s) updated"
