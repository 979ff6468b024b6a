//! A two-column CSV table with a header naming its columns: `argument, value`, then one
//! point a line. Blank lines and lines starting with `#` are skipped, so a data file can say
//! where it comes from.

use alloc::string::{String, ToString};

use crate::error::{ReadError, ReadErrorKind};
use crate::interpolant::Interpolation;
use crate::points::Points;
use crate::text::{comma_fields, error_at, header_and_data, number, PointsBuilder};

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
        let ((header_line, header), lines) = header_and_data(text, without_comment, HEADER)?;
        let names = two_fields(header_line, header)?;
        if names.iter().all(|(_, name)| name.parse::<f64>().is_ok()) {
            return Err(error_at(header_line, 1, ReadErrorKind::HeaderIsData));
        }
        let points = PointsBuilder::read(
            header_line,
            lines,
            interpolation,
            |points, line, content| {
                let [argument, value] = two_fields(line, content)?;
                let (x, y) = (number(line, argument)?, number(line, value)?);
                points.push(line, argument.0, x, y)
            },
        )?;
        Ok(Self {
            argument: names[0].1.to_string(),
            value: names[1].1.to_string(),
            points,
        })
    }
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
