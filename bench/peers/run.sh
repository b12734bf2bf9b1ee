#!/usr/bin/env bash
# Pinocchio's RNEA and tendyn's runtime solver on the scale mechanisms, in one run, pinned
# to one core (the protocol of docs/references.md). Needs python3 with pip and g++; Pinocchio
# comes from PyPI (`pin`, its C++ headers and libraries are in the wheel), into a virtual
# environment of its own. Not part of CI: a timing run wants an otherwise idle machine.
#
#   bench/peers/run.sh [DIR]     (DIR: where the environment and the builds go; /tmp/tendyn-peers)
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
dir="${1:-/tmp/tendyn-peers}"
mkdir -p "$dir"
if [ ! -x "$dir/venv/bin/python" ]; then
  python3 -m venv "$dir/venv"
  "$dir/venv/bin/pip" install --quiet "pin==4.1.0" cmeel-eigen
fi
prefix="$(ls -d "$dir"/venv/lib/python3*/site-packages/cmeel.prefix | head -1)"
# Pinocchio's own compile definitions (its CMake config), header-only templates.
g++ -O3 -march=native -std=c++17 -DNDEBUG -w \
  -DBOOST_MPL_LIMIT_LIST_SIZE=30 -DBOOST_MPL_LIMIT_VECTOR_SIZE=30 \
  -DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS -DBOOST_FUSION_INVOKE_MAX_ARITY=12 \
  -I"$prefix/include" -I"$prefix/include/eigen3" "$root/bench/peers/pinocchio_rnea.cpp" \
  -L"$prefix/lib" -lpinocchio_default -Wl,-rpath,"$prefix/lib" -o "$dir/pinocchio_rnea"
cd "$root"
export RUSTFLAGS="-C target-cpu=native"
cargo build --release -q -p tendyn-bench --example expanded_tree
for m in finger4 arm6 chain8 chain12; do
  ./target/release/examples/expanded_tree "bench/mechanisms/$m.ron" > "$dir/$m.tree"
  taskset -c 0 "$dir/pinocchio_rnea" "$dir/$m.tree"
done
taskset -c 0 cargo bench -q -p tendyn-bench --bench scale -- --noplot \
  "runtime Q|runtime inverse dynamics|generated Q" 2>&1 | grep -E "^[a-z0-9]+/|time:"
