//! `tendyn draw`: an SVG of a mechanism at a state, projected on a plane. Links are lines
//! from their joint point to their frame's origin, joints small squares with a tick along
//! the axis, pulleys their pitch circles as seen (ellipses where tilted) with their names, every tendon segment a line in its strand's colour (with `tensions`, as wide as
//! its tension), ground exits and anchors dots; a scale bar and a legend of the strands.
//!
//! Positions come from the model's own transforms (`transmission::body_transform`, the
//! recursion's `pre · RotZ(angle) · post`), the pulleys' centres and the segments' contact
//! points as validation placed them.

use plotters::prelude::*;
use tendyn_core::model::{BodyKind, Contact};
use tendyn_core::spatial::{Transform, Vec3};
use tendyn_core::transmission::body_transform;
use tendyn_core::Model;

/// The plane the mechanism is projected on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum View {
    /// Looking down the base's z axis.
    Xy,
    /// Looking along +y: x right, z up.
    Xz,
    /// Looking along −x: y right, z up.
    Yz,
    /// Isometric, seen from (1, 1, 1): y to the right and x to the left, 30° below the
    /// horizontal, z up; an orthographic projection, so lengths in the view's plane (a
    /// pulley's diameter across its ellipse) are to scale and the axes are foreshortened
    /// to `√(2/3)` of theirs.
    Iso,
}

impl View {
    /// The name `--view` takes.
    pub fn name(self) -> String {
        clap::ValueEnum::to_possible_value(&self).map_or(String::new(), |v| v.get_name().into())
    }

    fn project(self, p: Vec3<f64>) -> (f64, f64) {
        match self {
            View::Xy => (p.x, p.y),
            View::Xz => (p.x, p.z),
            View::Yz => (p.y, p.z),
            // Onto the plane normal to (1, 1, 1): coordinates along (−1, 1, 0)/√2 and
            // (−1, −1, 2)/√6.
            View::Iso => (
                (p.y - p.x) / 2f64.sqrt(),
                (2.0 * p.z - p.x - p.y) / 6f64.sqrt(),
            ),
        }
    }
}

/// World (base-frame) pose of every body frame at joint angles `q`.
fn poses(model: &Model<f64>, q: &[f64]) -> Vec<Transform<f64>> {
    let mut out: Vec<Transform<f64>> = Vec::with_capacity(model.bodies().len());
    for body in model.bodies() {
        let angle = body.offset + body.coupling.iter().zip(q).map(|(c, q)| c * q).sum::<f64>();
        let local = body_transform(body, angle);
        let pose = match body.parent {
            Some(p) => out[p].compose(&local),
            None => local,
        };
        out.push(pose);
    }
    out
}

/// What the drawing shows, in the base frame.
pub struct Scene {
    /// Per link: its name, joint point and frame origin.
    pub links: Vec<(String, Vec3<f64>, Vec3<f64>)>,
    /// Per joint: its point and axis (unit).
    pub joints: Vec<(Vec3<f64>, Vec3<f64>)>,
    /// Per pulley: its name, centre, axis (unit) and pitch radius.
    pub pulleys: Vec<(String, Vec3<f64>, Vec3<f64>, f64)>,
    /// Every tendon segment.
    pub segments: Vec<SegmentLine>,
    /// Exits and anchors on the base.
    pub ground: Vec<Vec3<f64>>,
}

/// A tendon segment as drawn.
pub struct SegmentLine {
    /// The strand it belongs to (its colour).
    pub strand: usize,
    /// Its end points, base frame.
    pub ends: [Vec3<f64>; 2],
    /// Its tension (N), when the drawing shows tensions.
    pub tension: Option<f64>,
}

