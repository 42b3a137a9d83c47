#!/bin/bash
# The acceptance grid's 15 buckled sliding cases (issue 16), each solved once by the release CLI
# at `--fidelity whole`: one line per case with the solve's seconds (`solver.seconds`), Newton
# iterations, factorizations, hook load (kN), whether the answer came from the buckled shape
# (`solver.buckled_start`) and, for a lock-up answer, the WOB the results are at (kN).
# Usage: bash benches/buckled_slides.sh [DIR]   (DIR: where the grid's cases are written,
# default target/grid-cases). Needs python3 for the JSON. docs/performance.md records the
# results ("The damped re-solve first").
set -euo pipefail
cd "$(dirname "$0")/.."
dir=$(realpath -m "${1:-target/grid-cases}")
cargo build --release --quiet
if [ ! -f "$dir/inc88_lat2000_sliding20_mu0.2/case.toml" ]; then
    DRILLPATH_GRID_CASES="$dir" cargo test --release --quiet --test verification \
        acceptance_grid::write_cases -- --ignored >/dev/null
fi
cases="inc88_lat2000_sliding20_mu0.2 inc88_lat2000_sliding60_mu0.2 inc90_lat2000_sliding20_mu0.2
inc90_lat2000_sliding60_mu0.2 inc92_lat2000_sliding20_mu0.2 inc92_lat2000_sliding60_mu0.2
inc95_lat2000_sliding20_mu0.2 inc95_lat2000_sliding60_mu0.2 inc88_lat1000_sliding20_mu0.35
inc90_lat1000_sliding20_mu0.2 inc92_lat1000_sliding20_mu0.2 inc95_lat1000_sliding60_mu0.2
inc100_lat1000_sliding20_mu0.2 inc88_lat1000_sliding60_mu0.35 inc110_lat1000_sliding20_mu0.2"
printf '%-32s %8s %6s %8s %10s %8s %10s\n' case seconds iter factor hook_kN buckled lockup_wob
for c in $cases; do
    json=$(target/release/drillpath solve "$dir/$c/case.toml" --fidelity whole --json 2>/dev/null) || {
        echo "$c: no answer (exit $?)"
        continue
    }
    echo "$json" | python3 -c '
import json, sys
d = json.load(sys.stdin); v = d["solver"]; l = d.get("lock_up") or {}
wob = l.get("results_at_wob_kN")
print("%-32s %8.2f %6d %8d %10.3f %8s %10s" % (sys.argv[1], v["seconds"], v["iterations"],
      v["factorizations"], d["surface"]["hook_load_kN"], bool(v.get("buckled_start")),
      "-" if wob is None else "%.2f" % wob))' "$c"
done
