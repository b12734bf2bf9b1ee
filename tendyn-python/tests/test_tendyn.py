"""The Python package against the Rust solver (through the command line), against the
physics' own relations, and against bad input.

Run from the repository: `pytest tendyn-python/tests` in a virtual environment where
`pip install ./tendyn-python` installed the module.
"""

import json
import pathlib
import subprocess

import numpy as np
import pytest

import tendyn

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples" / "mechanisms"
PAPER = ["example1_endless", "example2_open_ended", "example3_stanford_jpl"]
FRICTION = ["example2_friction", "example2_capstan"]


def model(name):
    return tendyn.load(str(EXAMPLES / f"{name}.ron"))


def states(m, count, seed):
    rng = np.random.default_rng(seed)
    n = m.dof
    q = rng.uniform(-np.pi, np.pi, (count, n))
    qd = rng.uniform(-3.0, 3.0, (count, n))
    qdd = rng.uniform(-10.0, 10.0, (count, n))
    return q, qd, qdd


def cli_eval(name, q, qd, qdd):
    """`tendyn eval --json` at one state: the Rust solver as the command line prints it
    (serde_json writes the shortest decimal that reads back to the same f64)."""
    arg = lambda v: ",".join(repr(float(x)) for x in v)
    out = subprocess.run(
        ["cargo", "run", "-q", "-p", "tendyn-cli", "--bin", "tendyn", "--", "eval",
         str(EXAMPLES / f"{name}.ron"), "--q", arg(q), "--qd", arg(qd), "--qdd", arg(qdd),
         "--json"],
        cwd=ROOT, check=True, capture_output=True, text=True,
    )
    return json.loads(out.stdout)


@pytest.mark.parametrize("name", PAPER)
def test_results_are_the_rust_solvers_to_the_bit(name):
    m = model(name)
    q, qd, qdd = (x[0] for x in states(m, 1, 7))
    want = cli_eval(name, q, qd, qdd)
    got = m.inverse_dynamics(q, qd, qdd)
    assert got["generalized_forces"].tolist() == want["generalized_forces"]
    assert got["tendon_tensions"].tolist() == [want["tendon_tensions"][t] for t in m.tendon_names]
    assert got["motor_torques"].tolist() == [want["motor_torques"][t] for t in m.motor_names]
    assert m.mass_matrix(q).tolist() == want["mass_matrix"]
    assert m.bias(q, qd).tolist() == want["bias"]
    assert m.gravity(q).tolist() == want["gravity"]
    bodies = m.joint_names + list(m.couplings)
    if got["bearings"] is not None:
        for body, (force, moment) in zip(bodies, got["bearings"].tolist()):
            assert force == want["bearings"][body]["force"]
            assert moment == want["bearings"][body]["moment"]
        assert got["base_reaction"][0].tolist() == want["base_reaction"]["force"]


@pytest.mark.parametrize("name", PAPER + FRICTION)
def test_a_batch_is_each_state_alone(name):
    m = model(name)
    q, qd, qdd = states(m, 20, 3)
    qd[::4] = 0.0  # some states at rest, where friction sticks
    batch = m.inverse_dynamics(q, qd, qdd)
    forward = m.forward_dynamics(q, qd, batch["motor_torques"], batch["tendon_tensions"])
    for k in range(len(q)):
        one = m.inverse_dynamics(q[k], qd[k], qdd[k])
        for key, value in one.items():
            if value is None:
                assert batch[key] is None
            else:
                assert np.array_equal(batch[key][k], value), key
        assert np.array_equal(m.mass_matrix(q)[k], m.mass_matrix(q[k]))
        assert np.array_equal(m.bias(q, qd)[k], m.bias(q[k], qd[k]))
        assert np.array_equal(m.gravity(q)[k], m.gravity(q[k]))
        alone = m.forward_dynamics(q[k], qd[k], one["motor_torques"], one["tendon_tensions"])
        assert np.array_equal(forward[k], alone)