/// The scene at `q`; `tensions[strand][segment]` when the drawing shows them.
pub fn scene(model: &Model<f64>, q: &[f64], tensions: Option<&[Vec<f64>]>) -> Scene {
    let poses = poses(model, q);
    let bodies = model.bodies();
    let origin = Transform::identity();
    let frame = |f: Option<usize>| f.map_or(&origin, |f| &poses[f]);
    let joint_point = |b: usize| frame(bodies[b].parent).apply(bodies[b].pre.translation);
    // A joint's (and a pulley's) axis is the z axis of its `pre` frame.
    let axis = |b: usize| {
        frame(bodies[b].parent)
            .rotation
            .mul_vec(bodies[b].pre.rotation.column(2))
    };
    let mut scene = Scene {
        links: Vec::new(),
        joints: Vec::new(),
        pulleys: Vec::new(),
        segments: Vec::new(),
        ground: Vec::new(),
    };
    for (b, body) in bodies.iter().enumerate() {
        match body.kind {
            BodyKind::Link { .. } => {
                let at = joint_point(b);
                scene
                    .links
                    .push((body.name.clone(), at, poses[b].translation));
                scene.joints.push((at, axis(b)));
            }
            BodyKind::Pulley { radius, .. } => {
                scene
                    .pulleys
                    .push((body.name.clone(), joint_point(b), axis(b), radius));
            }
        }
    }
    for (s, strand) in model.strands().iter().enumerate() {
        for (k, g) in strand.segments.iter().enumerate() {
            let f = frame(g.frame);
            let point = |c: &Contact<f64>| match c.body {
                Some(p) => joint_point(p) + f.rotation.mul_vec(c.rel),
                None => f.apply(c.rel),
            };
            let (from, to) = (point(&g.from), point(&g.to));
            for c in [&g.from, &g.to].into_iter().filter(|c| c.body.is_none()) {
                scene.ground.push(point(c));
            }
            let tension = tensions.and_then(|t| t.get(s)?.get(k).copied());
            scene.segments.push(SegmentLine {
                strand: s,
                ends: [from, to],
                tension,
            });
        }
    }
    scene
}

/// The pitch circle of a pulley (centre, unit axis, radius) as a closed run of points.
fn rim(centre: Vec3<f64>, axis: Vec3<f64>, radius: f64) -> Vec<Vec3<f64>> {
    // Two unit vectors spanning the pulley's plane.
    let helper = if axis.x.abs() < 0.9 {
        Vec3::new(1.0, 0.0, 0.0)
    } else {
        Vec3::new(0.0, 1.0, 0.0)
    };
    let u = axis.cross(helper);
    let u = u.scale(1.0 / u.dot(u).sqrt());
    let v = axis.cross(u);
    (0..=48)
        .map(|k| {
            let t = std::f64::consts::TAU * f64::from(k) / 48.0;
            centre + u.scale(radius * t.cos()) + v.scale(radius * t.sin())
        })
        .collect()
}

/// One colour per strand (a qualitative palette, repeated after ten).
fn colour(strand: usize) -> RGBColor {
    const PALETTE: [RGBColor; 10] = [
        RGBColor(31, 119, 180),
        RGBColor(214, 39, 40),
        RGBColor(44, 160, 44),
        RGBColor(255, 127, 14),
        RGBColor(148, 103, 189),
        RGBColor(140, 86, 75),
        RGBColor(227, 119, 194),
        RGBColor(23, 190, 207),
        RGBColor(188, 189, 34),
        RGBColor(127, 127, 127),
    ];
    PALETTE[strand % PALETTE.len()]
}

/// A round length near a fifth of `span` (1, 2 or 5 times a power of ten), for the scale bar.
fn scale_length(span: f64) -> f64 {
    let target = span / 5.0;
    let decade = 10f64.powf(target.log10().floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * decade)
        .find(|l| *l <= target)
        .unwrap_or(decade)
}

/// Where names go: each at its place or, where that would cover a name already placed,
/// moved down below it, until it covers none (pulleys on one axis sit at one point in a
/// view along it).
#[derive(Default)]
struct Labels {
    /// The boxes taken: left, top, right, bottom (pixels).
    taken: Vec<(i32, i32, i32, i32)>,
}

