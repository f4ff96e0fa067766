#!/usr/bin/env bash
# Links the Blender add-on and the built `bxdf` module into Blender's user script folders, so
# that Debian's Blender (which embeds /usr/bin/python3.11) finds both:
#   <scripts>/addons/bxdf_lab -> blender_addon/bxdf_lab
#   <scripts>/addons/modules/bxdf -> <build>/python/bxdf (on sys.path even with --factory-startup)
# <scripts> is $BLENDER_USER_SCRIPTS, else ~/.config/blender/<version>/scripts.
# Then enable "BxDF Lab" in Edit > Preferences > Add-ons (or: blender --addons bxdf_lab).
set -euo pipefail
BUILD=${1:-build}
cd "$(dirname "$0")/.."
ROOT=$(pwd)
case "$BUILD" in /*) ;; *) BUILD="$ROOT/$BUILD" ;; esac
module="$BUILD/python/bxdf"
if ! ls "$module"/_bxdf*.so >/dev/null 2>&1; then
  echo "install-addon: no built module in $module (build with: make build)" >&2
  exit 1
fi
version=$(blender --version 2>/dev/null | sed -n 's/^Blender \([0-9]*\.[0-9]*\).*/\1/p' | head -1)
scripts=${BLENDER_USER_SCRIPTS:-$HOME/.config/blender/${version:-3.4}/scripts}
mkdir -p "$scripts/addons/modules"
ln -sfn "$ROOT/blender_addon/bxdf_lab" "$scripts/addons/bxdf_lab"
ln -sfn "$module" "$scripts/addons/modules/bxdf"
echo "install-addon: linked bxdf_lab and bxdf into $scripts"
# Check the way Blender will: its own Python must import the module.
blender -b --factory-startup --python-exit-code 1 --python-expr \
  "import sys; sys.path.insert(0, '$scripts/addons/modules'); import bxdf; print('install-addon: bxdf imports in Blender, models:', ', '.join(bxdf.models()))" \
  2>&1 | grep '^install-addon' || { echo "install-addon: Blender cannot import bxdf" >&2; exit 1; }
