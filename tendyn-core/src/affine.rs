//! Quantities affine in the unknowns of the tension system.
//!
//! The paper carries tendon tensions as unknowns from the tip down to the base (Section 6):
//! every force and moment of the backward recursion is `c + Σ_k a_k x_k`, where the `x_k`
//! are the ground-level tensions, loop-side tensions and motor torques. The solver does not
//! need them (the recursion is linear in the unknowns: it is run with the tensions zero and
//! with them solved, and `E` comes from the transmission); they are how tests read `E` off
//! the recursion's own statics ([`crate::Data::balance_rows`]). The coefficients are stored
//! inline (no heap).

use crate::real::Real;
use crate::spatial::{Mat3, Vec3};

/// Most unknowns an affine form carries (tendon tensions plus motor torques): beyond it,
/// balance rows are not read off the recursion.
pub const MAX_UNKNOWNS: usize = 12;

/// A scalar `c + Σ_k a_k x_k` over `n` unknowns.
#[derive(Clone, Copy, Debug)]
pub struct Affine<T> {
    /// `c`: the value when every unknown is zero.
    pub constant: T,
    /// `a_k`, the coefficient of unknown `x_k`; only the first `n` are used.
    pub coefficients: [T; MAX_UNKNOWNS],
    /// The number of unknowns (the tension system's columns).
    pub n: usize,
}

impl<T: Real> Affine<T> {
    /// The known value `c` over `n` unknowns (every coefficient zero).
    pub fn constant(c: T, n: usize) -> Self {
        Affine {
            constant: c,
            coefficients: [T::zero(); MAX_UNKNOWNS],
            n,
        }
    }
    /// `offset + x_k`.
    pub fn unknown(k: usize, offset: T, n: usize) -> Self {
        let mut a = Affine::constant(offset, n);
        a.coefficients[k] = T::one();
        a
    }
    /// `self + o`.
    pub fn add(&self, o: &Self) -> Self {
        let mut r = *self;
        r.constant = self.constant + o.constant;
        for k in 0..self.n {
            r.coefficients[k] = self.coefficients[k] + o.coefficients[k];
        }
        r
    }
    /// `self − o`.
    pub fn sub(&self, o: &Self) -> Self {
        let mut r = *self;
        r.constant = self.constant - o.constant;
        for k in 0..self.n {
            r.coefficients[k] = self.coefficients[k] - o.coefficients[k];
        }
        r
    }
    /// `s · self`.
    pub fn scale(&self, s: T) -> Self {
        let mut r = *self;
        r.constant = self.constant * s;
        for k in 0..self.n {
            r.coefficients[k] = self.coefficients[k] * s;
        }
        r
    }
    /// `self + c` for a known `c`.
    pub fn add_constant(&self, c: T) -> Self {
        let mut r = *self;
        r.constant = self.constant + c;
        r
    }
    /// Value at the given unknowns.
    pub fn eval(&self, x: &[T]) -> T {
        let mut v = self.constant;
        for (a, xk) in self.coefficients[..self.n].iter().zip(x) {
            v = v + *a * *xk;
        }
        v
    }
}

/// A three-vector whose components are affine in the unknowns.
#[derive(Clone, Copy, Debug)]
pub struct Aff3<T> {
    /// The value when every unknown is zero.
    pub constant: Vec3<T>,
    /// The vector multiplying unknown `x_k`; only the first `n` are used.
    pub coefficients: [Vec3<T>; MAX_UNKNOWNS],
    /// The number of unknowns (the tension system's columns).
    pub n: usize,
}

impl<T: Real> Aff3<T> {
    /// The known vector `v` over `n` unknowns (every coefficient zero).
    pub fn known(v: Vec3<T>, n: usize) -> Self {
        Aff3 {
            constant: v,
            coefficients: [Vec3::zero(); MAX_UNKNOWNS],
            n,
        }
    }
    /// `dir · a` for a known direction and an affine magnitude (a tendon force `T d`).
    pub fn along(dir: Vec3<T>, a: &Affine<T>) -> Self {
        let mut r = Aff3::known(dir.scale(a.constant), a.n);
        for k in 0..a.n {
            r.coefficients[k] = dir.scale(a.coefficients[k]);
        }
        r
    }
    fn zip(&self, o: &Self, f: impl Fn(Vec3<T>, Vec3<T>) -> Vec3<T>) -> Self {
        let mut r = *self;
        r.constant = f(self.constant, o.constant);
        for k in 0..self.n {
            r.coefficients[k] = f(self.coefficients[k], o.coefficients[k]);
        }
        r
    }
    fn each(&self, f: impl Fn(Vec3<T>) -> Vec3<T>) -> Self {
        let mut r = *self;
        r.constant = f(self.constant);
        for k in 0..self.n {
            r.coefficients[k] = f(self.coefficients[k]);
        }
        r
    }
    /// `self + o`.
    pub fn add(&self, o: &Self) -> Self {
        self.zip(o, |a, b| a + b)
    }
    /// `self − o`.
    pub fn sub(&self, o: &Self) -> Self {
        self.zip(o, |a, b| a - b)
    }
    /// `−self`.
    pub fn neg(&self) -> Self {
        self.each(|a| -a)
    }
    /// `self + v` for a known vector `v`.
    pub fn add_known(&self, v: Vec3<T>) -> Self {
        let mut r = *self;
        r.constant = self.constant + v;
        r
    }
    /// `r × self` for a known lever arm `r`.
    pub fn moment_of(&self, r: Vec3<T>) -> Self {
        self.each(|a| r.cross(a))
    }
    /// `R · self`.
    pub fn rotate(&self, m: &Mat3<T>) -> Self {
        self.each(|a| m.mul_vec(a))
    }
    /// `Rᵀ · self`.
    pub fn rotate_back(&self, m: &Mat3<T>) -> Self {
        self.each(|a| m.tr_mul_vec(a))
    }
    /// `u · self`.
    pub fn dot(&self, u: Vec3<T>) -> Affine<T> {
        let mut r = Affine::constant(u.dot(self.constant), self.n);
        for k in 0..self.n {
            r.coefficients[k] = u.dot(self.coefficients[k]);
        }
        r
    }
    /// Value at the given unknowns.
    pub fn eval(&self, x: &[T]) -> Vec3<T> {
        let mut v = self.constant;
        for (a, xk) in self.coefficients[..self.n].iter().zip(x) {
            v = v + a.scale(*xk);
        }
        v
    }
}