impl Labels {
    /// The top-left corner for `text` in a font of `size` from `wanted`. The box is a
    /// little larger than the text drawn (plotters draws a font of `size` at `size / 1.24`
    /// pixels), so that names placed apart never touch.
    fn place(&mut self, text: &str, wanted: (i32, i32), size: i32) -> (i32, i32) {
        // Sans-serif letters are about 0.6 of the font's size wide.
        let width = (0.6 * f64::from(size) * text.chars().count() as f64).ceil() as i32;
        let (x, mut y) = wanted;
        let covers = |y: i32, b: &(i32, i32, i32, i32)| {
            x < b.2 && b.0 < x + width && y < b.3 && b.1 < y + size
        };
        // Below the lowest box in the way, until none is: `y` only grows, so a box that
        // was passed is never in the way again, and there are as many passes at most as
        // boxes.
        while let Some(bottom) = (self.taken.iter())
            .filter(|b| covers(y, b))
            .map(|b| b.3)
            .max()
        {
            y = bottom + 1;
        }
        self.taken.push((x, y, x + width, y + size));
        (x, y)
    }
}

/// The SVG of `model`'s `scene` seen in `view`.
pub fn svg(model: &Model<f64>, scene: &Scene, view: View) -> Result<String, String> {
    let mut text = String::new();
    draw(model, scene, view, &mut text).map_err(|e| format!("cannot draw: {e}"))?;
    Ok(text)
}

