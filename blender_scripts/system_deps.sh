#!/usr/bin/env bash
# The shared libraries the bpy wheel links against (X11 client libs) and needs for
# Workbench/EEVEE rendering without a GPU (Mesa's EGL + llvmpipe). Installs the missing ones
# with apt-get when run as root; otherwise says what to install.
set -euo pipefail
libs=(libX11.so.6 libXrender.so.1 libXfixes.so.3 libXi.so.6 libxkbcommon.so.0 libSM.so.6 libXext.so.6 libGL.so.1 libEGL.so.1)
pkgs="libx11-6 libxrender1 libxfixes3 libxi6 libxkbcommon0 libsm6 libxext6 libgl1 libegl1 libegl-mesa0 libgl1-mesa-dri"
missing=0
# Read the cache once: piping ldconfig into `grep -q` fails under pipefail when grep stops early.
cache=$(ldconfig -p)
for l in "${libs[@]}"; do
  grep -qF "$l" <<<"$cache" || missing=1
done
[ -e /usr/share/glvnd/egl_vendor.d/50_mesa.json ] || missing=1
[ "$missing" = 0 ] && exit 0
if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
  echo "installing system libraries for bpy: $pkgs"
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $pkgs >/dev/null
else
  echo "bpy needs these system libraries; install them (Debian/Ubuntu): sudo apt-get install $pkgs" >&2
  exit 1
fi
