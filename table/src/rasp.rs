//! The RASP engine format (`.eng`), which every rocketry tool reads: a header line
//! `name diameter_mm length_mm delays propellant_kg total_kg maker`, then `time thrust`
//! pairs (s, N), `;` starting a comment. The file lists the points after ignition; the curve
//! starts from (0 s, 0 N), as RockSim, OpenRocket and RocketPy read it.

use alloc::string::{String, ToString};

use crate::error::{ReadError, ReadErrorKind};
use crate::interpolant::Interpolation;
use crate::points::Points;
use crate::text::{error_at, number, read_table, whitespace_fields, PointsBuilder};

/// One motor of a RASP `.eng` file: its header and its thrust curve.
#[derive(Clone, Debug, PartialEq)]
pub struct Motor {
    /// The motor's designation, e.g. `M1670-BS`.
    pub name: String,
    /// Case diameter, mm.
    pub diameter_mm: f64,
    /// Case length, mm.
    pub length_mm: f64,
    /// The ejection delays available, as written (`6-10-14-18`, `0`, `P` for plugged).
    pub delays: String,
    /// Propellant mass, kg.
    pub propellant_kg: f64,
    /// Loaded mass (case and propellant), kg.
    pub total_kg: f64,
    /// Maker's abbreviation, e.g. `CTI`.
    pub maker: String,
    /// Thrust (N) against time since ignition (s), from (0, 0) unless the file lists t = 0.
    pub thrust: Points,
}

const HEADER: &str = "name diameter_mm length_mm delays propellant_kg total_kg maker";
const PAIR: &str = "2 fields (time thrust)";

impl Motor {
    /// Reads the first (and only) motor of `text` (for a linear table: [`Motor::parse_for`]).
    pub fn parse(text: &str) -> Result<Self, ReadError> {
        Self::parse_for(text, Interpolation::Linear)
    }

    /// Reads the motor of `text` for a thrust table interpolated by `interpolation`: a curve
    /// whose interpolant overflows is refused at the line that ends the piece
    /// ([`ReadErrorKind::InterpolantNotFinite`](crate::ReadErrorKind)).
    pub fn parse_for(text: &str, interpolation: Interpolation) -> Result<Self, ReadError> {
        let (motor, thrust) = read_table(
            text,
            without_comment,
            interpolation,
            HEADER,
            parse_header,
            thrust_row,
        )?;
        Ok(motor(thrust))
    }

    /// Total impulse, N·s: the integral of the thrust curve by exact trapezoids (the
    /// piecewise-linear curve the file describes).
    pub fn total_impulse(&self) -> f64 {
        self.thrust.trapezoid_integral()
    }

    /// Burn time, s: the last time of the curve.
    pub fn burn_time(&self) -> f64 {
        let times = self.thrust.arguments();
        times[times.len() - 1]
    }

    /// The effective exhaust speed u_e = total impulse / propellant mass, m/s, with which the
    /// rocketry tools make the mass follow the thrust: ṁ = −F/u_e.
    pub fn exhaust_speed(&self) -> f64 {
        self.total_impulse() / self.propellant_kg
    }
}

/// Puts in the thrust curve a data line of a RASP file: `time thrust`, both ≥ 0; the
/// curve starts from ignition at zero thrust unless the file says otherwise. A line of seven
/// fields or more that starts with a name is a second motor's header.
fn thrust_row(thrust: &mut PointsBuilder, line: usize, content: &str) -> Result<(), ReadError> {
    let fields = whitespace_fields(content);
    if fields.len() != 2 {
        let kind = if fields.len() >= 7 && fields[0].1.parse::<f64>().is_err() {
            ReadErrorKind::SecondMotor
        } else {
            ReadErrorKind::FieldCount {
                expected: PAIR,
                found: fields.len(),
            }
        };
        return Err(error_at(line, 1, kind));
    }
    let time = number(line, fields[0])?;
    let force = number(line, fields[1])?;
    if time < 0.0 {
        return Err(error_at(
            line,
            fields[0].0,
            ReadErrorKind::NegativeTime { time },
        ));
    }
    if force < 0.0 {
        return Err(error_at(
            line,
            fields[1].0,
            ReadErrorKind::NegativeThrust { thrust: force },
        ));
    }
    // The curve starts from ignition at zero thrust unless the file says otherwise.
    if thrust.len() == 0 && time > 0.0 {
        thrust.push(line, fields[0].0, 0.0, 0.0)?;
    }
    thrust.push(line, fields[0].0, time, force)
}

/// The line without its `;` comment.
fn without_comment(line: &str) -> &str {
    line.split(';').next().unwrap_or("")
}

/// What the header line says: the motor, once given its thrust curve.
fn parse_header(line: usize, text: &str) -> Result<impl FnOnce(Points) -> Motor, ReadError> {
    let fields = whitespace_fields(text);
    if fields.len() < 7 {
        let kind = ReadErrorKind::FieldCount {
            expected:
                "7 header fields (name diameter_mm length_mm delays propellant_kg total_kg maker)",
            found: fields.len(),
        };
        return Err(error_at(line, 1, kind));
    }
    let name = fields[0].1.to_string();
    let diameter_mm = number(line, fields[1])?;
    let length_mm = number(line, fields[2])?;
    let delays = fields[3].1.to_string();
    let propellant_kg = number(line, fields[4])?;
    let total_kg = number(line, fields[5])?;
    // A maker written in several words keeps them.
    let words = fields[6..].iter().map(|(_, word)| *word);
    let maker = words.collect::<alloc::vec::Vec<_>>().join(" ");
    Ok(move |thrust| Motor {
        name,
        diameter_mm,
        length_mm,
        delays,
        propellant_kg,
        total_kg,
        maker,
        thrust,
    })
}
