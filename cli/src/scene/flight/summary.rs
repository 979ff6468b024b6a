//! The flight summary: apogee (located), extremes, burnout, lift-off, rail exit, static
//! margin, phase changes, landing and the comparison with a measured log, computed from the
//! flight table (one column per role at every recorded row), printed as a block and
//! written as JSON.

use std::collections::BTreeMap;
use std::fmt::Write;

use serde::{Deserialize, Serialize};

use super::apogee::{locate_apogee, Apogee};
use super::log::Log;
use super::roles::{Role, Roles};
use crate::run::names::shown;
use crate::run::output::Table;
use crate::run::plan::condition;
use crate::scene::Change;

/// The largest value of a quantity over the recorded rows, and its time.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Extreme {
    /// The value.
    pub value: f64,
    /// The time of its row.
    pub time: f64,
}

/// Where the vehicle left its launch rail.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct RailExit {
    /// The time.
    pub time: f64,
    /// The speed there.
    pub speed: f64,
}

/// The static margin (calibers) at the moments that matter and over the ascent.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct StaticMargin {
    /// At the rail exit (if the scene has one).
    pub at_rail_exit: Option<f64>,
    /// At burnout (if known).
    pub at_burnout: Option<f64>,
    /// The least over the ascent (rail exit, or lift-off, or start, to the apogee or end).
    pub min: Extreme,
    /// The largest over the same rows.
    pub max: Extreme,
}

/// A change of phase (a stage, a parachute), with the flight's state there.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PhaseEvent {
    /// The phase entered (from 1).
    pub phase: usize,
    /// Its time.
    pub time: f64,
    /// `separation` or `capture`.
    pub rule: String,
    /// The altitude there.
    pub altitude: f64,
    /// The speed there (if the flight has a speed).
    pub speed: Option<f64>,
}

/// Where the run stopped on a `stop_when` on the altitude.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Landing {
    /// The time.
    pub time: f64,
    /// The vertical speed there.
    pub vertical_speed: f64,
    /// The east coordinate (if the flight has one).
    pub east: Option<f64>,
    /// The north coordinate.
    pub north: Option<f64>,
}

/// The end of the run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct End {
    /// The last time.
    pub time: f64,
    /// The altitude there.
    pub altitude: f64,
    /// The `stop_when` that ended it (else it reached `until`).
    pub stopped_by: Option<String>,
}

/// The measured log against the flight.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LogComparison {
    /// The log file.
    pub file: String,
    /// The highest altitude of the log and its time.
    pub apogee: Extreme,
    /// Our apogee minus the log's.
    pub apogee_difference: Option<f64>,
    /// That difference relative to the log's apogee.
    pub apogee_relative: Option<f64>,
    /// The root mean square of (ours − log) at the log's times within our run (ours
    /// interpolated linearly between rows).
    pub altitude_rms: Option<f64>,
}

/// Everything the summary says, as the JSON has it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FlightSummary {
    /// Each role present and its expression.
    pub roles: BTreeMap<String, String>,
    /// The located apogee (`None`: the vertical speed never fell through zero).
    pub apogee: Option<Apogee>,
    /// The largest speed.
    pub max_speed: Option<Extreme>,
    /// The largest Mach number.
    pub max_mach: Option<Extreme>,
    /// The largest dynamic pressure.
    pub max_qbar: Option<Extreme>,
    /// The largest acceleration.
    pub max_acceleration: Option<Extreme>,
    /// The burnout time.
    pub burnout: Option<f64>,
    /// When the vehicle left its support (`support`).
    pub lift_off: Option<f64>,
    /// When and how fast it left its rail.
    pub rail_exit: Option<RailExit>,
    /// The static margin.
    pub static_margin: Option<StaticMargin>,
    /// The changes of phase.
    pub phases: Vec<PhaseEvent>,
    /// The landing (a `stop_when` on the altitude ended the run).
    pub landing: Option<Landing>,
    /// The end of the run.
    pub end: End,
    /// The comparison with the measured log.
    pub log: Option<LogComparison>,
}

