//! Three-vectors, 3x3 matrices and rigid transforms, generic over [`Real`].
//!
//! Deliberately small: nalgebra's `RealField` asks for ordering and dozens of methods a
//! symbolic scalar cannot provide, so the recursion uses these instead. Every operation
//! is written out so that the code generator sees exactly the arithmetic that is done.

use crate::real::Real;
use core::ops::{Add, Mul, Neg, Sub};

/// A three-vector (a point, a direction, a velocity, a force, ...), components in a frame
/// the context names.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vec3<T> {
    /// The x component.
    pub x: T,
    /// The y component.
    pub y: T,
    /// The z component.
    pub z: T,
}

impl<T: Real> Vec3<T> {
    /// The vector `(x, y, z)`.
    pub fn new(x: T, y: T, z: T) -> Self {
        Vec3 { x, y, z }
    }
    /// `(0, 0, 0)`.
    pub fn zero() -> Self {
        Vec3::new(T::zero(), T::zero(), T::zero())
    }
    /// `(0, 0, 1)`: the joint or pulley axis in its own frame.
    pub fn unit_z() -> Self {
        Vec3::new(T::zero(), T::zero(), T::one())
    }
    /// `(a[0], a[1], a[2])`, each converted by [`Real::from_f64`].
    pub fn from_array(a: [f64; 3]) -> Self {
        Vec3::new(T::from_f64(a[0]), T::from_f64(a[1]), T::from_f64(a[2]))
    }
    /// The scalar product `self · o`.
    pub fn dot(self, o: Self) -> T {
        self.x * o.x + self.y * o.y + self.z * o.z
    }
    /// The vector product `self × o` (right-handed).
    pub fn cross(self, o: Self) -> Self {
        Vec3::new(
            self.y * o.z - self.z * o.y,
            self.z * o.x - self.x * o.z,
            self.x * o.y - self.y * o.x,
        )
    }
    /// `s · self`.
    pub fn scale(self, s: T) -> Self {
        Vec3::new(self.x * s, self.y * s, self.z * s)
    }
    /// `[x, y, z]`.
    pub fn to_array(self) -> [T; 3] {
        [self.x, self.y, self.z]
    }
    /// `f` applied to each component (a change of scalar).
    pub fn map<U: Real>(self, f: impl Fn(T) -> U) -> Vec3<U> {
        Vec3::new(f(self.x), f(self.y), f(self.z))
    }
}

impl<T: Real> Add for Vec3<T> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Vec3::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}
impl<T: Real> Sub for Vec3<T> {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Vec3::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}
impl<T: Real> Neg for Vec3<T> {
    type Output = Self;
    fn neg(self) -> Self {
        Vec3::new(-self.x, -self.y, -self.z)
    }
}

/// A 3x3 matrix stored by rows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mat3<T> {
    /// `rows[i][j]`: the entry in row `i`, column `j`.
    pub rows: [[T; 3]; 3],
}

impl<T: Real> Mat3<T> {
    /// The identity matrix.
    pub fn identity() -> Self {
        let (o, z) = (T::one(), T::zero());
        Mat3 {
            rows: [[o, z, z], [z, o, z], [z, z, o]],
        }
    }
    /// The matrix of these rows, each entry converted by [`Real::from_f64`].
    pub fn from_rows(rows: [[f64; 3]; 3]) -> Self {
        Mat3 {
            rows: rows.map(|r| r.map(T::from_f64)),
        }
    }
    /// Rotation about z by the angle whose sine and cosine are given.
    pub fn rot_z(s: T, c: T) -> Self {
        let (o, z) = (T::one(), T::zero());
        Mat3 {
            rows: [[c, -s, z], [s, c, z], [z, z, o]],
        }
    }
    /// `RotZ(s, c) · self` ([`Mat3::rot_z`]): a turn about z mixes the first two rows, 12
    /// products where the full product takes 27, with the same terms in the same order
    /// (the product's are zero or one, and only drop out).
    pub fn turned_about_z(&self, s: T, c: T) -> Self {
        let m = &self.rows;
        let minus_s = -s;
        Mat3 {
            rows: [
                core::array::from_fn(|j| c * m[0][j] + minus_s * m[1][j]),
                core::array::from_fn(|j| s * m[0][j] + c * m[1][j]),
                m[2],
            ],
        }
    }
    /// `self · RotZ(s, c)`: the first two columns mixed, as in [`Mat3::turned_about_z`].
    pub fn then_turned_about_z(&self, s: T, c: T) -> Self {
        let minus_s = -s;
        Mat3 {
            rows: self
                .rows
                .map(|r| [r[0] * c + r[1] * s, r[0] * minus_s + r[1] * c, r[2]]),
        }
    }
    /// `selfᵀ` (for a rotation, its inverse).
    pub fn transpose(&self) -> Self {
        let r = &self.rows;
        Mat3 {
            rows: [
                [r[0][0], r[1][0], r[2][0]],
                [r[0][1], r[1][1], r[2][1]],
                [r[0][2], r[1][2], r[2][2]],
            ],
        }
    }
    /// `self · v`.
    pub fn mul_vec(&self, v: Vec3<T>) -> Vec3<T> {
        let r = &self.rows;
        Vec3::new(
            r[0][0] * v.x + r[0][1] * v.y + r[0][2] * v.z,
            r[1][0] * v.x + r[1][1] * v.y + r[1][2] * v.z,
            r[2][0] * v.x + r[2][1] * v.y + r[2][2] * v.z,
        )
    }
    /// `selfᵀ v` without forming the transpose.
    pub fn tr_mul_vec(&self, v: Vec3<T>) -> Vec3<T> {
        let r = &self.rows;
        Vec3::new(
            r[0][0] * v.x + r[1][0] * v.y + r[2][0] * v.z,
            r[0][1] * v.x + r[1][1] * v.y + r[2][1] * v.z,
            r[0][2] * v.x + r[1][2] * v.y + r[2][2] * v.z,
        )
    }
    /// Column `j` (`0..3`); of a rotation, the image of axis `j` (column 2: the z axis).
    pub fn column(&self, j: usize) -> Vec3<T> {
        Vec3::new(self.rows[0][j], self.rows[1][j], self.rows[2][j])
    }
    /// `f` applied to each entry (a change of scalar).
    pub fn map<U: Real>(&self, f: impl Fn(T) -> U) -> Mat3<U> {
        Mat3 {
            rows: self.rows.map(|r| r.map(&f)),
        }
    }
}

