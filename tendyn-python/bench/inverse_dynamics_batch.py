"""Issue 12's speed goal: a 1,024-state batch of Example 3's inverse dynamics through
Python against the Rust solver's own loop over the same states, in one process.

    taskset -c 0 python tendyn-python/bench/inverse_dynamics_batch.py   # one core
    python tendyn-python/bench/inverse_dynamics_batch.py                # every core

Prints nanoseconds per state for both, each the best of 200 passes taken in turn with
the other's, and their ratio. The batch
call includes reading the numpy inputs and building the result dict's arrays; from 256
states on it spreads over the cores it may use (on one core, over one).
"""

import pathlib
import time

import numpy as np

import tendyn

ROOT = pathlib.Path(__file__).resolve().parents[2]
STATES, PASSES = 1024, 200

model = tendyn.load(str(ROOT / "examples" / "mechanisms" / "example3_stanford_jpl.ron"))
rng = np.random.default_rng(0)
q, qd, qdd = (rng.uniform(-s, s, (STATES, model.dof)) for s in (np.pi, 3.0, 10.0))

# Alternated passes, so that both see the same state of this machine; the best of each.
python_ns = rust_ns = np.inf
for _ in range(PASSES):
    start = time.perf_counter_ns()
    model.inverse_dynamics(q, qd, qdd)
    python_ns = min(python_ns, (time.perf_counter_ns() - start) / STATES)
    rust_ns = min(rust_ns, model._rust_loop_ns(q, qd, qdd, 1))
print(f"{STATES} states of {model.name}: Python batch {python_ns:.0f} ns per state, "
      f"Rust loop {rust_ns:.0f} ns per state, ratio {python_ns / rust_ns:.2f}")
