#!/bin/sh
# Install what sph needs on Debian when it is missing: a C compiler, make, pkg-config,
# Lua 5.4 (headers, and the stock interpreter the tests also run), Cairo headers, a font
# for labels, and Pillow (an independent PNG/APNG decoder used by the tests).
set -e
need=""
command -v cc >/dev/null 2>&1 || need="$need build-essential"
command -v pkg-config >/dev/null 2>&1 || need="$need pkg-config"
pkg-config --exists lua5.4 2>/dev/null || need="$need liblua5.4-dev"
command -v lua5.4 >/dev/null 2>&1 || need="$need lua5.4"
pkg-config --exists cairo 2>/dev/null || need="$need libcairo2-dev"
[ -e /usr/share/fonts/truetype/dejavu/DejaVuSans.ttf ] || need="$need fonts-dejavu-core"
/usr/bin/python3 -c "import PIL" 2>/dev/null || need="$need python3-pil"
[ -z "$need" ] && exit 0
if [ "$(id -u)" = 0 ]; then SUDO=; else SUDO=sudo; fi
echo "installing:$need"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq $need >/dev/null
