"""Dynamics of tendon-driven robotic mechanisms (recursive Newton-Euler) from a RON file.

Arrays of states are `(n,)` for one state or `(N, n)` for `N` states; results carry the
same leading axis.
"""

import os
from typing import Any, Optional, Union

import numpy as np
import numpy.typing as npt

Array = npt.NDArray[np.float64]
ArrayLike = npt.ArrayLike

__version__: str

class TendynError(Exception):
    """A mechanism file that cannot be read or does not validate, a state the solver
    cannot evaluate, or code that cannot be generated; the message is the command line's
    (for a file: the item, its line and column, and what would fix it)."""

def load(path: Union[str, os.PathLike[str]]) -> Model:
    """Loads and validates the mechanism file at `path`."""

def loads(text: str, name: str = "<string>") -> Model:
    """Validates the mechanism in `text` (RON); `name` stands for the file in messages."""

class Model:
    """A validated mechanism and the solver's buffers for it.

    Pickling (and `copy.deepcopy`, and sending a model to another process) keeps the
    mechanism's text: unpickling validates it again, with buffers of its own."""

    @property
    def name(self) -> str: ...
    @property
    def dof(self) -> int: ...
    @property
    def joint_names(self) -> list[str]: ...
    @property
    def tendon_names(self) -> list[str]: ...
    @property
    def motor_names(self) -> list[str]: ...
    @property
    def loop_names(self) -> list[str]:
        """The loops' names, in file order: the rows of `loop_sides`."""
    @property
    def pulley_names(self) -> list[str]: ...
    @property
    def friction_bodies(self) -> list[str]:
        """The bodies whose bearing has friction (joints, then pulleys): the entries of
        `bearing_friction` and `sticking`."""
    @property
    def guides(self) -> list[tuple[str, str]]:
        """Each fixed guide's pulley and tendon, strand by strand in route order: the
        entries of the `guide_…` arrays."""
    @property
    def strands(self) -> list[tuple[str, int]]:
        """Each strand's name and number of segments, in order (`segment_tensions` runs
        through them; a loop has two strands, `LOOP/ccw` and `LOOP/cw`)."""
    @property
    def structure_matrix(self) -> Array:
        """`A` (m), `(n, tendons)`: the tendons' part of `Q` is `A T` (paper Eqs. 33, 35).
        The frictionless, constant matrix: where tendons slide over guides with capstan
        friction the solver uses the state's `A(σ, q)` instead."""
    @property
    def couplings(self) -> dict[str, Array]:
        """Each pulley's angle relative to its carrier per joint angle, `(n,)`."""
    def inverse_dynamics(
        self, q: ArrayLike, qd: ArrayLike, qdd: ArrayLike
    ) -> dict[str, Optional[npt.NDArray[Any]]]:
        """`generalized_forces` `(n,)`, `motor_torques`, `tendon_tensions`,
        `minimal_norm_tensions`, `null_space_tensions`, `loop_sides` `(loops, 2)`
        (`loop_names` order; ccw, cw side; slack where either is negative),
        `pulley_moments` (`pulley_names` order),
        `bearing_friction` and `sticking` (bool; one entry per `friction_bodies`),
        `guide_wrap_angles`, `guide_sliding_speeds`, `guide_directions`,
        `guide_sticking` (bool) and `guide_dissipated_powers` (one entry per `guides`),
        `segment_tensions` (every segment of every strand, `strands` order, each from
        its anchor end), `bearings` `(bodies, 2, 3)` (force, moment; `joint_names` then
        `pulley_names`), `base_reaction` `(2, 3)` (these three, and
        `guide_dissipated_powers` where there are guides, `None` where the routing cannot
        attribute them); per state, with the batch axis first when the
        states are batched. Float64 arrays but `sticking` and `guide_sticking` (bool)."""
    def mass_matrix(self, q: ArrayLike) -> Array:
        """`M(q)` (kg·m²), `(n, n)` per state."""
    def bias(self, q: ArrayLike, qd: ArrayLike) -> Array:
        """`h(q, q̇)` (N·m)."""
    def gravity(self, q: ArrayLike) -> Array:
        """`g(q)` (N·m)."""
    def forward_dynamics(
        self,
        q: ArrayLike,
        qd: ArrayLike,
        motor_torques: Optional[ArrayLike] = None,
        tendon_tensions: Optional[ArrayLike] = None,
    ) -> Array:
        """`q̈` (rad/s²) from motor torques and ground-level tendon tensions."""
    def forward_at_rest(self, q: ArrayLike, qd: ArrayLike) -> dict[str, npt.NDArray[np.bool_]]:
        """Where `forward_dynamics` is not exact: `{"sticking": (…, friction bodies),
        "guide_sticking": (…, guides)}` of booleans, the bearings with Coulomb friction and
        the guides with friction touching their tendon that it takes without friction at
        `(q, q̇)` (within the band of rest, where only `q̈` would direct them); all false
        with `friction_smoothing`."""
    def generalized_forces_derivatives(
        self, q: ArrayLike, qd: ArrayLike, qdd: ArrayLike
    ) -> Array:
        """`(2, n, n)` per state: `[0] = ∂Q/∂q`, `[1] = ∂Q/∂q̇`, exact."""
    def forward_dynamics_derivatives(
        self,
        q: ArrayLike,
        qd: ArrayLike,
        motor_torques: Optional[ArrayLike] = None,
        tendon_tensions: Optional[ArrayLike] = None,
    ) -> Array:
        """`(n, 2n + m)` per state: `∂q̈/∂q`, `∂q̈/∂q̇`, `∂q̈/∂u` side by side, exact;
        `u` the motor torques then the tendon tensions (`m` = motors + tendons); actuators
        not given are zero, as in `forward_dynamics`."""
    def regressor(self, q: ArrayLike, qd: ArrayLike, qdd: ArrayLike) -> Array:
        """`Y` (`(n, p)` per state, columns `parameter_names`): `Q = Y π + offset`."""
    def regressor_offset(self, q: ArrayLike) -> Array:
        """`Q₀` (N·m): the external wrench's part of `Q`."""
    @property
    def parameter_names(self) -> list[str]:
        """The regressor's parameters (`BODY.m`, `BODY.mx`, …, `BODY.coulomb`, …)."""
    def parameter_values(self) -> Array:
        """The file's values of `parameter_names`."""
    def base_parameters(self) -> list[dict]:
        """The base parameters: `name`, `value`, `kept`, `merged` (docs/outputs.md §6d)."""
    def check(self) -> dict:
        """The `tendyn check --json` report."""
    def generate(
        self,
        outputs: Optional[Union[str, list[str], tuple[str, ...]]] = None,
        scalar: str = "generic",
    ) -> str:
        """The generated Rust source of `outputs` (a name or names; the default ones
        available when `None`);
        `ValueError` for an unknown output or scalar, `TendynError` for an output the
        mechanism cannot provide (among the defaults too: forward dynamics where a joint
        moves no mass)."""
    def _rust_loop_ns(self, q: ArrayLike, qd: ArrayLike, qdd: ArrayLike, repeats: int) -> float:
        """Private, for `bench/inverse_dynamics_batch.py`: the Rust solver alone on the
        states, one thread, best of `repeats` passes, nanoseconds per state."""