@pytest.mark.parametrize("name", FRICTION)
def test_friction_and_guides_are_the_command_lines(name):
    """Bearing friction, what sticks and what each guide does, moving and at rest (where
    every bearing and guide with friction sticks), as `tendyn eval --json` gives them."""
    m = model(name)
    assert m.friction_bodies or m.guides
    q, qd, qdd = (x[0] for x in states(m, 1, 5))
    for velocity in (qd, np.zeros_like(qd)):
        want = cli_eval(name, q, velocity, qdd)
        got = m.inverse_dynamics(q, velocity, qdd)
        friction = [want["bearing_friction"][b] for b in m.friction_bodies]
        assert got["bearing_friction"].tolist() == friction
        assert got["sticking"].dtype == bool
        assert [b for b, s in zip(m.friction_bodies, got["sticking"]) if s] == want["sticking"]
        assert [(g["pulley"], g["tendon"]) for g in want["guides"]] == m.guides
        for key, plural in [("wrap_angle", "guide_wrap_angles"),
                            ("sliding_speed", "guide_sliding_speeds"),
                            ("direction", "guide_directions"), ("sticking", "guide_sticking"),
                            ("dissipated_power", "guide_dissipated_powers")]:
            assert got[plural].tolist() == [g[key] for g in want["guides"]], key
        assert got["guide_sticking"].dtype == bool
    # At rest every bearing and guide with friction sticks.
    assert got["sticking"].all() and got["guide_sticking"].all()


@pytest.mark.parametrize("name", FRICTION)
def test_forward_at_rest_flags_where_forward_dynamics_does_not_give_the_motion_back(name):
    """Forward dynamics does not know `q̈`, so within the band of rest it takes friction as
    none. Fed the tensions inverse dynamics solved for, it gives `q̈` back exactly where
    `forward_at_rest` flags nothing (every joint moving, and some states at rest), and not
    where it flags a bearing or guide (the impending motion gave friction a direction)."""
    m = model(name)
    q, qd, qdd = states(m, 12, 9)
    qd[::3] = 0.0
    flags = m.forward_at_rest(q, qd)
    assert flags["sticking"].dtype == bool and flags["guide_sticking"].dtype == bool
    flagged = flags["sticking"].any(axis=1) | flags["guide_sticking"].any(axis=1)
    # At rest something is flagged (a guide whose tendon bends away from it at that `q`
    # has no friction to lose), moving nothing is.
    assert flagged[::3].any() and not flagged[1::3].any()
    r = m.inverse_dynamics(q, qd, qdd)
    back = m.forward_dynamics(q, qd, r["motor_torques"], r["tendon_tensions"])
    gives_back = np.isclose(back, qdd, rtol=1e-9, atol=1e-9).all(axis=1)
    assert np.array_equal(gives_back, ~flagged)
    one = m.forward_at_rest(q[0], qd[0])
    assert np.array_equal(one["guide_sticking"], flags["guide_sticking"][0])


@pytest.mark.parametrize("name", PAPER)
def test_the_outputs_obey_the_equations_of_motion(name):
    """`Q = M q̈ + h + g` (no friction in the paper's examples), and forward dynamics of the
    solved actuation gives `q̈` back."""
    m = model(name)
    q, qd, qdd = states(m, 50, 11)
    r = m.inverse_dynamics(q, qd, qdd)
    mm, h, g = m.mass_matrix(q), m.bias(q, qd), m.gravity(q)
    q_from_terms = np.einsum("kij,kj->ki", mm, qdd) + h + g
    scale = np.abs(q_from_terms).max(axis=1, keepdims=True) + 1e-300
    assert np.abs(r["generalized_forces"] - q_from_terms).max() <= 1e-12 * scale.max()
    back = m.forward_dynamics(q, qd, r["motor_torques"], r["tendon_tensions"])
    assert np.allclose(back, qdd, rtol=1e-9, atol=1e-9)


def test_lists_and_integer_arrays_are_states_too():
    m = model("example2_open_ended")
    assert np.array_equal(m.gravity([0, 1]), m.gravity(np.array([0.0, 1.0])))
    assert np.array_equal(m.gravity(np.array([[0, 1]], dtype=np.int32))[0], m.gravity([0.0, 1.0]))


