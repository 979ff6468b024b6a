//! `varmass fit --plot`: each fitted quantity's data (points) and the fitted run (line)
//! against t, one panel per quantity.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::{Fit, Series};
use crate::error::CliError;
use crate::run::plot::{bounds, render, Picture};

/// Draws the fit over the data into `path` (SVG, or PNG with the `png` feature).
pub fn plot(fit: &Fit, series: &[Series], title: &str, path: &Path) -> Result<(), CliError> {
    let picture = FitPicture { fit, series, title };
    render(&picture, (900, 300 * series.len().max(1) as u32), path)
}

struct FitPicture<'a> {
    fit: &'a Fit,
    series: &'a [Series],
    title: &'a str,
}

impl Picture for FitPicture<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let error = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
        area.fill(&WHITE).map_err(error)?;
        let area = area.titled(self.title, ("sans-serif", 22)).map_err(error)?;
        let panels = area.split_evenly((self.series.len().max(1), 1));
        let table = &self.fit.table;
        for (s, panel) in self.series.iter().zip(&panels) {
            let Some(column) = table.names.iter().position(|n| *n == s.quantity) else {
                continue;
            };
            let model = || {
                table
                    .times()
                    .iter()
                    .copied()
                    .zip(table.column(column).iter().copied())
            };
            let (t0, t1) = bounds(s.times.iter().copied().chain(table.times().iter().copied()));
            let (lo, hi) = bounds(s.values.iter().copied().chain(model().map(|(_, v)| v)));
            let mut chart = ChartBuilder::on(panel)
                .margin(12)
                .x_label_area_size(32)
                .y_label_area_size(70)
                .build_cartesian_2d(t0..t1, lo..hi)
                .map_err(error)?;
            chart
                .configure_mesh()
                .x_desc("t")
                .y_desc(s.quantity.as_str())
                .draw()
                .map_err(error)?;
            let data = s
                .times
                .iter()
                .zip(&s.values)
                .map(|(t, v)| Circle::new((*t, *v), 2, BLACK.filled()));
            chart.draw_series(data).map_err(error)?.label("data");
            let line = LineSeries::new(
                model().filter(|(t, v)| t.is_finite() && v.is_finite()),
                RED.stroke_width(2),
            );
            chart.draw_series(line).map_err(error)?.label("fit");
        }
        area.present().map_err(error)
    }
}
