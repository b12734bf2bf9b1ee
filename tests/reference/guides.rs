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
