//! Tiny models built in code (no file format; [`Model::rigid_tree`]) for tests with closed
//! forms.
//!
//! Bodies are filled in field by field as the model's documentation defines them; derived
//! fields (`axis`, `joint_to_origin`) are computed from `post` the way the validator is
//! meant to. Every body starts massless; give it inertia with [`with_inertia`].

use tendyn_core::model::{Body, BodyKind, Model, PulleyRole, Wrench};
use tendyn_core::spatial::{rot_x, Mat3, Transform, Vec3};

/// Primary link `joint` of a DH chain with `[a, alpha, d, offset]`: `pre = I`,
/// `post = (RotX(alpha), (a, 0, d))`, so its frame is at the link's distal end.
pub fn dh_link(dof: usize, joint: usize, parent: Option<usize>, dh: [f64; 4]) -> Body<f64> {
    let [a, alpha, d, offset] = dh;
    let mut coupling = vec![0.0; dof];
    coupling[joint] = 1.0;
    body(
        format!("link{joint}"),
        BodyKind::Link { joint },
        parent,
        Transform::identity(),
        Transform {
            rotation: rot_x(alpha),
            translation: Vec3::new(a, 0.0, d),
        },
        offset,
        coupling,
        true,
    )
}

/// An intermediate link (pulley, drum) on `parent` whose joint frame is `pre` and whose
/// body frame is tilted from it by `post_rotation` (no offset from the axis).
pub fn pulley(
    name: &str,
    parent: Option<usize>,
    pre: Transform<f64>,
    post_rotation: Mat3<f64>,
    coupling: Vec<f64>,
    spins: bool,
) -> Body<f64> {
    body(
        name.into(),
        BodyKind::Pulley {
            radius: 0.01,
            role: PulleyRole::Coupled,
        },
        parent,
        pre,
        Transform {
            rotation: post_rotation,
            translation: Vec3::zero(),
        },
        0.0,
        coupling,
        spins,
    )
}

/// `body` with mass, centre of mass (body frame) and inertia about it (body axes).
pub fn with_inertia(
    mut body: Body<f64>,
    mass: f64,
    com: [f64; 3],
    inertia: [[f64; 3]; 3],
) -> Body<f64> {
    body.mass = mass;
    body.com = Vec3::from_array(com);
    body.inertia = Mat3::from_rows(inertia);
    body
}

/// A model of these bodies with no tendons, motors or external wrench (checked as
/// [`Model::rigid_tree`] checks every model built in code).
pub fn model(dof: usize, gravity: [f64; 3], bodies: Vec<Body<f64>>) -> Model<f64> {
    Model::rigid_tree("fixture", gravity, dof, bodies, None).expect("a valid fixture")
}

/// `model` with an external wrench on one link.
pub fn with_wrench(model: &Model<f64>, wrench: Wrench<f64>) -> Model<f64> {
    let g = model.gravity().to_array();
    rebuilt(model, model.bodies().to_vec(), g, Some(wrench))
}

/// A model of `model`'s joints with other bodies, gravity and wrench.
pub fn rebuilt(
    model: &Model<f64>,
    bodies: Vec<Body<f64>>,
    gravity: [f64; 3],
    wrench: Option<Wrench<f64>>,
) -> Model<f64> {
    Model::rigid_tree(model.name(), gravity, model.dof(), bodies, wrench).expect("a valid model")
}

#[allow(clippy::too_many_arguments)]
fn body(
    name: String,
    kind: BodyKind,
    parent: Option<usize>,
    pre: Transform<f64>,
    post: Transform<f64>,
    offset: f64,
    coupling: Vec<f64>,
    spins: bool,
) -> Body<f64> {
    Body {
        name,
        kind,
        parent,
        pre,
        post,
        offset,
        coupling,
        spins,
        mass: 0.0,
        com: Vec3::zero(),
        inertia: Mat3::from_rows([[0.0; 3]; 3]),
        axis: post.rotation.tr_mul_vec(Vec3::unit_z()),
        joint_to_origin: post.rotation.tr_mul_vec(post.translation),
        friction: None,
    }
}
