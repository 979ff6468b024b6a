//! What the two readers share: fields with their columns, numbers with their positions, and
//! the growing list of points that checks its knots increase as each line is read.

use alloc::string::ToString;
use alloc::vec::Vec;

use crate::error::{ReadError, ReadErrorKind};
use crate::interpolant::Interpolation;
use crate::points::{InvalidPoints, Points};

/// A field of a line: its 1-based column (in characters) and its text.
pub(crate) type Field<'a> = (usize, &'a str);

/// The fields of `line` split at whitespace, with their columns.
pub(crate) fn whitespace_fields(line: &str) -> Vec<Field<'_>> {
    let mut fields = Vec::new();
    let mut start = None;
    for (column, (offset, c)) in line.char_indices().enumerate() {
        match (c.is_whitespace(), start) {
            (false, None) => start = Some((column, offset)),
            (true, Some((first, from))) => {
                fields.push((first + 1, &line[from..offset]));
                start = None;
            }
            _ => {}
        }
    }
    if let Some((first, from)) = start {
        fields.push((first + 1, &line[from..]));
    }
    fields
}

/// The fields of `line` split at commas and trimmed, with the columns where their text starts.
pub(crate) fn comma_fields(line: &str) -> Vec<Field<'_>> {
    let mut fields = Vec::new();
    let mut column = 1;
    for part in line.split(',') {
        let leading = part.len() - part.trim_start().len();
        fields.push((column + part[..leading].chars().count(), part.trim()));
        column += part.chars().count() + 1;
    }
    fields
}

/// Reads a table file: its header, the first line that holds data (read by `header`; if
/// there is none, [`ReadErrorKind::MissingHeader`] names `expected`), then its points, each
/// data line put in by `row` (which checks it, and may put in more than one point). Lines are
/// numbered from 1; `data` gives a line's data (the line without its comment), and blank
/// ones are skipped. Points whose interpolant by `interpolation` overflows are refused at
/// the line that ends the piece ([`ReadErrorKind::InterpolantNotFinite`]).
pub(crate) fn read_table<'t, H>(
    text: &'t str,
    data: fn(&str) -> &str,
    interpolation: Interpolation,
    expected: &'static str,
    header: impl FnOnce(usize, &'t str) -> Result<H, ReadError>,
    row: impl FnMut(&mut PointsBuilder, usize, &'t str) -> Result<(), ReadError>,
) -> Result<(H, Points), ReadError> {
    let mut lines = text
        .lines()
        .enumerate()
        .map(move |(index, line)| (index + 1, data(line)))
        .filter(|(_, line)| !line.trim().is_empty());
    let missing = ReadErrorKind::MissingHeader { expected };
    let (header_line, header_text) =
        lines
            .next()
            .ok_or(error_at(text.lines().count().max(1), 1, missing))?;
    let header = header(header_line, header_text)?;
    let points = PointsBuilder::read(header_line, lines, interpolation, row)?;
    Ok((header, points))
}

/// A line's number (from 1) and its text.
pub(crate) type Line<'t> = (usize, &'t str);

/// An error at `line`, `column`.
pub(crate) fn error_at(line: usize, column: usize, kind: ReadErrorKind) -> ReadError {
    ReadError { line, column, kind }
}

/// The field read as a finite number.
pub(crate) fn number(line: usize, (column, text): Field<'_>) -> Result<f64, ReadError> {
    let value: f64 = text.parse().map_err(|_| {
        error_at(
            line,
            column,
            ReadErrorKind::NotANumber {
                field: text.to_string(),
            },
        )
    })?;
    if value.is_finite() {
        Ok(value)
    } else {
        Err(error_at(
            line,
            column,
            ReadErrorKind::NotFinite {
                field: text.to_string(),
            },
        ))
    }
}

/// Points read line by line: each knot is checked against the previous one where it is read,
/// so the error names its line.
#[derive(Default)]
pub(crate) struct PointsBuilder {
    arguments: Vec<f64>,
    values: Vec<f64>,
    /// The line each point was read on.
    lines: Vec<usize>,
}

impl PointsBuilder {
    /// Appends (x, y), read at `line` with x at `column`.
    pub(crate) fn push(
        &mut self,
        line: usize,
        column: usize,
        x: f64,
        y: f64,
    ) -> Result<(), ReadError> {
        if let Some(&previous) = self.arguments.last() {
            if x <= previous {
                let kind = ReadErrorKind::NotIncreasing { previous, knot: x };
                return Err(error_at(line, column, kind));
            }
        }
        self.arguments.push(x);
        self.values.push(y);
        self.lines.push(line);
        Ok(())
    }

    /// Number of points so far.
    pub(crate) fn len(&self) -> usize {
        self.arguments.len()
    }

    /// The points of the data `lines` after the header at `header_line`, each line put in
    /// by `row` (which checks it, and may put in more than one point), checked to give a
    /// finite interpolant by `interpolation` ([`Interpolation::checked`]).
    fn read<'t>(
        header_line: usize,
        lines: impl Iterator<Item = Line<'t>>,
        interpolation: Interpolation,
        mut row: impl FnMut(&mut Self, usize, &'t str) -> Result<(), ReadError>,
    ) -> Result<Points, ReadError> {
        let mut points = Self::default();
        let mut last_line = header_line;
        for (line, content) in lines {
            row(&mut points, line, content)?;
            last_line = line;
        }
        let lines = points.lines.clone();
        let points = points.finish(last_line)?;
        match interpolation.checked(&points) {
            Err(InvalidPoints::InterpolantNotFinite { index }) => {
                let (x, y) = (points.arguments(), points.values());
                let kind = ReadErrorKind::InterpolantNotFinite {
                    interpolation: interpolation.name(),
                    from_line: lines[index - 1],
                    from: (x[index - 1], y[index - 1]),
                    to: (x[index], y[index]),
                };
                Err(error_at(lines[index], 1, kind))
            }
            // `checked` refuses nothing else: the points were checked by `finish`.
            _ => Ok(points),
        }
    }

    /// The points; `last_line` is where a too-short file is reported.
    fn finish(self, last_line: usize) -> Result<Points, ReadError> {
        let found = self.arguments.len();
        let lines = self.lines;
        // Every check of `Points::new` but the count and the slopes was made as the lines
        // were read.
        let (arguments, values) = (self.arguments.clone(), self.values.clone());
        Points::new(self.arguments, self.values).map_err(|invalid| match invalid {
            InvalidPoints::SlopeNotFinite { index } => {
                let kind = ReadErrorKind::SlopeNotFinite {
                    from: (arguments[index - 1], values[index - 1]),
                    to: (arguments[index], values[index]),
                };
                error_at(lines[index], 1, kind)
            }
            InvalidPoints::SpacingNotFinite { from, index } => {
                let kind = ReadErrorKind::SpacingNotFinite {
                    from: (arguments[from], values[from]),
                    to: (arguments[index], values[index]),
                };
                error_at(lines[index], 1, kind)
            }
            _ => error_at(last_line, 1, ReadErrorKind::TooFewPoints { found }),
        })
    }
}
