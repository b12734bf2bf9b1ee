"""Issue 12's speed goal: a 1,024-state batch of Example 3's inverse dynamics through
Python against the Rust solver's own loop over the same states, in one process.

    taskset -c 0 python tendyn-python/bench/inverse_dynamics_batch.py   # one core
    python tendyn-python/bench/inverse_dynamics_batch.py                # every core

Takes 200 passes of each in turn, and prints nanoseconds per state for both (the best
pass of each) and their ratio two ways: the ratio of the two bests, and the median over
passes of each pass's ratio to the Rust pass right after it. On a shared machine the
second is the steadier: the two passes of a pair see the same load, while the two bests
may come from different moments. The batch call includes reading the numpy inputs and
building the result dict's arrays; from 256 states on it spreads over the cores it may
use (on one core, over one).
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

python_ns, rust_ns = np.empty(PASSES), np.empty(PASSES)
for i in range(PASSES):
    start = time.perf_counter_ns()
    model.inverse_dynamics(q, qd, qdd)
    python_ns[i] = (time.perf_counter_ns() - start) / STATES
    rust_ns[i] = model._rust_loop_ns(q, qd, qdd, 1)
print(f"{STATES} states of {model.name}: Python batch {python_ns.min():.0f} ns per state, "
      f"Rust loop {rust_ns.min():.0f} ns per state (best of {PASSES}); ratio of the bests "
      f"{python_ns.min() / rust_ns.min():.2f}, median ratio of a pair "
      f"{np.median(python_ns / rust_ns):.2f}")