def test_any_memory_layout_and_empty_batches_are_states_too():
    m = model("example3_stanford_jpl")
    q, qd, qdd = states(m, 8, 7)
    want = m.inverse_dynamics(q, qd, qdd)["tendon_tensions"]
    fortran = [np.asfortranarray(x) for x in (q, qd, qdd)]
    assert np.array_equal(m.inverse_dynamics(*fortran)["tendon_tensions"], want)
    reversed_rows = [x[::-1] for x in (q, qd, qdd)]
    assert np.array_equal(m.inverse_dynamics(*reversed_rows)["tendon_tensions"], want[::-1])
    assert m.inverse_dynamics(q[:0], qd[:0], qdd[:0])["tendon_tensions"].shape == (0, 4)
    r = m.inverse_dynamics(q, qd, qdd)  # no motors: (N, 0) motor torques
    assert r["motor_torques"].shape == (8, 0)
    back = m.forward_dynamics(q, qd, r["motor_torques"], r["tendon_tensions"])
    assert np.allclose(back, qdd, rtol=1e-9, atol=1e-9)


def test_model_describes_the_mechanism():
    m = model("example3_stanford_jpl")
    assert m.dof == 3
    assert m.joint_names == ["knuckle", "proximal", "distal"]
    assert m.tendon_names == ["Ta", "Tb", "Tc", "Td"]
    assert m.structure_matrix.shape == (3, 4)
    assert set(m.couplings) >= {"drum2", "drum3a", "drum3b"}
    assert all(row.shape == (3,) for row in m.couplings.values())
    assert m.pulley_names == list(m.couplings)
    r = m.inverse_dynamics(np.zeros(3), np.zeros(3), np.zeros(3))
    assert r["pulley_moments"].shape == (len(m.pulley_names),)
    assert r["segment_tensions"].shape == (sum(count for _, count in m.strands),)
    assert [name for name, _ in m.strands] == ["Ta", "Tb", "Tc", "Td"]
    source = m.generate(["gravity"], "f64")
    assert "pub fn gravity" in source and "pub fn actuation" not in source


def test_loops_paths_and_the_version_are_named():
    # A path-like object loads as its string does.
    m = tendyn.load(EXAMPLES / "example1_endless.ron")
    assert m.name == model("example1_endless").name
    assert isinstance(tendyn.__version__, str) and tendyn.__version__
    # Example 1 has one loop: its row of `loop_sides`, ccw then cw side.
    assert len(m.loop_names) == 1
    r = m.inverse_dynamics(np.zeros(2), np.zeros(2), np.ones(2))
    assert r["loop_sides"].shape == (1, 2)
    # An explicitly coupled pulley leaves bearings unattributed (None), but with no guides
    # their dissipated powers are an empty array, as the command line's `"guides": []`.
    coupled = tendyn.load(ROOT / "tests" / "mechanisms" / "random" / "random_1_coupled.ron")
    assert coupled.guides == []
    r = coupled.inverse_dynamics(*(np.zeros(coupled.dof) for _ in range(3)))
    assert r["bearings"] is None
    assert r["guide_dissipated_powers"].shape == (0,)


def test_a_model_pickles_and_copies_as_its_mechanism():
    # What multiprocessing sends to another process: the text, validated again there.
    import copy
    import pickle

    for name in PAPER + FRICTION:
        m = model(name)
        q, qd, qdd = states(m, 3, 11)
        for again in (pickle.loads(pickle.dumps(m)), copy.deepcopy(m)):
            assert again is not m
            assert (again.name, again.tendon_names, again.motor_names) == (
                m.name, m.tendon_names, m.motor_names,
            )
            got, want = again.inverse_dynamics(q, qd, qdd), m.inverse_dynamics(q, qd, qdd)
            for key in ("generalized_forces", "tendon_tensions", "motor_torques"):
                assert np.array_equal(got[key], want[key]), key


def test_actuators_not_given_are_zero_and_one_output_may_be_named_alone():
    m = model("example3_stanford_jpl")  # tendons only, no motors
    q, qd, _ = states(m, 1, 5)
    tt = np.full(len(m.tendon_names), 7.0)
    given = m.forward_dynamics_derivatives(q[0], qd[0], [], tt)
    assert np.array_equal(m.forward_dynamics_derivatives(q[0], qd[0], tendon_tensions=tt), given)
    assert np.array_equal(
        m.forward_dynamics_derivatives(q[0], qd[0]),
        m.forward_dynamics_derivatives(q[0], qd[0], [], np.zeros(len(m.tendon_names))),
    )
    assert m.generate("actuation", "f64") == m.generate(["actuation"], "f64")


