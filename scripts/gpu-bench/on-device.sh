#!/usr/bin/env bash
# On a GPU machine with no browser: joins the parts scripts/gpu-bench/pack-browser.sh made
# (PARTS: their paths, in order), unpacks Chromium into /tmp/chrpkg, finds the flags under which
# WebGL2 draws on the GPU (ANGLE over the NVIDIA driver's EGL, else its Vulkan), and runs
# scripts/gpu-bench/run.sh with QUERY, writing what it prints and the browser's log under OUT.
set -uo pipefail
cd "$(dirname "$0")/../.."
out="${OUT:-$(mktemp -d)}"
nvidia-smi -L 2>/dev/null
if [[ ! -x /tmp/chrpkg/chromium/chromium ]]; then
  # shellcheck disable=SC2086
  cat ${PARTS:?PARTS: the packed parts, in order} | xz -d | tar -xf - -C /tmp && mv /tmp/pkg /tmp/chrpkg || { echo 'unpacking failed'; exit 1; }
fi
export LD_LIBRARY_PATH=/tmp/chrpkg/lib:/tmp/chrpkg/glvnd:/usr/local/nvidia/lib64
export FONTCONFIG_FILE=/tmp/chrpkg/fonts/fonts.conf CHROMIUM=/tmp/chrpkg/chromium/chromium
nvidia=/usr/local/nvidia/share
[[ -f $nvidia/glvnd/egl_vendor.d/10_nvidia.json ]] && export __EGL_VENDOR_LIBRARY_FILENAMES=$nvidia/glvnd/egl_vendor.d/10_nvidia.json
[[ -f $nvidia/vulkan/icd.d/nvidia_icd.json ]] && export VK_DRIVER_FILES=$nvidia/vulkan/icd.d/nvidia_icd.json
if [[ -z "${FLAGS:-}" ]]; then
  for flags in "--use-angle=gl-egl --use-gl=angle --ozone-platform=headless --ignore-gpu-blocklist --enable-gpu" \
    "--use-angle=vulkan --enable-features=Vulkan --ignore-gpu-blocklist --enable-gpu"; do
    FLAGS="$flags" TIMEOUT=40 LOG_TO="$out/preflight.log" bash scripts/gpu-bench/run.sh "counts=2000&frames=1&qualities=draft" > "$out/preflight.jsonl"
    head -1 "$out/preflight.jsonl"
    if grep -q NVIDIA "$out/preflight.jsonl"; then export FLAGS="$flags"; break; fi
  done
  [[ -n "${FLAGS:-}" ]] || { echo 'WebGL2 does not draw on the GPU here'; exit 2; }
fi
echo "FLAGS=$FLAGS"
TIMEOUT="${BENCH_TIMEOUT:-400}" LOG_TO="$out/bench.log" bash scripts/gpu-bench/run.sh "${QUERY:-counts=100000,1000000&qualities=standard,draft&steppers=cpu,gpu&live=6}" | tee "$out/gpu-bench.jsonl"
