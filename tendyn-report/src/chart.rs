//! The chart: max relative error (log) against ns per call (log), one panel per output,
//! one point per evaluator and mechanism, the time's interquartile range as a horizontal
//! bar, the mechanism's number beside each point. Colours are evaluators; the legend at the
//! top says which and numbers the mechanisms.

use crate::{Evaluator, Output, Report};
use plotters::prelude::*;
use std::path::Path;

/// Errors below this (an exact 0 included) are drawn at it.
pub const ERROR_FLOOR: f64 = 1e-18;

fn colour(e: Evaluator) -> RGBColor {
    match e {
        Evaluator::GeneratedF64 => RGBColor(31, 119, 180),
        Evaluator::GeneratedF32 => RGBColor(114, 180, 230),
        Evaluator::RuntimeF64 => RGBColor(214, 39, 40),
        Evaluator::RuntimeF32 => RGBColor(255, 152, 120),
    }
}

/// Bounds in decades (log10) around the positive finite values, padded by a third of a
/// decade; `fallback` when there are none.
fn decades(values: impl Iterator<Item = f64>, fallback: (f64, f64)) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite() && *v > 0.0)
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if hi == 0.0 {
        return fallback;
    }
    (lo.log10().floor() - 0.3, hi.log10().ceil() + 0.3)
}

/// The label of a tick at `10^e`: `1e-16`, `10`, `1000`; blank between decades (and with
/// `even`, at odd decades).
fn power_label(e: f64, even: bool) -> String {
    if (e - e.round()).abs() > 1e-6 || (even && e.round() as i64 % 2 != 0) {
        return String::new();
    }
    let e = e.round() as i32;
    if (0..=4).contains(&e) {
        format!("{}", 10i64.pow(e as u32))
    } else {
        format!("1e{e}")
    }
}

/// Writes the chart of `report` to `path` as SVG.
pub fn write_svg(report: &Report, path: &Path) -> Result<(), String> {
    draw(report, path).map_err(|e| format!("{}: cannot draw the chart: {e}", path.display()))
}

fn draw(report: &Report, path: &Path) -> Result<(), Box<dyn std::error::Error>> {
    let mut outputs: Vec<Output> = report.rows.iter().map(|r| r.output).collect();
    outputs.sort();
    outputs.dedup();
    let mut mechanisms: Vec<&str> = Vec::new();
    for r in &report.rows {
        if !mechanisms.contains(&r.mechanism.as_str()) {
            mechanisms.push(&r.mechanism);
        }
    }
    let cols = outputs.len().clamp(1, 3);
    let rows = outputs.len().div_ceil(cols).max(1);
    let (panel_w, panel_h, legend_h) = (420u32, 330u32, 70u32);
    let size = (panel_w * cols as u32, legend_h + panel_h * rows as u32);
    let root = SVGBackend::new(path, size).into_drawing_area();
    root.fill(&WHITE)?;
    let (legend, grid) = root.split_vertically(legend_h);

    // Legend: evaluators by colour, mechanisms by number.
    let font = ("sans-serif", 14).into_font();
    legend.draw(&Text::new(
        "max relative error (log) against ns per call (log); bar: time IQR; \
         errors of 0 drawn at 1e-18",
        (10, 8),
        font.clone(),
    ))?;
    for (i, e) in Evaluator::ALL.iter().enumerate() {
        let x = 10 + 170 * i as i32;
        legend.draw(&Circle::new((x + 6, 36), 5, colour(*e).filled()))?;
        legend.draw(&Text::new(e.name(), (x + 16, 29), font.clone()))?;
    }
    let names: Vec<String> = mechanisms
        .iter()
        .enumerate()
        .map(|(i, m)| format!("{} {m}", i + 1))
        .collect();
    legend.draw(&Text::new(
        format!("mechanisms: {}", names.join(", ")),
        (10, 50),
        font,
    ))?;

    // Both axes in decades on a linear scale (plotters' log axis skips ticks below f64's
    // epsilon), labelled as powers of ten.
    let x_range = decades(report.rows.iter().map(|r| r.time.median), (0.0, 4.0));
    let y_range = decades(
        report.rows.iter().map(|r| r.max_error.max(ERROR_FLOOR)),
        (-18.0, 0.0),
    );
    let panels = grid.split_evenly((rows, cols));
    for (panel, output) in panels.iter().zip(&outputs) {
        let mut chart = ChartBuilder::on(panel)
            .caption(output.name(), ("sans-serif", 16))
            .margin(10)
            .x_label_area_size(34)
            .y_label_area_size(52)
            .build_cartesian_2d(x_range.0..x_range.1, y_range.0..y_range.1)?;
        chart
            .configure_mesh()
            // A tick per decade at most; the formatters label whole decades.
            .x_labels((x_range.1 - x_range.0) as usize + 1)
            .y_labels((y_range.1 - y_range.0) as usize + 1)
            .x_label_formatter(&|x| power_label(*x, false))
            .y_label_formatter(&|y| power_label(*y, true))
            .x_desc("ns per call")
            .y_desc("max rel. error")
            .light_line_style(WHITE.mix(0.0))
            .draw()?;
        for r in report.rows.iter().filter(|r| r.output == *output) {
            let c = colour(r.evaluator);
            let y = if r.max_error.is_finite() {
                r.max_error.max(ERROR_FLOOR).log10()
            } else {
                y_range.1
            };
            let x = |t: f64| t.max(1e-300).log10();
            let number = mechanisms
                .iter()
                .position(|m| *m == r.mechanism)
                .map_or(0, |i| i + 1);
            chart.draw_series(std::iter::once(PathElement::new(
                vec![(x(r.time.p25), y), (x(r.time.p75), y)],
                c.stroke_width(2),
            )))?;
            chart.draw_series(std::iter::once(
                EmptyElement::at((x(r.time.median), y))
                    + Circle::new((0, 0), 4, c.filled())
                    + Text::new(number.to_string(), (5, -14), ("sans-serif", 12)),
            ))?;
        }
    }
    root.present()?;
    Ok(())
}
