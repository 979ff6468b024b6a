//! A two-column CSV table with a header naming its columns: `argument, value`, then one
//! point a line. Blank lines and lines starting with `#` are skipped, so a data file can say
//! where it comes from.

use alloc::string::{String, ToString};

use crate::error::{ReadError, ReadErrorKind};
use crate::interpolant::Interpolation;
use crate::points::Points;
use crate::text::{comma_fields, error_at, number, read_table, PointsBuilder};

/// A table read from CSV: the names its header gives the columns, and the points.
#[derive(Clone, Debug, PartialEq)]
pub struct CsvTable {
    /// The header's name of the first column (the argument), e.g. `altitude_m`.
    pub argument: String,
    /// The header's name of the second column (the value), e.g. `density_kg_m3`.
    pub value: String,
    /// The points, arguments strictly increasing.
    pub points: Points,
}

const HEADER: &str = "argument, value";
const PAIR: &str = "2 fields (argument, value)";

impl CsvTable {
    /// Reads `text` (for a linear table: [`CsvTable::parse_for`]).
    pub fn parse(text: &str) -> Result<Self, ReadError> {
        Self::parse_for(text, Interpolation::Linear)
    }

    /// Reads `text` for a table interpolated by `interpolation`: data whose interpolant
    /// overflows are refused at the line that ends the piece
    /// ([`ReadErrorKind::InterpolantNotFinite`]).
    pub fn parse_for(text: &str, interpolation: Interpolation) -> Result<Self, ReadError> {
        let ([argument, value], points) = read_table(
            text,
            without_comment,
            interpolation,
            HEADER,
            column_names,
            point_row,
        )?;
        Ok(Self {
            argument,
            value,
            points,
        })
    }
}

/// The names the header line gives the columns; a header of two numbers is data.
fn column_names(line: usize, text: &str) -> Result<[String; 2], ReadError> {
    let names = two_fields(line, text)?;
    if names.iter().all(|(_, name)| name.parse::<f64>().is_ok()) {
        return Err(error_at(line, 1, ReadErrorKind::HeaderIsData));
    }
    Ok(names.map(|(_, name)| name.to_string()))
}

/// Puts in the points a data line: `argument, value`.
fn point_row(points: &mut PointsBuilder, line: usize, text: &str) -> Result<(), ReadError> {
    let [argument, value] = two_fields(line, text)?;
    let (x, y) = (number(line, argument)?, number(line, value)?);
    points.push(line, argument.0, x, y)
}

/// The line, or nothing if it is a `#` comment.
fn without_comment(line: &str) -> &str {
    if line.trim_start().starts_with('#') {
        ""
    } else {
        line
    }
}

/// The line's two comma-separated fields.
fn two_fields(line: usize, text: &str) -> Result<[(usize, &str); 2], ReadError> {
    match comma_fields(text)[..] {
        [first, second] => Ok([first, second]),
        ref fields => Err(error_at(
            line,
            1,
            ReadErrorKind::FieldCount {
                expected: PAIR,
                found: fields.len(),
            },
        )),
    }
}
