//! Mechanisms with fixed guides (format.md §6a), made from mechanisms with idlers.

/// `text` with every idler made a fixed guide: the tendon slides over it instead of turning
/// it (`fixed: true` after a route's anchor).
pub fn idlers_as_guides(text: &str) -> String {
    let model = tendyn_core::parse(text).unwrap();
    let mut out = text.to_string();
    for b in &model.bodies {
        if let tendyn_core::model::BodyKind::Pulley {
            role: tendyn_core::model::PulleyRole::Idler { .. },
            ..
        } = b.kind
        {
            let at = format!("name: \"{}\",", b.name);
            assert_eq!(out.matches(&at).count(), 1, "{at}");
            out = out.replacen(&at, &format!("{at} fixed: true,"), 1);
        }
    }
    out
}
