//! Mechanisms with fixed guides (format.md §6a), made from mechanisms with idlers.

/// `text` with every idler made a fixed guide: the tendon slides over it instead of turning
/// it (`fixed: true` after a route's anchor).
pub fn idlers_as_guides(text: &str) -> String {
    idlers_as_guides_with(text, None)
}

/// [`idlers_as_guides`] with capstan friction `mu` on every guide.
pub fn idlers_as_capstans(text: &str, mu: f64) -> String {
    idlers_as_guides_with(text, Some(mu))
}

/// `text` with the first idler of every strand made a guide with capstan friction `mu`,
/// the idlers after it left turning: their inertia then reaches the joints through the
/// guide's friction.
pub fn first_idlers_as_capstans(text: &str, mu: f64) -> String {
    let model = tendyn_core::parse(text).unwrap();
    let first: Vec<usize> = (model.strands().iter())
        .filter_map(|s| s.idlers.first().map(|i| i.body))
        .collect();
    made_guides(text, &model, |b| first.contains(&b), Some(mu))
}

fn idlers_as_guides_with(text: &str, mu: Option<f64>) -> String {
    let model = tendyn_core::parse(text).unwrap();
    made_guides(text, &model, |_| true, mu)
}

/// `text` with the idlers `pick` chooses (by body index) made fixed guides.
fn made_guides(
    text: &str,
    model: &tendyn_core::Model<f64>,
    pick: impl Fn(usize) -> bool,
    mu: Option<f64>,
) -> String {
    let mut out = text.to_string();
    for (i, b) in model.bodies().iter().enumerate() {
        if let tendyn_core::model::BodyKind::Pulley {
            role: tendyn_core::model::PulleyRole::Idler { .. },
            ..
        } = b.kind
        {
            if !pick(i) {
                continue;
            }
            let at = format!("name: \"{}\",", b.name);
            assert_eq!(out.matches(&at).count(), 1, "{at}");
            let friction = mu.map_or(String::new(), |mu| format!(" mu: {mu:?},"));
            out = out.replacen(&at, &format!("{at} fixed: true,{friction}"), 1);
        }
    }
    out
}

/// Example 2 with capstan friction on its guides (`example2_capstan.ron`, passed as
/// `text`) and a fourth tendon on drum 1 that pulls against `T11`: four tendons on two
/// joints, a two-dimensional null space that the guides' friction makes depend on the
/// state.
pub fn with_antagonist_on_drum1(text: &str) -> String {
    let t11 = r#"(name: "T11", route: [("drum1", Ccw)], exit: (-0.25, 0.10, 0.0)),"#;
    assert_eq!(text.matches(t11).count(), 1, "{t11}");
    let t12 = r#"(name: "T12", route: [("drum1", Cw)], exit: (-0.25, -0.10, 0.0)),"#;
    text.replacen(t11, &format!("{t11}\n        {t12}"), 1)
        .replacen(
            "name: \"example2_capstan\"",
            "name: \"example2_capstan_friction_antagonist\"",
            1,
        )
}

/// `text` with `max_tension` on the named tendons.
pub fn with_maxima(text: &str, maxima: &[(&str, f64)]) -> String {
    maxima.iter().fold(text.to_string(), |text, (name, max)| {
        let from = format!("(name: \"{name}\", route:");
        assert_eq!(text.matches(&from).count(), 1, "{from}");
        text.replacen(
            &from,
            &format!("(name: \"{name}\", max_tension: {max:?}, route:"),
            1,
        )
    })
}

/// One joint. A drum of radius 0.02 m on the joint axis; `over_pin` leaves its top
/// horizontally to the left, meets the top of a pin (radius 0.01 m, centre (−0.1, 0.01) in
/// the base) tangentially, wraps it a quarter turn counter-clockwise and leaves straight
/// down to its exit; `direct` leaves the drum's bottom to the left. By hand: both tendons
/// have a moment arm of 0.02 m, of opposite signs, so `Q = 0.02 (T_over − T_direct)`; the
/// pin's wrap angle is π/2; turning the drum counter-clockwise pays `over_pin` out towards
/// its exit at `0.02 q̇`, which is its speed over the pin.
pub const PIN: &str = r#"(
    name: "one_pin",
    gravity: (0.0, -9.81, 0.0),
    tension_floor: 2.0,
    links: [
        (name: "link1", dh: (a: 0.3, alpha: 0.0, d: 0.0), mass: 0.5, com: (-0.15, 0.0, 0.0),
            inertia: (xx: 0.0001, yy: 0.004, zz: 0.004)),
    ],
    pulleys: [
        (name: "drum", carrier: "link1", at: Joint(joint: "link1", height: 0.0), radius: 0.02, fixed: true),
        (name: "pin", carrier: "base", at: Pose(origin: (-0.1, 0.01, 0.0), rpy: (0.0, 0.0, 0.0)), radius: 0.01, fixed: true, mu: 0.0),
    ],
    tendons: [
        (name: "over_pin", route: [("drum", Ccw), ("pin", Ccw)], exit: (-0.11, -0.2, 0.0)),
        (name: "direct", route: [("drum", Cw)], exit: (-0.2, -0.02, 0.0)),
    ],
)
"#;

/// `PIN` with the pin's line changed.
pub fn pin_with(from: &str, to: &str) -> String {
    assert_eq!(PIN.matches(from).count(), 1, "{from}");
    PIN.replacen(from, to, 1)
}

/// `PIN` with capstan friction `mu` on the pin and a turning idler after it on `over_pin`'s
/// way to its exit (the idler light enough that the segment between pin and idler stays
/// taut): the idler's inertia reaches the joint scaled by the pin's friction.
pub fn pin_then_idler(mu: f64) -> String {
    let pin = format!("fixed: true, mu: {mu:?}),");
    let idler =
        "\n        (name: \"idl\", carrier: \"base\", at: Pose(origin: (-0.12, -0.1, 0.0), \
                 rpy: (0.0, 0.0, 0.0)), radius: 0.01, mass: 0.005, inertia: (xx: 0.00001, \
                 yy: 0.00001, zz: 0.00002)),";
    pin_with("mu: 0.0", &format!("mu: {mu:?}"))
        .replacen(&pin, &format!("{pin}{idler}"), 1)
        .replacen(
            "(name: \"over_pin\", route: [(\"drum\", Ccw), (\"pin\", Ccw)], exit: (-0.11, -0.2, 0.0)),",
            "(name: \"over_pin\", route: [(\"drum\", Ccw), (\"pin\", Ccw), (\"idl\", Cw)], \
             exit: (-0.3, -0.11, 0.0)),",
            1,
        )
}
