#!/usr/bin/env bash
# Packs this machine's Debian Chromium for a GPU machine that has no browser: the browser's
# folder (less its Vulkan validation layer and all locales but en-US), the libraries it links
# (less glibc's and the C++ runtime, which the other machine has), glvnd's EGL loader (for
# ANGLE's OpenGL ES back end over the NVIDIA driver's EGL), one font and a fontconfig file
# naming it; xz-compressed and cut into parts of PART bytes (40 MB by default) so that each
# fits a transfer. Usage: scripts/gpu-bench/pack-browser.sh OUT_DIR. On the other machine,
# scripts/gpu-bench/on-device.sh joins the parts and runs the benchmark.
set -euo pipefail
out="${1:?usage: pack-browser.sh OUT_DIR}"
pkg="$(mktemp -d)/pkg"
mkdir -p "$pkg/chromium/locales" "$pkg/lib" "$pkg/glvnd" "$pkg/fonts" "$out"
for f in /usr/lib/chromium/*; do
  case "$(basename "$f")" in libVkLayer_khronos_validation.so* | libVkICD_mock_icd.so* | locales) ;; *) cp -a "$f" "$pkg/chromium/" ;; esac
done
cp /usr/lib/chromium/locales/en-US.pak "$pkg/chromium/locales/"
ldd /usr/lib/chromium/chromium | awk '$3 ~ /^\// {print $1, $3}' | while read -r name path; do
  case "$name" in libc.so.* | libm.so.* | libpthread.so.* | libdl.so.* | librt.so.* | libresolv.so.* | libstdc++.so.* | libgcc_s.so.*) ;; *) cp -L "$path" "$pkg/lib/" ;; esac
done
cp -L /usr/lib/x86_64-linux-gnu/nss/*.so "$pkg/lib/"
for f in libEGL.so.1 libGLdispatch.so.0 libGLESv2.so.2; do cp -L "/usr/lib/x86_64-linux-gnu/$f" "$pkg/glvnd/"; done
cp /usr/share/fonts/truetype/dejavu/DejaVuSans.ttf "$pkg/fonts/"
printf '<?xml version="1.0"?>\n<fontconfig><dir>/tmp/chrpkg/fonts</dir><cachedir>/tmp/chrpkg/fontcache</cachedir></fontconfig>\n' > "$pkg/fonts/fonts.conf"
tar -C "$(dirname "$pkg")" -cf - pkg | xz -9 -T0 | split -b "${PART:-40000000}" -a 2 - "$out/part_"
rm -rf "$(dirname "$pkg")"
ls -l "$out"