def test_a_bad_file_raises_tendyn_error_naming_line_and_column():
    with pytest.raises(tendyn.TendynError, match=r"mine.ron: .*line 1, column 21"):
        tendyn.loads('(name: "x", links: [)', name="mine.ron")
    with pytest.raises(tendyn.TendynError, match="no-such.ron"):
        tendyn.load("no-such.ron")


def test_record_fields_misaligned_buffers_and_broadcasts_are_read_as_their_numbers():
    """Float64 arrays a view of which would read the wrong numbers (a record field whose
    stride is no multiple of 8), misaligned memory, or one state broadcast to many."""
    m = model("example3_stanford_jpl")
    n = m.dof
    q, qd, qdd = states(m, 5, 9)
    want = m.mass_matrix(q)
    record = np.zeros(5, dtype=[("q", "<f8", (n,)), ("flag", "<f4")])
    record["q"] = q
    assert record["q"].strides[0] % 8 != 0
    assert np.array_equal(m.mass_matrix(record["q"]), want)
    buffer = bytearray(8 * q.size + 1)
    misaligned = np.frombuffer(buffer, dtype="<f8", count=q.size, offset=1).reshape(q.shape)
    misaligned[...] = q
    assert not misaligned.flags.aligned
    assert np.array_equal(m.mass_matrix(misaligned), want)
    broadcast = np.broadcast_to(q[0], (3, n))
    assert np.array_equal(m.mass_matrix(broadcast), np.stack([want[0]] * 3))
    with pytest.raises(ValueError):  # numpy 1 refuses 33 dimensions itself; tendyn, with numpy 2
        m.mass_matrix(np.ones((1,) * 33))


def test_bad_shapes_and_states_are_named():
    m = model("example1_endless")
    n = m.dof
    with pytest.raises(ValueError, match=r"`q` has shape \(3,\)"):
        m.gravity(np.zeros(n + 1))
    with pytest.raises(ValueError, match="mix one state"):
        m.bias(np.zeros(n), np.zeros((1, n)))
    with pytest.raises(ValueError, match="`qd` has another number of states than `q`"):
        m.bias(np.zeros((4, n)), np.zeros((3, n)))
    with pytest.raises(ValueError, match="unknown output `nope`"):
        m.generate(["nope"])
    bad = np.zeros((2, n))
    bad[1, 0] = np.nan
    with pytest.raises(tendyn.TendynError, match=r"batch row 1: .*qd\[0\] is NaN"):
        m.inverse_dynamics(np.zeros((2, n)), bad, np.zeros((2, n)))


@pytest.mark.parametrize("name", PAPER)
def test_a_batch_spread_over_threads_is_the_same_batch_in_order(name):
    """From 256 states a batch runs on several threads, each with buffers of its own."""
    m = model(name)
    q, qd, qdd = states(m, 600, 5)
    together = m.inverse_dynamics(q, qd, qdd)
    for start in range(0, 600, 200):
        part = m.inverse_dynamics(q[start:start + 200], qd[start:start + 200], qdd[start:start + 200])
        for key, value in part.items():
            if value is not None:
                assert np.array_equal(together[key][start:start + 200], value), key
    assert np.array_equal(m.mass_matrix(q)[:200], m.mass_matrix(q[:200]))
    bad = qd.copy()
    bad[599, 0] = np.inf
    with pytest.raises(tendyn.TendynError, match=r"batch row 599: .*qd\[0\] is inf"):
        m.inverse_dynamics(q, bad, qdd)
    # With failures in both threads' runs, the first row is named.
    bad[100, 0] = np.nan
    with pytest.raises(tendyn.TendynError, match=r"batch row 100: .*qd\[0\] is NaN"):
        m.inverse_dynamics(q, bad, qdd)