/// What the summary is made from besides the flight table.
pub struct Events<'a> {
    /// The scene's changes of phase.
    pub changes: &'a [Change],
    /// The lift-off from the support.
    pub lift_off: Option<f64>,
    /// The rail exit (time, speed), when the scene's run has one.
    pub rail_exit: Option<(f64, f64)>,
    /// The `stop_when` that ended the run.
    pub stopped_by: Option<&'a str>,
    /// `[flight] burnout`, given.
    pub burnout: Option<f64>,
    /// The measured log.
    pub log: Option<&'a Log>,
}

/// The summary of the flight `table` (its columns the `roles` present).
pub fn summarize(table: &Table, roles: &Roles, events: &Events<'_>) -> FlightSummary {
    let t = table.times();
    let column = |role: Role| roles.index(role).map(|k| table.column(k));
    let altitude = column(Role::Altitude).unwrap_or(&[]);
    let vertical = column(Role::VerticalSpeed).unwrap_or(&[]);
    let apogee = locate_apogee(t, altitude, vertical);
    let largest = |role: Role| column(role).and_then(|c| largest(t, c, |_| true));
    let burnout = events
        .burnout
        .or_else(|| column(Role::Thrust).and_then(|f| burnout(t, f)));
    let rail_exit = events
        .rail_exit
        .map(|(time, speed)| RailExit { time, speed });
    let static_margin = column(Role::StaticMargin).and_then(|c| {
        let start = rail_exit.map(|r| r.time).or(events.lift_off);
        let window = (start, apogee.as_ref().map(|a| a.time));
        static_margin(t, c, window, (rail_exit.map(|r| r.time), burnout))
    });
    let (last_time, last_altitude) = (t.last().copied(), altitude.last().copied());
    FlightSummary {
        roles: roles
            .present
            .iter()
            .map(|(r, e)| (r.key().to_string(), e.clone()))
            .collect(),
        max_speed: largest(Role::Speed),
        max_mach: largest(Role::Mach),
        max_qbar: largest(Role::Qbar),
        max_acceleration: largest(Role::Acceleration),
        burnout,
        lift_off: events.lift_off,
        rail_exit,
        static_margin,
        phases: phase_events(t, events.changes, altitude, column(Role::Speed)),
        landing: landing(table, roles, events.stopped_by),
        end: End {
            time: last_time.unwrap_or(f64::NAN),
            altitude: last_altitude.unwrap_or(f64::NAN),
            stopped_by: events.stopped_by.map(str::to_string),
        },
        log: events
            .log
            .map(|log| compare(log, t, altitude, apogee.as_ref())),
        apogee,
    }
}

/// The largest of `values` over the rows `keep` accepts, with its time.
fn largest(t: &[f64], values: &[f64], keep: impl Fn(f64) -> bool) -> Option<Extreme> {
    t.iter()
        .zip(values)
        .filter(|(t, v)| keep(**t) && v.is_finite())
        .map(|(t, v)| Extreme {
            value: *v,
            time: *t,
        })
        .reduce(|a, b| if b.value > a.value { b } else { a })
}

/// The first time after which the thrust `f` stays ≤ 0 (the row after the last positive
/// one): on a thrust curve whose last knot is zero, that knot (a row: runs land on knots);
/// at a switch or change of phase that cuts the thrust, the row where it is cut. `None` if
/// it never burned or still burns at the end.
fn burnout(t: &[f64], f: &[f64]) -> Option<f64> {
    let last = f.iter().rposition(|f| *f > 0.0)?;
    t.get(last + 1).copied()
}

/// The value of `values` at `time`, linear between the rows around it (the first of two
/// rows at one time: the state before a change).
fn value_at(t: &[f64], values: &[f64], time: f64) -> Option<f64> {
    let i = t.iter().position(|s| *s >= time)?;
    if t[i] == time || i == 0 {
        return (t[i] == time).then_some(values[i]);
    }
    let w = (time - t[i - 1]) / (t[i] - t[i - 1]);
    Some(values[i - 1] + w * (values[i] - values[i - 1]))
}

