//! `--plot FILE.svg` on a scene with `[flight]`: panels of altitude (the measured log
//! overlaid), speed, attitude, angle of attack and static margin against t, each panel
//! titled and its series named in a legend; a panel whose roles the flight lacks is left
//! out.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::log::Log;
use super::roles::{Role, Roles};
use crate::error::CliError;
use crate::run::output::Table;
use crate::run::plot::{bounds, render, Picture};

const WIDTH: u32 = 900;
const PANEL_HEIGHT: u32 = 280;

/// The panels: title and the roles drawn in it.
const PANELS: [(&str, &[Role]); 5] = [
    ("altitude", &[Role::Altitude]),
    ("speed", &[Role::Speed, Role::VerticalSpeed]),
    ("attitude", &[Role::Pitch, Role::Heading]),
    ("angle of attack", &[Role::Alpha]),
    ("static margin", &[Role::StaticMargin]),
];

/// The name of the log's series in the altitude panel's legend.
pub const LOG_SERIES: &str = "measured log";

/// One series: its legend name and points.
type Series = (String, Vec<(f64, f64)>);

/// Draws the flight panels of `table` (columns: `roles`) and `log` into `path` (SVG, or
/// PNG with the `png` feature).
pub fn plot(
    table: &Table,
    roles: &Roles,
    log: Option<&Log>,
    title: &str,
    path: &Path,
) -> Result<(), CliError> {
    let panels = panels(table, roles, log);
    let size = (WIDTH, PANEL_HEIGHT * panels.len().max(1) as u32);
    render(&FlightPicture { panels, title }, size, path)
}

/// The flight's picture: its panels under `title`.
struct FlightPicture<'a> {
    panels: Vec<(&'static str, Vec<Series>)>,
    title: &'a str,
}

impl Picture for FlightPicture<'_> {
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), String> {
        draw(area, &self.panels, self.title)
    }
}

/// The panels that have at least one series, each with its series.
fn panels(table: &Table, roles: &Roles, log: Option<&Log>) -> Vec<(&'static str, Vec<Series>)> {
    let t = table.times();
    let mut out = Vec::new();
    for (title, members) in PANELS {
        let mut series: Vec<Series> = members
            .iter()
            .filter_map(|role| {
                let k = roles.index(*role)?;
                let points = t.iter().copied().zip(table.column(k).iter().copied());
                Some((role.key().replace('_', " "), points.collect()))
            })
            .collect();
        if let (Some(log), Role::Altitude) = (log, members[0]) {
            let points = log.times.iter().copied().zip(log.altitudes.iter().copied());
            series.push((LOG_SERIES.to_string(), points.collect()));
        }
        if !series.is_empty() {
            out.push((title, series));
        }
    }
    out
}

fn draw<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    panels: &[(&str, Vec<Series>)],
    title: &str,
) -> Result<(), String> {
    let error = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    area.fill(&WHITE).map_err(error)?;
    let area = area.titled(title, ("sans-serif", 22)).map_err(error)?;
    let areas = area.split_evenly((panels.len().max(1), 1));
    let all = || panels.iter().flat_map(|(_, s)| s).flat_map(|(_, p)| p);
    let (t0, t1) = bounds(all().map(|(t, _)| *t));
    for ((panel_title, series), panel) in panels.iter().zip(&areas) {
        let (lo, hi) = bounds(series.iter().flat_map(|(_, p)| p).map(|(_, v)| *v));
        let mut chart = ChartBuilder::on(panel)
            .caption(*panel_title, ("sans-serif", 18))
            .margin(10)
            .x_label_area_size(30)
            .y_label_area_size(70)
            .build_cartesian_2d(t0..t1, lo..hi)
            .map_err(error)?;
        chart.configure_mesh().x_desc("t").draw().map_err(error)?;
        for (k, (name, points)) in series.iter().enumerate() {
            let color = Palette99::pick(k);
            let finite = points
                .iter()
                .copied()
                .filter(|(t, v)| t.is_finite() && v.is_finite());
            chart
                .draw_series(LineSeries::new(finite, color.stroke_width(2)))
                .map_err(error)?
                .label(name.as_str())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                });
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(error)?;
    }
    area.present().map_err(error)
}
