//! The work-precision figure: one column per problem, error against wall time (top row) and
//! against state-rate evaluations (bottom row), log–log, one line per method.

use std::path::Path;

use plotters::prelude::*;

use crate::{Method, Point};

/// Colours that stay apart in print and for common colour-vision deficiencies (Okabe–Ito).
/// Three more (Tol's muted scheme) for the high-order and stiff methods.
const PALETTE: [RGBColor; 11] = [
    RGBColor(0, 0, 0),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(0, 158, 115),
    RGBColor(213, 94, 0),
    RGBColor(0, 114, 178),
    RGBColor(204, 121, 167),
    RGBColor(136, 34, 85),
    RGBColor(153, 153, 51),
    RGBColor(136, 136, 136),
    RGBColor(0, 0, 0),
];

/// Errors above this are off the chart (the method has not converged at that setting).
const WORST_SHOWN: f64 = 1.0;
/// Below the rounding floor of doubles nothing is resolved.
const BEST_SHOWN: f64 = 1e-15;

fn colour(method: Method) -> RGBColor {
    let index = Method::ALL
        .iter()
        .chain(&Method::STIFF_ONLY)
        .position(|m| *m == method)
        .unwrap_or(0);
    PALETTE[index % PALETTE.len()]
}

/// The decade bounds enclosing every positive value of `values`.
fn decades(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| *v > 0.0 && v.is_finite())
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if lo > hi {
        return (1.0, 10.0);
    }
    (
        10f64.powf(lo.log10().floor()),
        10f64.powf(hi.log10().ceil()),
    )
}

/// Draws the figure into an SVG file.
pub fn work_precision(
    path: &Path,
    problems: &[&str],
    points: &[Point],
) -> Result<(), Box<dyn std::error::Error>> {
    let root = SVGBackend::new(path, (520 * problems.len() as u32, 900)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(
        "varmass work-precision: relative error at the end vs. cost (fastest of several runs)",
        ("sans-serif", 20),
    )?;
    let panels = root.split_evenly((2, problems.len()));
    for (row, by_time) in [true, false].into_iter().enumerate() {
        for (column, problem) in problems.iter().enumerate() {
            let area = &panels[row * problems.len() + column];
            let shown: Vec<&Point> = points
                .iter()
                .filter(|p| p.problem == *problem && p.error <= WORST_SHOWN)
                .collect();
            let cost = |p: &Point| {
                if by_time {
                    p.seconds
                } else {
                    p.statistics.rate_evaluations as f64
                }
            };
            let (x_lo, x_hi) = decades(shown.iter().map(|p| cost(p)));
            let (y_lo, _) = decades(shown.iter().map(|p| p.error.max(BEST_SHOWN)));
            let mut chart = ChartBuilder::on(area)
                .caption(*problem, ("sans-serif", 16))
                .margin(10)
                .x_label_area_size(40)
                .y_label_area_size(60)
                .build_cartesian_2d((x_lo..x_hi).log_scale(), (y_lo..WORST_SHOWN).log_scale())?;
            chart
                .configure_mesh()
                .x_desc(if by_time {
                    "wall time (s)"
                } else {
                    "state-rate evaluations"
                })
                .y_desc("relative error")
                .x_label_formatter(&|x| format!("{x:.0e}"))
                .y_label_formatter(&|y| format!("{y:.0e}"))
                .draw()?;
            for &method in Method::ALL.iter().chain(&Method::STIFF_ONLY) {
                let series: Vec<(f64, f64)> = shown
                    .iter()
                    .filter(|p| p.method == method)
                    .map(|p| (cost(p), p.error.max(BEST_SHOWN)))
                    .collect();
                if series.is_empty() {
                    continue;
                }
                let style = colour(method).stroke_width(2);
                chart
                    .draw_series(LineSeries::new(series.iter().copied(), style))?
                    .label(method.name())
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 20, y)], colour(method).stroke_width(2))
                    });
                chart.draw_series(
                    series
                        .iter()
                        .map(|&(x, y)| Circle::new((x, y), 3, colour(method).filled())),
                )?;
            }
            if row == 0 && column == 0 {
                chart
                    .configure_series_labels()
                    .background_style(WHITE.mix(0.85))
                    .border_style(BLACK)
                    .position(SeriesLabelPosition::LowerLeft)
                    .draw()?;
            }
        }
    }
    root.present()?;
    Ok(())
}
