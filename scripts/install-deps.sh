#!/usr/bin/env bash
# Installs what Undergrowth needs from Debian 12's own packages (nothing else is downloaded).
# Run as root, or with sudo available. Skips apt entirely when everything is already installed.
set -euo pipefail

packages=(
  build-essential cmake pkg-config git
  libglm-dev nlohmann-json3-dev libtinygltf-dev libopenmesh-dev libmeshoptimizer-dev libstb-dev
  libglfw3-dev libimgui-dev libgl-dev
  libgtest-dev
  xvfb xauth
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
