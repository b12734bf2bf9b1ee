"""`tendyn export --mjcf` loaded in MuJoCo: the same dynamics as tendyn's.

With the pulley hinges set from the couplings (`q_full = G q`, `G` the identity on the
joints and each exported pulley's coupling row), MuJoCo's `Gᵀ M_full G` and `Gᵀ qfrc_bias`
are tendyn's `M` and `h + g`; a passive simulation keeps every coupling. On the paper's
examples and on seeded random mechanisms.
"""

import pathlib
import subprocess

import numpy as np
import pytest

import tendyn

mujoco = pytest.importorskip("mujoco")

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples" / "mechanisms"
PAPER = [EXAMPLES / f"{name}.ron" for name in
         ["example1_endless", "example2_open_ended", "example3_stanford_jpl"]]
# Seeded random mechanisms (tilted, off-axis pulleys with explicit couplings, an endless
# loop, full inertias, gravity in any direction), written by the Rust test crate's
# generator and kept equal to it by `cargo test -p tendyn-spec --test random_fixtures`.
RANDOM = sorted((ROOT / "tests" / "mechanisms" / "random").glob("*.ron"))


def exported(path, tmp_path):
    out = tmp_path / f"{path.stem}.xml"
    subprocess.run(
        ["cargo", "run", "-q", "-p", "tendyn-cli", "--bin", "tendyn", "--", "export",
         str(path), "--mjcf", "-o", str(out)],
        cwd=ROOT, check=True, capture_output=True, text=True,
    )
    return mujoco.MjModel.from_xml_path(str(out)), tendyn.load(str(path))


def reduction(m, tm):
    """`G`: MuJoCo's joint velocities per joint velocity of tendyn's."""
    G = np.zeros((m.nv, tm.dof))
    for j, joint in enumerate(tm.joint_names):
        G[m.joint(joint).dofadr[0], j] = 1.0
    for pulley, coupling in tm.couplings.items():
        try:
            G[m.joint(pulley).dofadr[0], :] = coupling
        except KeyError:  # a pulley without mass is not exported
            pass
    return G


def test_the_random_mechanisms_are_there():
    assert len(RANDOM) == 3, RANDOM


@pytest.mark.parametrize("path", PAPER + RANDOM, ids=lambda p: p.stem)
def test_mujoco_has_the_mass_matrix_bias_and_gravity_of_tendyn(path, tmp_path):
    m, tm = exported(path, tmp_path)
    G = reduction(m, tm)
    d = mujoco.MjData(m)
    rng = np.random.default_rng(0)
    for _ in range(50):
        q, qd = rng.uniform(-np.pi, np.pi, tm.dof), rng.uniform(-3.0, 3.0, tm.dof)
        d.qpos[:], d.qvel[:] = G @ q, G @ qd  # hinges only: position and velocity align
        mujoco.mj_forward(m, d)
        full = np.zeros((m.nv, m.nv))
        mujoco.mj_fullM(m, d, full)
        mass, terms = tm.mass_matrix(q), tm.bias(q, qd) + tm.gravity(q)
        # Measured 2.5e-15 and 1.3e-14 at most (README); the bound leaves room for
        # MuJoCo's own order of operations, not for a different model.
        assert np.abs(G.T @ full @ G - mass).max() <= 1e-12 * np.abs(mass).max()
        assert np.abs(G.T @ d.qfrc_bias - terms).max() <= 1e-12 * np.abs(terms).max()


@pytest.mark.parametrize("path", PAPER + RANDOM, ids=lambda p: p.stem)
def test_a_simulation_with_every_tendon_at_its_floor_keeps_the_couplings(path, tmp_path):
    """With zero controls MuJoCo holds each tendon actuator at the bottom of its force
    range, the tendon's floor: the mechanism moves under gravity and the floors."""
    m, tm = exported(path, tmp_path)
    G = reduction(m, tm)
    d = mujoco.MjData(m)
    rng = np.random.default_rng(1)
    q, qd = rng.uniform(-1.0, 1.0, tm.dof), rng.uniform(-1.0, 1.0, tm.dof)
    d.qpos[:], d.qvel[:] = G @ q, G @ qd
    couplings = [k for k in range(m.ntendon) if m.tendon(k).name.startswith("coupling/")]
    assert couplings, "every mechanism here has pulleys with mass"
    worst = 0.0
    for _ in range(500):  # 1 s at MuJoCo's default 2 ms step
        mujoco.mj_step(m, d)
        worst = max([worst] + [abs(d.ten_length[k]) for k in couplings])
    # MuJoCo's equalities are soft: measured 2.5e-3 rad at most over a 1 s fall of the
    # paper's finger (Euler, 2 ms), against 0.09 rad at MuJoCo's default impedance.
    assert worst <= 5e-3, f"a coupling drifted by {worst} rad"
