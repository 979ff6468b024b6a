//! A flight log as `varmass fit` reads it: a CSV file with a header, a time column and the
//! measured columns, numbers in any form Rust reads; an empty field (a log's gap) is no
//! datum. RocketPy's published logs are such files (`Time (s),Altitude (m)`).

use std::path::Path;

use crate::error::CliError;
use crate::run::output::csv_fields as fields;

/// One measured quantity: the model's name for it and its (time, value) pairs.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// The model's quantity (`y`, `y'`, `m`, `H`).
    pub quantity: String,
    /// The times, increasing.
    pub times: Vec<f64>,
    /// The measured values.
    pub values: Vec<f64>,
    /// The standard deviation of each value (weights 1/σ²); `None`: unknown, estimated
    /// from the residuals.
    pub sigma: Option<f64>,
}

/// Keeps the data at times from `from` to `until` (the run's span: the ascent of a flight
/// log, say); returns how many were left out.
pub fn window(series: &mut [Series], from: f64, until: Option<f64>) -> usize {
    let inside = |t: f64| t >= from && until.is_none_or(|u| t <= u);
    let mut left_out = 0;
    for s in series {
        let kept: Vec<(f64, f64)> = (s.times.iter().zip(&s.values))
            .filter(|(t, _)| inside(**t))
            .map(|(t, x)| (*t, *x))
            .collect();
        left_out += s.times.len() - kept.len();
        (s.times, s.values) = kept.into_iter().unzip();
    }
    left_out
}

/// Reads the series `columns` ((quantity, CSV column) pairs) from the CSV text `text` (named
/// `path` in messages), with the times in `time` (default: the first column).
pub fn read(
    text: &str,
    path: &Path,
    time: Option<&str>,
    columns: &[(String, String)],
) -> Result<Vec<Series>, CliError> {
    let at =
        |line: usize, what: String| CliError::Input(format!("{}:{line}: {what}", path.display()));
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty());
    let (_, header) = lines
        .next()
        .ok_or_else(|| at(1, "the file is empty".to_string()))?;
    let header = fields(header);
    let index = |name: &str| {
        header.iter().position(|h| h == name).ok_or_else(|| {
            at(
                1,
                format!("no column `{name}`; the columns are {}", header.join(", ")),
            )
        })
    };
    let t = match time {
        Some(name) => index(name)?,
        None => 0,
    };
    let wanted: Vec<usize> = columns
        .iter()
        .map(|(_, c)| index(c))
        .collect::<Result<_, _>>()?;
    let mut series: Vec<Series> = columns
        .iter()
        .map(|(quantity, _)| Series {
            quantity: quantity.clone(),
            times: Vec::new(),
            values: Vec::new(),
            sigma: None,
        })
        .collect();
    for (number, line) in lines {
        let row = fields(line);
        let value = |k: usize| -> Result<Option<f64>, CliError> {
            let text = row.get(k).map(String::as_str).unwrap_or("");
            if text.is_empty() {
                return Ok(None);
            }
            match text.parse::<f64>() {
                Ok(x) if x.is_finite() => Ok(Some(x)),
                _ => Err(at(number + 1, format!("`{text}` is not a finite number"))),
            }
        };
        let Some(time) = value(t)? else { continue };
        for (s, k) in series.iter_mut().zip(&wanted) {
            if let Some(x) = value(*k)? {
                if s.times.last().is_some_and(|last| *last >= time) {
                    return Err(at(number + 1, format!("the time {time} does not increase")));
                }
                s.times.push(time);
                s.values.push(x);
            }
        }
    }
    if let Some(empty) = series.iter().find(|s| s.times.is_empty()) {
        return Err(at(1, format!("no datum for `{}`", empty.quantity)));
    }
    Ok(series)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_log_with_quotes_gaps_and_a_time_column_is_read() {
        let text = "\"Time (s)\",\"Altitude, AGL (m)\",Speed\n0,0,1\n0.5,,2\n1,3.5,\n";
        let columns = [
            ("y".to_string(), "Altitude, AGL (m)".to_string()),
            ("y'".to_string(), "Speed".to_string()),
        ];
        let series = read(text, Path::new("log.csv"), Some("Time (s)"), &columns).unwrap();
        assert_eq!(series[0].times, [0.0, 1.0]);
        assert_eq!(series[0].values, [0.0, 3.5]);
        assert_eq!(series[1].times, [0.0, 0.5]);
        let bad = read("t,y\n0,x\n", Path::new("log.csv"), None, &columns[..1]);
        assert!(bad.is_err());
        let missing = read(
            "t,y\n0,1\n",
            Path::new("log.csv"),
            None,
            &[("y".into(), "z".into())],
        );
        assert!(matches!(missing, Err(CliError::Input(m)) if m.contains("no column `z`")));
    }
}
