#!/usr/bin/env bash
# Render a drillpath solve report to a PNG with headless Chromium (Debian's `chromium` package).
# Not part of the test run. Usage (from anywhere):
#   docs/report-screenshot.sh [CASE.toml] [OUT.png]
# defaults: wells/j-shape/case.toml, docs/report-screenshot.png; HEIGHT=2400 sets the page height
# in pixels (the width is 1000). Extra solve options go in SOLVE_ARGS, e.g. SOLVE_ARGS="--units oilfield".
set -euo pipefail
cd "$(dirname "$0")/.."
case_file=${1:-wells/j-shape/case.toml}
out=${2:-docs/report-screenshot.png}
height=${HEIGHT:-2400}
browser=$(command -v chromium || command -v chromium-browser || true)
if [ -z "$browser" ]; then
  echo "error: needs headless Chromium (apt-get install chromium)" >&2
  exit 1
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# shellcheck disable=SC2086
cargo run --release --quiet -- solve "$case_file" --report "$tmp/report.html" ${SOLVE_ARGS:-} >/dev/null
# --no-sandbox: Chromium refuses to run as root with its sandbox (CI and containers run as root)
"$browser" --headless --no-sandbox --disable-gpu --hide-scrollbars --window-size=1000,"$height" \
  --screenshot="$tmp/shot.png" "file://$tmp/report.html" >/dev/null 2>&1
test -s "$tmp/shot.png"
mv "$tmp/shot.png" "$out"
echo "wrote $out"
