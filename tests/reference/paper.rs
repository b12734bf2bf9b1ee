//! The paper's Examples 1 and 2 written out by hand (with the corrections recorded in
//! `docs/paper-errata.md`), for the tests of the runtime solver and of generated code.
//!
//! The numbers are those of `examples/mechanisms/example1_endless.ron` and
//! `example2_open_ended.ron`. The paper leaves gravity out; each formula takes the
//! gravity `g` along −y in the arm's plane (0 for the shipped, horizontal arm).

/// The two-link arm of Examples 1 and 2.
pub struct Arm {
    pub a1: f64,
    pub s1: f64,
    pub m1: f64,
    pub i1: f64,
    pub a2: f64,
    pub s2: f64,
    pub m2: f64,
    pub i2: f64,
}

pub const ARM: Arm = Arm {
    a1: 0.30,
    s1: 0.15,
    m1: 1.2,
    i1: 0.009,
    a2: 0.25,
    s2: 0.125,
    m2: 0.8,
    i2: 0.0041667,
};

/// Example 1's pulleys: link 2's drum `r2`, the base pulley `r3` with inertia `i3`.
pub const EX1: (f64, f64, f64) = (0.02, 0.03, 0.000045);

/// Example 2's radii `r1..r4` and idler inertias `i3`, `i4`.
pub const EX2: [f64; 6] = [0.04, 0.02, 0.03, 0.03, 0.0000225, 0.0000225];

impl Arm {
    /// Joint torques of the bare arm (no pulleys) from the textbook closed form (Lagrange),
    /// with `l_c1 = a1 − s1`, `l_c2 = a2 − s2`.
    pub fn torques(&self, q: &[f64], qd: &[f64], qdd: &[f64], g: f64) -> (f64, f64) {
        let (lc1, lc2) = (self.a1 - self.s1, self.a2 - self.s2);
        let (c2, s2) = (q[1].cos(), q[1].sin());
        let m11 = self.i1
            + self.m1 * lc1 * lc1
            + self.i2
            + self.m2 * (self.a1 * self.a1 + lc2 * lc2 + 2.0 * self.a1 * lc2 * c2);
        let m12 = self.i2 + self.m2 * (lc2 * lc2 + self.a1 * lc2 * c2);
        let m22 = self.i2 + self.m2 * lc2 * lc2;
        let hh = self.m2 * self.a1 * lc2 * s2;
        let g1 = (self.m1 * lc1 + self.m2 * self.a1) * g * q[0].cos()
            + self.m2 * lc2 * g * (q[0] + q[1]).cos();
        let g2 = self.m2 * lc2 * g * (q[0] + q[1]).cos();
        (
            m11 * qdd[0] + m12 * qdd[1] - hh * (2.0 * qd[0] * qd[1] + qd[1] * qd[1]) + g1,
            m12 * qdd[0] + m22 * qdd[1] + hh * qd[0] * qd[0] + g2,
        )
    }

    /// Eq. 28: the right-hand side of `r2 (T21 − T22) = cI2 (θ̈1 + θ̈2) + m2 (a2 − s2)
    /// [a1 (sin θ2 θ̇1² + cos θ2 θ̈1) + (a2 − s2)(θ̈1 + θ̈2)]` (+ gravity).
    pub fn eq28(&self, q: &[f64], qd: &[f64], qdd: &[f64], g: f64) -> f64 {
        let lc2 = self.a2 - self.s2;
        self.i2 * (qdd[0] + qdd[1])
            + self.m2
                * lc2
                * (self.a1 * (q[1].sin() * qd[0] * qd[0] + q[1].cos() * qdd[0])
                    + lc2 * (qdd[0] + qdd[1]))
            + self.m2 * g * lc2 * (q[0] + q[1]).cos()
    }

    /// Eq. 29: `n30 = r3 (T21 − T22) + cI3 (θ̈1 + γ23 θ̈2)`, `γ23 = r2 / r3`.
    pub fn eq29(&self, qdd: &[f64], t21: f64, t22: f64) -> f64 {
        let (r2, r3, i3) = EX1;
        r3 * (t21 - t22) + i3 * (qdd[0] + r2 / r3 * qdd[1])
    }

    /// Eq. 30, corrected: `n10 = (r3 − r2)(T22 − T21) + (cI1 + m1 l_c1² + m2 a1²) θ̈1 +
    /// m2 a1 l_c2 [cos θ2 (θ̈1 + θ̈2) − sin θ2 (θ̇1 + θ̇2)²] + (m1 l_c1 + m2 a1) g cos θ1`.
    pub fn eq30(&self, q: &[f64], qd: &[f64], qdd: &[f64], g: f64, t21: f64, t22: f64) -> f64 {
        let (r2, r3, _) = EX1;
        let (lc1, lc2) = (self.a1 - self.s1, self.a2 - self.s2);
        (r3 - r2) * (t22 - t21)
            + (self.i1 + self.m1 * lc1 * lc1 + self.m2 * self.a1 * self.a1) * qdd[0]
            + self.m2
                * self.a1
                * lc2
                * (q[1].cos() * (qdd[0] + qdd[1]) - q[1].sin() * (qd[0] + qd[1]).powi(2))
            + (self.m1 * lc1 + self.m2 * self.a1) * g * q[0].cos()
    }

    /// Eq. 33's `B = (b1, b2)` (rows joint 2, joint 1): the arm's torques plus each idler's
    /// inertia through its coupling, `θ3 = θ1 − (r2/r3) θ2`, `θ4 = θ1 + (r2/r4) θ2`.
    pub fn eq33_b(&self, q: &[f64], qd: &[f64], qdd: &[f64], g: f64) -> (f64, f64) {
        let [_, r2, r3, r4, i3, i4] = EX2;
        let (tau1, tau2) = self.torques(q, qd, qdd, g);
        let (c3, c4) = ([1.0, -r2 / r3], [1.0, r2 / r4]);
        let (a3, a4) = (
            c3[0] * qdd[0] + c3[1] * qdd[1],
            c4[0] * qdd[0] + c4[1] * qdd[1],
        );
        (
            tau2 + i3 * c3[1] * a3 + i4 * c4[1] * a4,
            tau1 + i3 * c3[0] * a3 + i4 * c4[0] * a4,
        )
    }

    /// Eq. 33's `A` with rows in joint order (joint 1, joint 2), columns `(T32, T42, T11)`.
    pub fn eq33_a(&self) -> [[f64; 3]; 2] {
        let [r1, r2, r3, r4, _, _] = EX2;
        [[-r3, -r4, r1], [r2, -r2, 0.0]]
    }
}
