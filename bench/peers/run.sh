#!/usr/bin/env bash
# Pinocchio's RNEA, Pinocchio's RNEA on CasADi's symbolic scalar generated as C, and
# tendyn's runtime solver and generated code on the scale mechanisms, in one run, pinned to
# one core (the protocol of docs/references.md). Needs python3 with pip, g++ and gcc;
# Pinocchio and CasADi come from PyPI (`pin`, `casadi`: their C++ headers and libraries are
# in the wheels), into a virtual environment of its own. Not part of CI: a timing run wants
# an otherwise idle machine.
#
#   bench/peers/run.sh [DIR]
#
# DIR is where the environment and the builds go (default /tmp/tendyn-peers).
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
dir="${1:-/tmp/tendyn-peers}"
mkdir -p "$dir"
if [ ! -x "$dir/venv/bin/python" ]; then
  python3 -m venv "$dir/venv"
  "$dir/venv/bin/pip" install --quiet "pin==4.1.0" cmeel-eigen
fi
# CasADi's wheel carries its C++ headers and library too.
"$dir/venv/bin/pip" install --quiet "casadi==3.8.2"
prefix="$(ls -d "$dir"/venv/lib/python3*/site-packages/cmeel.prefix | head -1)"
casadi="$(ls -d "$dir"/venv/lib/python3*/site-packages/casadi | head -1)"
# Pinocchio's own compile definitions (its CMake config), header-only templates.
g++ -O3 -march=native -std=c++17 -DNDEBUG -w \
  -DBOOST_MPL_LIMIT_LIST_SIZE=30 -DBOOST_MPL_LIMIT_VECTOR_SIZE=30 \
  -DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS -DBOOST_FUSION_INVOKE_MAX_ARITY=12 \
  -I"$prefix/include" -I"$prefix/include/eigen3" "$root/bench/peers/pinocchio_rnea.cpp" \
  -L"$prefix/lib" -lpinocchio_default -Wl,-rpath,"$prefix/lib" -o "$dir/pinocchio_rnea"
# Pinocchio's RNEA on CasADi's symbolic scalar: the program traces it and writes C.
g++ -O2 -std=c++17 -DNDEBUG -w \
  -DBOOST_MPL_LIMIT_LIST_SIZE=30 -DBOOST_MPL_LIMIT_VECTOR_SIZE=30 \
  -DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS -DBOOST_FUSION_INVOKE_MAX_ARITY=12 \
  -I"$prefix/include" -I"$prefix/include/eigen3" -I"$casadi/include" \
  "$root/bench/peers/pinocchio_casadi.cpp" -L"$prefix/lib" -lpinocchio_default \
  -L"$casadi" -lcasadi -Wl,-rpath,"$prefix/lib" -Wl,-rpath,"$casadi" -o "$dir/pinocchio_casadi"
cd "$root"
export RUSTFLAGS="-C target-cpu=native"
cargo build --release -q -p tendyn-bench --example expanded_tree
for m in finger4 arm6 chain8 chain12; do
  ./target/release/examples/expanded_tree "bench/mechanisms/$m.ron" > "$dir/$m.tree"
  taskset -c 0 "$dir/pinocchio_rnea" "$dir/$m.tree"
  "$dir/pinocchio_casadi" "$dir/$m.tree" "$m" "$dir"
  TIMEFORMAT="$m: gcc -O3 -march=native compiled CasADi's C (and the driver) in %R s"
  time gcc -O3 -march=native -o "$dir/${m}_casadi" "$dir/${m}_casadi.c" bench/peers/casadi_time.c -lm
  taskset -c 0 "$dir/${m}_casadi" "$dir/$m.states"
done
# The generated derivatives of arm6, in a crate of their own outside the workspace.
crate="$dir/generated_derivatives"
mkdir -p "$crate/src"
printf '[package]\nname = "generated_derivatives"\nversion = "0.1.0"\nedition = "2021"\n[dependencies]\ntendyn-core = { path = "%s/tendyn-core" }\n[profile.release]\ncodegen-units = 1\n[workspace]\n' "$root" > "$crate/Cargo.toml"
cp bench/peers/generated_derivatives.rs "$crate/src/main.rs"
cargo run --release -q -p tendyn-cli -- generate bench/mechanisms/arm6.ron --scalar f64 \
  --outputs generalized_forces_derivatives,generalized_forces -o "$crate/src/arm6d.rs"
RUST_MIN_STACK=268435456 CARGO_TARGET_DIR="$dir/target" cargo build --release -q \
  --manifest-path "$crate/Cargo.toml"
taskset -c 0 "$dir/target/release/generated_derivatives" "$dir/arm6.tree"
taskset -c 0 cargo bench -q -p tendyn-bench --bench scale -- --noplot \
  "runtime Q|runtime inverse dynamics|generated Q" 2>&1 | grep -E "^[a-z0-9]+/|time:"