/// The static margin `c` at the rail exit and burnout (`at`), and its least and largest
/// over the rows of `window` (from its start, to its end).
fn static_margin(
    t: &[f64],
    c: &[f64],
    (from, to): (Option<f64>, Option<f64>),
    (rail, burnout): (Option<f64>, Option<f64>),
) -> Option<StaticMargin> {
    let inside = |s: f64| from.is_none_or(|f| s >= f) && to.is_none_or(|e| s <= e);
    let max = largest(t, c, inside)?;
    let negated: Vec<f64> = c.iter().map(|v| -v).collect();
    let min = largest(t, &negated, inside).map(|e| Extreme {
        value: -e.value,
        time: e.time,
    })?;
    Some(StaticMargin {
        at_rail_exit: rail.and_then(|r| value_at(t, c, r)),
        at_burnout: burnout.and_then(|b| value_at(t, c, b)),
        min,
        max,
    })
}

/// The changes of phase with the altitude and speed at each (the row after the change).
fn phase_events(
    t: &[f64],
    changes: &[Change],
    altitude: &[f64],
    speed: Option<&[f64]>,
) -> Vec<PhaseEvent> {
    changes
        .iter()
        .map(|change| {
            let row = t.iter().position(|s| *s >= change.time);
            let at = |c: &[f64]| row.and_then(|i| c.get(i)).copied();
            PhaseEvent {
                phase: change.phase,
                time: change.time,
                rule: change.rule.to_string(),
                altitude: at(altitude).unwrap_or(f64::NAN),
                speed: speed.and_then(at),
            }
        })
        .collect()
}

/// The landing: the last row, when the run stopped on a `stop_when` while descending, back
/// at or below the launch height (the altitude's first row, to 1e-9 of it): a stop on the
/// way up (`z > 50`) or in the air (`altitude < 450`) is no landing, and a stop written on
/// another name of the altitude (`z < 0` where the altitude role is `altitude = z`) is one
/// (review of session 36: the condition's text was compared with the role's).
fn landing(table: &Table, roles: &Roles, stopped_by: Option<&str>) -> Option<Landing> {
    condition(stopped_by?, "stop_when").ok()?;
    let (time, row) = table.last()?;
    let at = |role: Role| roles.index(role).map(|k| row[k]);
    let k = roles.index(Role::Altitude)?;
    let launch = (!table.is_empty()).then(|| table.row(0).1[k])?;
    if at(Role::Altitude)? > launch + 1e-9 * (1.0 + launch.abs()) {
        return None;
    }
    let vertical_speed = at(Role::VerticalSpeed).filter(|v| *v <= 0.0)?;
    Some(Landing {
        time,
        vertical_speed,
        east: at(Role::East),
        north: at(Role::North),
    })
}

/// The log against our altitude: its highest row, our apogee's difference from it, and
/// the RMS difference at its times within our run.
fn compare(log: &Log, t: &[f64], altitude: &[f64], apogee: Option<&Apogee>) -> LogComparison {
    let measured = largest(&log.times, &log.altitudes, |_| true).unwrap_or(Extreme {
        value: f64::NAN,
        time: f64::NAN,
    });
    let difference = apogee.map(|a| a.altitude - measured.value);
    let (first, last) = (t.first().copied(), t.last().copied());
    let within = |s: f64| first.is_some_and(|f| s >= f) && last.is_some_and(|l| s <= l);
    let squares: Vec<f64> = (log.times.iter().zip(&log.altitudes))
        .filter(|(s, _)| within(**s))
        .filter_map(|(s, h)| value_at(t, altitude, *s).map(|ours| (ours - h).powi(2)))
        .collect();
    let rms =
        (!squares.is_empty()).then(|| (squares.iter().sum::<f64>() / squares.len() as f64).sqrt());
    LogComparison {
        file: log.file.display().to_string(),
        apogee: measured,
        apogee_difference: difference,
        apogee_relative: difference
            .filter(|_| measured.value != 0.0)
            .map(|d| d / measured.value),
        altitude_rms: rms,
    }
}

