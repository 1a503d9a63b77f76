#!/usr/bin/env bash
# Installs what Undergrowth needs from Debian 12's own packages (nothing else is downloaded).
# Run as root, or with sudo available. Skips apt entirely when everything is already installed.
set -euo pipefail

packages=(
  build-essential cmake pkg-config git
  libglm-dev nlohmann-json3-dev libtinygltf-dev libopenmesh-dev libmeshoptimizer-dev libstb-dev
  libglfw3-dev libimgui-dev libgl-dev libepoxy-dev
  libegl-dev libegl1 libegl-mesa0 libgl1-mesa-dri  # undergrowth render: EGL without a display
  libgtest-dev
  xvfb xauth xdotool
  slurm-wlm munge  # region jobs: the single-node cluster of tests/cli/run_world_tests.sh
  nodejs npm
)

missing=()
for p in "${packages[@]}"; do
  # Node.js and npm (the independent glTF checks, tests/gltf) count as present when the commands are
  # there: a Node.js from another source (e.g. nodesource's nodejs, which bundles npm) must not be
  # replaced by, or conflict with, Debian's packages.
  case "$p" in
    nodejs) command -v node >/dev/null 2>&1 && continue ;;
    npm) command -v npm >/dev/null 2>&1 && continue ;;
  esac
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