fn draw(
    model: &Model<f64>,
    scene: &Scene,
    view: View,
    text: &mut String,
) -> Result<(), Box<dyn std::error::Error>> {
    let (width, height, margin, legend) = (800.0, 600.0, 40.0, 160.0);
    // Bounds of everything drawn, pulleys' rims included.
    let mut points: Vec<(f64, f64, f64)> = Vec::new();
    points.extend(
        scene
            .links
            .iter()
            .flat_map(|(_, a, b)| [(*a, 0.0), (*b, 0.0)])
            .map(|(p, r)| {
                let (x, y) = view.project(p);
                (x, y, r)
            }),
    );
    points.extend(
        scene
            .pulleys
            .iter()
            .flat_map(|(_, c, a, r)| rim(*c, *a, *r))
            .map(|p| {
                let (x, y) = view.project(p);
                (x, y, 0.0)
            }),
    );
    points.extend(scene.segments.iter().flat_map(|g| g.ends).map(|p| {
        let (x, y) = view.project(p);
        (x, y, 0.0)
    }));
    points.push((0.0, 0.0, 0.0));
    let lo = |f: fn(&(f64, f64, f64)) -> f64| points.iter().map(f).fold(f64::INFINITY, f64::min);
    let hi =
        |f: fn(&(f64, f64, f64)) -> f64| points.iter().map(f).fold(f64::NEG_INFINITY, f64::max);
    let (x0, x1) = (lo(|p| p.0 - p.2), hi(|p| p.0 + p.2));
    let (y0, y1) = (lo(|p| p.1 - p.2), hi(|p| p.1 + p.2));
    let span = (x1 - x0).max(y1 - y0).max(1e-6);
    let (dx, dy) = ((x1 - x0).max(1e-6), (y1 - y0).max(1e-6));
    let (room_x, room_y) = (width - legend - 2.0 * margin, height - 2.0 * margin);
    let scale = (room_x / dx).min(room_y / dy);
    // Centred in the room left of the legend, so a flat mechanism sits mid-page.
    let (left, bottom) = (
        margin + (room_x - dx * scale) / 2.0,
        margin + (room_y - dy * scale) / 2.0,
    );
    let at = |p: Vec3<f64>| {
        let (x, y) = view.project(p);
        (
            (left + (x - x0) * scale) as i32,
            (height - bottom - (y - y0) * scale) as i32,
        )
    };
    let mut labels = Labels::default();
    let root = SVGBackend::with_string(text, (width as u32, height as u32)).into_drawing_area();
    root.fill(&WHITE)?;
    let font = ("sans-serif", 13).into_font();
    let small = ("sans-serif", 11).into_font();
    let grey = RGBColor(90, 90, 90);
    for (name, centre, axis, radius) in &scene.pulleys {
        let outline: Vec<(i32, i32)> = rim(*centre, *axis, *radius).into_iter().map(at).collect();
        root.draw(&PathElement::new(outline, grey.stroke_width(1)))?;
        let (x, y) = at(*centre);
        let r = (radius * scale).round() as i32;
        let place = labels.place(name, (x + r + 2, y - r - 2), 11);
        root.draw(&Text::new(name.clone(), place, small.clone()))?;
    }
    let max_tension = scene
        .segments
        .iter()
        .filter_map(|g| g.tension)
        .fold(0.0f64, |m, t| m.max(t.abs()));
    for g in &scene.segments {
        let width = match g.tension {
            Some(t) if max_tension > 0.0 => 1 + (6.0 * t.abs() / max_tension).round() as u32,
            _ => 2,
        };
        let line = g.ends.map(at).to_vec();
        root.draw(&PathElement::new(
            line,
            colour(g.strand).stroke_width(width),
        ))?;
    }
    for (name, a, b) in &scene.links {
        root.draw(&PathElement::new(
            vec![at(*a), at(*b)],
            BLACK.stroke_width(4),
        ))?;
        let (x, y) = at(*b);
        let place = labels.place(name, (x + 4, y + 4), 13);
        root.draw(&Text::new(name.clone(), place, font.clone()))?;
    }
    for (point, axis) in &scene.joints {
        let (x, y) = at(*point);
        root.draw(&Rectangle::new(
            [(x - 4, y - 4), (x + 4, y + 4)],
            BLACK.filled(),
        ))?;
        // A tick along the axis, a tenth of the drawing long where it is not seen end-on.
        let tip = at(*point + axis.scale(span / 10.0));
        root.draw(&PathElement::new(vec![(x, y), tip], BLACK.stroke_width(1)))?;
    }
    for p in &scene.ground {
        root.draw(&Circle::new(at(*p), 3, BLACK.filled()))?;
    }
    // Scale bar, bottom left.
    let bar = scale_length(span);
    let (bx, by) = (margin as i32, (height - margin / 2.0) as i32);
    let bar_px = (bar * scale).round() as i32;
    root.draw(&PathElement::new(
        vec![(bx, by), (bx + bar_px, by)],
        BLACK.stroke_width(2),
    ))?;
    root.draw(&Text::new(
        format!("{bar} m"),
        (bx + bar_px + 6, by - 7),
        font.clone(),
    ))?;
    // Legend: the mechanism, the view, each strand's colour.
    let lx = (width - legend + 10.0) as i32;
    root.draw(&Text::new(model.name().to_string(), (lx, 12), font.clone()))?;
    root.draw(&Text::new(
        format!("view {}", view.name()),
        (lx, 30),
        small.clone(),
    ))?;
    for (s, strand) in model.strands().iter().enumerate() {
        let y = 52 + 18 * s as i32;
        root.draw(&PathElement::new(
            vec![(lx, y), (lx + 24, y)],
            colour(s).stroke_width(3),
        ))?;
        root.draw(&Text::new(
            strand.name.clone(),
            (lx + 30, y - 7),
            small.clone(),
        ))?;
    }
    root.present()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn count(svg: &str, tag: &str) -> usize {
        svg.matches(&format!("<{tag}")).count()
    }

    /// Every view is an orthographic projection, so the scale bar holds for lengths in its
    /// plane: a unit vector in the plane keeps its length (a pulley's largest diameter is
    /// to scale), the viewing direction vanishes, and a base axis keeps `√(2/3)` of its
    /// length in `iso`.
    #[test]
    fn each_view_projects_lengths_in_its_plane_to_scale() {
        let length = |view: View, v: [f64; 3]| {
            let (x, y) = view.project(Vec3::new(v[0], v[1], v[2]));
            x.hypot(y)
        };
        let s = 1.0 / 2f64.sqrt();
        for (view, normal, in_plane) in [
            (View::Xy, [0.0, 0.0, 1.0], [s, s, 0.0]),
            (View::Xz, [0.0, 1.0, 0.0], [s, 0.0, -s]),
            (View::Yz, [1.0, 0.0, 0.0], [0.0, s, s]),
            (
                View::Iso,
                [1.0, 1.0, 1.0],
                [1.0 / 6f64.sqrt(), 1.0 / 6f64.sqrt(), -2.0 / 6f64.sqrt()],
            ),
        ] {
            assert!(length(view, normal) < 1e-15, "{view:?}");
            assert!((length(view, in_plane) - 1.0).abs() < 1e-15, "{view:?}");
        }
        for axis in [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] {
            assert!((length(View::Iso, axis) - (2.0f64 / 3.0).sqrt()).abs() < 1e-15);
        }
    }

    /// Every part is drawn once: for each of the paper's examples, in every view, one circle
    /// per ground point, one line per pulley's rim, segment, link, joint tick and legend
    /// entry and the scale bar; every pulley, link and strand named.
    #[test]
    fn the_drawing_shows_every_part_of_the_mechanism() {
        for (file, text) in tendyn_codegen::report::BUILT_IN {
            let model = tendyn_core::parse(text).unwrap();
            let q = vec![0.3; model.dof()];
            let scene = scene(&model, &q, None);
            assert_eq!(scene.links.len(), model.dof());
            for view in [View::Xy, View::Xz, View::Yz, View::Iso] {
                let svg = svg(&model, &scene, view).unwrap();
                assert_eq!(count(&svg, "circle"), scene.ground.len(), "{file}");
                let lines = scene.pulleys.len()
                    + scene.segments.len()
                    + 2 * model.dof()
                    + model.strands().len()
                    + 1;
                assert_eq!(count(&svg, "polyline"), lines, "{file} {view:?}");
                let pulleys = scene.pulleys.iter().map(|p| &p.0);
                for name in pulleys.chain(scene.links.iter().map(|l| &l.0)) {
                    assert!(svg.contains(&format!("\n{name}\n")), "{file}: {name}");
                }
                for strand in model.strands() {
                    assert!(svg.contains(&format!("\n{}\n", strand.name)), "{file}");
                }
            }
        }
    }

    /// Names asked for at one place (pulleys on one axis, seen along it) are stacked line
    /// by line; a name clear of the others stays where it was asked for.
    #[test]
    fn names_at_one_place_are_stacked_not_overprinted() {
        let mut labels = Labels::default();
        assert_eq!(labels.place("drum3a", (100, 50), 11), (100, 50));
        assert_eq!(labels.place("drum3b", (100, 50), 11), (100, 62));
        // 55 is in the first name's box (50–61): below it, 62 is in the second's (62–73).
        assert_eq!(labels.place("drum3c", (104, 55), 11), (104, 74));
        assert_eq!(labels.place("far", (300, 50), 11), (300, 50));
        // Two boxes apart block one name twice, and it ends below both.
        let mut apart = Labels::default();
        apart.place("a", (0, 50), 11);
        apart.place("b", (0, 70), 11);
        assert_eq!(apart.place("c", (0, 40), 11), (0, 82));
    }

    /// The drawing puts things where the model has them: segments touch their pulleys'
    /// rims (contact points at the pitch radius from the centre) and end at the exits.
    #[test]
    fn segments_run_between_pulley_rims() {
        for (_, text) in tendyn_codegen::report::BUILT_IN {
            let model = tendyn_core::parse(text).unwrap();
            let q: Vec<f64> = (0..model.dof()).map(|j| 0.2 + 0.3 * j as f64).collect();
            let scene = scene(&model, &q, None);
            let centres: Vec<(Vec3<f64>, f64)> =
                scene.pulleys.iter().map(|(_, c, _, r)| (*c, *r)).collect();
            let mut touching = 0;
            for g in &scene.segments {
                for p in &g.ends {
                    let on_rim = centres.iter().any(|(c, r)| {
                        let d = *p - *c;
                        (d.dot(d).sqrt() - r).abs() <= 1e-9
                    });
                    let on_ground = scene.ground.iter().any(|g| {
                        let d = *p - *g;
                        d.dot(d).sqrt() <= 1e-12
                    });
                    assert!(
                        on_rim || on_ground,
                        "{}: a segment end floats",
                        model.name()
                    );
                    touching += usize::from(on_rim);
                }
            }
            assert!(touching > 0);
        }
    }
}
