#!/usr/bin/env bash
# Four shards of one err-sim run under GNU parallel, as on a cluster (docs/scale.md), merge into
# the report of the unsharded run, bit for bit (issue 12 item 8). Usage: ERR_SIM CHAIN
set -euo pipefail
err_sim=$1
chain=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
args=(--samples 20000 --budget-samples 4000 --threads 1 -q)
"$err_sim" run "$chain" "${args[@]}" -o "$tmp/single.json"
parallel --will-cite --halt now,fail=1 -j 2 \
  "$err_sim" run "$chain" "${args[@]}" --shard {}/4 -o "$tmp/shard-{}.json" ::: 0 1 2 3
"$err_sim" merge "$chain" "$tmp"/shard-3.json "$tmp"/shard-1.json "$tmp"/shard-0.json "$tmp"/shard-2.json \
  -o "$tmp/merged.json" -q
# Every field but the provenance (the command lines differ): numbers compared as doubles, i.e. bits.
/usr/bin/python3 - "$tmp/single.json" "$tmp/merged.json" <<'PY'
import json, sys
single, merged = (json.load(open(p)) for p in sys.argv[1:3])
for report in (single, merged):
    report.pop("provenance")
if single != merged:
    print("the merged report differs from the unsharded run")
    sys.exit(1)
print(f"4 shards under GNU parallel merge into the unsharded report ({len(json.dumps(merged))} bytes compared)")
PY
