#!/usr/bin/env bash
# The real-time view's frame rate on this machine's GPU: headless Chromium with WebGL2 on the
# GPU (ANGLE's Vulkan back end, or what FLAGS names), the built site (dist/, `npm run build`)
# served by Python, and scripts/gpu-bench/page.js reporting through the console. Needs no Node
# on the GPU machine.
#   CHROMIUM=/path/to/chromium scripts/gpu-bench/run.sh [query]   e.g. "frames=10&counts=10000"
# (query: frames, counts, qualities, steppers, solids, profile, live, liveView, twin, flow, presets; TIMEOUT seconds,
# 600 by default).
# Prints one JSON object per line (the renderer's name first). docs/BENCHMARKS.md records a run.
# On a machine with no browser: pack-browser.sh here, on-device.sh there.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
chromium="${CHROMIUM:-/usr/bin/chromium}"
port="${PORT:-8719}"
site="$(mktemp -d)"
profile="$(mktemp -d)"
log="$(mktemp)"
# LOG_TO=path keeps the browser's whole log (for a run that fails on a machine given back after).
trap 'kill $server $browser 2>/dev/null || true; [ -z "${LOG_TO:-}" ] || cp "$log" "$LOG_TO"; rm -rf "$site" "$profile" "$log"' EXIT
cp -r "$root/dist/." "$site/"
cp "$root/scripts/gpu-bench/page.js" "$site/gpu-bench.js"
cp "$root/scripts/gpu-bench/flow.js" "$site/flow-bench.js"
cp -r "$root/web/src/flow-gpu" "$site/flow-gpu"
cp "$root/tests/support/gas-twin.js" "$root/scripts/plume-spheres.js" "$site/"
for f in dense-plume small-plume; do cp "$root/tests/fixtures/$f.json" "$site/"; done
sed 's#</body>#<script type="module" src="./gpu-bench.js"></script></body>#' "$root/dist/index.html" > "$site/gpu-bench.html"
python3 -m http.server "$port" --bind 127.0.0.1 --directory "$site" >/dev/null 2>&1 & server=$!
sleep 1
# FLAGS replaces the GPU flags (e.g. "--use-angle=swiftshader --enable-unsafe-swiftshader").
# shellcheck disable=SC2086
"$chromium" --headless=new --no-sandbox ${FLAGS:---use-angle=vulkan --enable-features=Vulkan --ignore-gpu-blocklist --enable-gpu} \
  --enable-logging=stderr --log-level=0 \
  --disable-background-networking --disable-component-update --disable-sync \
  --window-size=1920,1080 --user-data-dir="$profile" \
  "http://127.0.0.1:$port/gpu-bench.html?${1:-}" 2>"$log" & browser=$!
for _ in $(seq 1 "${TIMEOUT:-600}"); do
  sleep 1
  kill -0 "$browser" 2>/dev/null || break
  grep -a -q 'GPUBENCH {"done"\|GPUBENCH {"error"' "$log" && break
done
grep -a -o 'GPUBENCH {.*}' "$log" | sed 's/^GPUBENCH //'
grep -a -q 'GPUBENCH {"done"' "$log"
