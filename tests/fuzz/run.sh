#!/usr/bin/env bash
# Runs every fuzz target of a fuzz build for a bounded time: run.sh BUILD_DIR SECONDS
set -euo pipefail
build=$1
seconds=${2:-60}
here=$(cd "$(dirname "$0")" && pwd)
status=0
for target in "$build"/tests/fuzz/fuzz_*; do
  [ -x "$target" ] || continue
  name=$(basename "$target")
  corpus="$here/corpus/${name#fuzz_}"
  work=$(mktemp -d)
  cp -r "$corpus"/. "$work"/ 2>/dev/null || true
  echo "== $name: ${seconds}s (seed corpus $corpus)"
  if ! "$target" -max_total_time="$seconds" -max_len=4096 -timeout=10 -artifact_prefix="$build/$name-" "$work" 2>&1 |
      grep -E "^#[0-9]+ *(DONE|pulse)|ERROR|SUMMARY|Done|crash-|timeout-|leak-" | tail -5; then
    :
  fi
  if ls "$build/$name-"* >/dev/null 2>&1; then
    echo "$name: findings in $build/$name-*"
    status=1
  else
    echo "$name: no findings"
  fi
  rm -rf "$work"
done
exit $status