def test_one_state_and_a_batch_of_one_differ_only_by_the_batch_axis():
    m = model("example3_stanford_jpl")
    q, qd, qdd = states(m, 1, 7)
    batch = m.inverse_dynamics(q, qd, qdd)
    one = m.inverse_dynamics(q[0], qd[0], qdd[0])
    for key, value in one.items():
        if value is not None:
            assert batch[key].shape == (1,) + value.shape, key
            assert np.array_equal(batch[key][0], value), key
    bad = qd.copy()
    bad[0, 0] = np.nan
    # A call of one state names the input alone, batched or not (rows only from two on).
    for args in [(q[0], bad[0], qdd[0]), (q, bad, qdd)]:
        with pytest.raises(tendyn.TendynError, match=r"^(?!batch row).*qd\[0\] is NaN"):
            m.inverse_dynamics(*args)


def test_arrays_laid_out_in_any_order_in_memory_give_the_same_results():
    """Views with strides (every other state, Fortran order) are read in logical order."""
    m = model("example3_stanford_jpl")
    q, qd, qdd = states(m, 40, 6)
    strided = m.inverse_dynamics(q[::2], qd[::2], np.asfortranarray(qdd[::2]))
    packed = m.inverse_dynamics(*(np.ascontiguousarray(a[::2]) for a in (q, qd, qdd)))
    for key, value in packed.items():
        if value is not None:
            assert np.array_equal(strided[key], value), key


def test_check_is_the_command_lines_report():
    name = "example3_stanford_jpl"
    report = model(name).check()
    out = subprocess.run(
        ["cargo", "run", "-q", "-p", "tendyn-cli", "--bin", "tendyn", "--", "check",
         str(EXAMPLES / f"{name}.ron"), "--json"],
        cwd=ROOT, check=True, capture_output=True, text=True,
    )
    assert report == json.loads(out.stdout)


@pytest.mark.parametrize("name", PAPER)
def test_the_regressor_times_the_parameters_is_the_generalized_force(name):
    m = model(name)
    q, qd, qdd = states(m, 50, 11)
    y = m.regressor(q, qd, qdd)
    assert y.shape == (50, m.dof, len(m.parameter_names))
    q_of = y @ m.parameter_values() + m.regressor_offset(q)
    expected = m.inverse_dynamics(q, qd, qdd)["generalized_forces"]
    assert np.abs(q_of - expected).max() <= 1e-12 * np.abs(expected).max()
    # The base regressor (its kept columns) times the base parameters' values, likewise.
    base = m.base_parameters()
    columns = [m.parameter_names.index(b["kept"]) for b in base]
    values = np.array([b["value"] for b in base])
    assert np.abs(y[:, :, columns] @ values - expected).max() <= 1e-12 * np.abs(expected).max()


@pytest.mark.parametrize("name", PAPER)
def test_derivatives_are_the_limits_of_difference_quotients(name):
    """Central differences in f64 (step 1e-6, so agreement to about 1e-8 of the size)."""
    m = model(name)
    q, qd, qdd = states(m, 1, 12)
    q, qd, qdd = q[0], qd[0], qdd[0]
    d = m.generalized_forces_derivatives(q, qd, qdd)
    assert d.shape == (2, m.dof, m.dof)
    h = 1e-6
    f = lambda q, qd: m.inverse_dynamics(q, qd, qdd)["generalized_forces"]
    for k in range(m.dof):
        e = np.eye(m.dof)[k] * h
        for which, (a, b) in enumerate([((q + e, qd), (q - e, qd)), ((q, qd + e), (q, qd - e))]):
            column = (f(*a) - f(*b)) / (2 * h)
            assert np.abs(d[which][:, k] - column).max() <= 1e-7 * max(np.abs(d[which]).max(), 1.0)
    r = m.inverse_dynamics(q, qd, qdd)
    mt, tt = r["motor_torques"], r["tendon_tensions"]
    fd = m.forward_dynamics_derivatives(q, qd, mt, tt)
    u = np.concatenate([mt, tt])
    assert fd.shape == (m.dof, 2 * m.dof + len(u))
    # q̈ is affine in u: a unit step in each actuator moves it by that column exactly.
    nm = len(mt)
    for k in range(len(u)):
        step = np.eye(len(u))[k]
        after = m.forward_dynamics(q, qd, mt + step[:nm], tt + step[nm:])
        before = m.forward_dynamics(q, qd, mt, tt)
        assert np.allclose(after - before, fd[:, 2 * m.dof + k], rtol=1e-9, atol=1e-9 * np.abs(fd).max())
