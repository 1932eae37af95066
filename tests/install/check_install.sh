#!/usr/bin/env bash
# `cmake --install` works like a C++ library's (docs/install.md): the installed gaitopt runs from
# any folder and names the default robot it uses; a CMake project finds the package
# (gaitopt::gaitopt, gaitopt::walker, GAITOPT_DATA_DIR) and a pkg-config build links the same
# library; both programs give the same model.
#   check_install.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
source_dir="$1"
build_dir="$2"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
fail() { echo "check_install: $*" >&2; exit 1; }

cmake --install "$build_dir" --prefix "$work/prefix" >"$work/install.log"
data="$work/prefix/share/gaitopt"
for f in bin/gaitopt lib/libgaitopt.a lib/libgaitopt_walker.so include/gaitopt/control/walker.h \
         include/gaitopt/model/model.hpp lib/cmake/gaitopt/gaitoptConfig.cmake \
         lib/pkgconfig/gaitopt.pc share/gaitopt/configs/default.yaml \
         share/gaitopt/configs/robot/rabbit_miossec.yaml share/gaitopt/scripts/plot/stick.py; do
  [ -e "$work/prefix/$f" ] || fail "not installed: $f"
done

# The installed tool, from another folder, resolves its default robot in the installed data.
(cd "$work" && "$work/prefix/bin/gaitopt" model --q 0.1,-3,-3,0.1,-3 >model.json 2>model.err)
grep -q "using $data/configs/robot/rabbit_miossec.yaml" "$work/model.err" ||
  fail "the default robot's path is not printed: $(cat "$work/model.err")"
grep -q '"robot": "rabbit_miossec"' "$work/model.json" || fail "model output: $(head -3 "$work/model.json")"
# and an optimisation of an installed configuration, written where asked
(cd "$work" && "$work/prefix/bin/gaitopt" optimize --config "$data/configs/default.yaml" \
   --out "$work/opt" --quiet >opt.log 2>&1) || fail "optimize: $(tail -3 "$work/opt.log")"
grep -q '"status": "optimal"' "$work/opt/summary.json" || fail "optimize did not end optimal"

# A CMake user project.
cmake -S "$source_dir/tests/install/consumer" -B "$work/consumer" \
  -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_BUILD_TYPE=Release >"$work/configure.log" 2>&1 ||
  fail "find_package(gaitopt) failed: $(tail -5 "$work/configure.log")"
cmake --build "$work/consumer" >"$work/build.log" 2>&1 || fail "build: $(tail -5 "$work/build.log")"
"$work/consumer/consumer" >"$work/cmake.out" || fail "the CMake-built program failed"

# The same program built with pkg-config.
PKG_CONFIG_PATH="$work/prefix/lib/pkgconfig" pkg-config --exists gaitopt || fail "pkg-config: no gaitopt"
# shellcheck disable=SC2046  # the flags are words
g++ -std=c++17 -O1 -DGAITOPT_DATA_DIR="\"$data\"" "$source_dir/tests/install/consumer/consumer.cpp" \
  -o "$work/pc_consumer" $(PKG_CONFIG_PATH="$work/prefix/lib/pkgconfig" pkg-config --cflags --libs --static gaitopt) \
  -L"$work/prefix/lib" -lgaitopt_walker -Wl,-rpath,"$work/prefix/lib" >"$work/pc.log" 2>&1 ||
  fail "pkg-config build: $(tail -5 "$work/pc.log")"
"$work/pc_consumer" >"$work/pc.out" || fail "the pkg-config-built program failed"

# the library's model is the tool's (total mass of the default robot in `gaitopt model`)
mass="$(sed -n 's/^ *"total_mass": \([0-9.e+-]*\),*$/\1/p' "$work/model.json")"
[ -n "$mass" ] || fail "no total_mass in the model output"
grep -q "^robot rabbit_miossec mass $mass\$" "$work/cmake.out" ||
  fail "the library's model differs from the tool's (mass $mass): $(cat "$work/cmake.out")"
grep -q "^walker refused: absent.json" "$work/cmake.out" || fail "walker error: $(cat "$work/cmake.out")"
cmp -s "$work/cmake.out" "$work/pc.out" || fail "the two builds differ: $(cat "$work/cmake.out" "$work/pc.out")"
echo "check_install: installed to a temporary prefix; the tool, find_package(gaitopt) and pkg-config work"
