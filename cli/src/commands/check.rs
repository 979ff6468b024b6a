//! `varmass check FILE`: derive the model and verify its `check`s.

use varmass::symbolic::expr::Identity;

use crate::args::ModelArgs;
use crate::error::CliError;
use crate::model::load;

/// Derives the model; on success prints how each `check` was decided.
pub fn check(args: &ModelArgs) -> Result<String, CliError> {
    let model = load(args)?;
    for warning in &model.warnings {
        eprintln!("warning: {warning}");
    }
    let file = &args.file;
    let d = &model.derivation;
    let mut out = format!(
        "{}: derives ({} coordinate{}, {} mass{}, parameters: {})\n",
        file.display(),
        d.coordinates.len(),
        plural(d.coordinates.len()),
        d.masses.len(),
        if d.masses.len() == 1 { "" } else { "es" },
        list(&d.used_parameters()),
    );
    for c in &d.checks {
        let text = &c.source;
        let how = match &c.verdict {
            Identity::Proven => "proven".to_string(),
            Identity::Numerical { points } => format!(
                "not proven: the two sides agree at {points} random points, which is evidence, \
                 not proof"
            ),
            other => format!("{other:?}"),
        };
        out.push_str(&format!("{text} ... ok ({how})\n"));
    }
    Ok(out)
}

fn plural(count: usize) -> &'static str {
    if count == 1 {
        ""
    } else {
        "s"
    }
}

fn list(names: &[String]) -> String {
    if names.is_empty() {
        "none".to_string()
    } else {
        names.join(", ")
    }
}
