#!/bin/sh
# Installs the Debian packages tinlod needs (idempotent; quick when all are present).
# Used by `make demo`, `make test` and `make bench`; run as root on Debian 12.
set -eu
PKGS="cmake g++ make pkg-config libopenmesh-dev libglm-dev libopenimageio-dev openimageio-tools
libtiff-dev libpng-dev libproj-dev libcli11-dev nlohmann-json3-dev libgtest-dev libgmock-dev
libbenchmark-dev libmeshoptimizer-dev libegl-dev libegl1-mesa-dev libgl-dev libgl1-mesa-dri
libosmesa6-dev libgbm-dev libglfw3-dev libimgui-dev xvfb xauth unzip clang-format dpkg-dev file
binutils $*"
missing=""
for p in $PKGS; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
[ -z "$missing" ] && exit 0
echo "setup: installing$missing"
if [ "$(id -u)" != 0 ]; then
    echo "setup: missing Debian packages:$missing (run as root, or install them)" >&2
    exit 1
fi
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq || apt-get update
apt-get install -y -qq --no-install-recommends $missing
