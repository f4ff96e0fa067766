#!/usr/bin/env bash
# Writes <build>/bxdf_lab-<version>.zip: the add-on package with the compiled `bxdf` module inside
# it (bxdf_lab/vendor/bxdf, which dependency.py puts on sys.path when no other `bxdf` imports), for
# Edit > Preferences > Add-ons > Install. The module is built for /usr/bin/python3.11 (Debian's
# Blender 3.4) and links the system's Embree, TBB and OpenImageIO.
set -euo pipefail
BUILD=${1:-build}
cd "$(dirname "$0")/.."
module="$BUILD/python/bxdf"
if ! ls "$module"/_bxdf*.so >/dev/null 2>&1; then
  echo "addon-zip: no built module in $module (build with: make build)" >&2
  exit 1
fi
/usr/bin/python3 - "$BUILD" <<'PY'
import ast, pathlib, sys, zipfile
build = pathlib.Path(sys.argv[1])
addon = pathlib.Path("blender_addon/bxdf_lab")
tree = ast.parse((addon / "__init__.py").read_text())
bl_info = next(ast.literal_eval(n.value) for n in tree.body
               if isinstance(n, ast.Assign) and getattr(n.targets[0], "id", "") == "bl_info")
version = ".".join(str(v) for v in bl_info["version"])
out = build / f"bxdf_lab-{version}.zip"
skip = {"__pycache__"}
with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as z:
    for path in sorted(addon.rglob("*")):
        if path.is_file() and not skip & set(path.parts) and path.suffix != ".pyc":
            z.write(path, "bxdf_lab/" + str(path.relative_to(addon)))
    for path in sorted((build / "python" / "bxdf").iterdir()):
        if path.is_file():
            z.write(path, "bxdf_lab/vendor/bxdf/" + path.name)
print(f"addon-zip: wrote {out} ({out.stat().st_size / 1e6:.1f} MB)")
PY
