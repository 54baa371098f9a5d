#!/usr/bin/env bash
# cpack builds idbench_<version>_amd64.deb; its file list, its dependencies
# (from dpkg-shlibdeps), and the packaged binary extracted into a temporary
# root running `idbench run` (the paper's table).
# Usage: deb_test.sh BUILD_DIR VERSION
set -euo pipefail
build=$1 version=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cpack -G DEB --config "$build/CPackConfig.cmake" -B "$work" > "$work/cpack.log"
deb="$work/idbench_${version}_amd64.deb"
test -f "$deb" || { echo "no $deb"; ls "$work"; cat "$work/cpack.log"; exit 1; }
dpkg-deb -I "$deb" | tee "$work/info" | grep -E '^ (Package|Version|Depends|Recommends):'
for dep in libbullet libnlopt liburdfdom libassimp libosmesa libcairo libglfw libpng; do
  grep -q "Depends:.*$dep" "$work/info" || { echo "Depends lacks $dep"; exit 1; }
done
dpkg-deb -c "$deb" | awk '{print $6}' > "$work/files"
for file in ./usr/bin/idbench ./usr/share/doc/idbench/copyright ./usr/include/idbench/engine/robot_model.h \
            ./usr/lib/cmake/idbench/idbenchConfig.cmake ./usr/share/idbench/robots/paper6r.urdf; do
  grep -qx "$file" "$work/files" || { echo "missing $file"; exit 1; }
done
grep -q '^./usr/lib/python3/dist-packages/idbench\..*\.so$' "$work/files" || { echo "missing the Python module"; exit 1; }
dpkg-deb -x "$deb" "$work/root"
"$work/root/usr/bin/idbench" --version
(cd "$work" && "$work/root/usr/bin/idbench" run --out "$work/out") | tee "$work/run.txt"
grep -q "^largest relative error over identifiable parameters" "$work/run.txt"
PYTHONPATH="$work/root/usr/lib/python3/dist-packages" /usr/bin/python3 -c \
  "import idbench; print('python module', idbench.__version__); assert idbench.__version__ == '$version'"