/// The block `varmass run SCENE.toml` prints.
pub fn text(s: &FlightSummary) -> String {
    let mut out = String::from("flight:\n");
    match &s.apogee {
        Some(a) => {
            let _ = write!(
                out,
                "  apogee: altitude {} at t = {} (located between the rows at t = {} and {}",
                shown(a.altitude),
                shown(a.time),
                shown(a.between.0),
                shown(a.between.1)
            );
            if let (Some(h), Some(time)) = (a.altitude_error, a.time_error) {
                let _ = write!(
                    out,
                    "; interpolation error ≲ {} in altitude, {} in time",
                    shown(h),
                    shown(time)
                );
            }
            out.push_str(")\n");
        }
        None => out.push_str("  apogee: not reached (the vertical speed never fell through 0)\n"),
    }
    let extremes = [
        ("max speed", s.max_speed),
        ("max mach", s.max_mach),
        ("max qbar", s.max_qbar),
        ("max acceleration", s.max_acceleration),
    ];
    for (what, extreme) in extremes {
        if let Some(e) = extreme {
            let _ = writeln!(out, "  {what}: {} at t = {}", shown(e.value), shown(e.time));
        }
    }
    events_text(s, &mut out);
    out
}

/// The summary's lines after the extremes.
fn events_text(s: &FlightSummary, out: &mut String) {
    let time = |t: Option<f64>| t.map_or("none".to_string(), |t| format!("t = {}", shown(t)));
    let _ = writeln!(out, "  burnout: {}", time(s.burnout));
    let _ = writeln!(out, "  lift-off: {}", time(s.lift_off));
    if let Some(r) = s.rail_exit {
        let _ = writeln!(
            out,
            "  rail exit: t = {}, speed {}",
            shown(r.time),
            shown(r.speed)
        );
    }
    if let Some(m) = s.static_margin {
        let at = |v: Option<f64>| v.map_or("-".to_string(), shown);
        let _ = writeln!(
            out,
            "  static margin: {} at rail exit, {} at burnout; min {} at t = {}, max {} at t = {}",
            at(m.at_rail_exit),
            at(m.at_burnout),
            shown(m.min.value),
            shown(m.min.time),
            shown(m.max.value),
            shown(m.max.time)
        );
    }
    for p in &s.phases {
        let speed = p
            .speed
            .map_or(String::new(), |v| format!(", speed {}", shown(v)));
        let _ = writeln!(
            out,
            "  phase {} at t = {} ({}): altitude {}{speed}",
            p.phase,
            shown(p.time),
            p.rule,
            shown(p.altitude)
        );
    }
    if let Some(l) = s.landing {
        let point = match (l.east, l.north) {
            (Some(e), Some(n)) => format!(" at east {}, north {}", shown(e), shown(n)),
            _ => String::new(),
        };
        let _ = writeln!(
            out,
            "  landing: t = {}{point}, vertical speed {}",
            shown(l.time),
            shown(l.vertical_speed)
        );
    }
    if let Some(log) = &s.log {
        log_text(log, out);
    }
}

fn log_text(log: &LogComparison, out: &mut String) {
    let _ = write!(
        out,
        "  log {}: measured apogee {} at t = {}",
        log.file,
        shown(log.apogee.value),
        shown(log.apogee.time)
    );
    if let (Some(d), Some(r)) = (log.apogee_difference, log.apogee_relative) {
        let _ = write!(out, "; ours − measured {} ({:.2} %)", shown(d), 100.0 * r);
    }
    if let Some(rms) = log.altitude_rms {
        let _ = write!(out, "; altitude RMS difference {}", shown(rms));
    }
    out.push('\n');
}
