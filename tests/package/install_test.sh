#!/usr/bin/env bash
# `cmake --install` into a temporary prefix, then a project outside the tree
# (consumer/) finds it with find_package(idbench), builds and runs.
# Usage: install_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1 source=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
test -x "$work/prefix/bin/idbench"
test -f "$work/prefix/include/idbench/ident/joint_torque_identifier.h"
test -f "$work/prefix/include/idbench/logs/joint_log_csv_reader.h"
test -f "$work/prefix/lib/cmake/idbench/idbenchConfig.cmake"
# Internal headers stay out.
if find "$work/prefix/include" -name number_format.h -o -name plausible_program.h | grep -q .; then
  echo "internal headers were installed"; exit 1
fi
"$work/prefix/bin/idbench" --version
launcher=()
if command -v ccache > /dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S "$source/tests/package/consumer" -B "$work/consumer" -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$work/prefix" "${launcher[@]}" > "$work/configure.log"
cmake --build "$work/consumer" > "$work/build.log"
"$work/consumer/consumer" | tee "$work/consumer.txt"
# The line README.md quotes for this program (its "consumer" example).
/usr/bin/python3 "$source/tests/docs/doc_examples_test.py" --source "$source" \
  --check-output README.md consumer "$work/consumer.txt"
# The Python module from the installed prefix.
PYTHONPATH="$work/prefix/lib/python3/dist-packages" /usr/bin/python3 -c \
  "import idbench; print('python module', idbench.__version__, 'from', idbench.__file__)" | tee "$work/python.txt"
grep -q "from $work/prefix/" "$work/python.txt"
