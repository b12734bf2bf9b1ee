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

fn idlers_as_guides_with(text: &str, mu: Option<f64>) -> String {
    let model = tendyn_core::parse(text).unwrap();
    let mut out = text.to_string();
    for b in model.bodies() {
        if let tendyn_core::model::BodyKind::Pulley {
            role: tendyn_core::model::PulleyRole::Idler { .. },
            ..
        } = b.kind
        {
            let at = format!("name: \"{}\",", b.name);
            assert_eq!(out.matches(&at).count(), 1, "{at}");
            let friction = mu.map_or(String::new(), |mu| format!(" mu: {mu:?},"));
            out = out.replacen(&at, &format!("{at} fixed: true,{friction}"), 1);
        }
    }
    out
}
