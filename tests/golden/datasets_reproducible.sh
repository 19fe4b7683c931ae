#!/usr/bin/env bash
# Regenerates the shipped datasets into a temporary directory and compares every byte.
set -euo pipefail
root=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$root/scripts/make-datasets" "$tmp" 2>/dev/null
status=0
for f in $(cd "$root/datasets" && ls seed000/*.json zedmini/*.json); do
  if ! cmp -s "$tmp/$f" "$root/datasets/$f"; then
    echo "datasets/$f differs from what scripts/make-datasets writes" >&2
    status=1
  fi
done
exit $status