impl<T: Real> Mul for Mat3<T> {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        let a = &self.rows;
        let b = &o.rows;
        let mut rows = [[T::zero(); 3]; 3];
        for (i, row) in rows.iter_mut().enumerate() {
            for (j, e) in row.iter_mut().enumerate() {
                *e = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
            }
        }
        Mat3 { rows }
    }
}

/// A rigid transform `p ↦ rotation · p + translation` (the frame of a child expressed in
/// its parent's frame).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform<T> {
    /// The child frame's axes as columns, in the parent frame.
    pub rotation: Mat3<T>,
    /// The child frame's origin in the parent frame (m).
    pub translation: Vec3<T>,
}

impl<T: Real> Transform<T> {
    /// The transform that changes nothing (coincident frames).
    pub fn identity() -> Self {
        Transform {
            rotation: Mat3::identity(),
            translation: Vec3::zero(),
        }
    }
    /// `self · o`: `o` applied first. If `o` places frame C in frame B and `self` places B
    /// in A, the result places C in A.
    pub fn compose(&self, o: &Self) -> Self {
        Transform {
            rotation: self.rotation * o.rotation,
            translation: self.rotation.mul_vec(o.translation) + self.translation,
        }
    }
    /// The inverse transform (the parent frame in the child's); `rotation` must be a
    /// rotation, whose inverse is its transpose.
    pub fn inverse(&self) -> Self {
        let rt = self.rotation.transpose();
        Transform {
            rotation: rt,
            translation: -rt.mul_vec(self.translation),
        }
    }
    /// The point `p` of the child frame, in the parent frame.
    pub fn apply(&self, p: Vec3<T>) -> Vec3<T> {
        self.rotation.mul_vec(p) + self.translation
    }
    /// `f` applied to every number (a change of scalar).
    pub fn map<U: Real>(&self, f: impl Fn(T) -> U + Copy) -> Transform<U> {
        Transform {
            rotation: self.rotation.map(f),
            translation: self.translation.map(f),
        }
    }
}

/// `sin` and `cos` of `angle`, exactly `0` and `±1` where it is within `within` of a
/// multiple of π/2: an angle that is one in exact arithmetic (a twist written as a decimal,
/// a tangent along an axis) then gives no `cos(π/2) ≈ 6e-17` leftovers, which generated code
/// and printed equations would carry as terms.
pub fn sin_cos_snapped(angle: f64, within: f64) -> (f64, f64) {
    let quarter = (angle / core::f64::consts::FRAC_PI_2).round();
    if (angle - quarter * core::f64::consts::FRAC_PI_2).abs() <= within {
        match (quarter as i64).rem_euclid(4) {
            0 => (0.0, 1.0),
            1 => (1.0, 0.0),
            2 => (0.0, -1.0),
            _ => (-1.0, 0.0),
        }
    } else {
        angle.sin_cos()
    }
}

/// Rotation matrix of `RotX(angle)` for a number known at validation time.
pub fn rot_x(angle: f64) -> Mat3<f64> {
    let (s, c) = angle.sin_cos();
    Mat3::from_rows([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])
}

/// Rotation matrix of `RotY(angle)`.
pub fn rot_y(angle: f64) -> Mat3<f64> {
    let (s, c) = angle.sin_cos();
    Mat3::from_rows([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])
}

/// Rotation matrix of `RotZ(angle)`.
pub fn rot_z(angle: f64) -> Mat3<f64> {
    let (s, c) = angle.sin_cos();
    Mat3::rot_z(s, c)
}
