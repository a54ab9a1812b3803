#!/bin/sh
# Installs the Debian packages tinlod needs (idempotent; quick when all are present).
# Used by `make demo`, `make test` and `make bench`; run as root on Debian 12.
set -eu
PKGS="cmake g++ make pkg-config libopenmesh-dev libglm-dev libopenimageio-dev openimageio-tools
libtiff-dev libpng-dev libproj-dev libcli11-dev nlohmann-json3-dev libgtest-dev libgmock-dev
libbenchmark-dev libmeshoptimizer-dev libegl-dev libegl1-mesa-dev libgl-dev libgl1-mesa-dri
libosmesa6-dev libgbm-dev libglfw3-dev libimgui-dev xvfb xauth unzip clang-format dpkg-dev file
binutils zlib1g-dev $*"
# The CesiumJS test of the tiles (tests/test_tiles_cesium.cpp) draws them in headless Chromium.
PKGS="$PKGS chromium"
# The tile build over a Dask cluster (python/tinlod_dask) runs under Debian's /usr/bin/python3.
PKGS="$PKGS python3-distributed"
missing=""
for p in $PKGS; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
# The tile tests read tinlod's tiles with a decoder and CesiumJS from npm (tests/tiles), installed
# here so the tests run offline.
npm_tiles() {
    tiles="$(dirname "$0")/../tests/tiles"
    [ -d "$tiles/node_modules/@here/quantized-mesh-decoder" ] && [ -d "$tiles/node_modules/cesium" ] &&
        [ -d "$tiles/node_modules/puppeteer-core" ] && return 0
    command -v npm >/dev/null || [ "$(id -u)" != 0 ] ||
        { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq nodejs npm; } ||
        true
    (cd "$tiles" && npm ci --no-audit --no-fund --loglevel=error) ||
        echo "setup: npm ci in tests/tiles failed; test_tiles will fail" >&2
}
[ -z "$missing" ] && { npm_tiles; exit 0; }
echo "setup: installing$missing"
if [ "$(id -u)" != 0 ]; then
    echo "setup: missing Debian packages:$missing (run as root, or install them)" >&2
    exit 1
fi
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq || apt-get update
apt-get install -y -qq --no-install-recommends $missing
npm_tiles
