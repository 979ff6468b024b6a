//! `--plot`: the recorded quantities against t with plotters, one panel per quantity, as
//! SVG (or PNG, with the `png` feature).

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::output::Table;
use crate::error::CliError;

/// Width of the image, and height of one panel, in pixels.
const WIDTH: u32 = 900;
const PANEL_HEIGHT: u32 = 260;

/// Draws `table` into `path`; the extension chooses the format.
pub fn plot(table: &Table, title: &str, path: &Path) -> Result<(), CliError> {
    let picture = TablePicture { table, title };
    render(
        &picture,
        (WIDTH, PANEL_HEIGHT * table.names.len().max(1) as u32),
        path,
    )
}

/// A picture that can be drawn on any plotters backend.
pub(crate) trait Picture {
    /// Draws the picture on `area`.
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), String>;
}

/// Draws `picture` at `size` (pixels) into `path`: SVG, or PNG with the `png` feature, as
/// the extension says; the one place a plot's format is chosen (`--plot` and a scene's
/// flight panels).
pub(crate) fn render(
    picture: &impl Picture,
    size: (u32, u32),
    path: &Path,
) -> Result<(), CliError> {
    let failed = |reason: String| CliError::Write {
        path: path.to_path_buf(),
        reason,
    };
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match extension.as_deref() {
        Some("svg") => picture.draw(&SVGBackend::new(path, size).into_drawing_area()),
        #[cfg(feature = "png")]
        Some("png") => picture.draw(&BitMapBackend::new(path, size).into_drawing_area()),
        #[cfg(not(feature = "png"))]
        Some("png") => Err("PNG needs the tool built with `--features png`; use .svg".to_string()),
        _ => Err("the plot's extension must be .svg or .png".to_string()),
    }
    .map_err(failed)
}

/// `--plot`'s picture: every recorded column of `table` against t.
struct TablePicture<'a> {
    table: &'a Table,
    title: &'a str,
}

impl Picture for TablePicture<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), String> {
        draw(area, self.table, self.title)
    }
}

fn draw<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    table: &Table,
    title: &str,
) -> Result<(), String> {
    let error = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    area.fill(&WHITE).map_err(error)?;
    let area = area.titled(title, ("sans-serif", 22)).map_err(error)?;
    let panels = area.split_evenly((table.names.len().max(1), 1));
    let (t0, t1) = bounds(table.times().iter().copied());
    for (column, (name, panel)) in table.names.iter().zip(&panels).enumerate() {
        let values = || {
            table
                .times()
                .iter()
                .copied()
                .zip(table.column(column).iter().copied())
        };
        let (lo, hi) = bounds(values().map(|(_, v)| v));
        let mut chart = ChartBuilder::on(panel)
            .margin(12)
            .x_label_area_size(32)
            .y_label_area_size(70)
            .build_cartesian_2d(t0..t1, lo..hi)
            .map_err(error)?;
        chart
            .configure_mesh()
            .x_desc("t")
            .y_desc(name.as_str())
            .draw()
            .map_err(error)?;
        let finite = values().filter(|(t, v)| t.is_finite() && v.is_finite());
        chart
            .draw_series(LineSeries::new(
                finite,
                Palette99::pick(column).stroke_width(2),
            ))
            .map_err(error)?;
    }
    area.present().map_err(error)
}

/// The range of the finite values, widened when it is a single point.
pub(crate) fn bounds(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let pad = if hi > lo {
        0.05 * (hi - lo)
    } else {
        0.5 * lo.abs().max(1.0)
    };
    (lo - pad, hi + pad)
}
