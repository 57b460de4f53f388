#!/usr/bin/env bash
# Installs the build tree BUILD into a scratch prefix and builds and runs the consumer project
# against it with find_package(spdfit), with the C++ compiler CXX and compiler and linker FLAGS
# when given (the sanitizer build's, whose library needs their runtime).
# Usage: check.sh BUILD [CXX [FLAGS]]
set -euo pipefail
build=$1
cxx=${2:-}
flags=${3:-}
source_dir=$(cd "$(dirname "$0")" && pwd)
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
cmake --install "$build" --prefix "$scratch/prefix" >/dev/null
cmake -S "$source_dir" -B "$scratch/build" -DCMAKE_PREFIX_PATH="$scratch/prefix" -DCMAKE_BUILD_TYPE=Release \
  ${cxx:+"-DCMAKE_CXX_COMPILER=$cxx"} ${flags:+"-DCMAKE_CXX_FLAGS=$flags" "-DCMAKE_EXE_LINKER_FLAGS=$flags"} >/dev/null
cmake --build "$scratch/build" >/dev/null
"$scratch/build/consumer" | tee "$scratch/output.txt"
# docs/cpp.md shows this program's output: it must be what the program prints.
python3=/usr/bin/python3
"$python3" - "$source_dir/../../docs/cpp.md" "$scratch/output.txt" <<'PYTHON'
import sys
doc, output = open(sys.argv[1]).read(), open(sys.argv[2]).read()
shown = doc.split("It prints:\n\n```\n", 1)[1].split("```", 1)[0]
if shown != output:
    sys.exit("docs/cpp.md shows a different output than tests/package/consumer.cpp prints:\n" + output)
PYTHON
