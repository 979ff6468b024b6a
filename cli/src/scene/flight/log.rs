//! A measured flight log (`[flight] log = { file, time, altitude }`): two columns of a CSV
//! file read by their headers, checked before the first step.

use std::path::{Path, PathBuf};

use super::roles::LogEntry;
use crate::error::CliError;
use crate::run::output::csv_fields as fields;

/// The log's times and altitudes, in the file's order.
#[derive(Clone, Debug)]
pub struct Log {
    /// The file read.
    pub file: PathBuf,
    /// Its time column.
    pub times: Vec<f64>,
    /// Its altitude column.
    pub altitudes: Vec<f64>,
}

/// Reads the log `entry` (its file relative to `base`); `at` locates a byte offset of the
/// scene file. A missing file, a column not in its header, a field that is not a number
/// (blank rows and `#` comments are skipped) or a log of no row is a message at the line.
pub fn read(entry: &LogEntry, base: &Path, at: &dyn Fn(usize) -> String) -> Result<Log, CliError> {
    let file = base.join(entry.file.get_ref());
    let here = at(entry.file.span().start);
    let text = std::fs::read_to_string(&file).map_err(|e| {
        CliError::Input(format!(
            "{here}: `[flight]` log `{}`: cannot read it: {e}",
            file.display()
        ))
    })?;
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
    let Some((_, header)) = lines.next() else {
        return Err(CliError::Input(format!(
            "{here}: `[flight]` log `{}` is empty",
            file.display()
        )));
    };
    let header = fields(header);
    let column = |name: &toml::Spanned<String>| {
        header
            .iter()
            .position(|h| h == name.get_ref().trim())
            .ok_or_else(|| {
                CliError::Input(format!(
                    "{}: `[flight]` log `{}` has no column `{}`; its columns are {}",
                    at(name.span().start),
                    file.display(),
                    name.get_ref(),
                    quoted(&header)
                ))
            })
    };
    let (time, altitude) = (column(&entry.time)?, column(&entry.altitude)?);
    let mut log = Log {
        file: file.clone(),
        times: Vec::new(),
        altitudes: Vec::new(),
    };
    for (line, row) in lines {
        let row = fields(row);
        let number = |k: usize| {
            let field = row.get(k).map(String::as_str).unwrap_or("");
            field
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| {
                    CliError::Input(format!(
                        "{}:{}: `{}` in column `{}` is not a number (the `[flight]` log of {here})",
                        file.display(),
                        line + 1,
                        field,
                        header[k]
                    ))
                })
        };
        log.times.push(number(time)?);
        log.altitudes.push(number(altitude)?);
    }
    if log.times.is_empty() {
        return Err(CliError::Input(format!(
            "{here}: `[flight]` log `{}` has a header but no row",
            file.display()
        )));
    }
    Ok(log)
}

fn quoted(names: &[String]) -> String {
    let quoted: Vec<String> = names.iter().map(|n| format!("`{n}`")).collect();
    quoted.join(", ")
}
