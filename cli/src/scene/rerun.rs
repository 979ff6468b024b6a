//! A scene file read once and run again with other values: the evaluations of `varmass fit
//! SCENE.toml` (docs/sensitivities.md#fitting-a-scene). Each run parses the text kept, puts
//! the values in the scene's own `[set]` and `[init]` (so every phase, check and message
//! sees them as if written there) and runs it as `varmass run` does, the models derived
//! once and kept.

use std::path::{Path, PathBuf};

use toml::Spanned;

use super::file::{self, Read};
use super::{run_read, Models, Request, SceneRun};
use crate::args::ModelArgs;
use crate::error::CliError;

/// A scene kept for running again.
pub struct Rerun {
    path: PathBuf,
    source: String,
    models: Models,
    runs: usize,
}

impl Rerun {
    /// Reads the scene file at `path` (a TOML or schema mistake is the error here).
    pub fn new(path: &Path) -> Result<Self, CliError> {
        let read = file::read(path)?;
        Ok(Self {
            path: path.to_path_buf(),
            source: read.source,
            models: Models::default(),
            runs: 0,
        })
    }

    /// How many runs were made.
    pub fn runs(&self) -> usize {
        self.runs
    }

    /// The scene file's path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The scene as written.
    fn read(&self) -> Result<Read, CliError> {
        file::parse(self.source.clone(), &self.path)
    }

    /// The scene's span: its `from` and `until`.
    pub fn span(&self) -> Result<(f64, f64), CliError> {
        let read = self.read()?;
        Ok((read.scene.from, read.scene.until))
    }

    /// The value the scene starts `name` with: a parameter's from its `[set]` or else the
    /// first phase's model's default, an initial value's (`init:x'`) from its `[init]`;
    /// `None` where it gives none.
    pub fn start_value(&mut self, name: &str) -> Result<Option<f64>, CliError> {
        let read = self.read()?;
        if let Some(entry) = name.strip_prefix("init:") {
            let entry = entry.trim();
            let given = read.scene.init.iter().find(|(n, _)| n.get_ref() == entry);
            return Ok(given.map(|(_, v)| *v));
        }
        if let Some((_, v)) = read.scene.set.iter().find(|(n, _)| n.get_ref() == name) {
            return Ok(Some(*v));
        }
        let base = self
            .path
            .parent()
            .map(Path::to_path_buf)
            .unwrap_or_default();
        let model = ModelArgs {
            file: base.join(read.scene.model.get_ref()),
            with: read
                .scene
                .with
                .iter()
                .map(|t| t.get_ref().clone())
                .collect(),
        };
        // Derived as the fit's runs will derive it, with the Jacobians.
        self.models.set_sensitivities(true);
        let defaults = self.models.load(&model)?.with_defaults(&[]);
        Ok(defaults
            .into_iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v))
    }

    /// Runs the scene with `values` (parameters, and initial values `init:x`) in place of
    /// its own, recording `record` only (the scene's own record may hold expressions, which
    /// have no derivative columns), with `request`'s columns and landing times.
    pub fn run(
        &mut self,
        values: &[(String, f64)],
        record: &[&str],
        request: &Request<'_>,
    ) -> Result<SceneRun, CliError> {
        self.run_to(values, record, request, None)
    }

    /// [`Self::run`] with `stop`, a condition (`stop_when`'s syntax) and a time, in place of
    /// the scene's own `stop_when` and `until` (a fit's prediction).
    pub fn run_to(
        &mut self,
        values: &[(String, f64)],
        record: &[&str],
        request: &Request<'_>,
        stop: Option<(&str, f64)>,
    ) -> Result<SceneRun, CliError> {
        let mut read = self.read()?;
        let scene = &mut read.scene;
        if let Some((condition, until)) = stop {
            scene.stop_when = Some(unplaced(condition));
            scene.until = until;
        }
        for (name, value) in values {
            // A key already written keeps its place (`Spanned` keys compare by name).
            match name.strip_prefix("init:") {
                Some(entry) => scene.init.insert(unplaced(entry.trim()), *value),
                None => scene.set.insert(unplaced(name), *value),
            };
        }
        scene.record = record.iter().map(|q| unplaced(q)).collect();
        // A run at least as long as the data (a fitted offset may move them past `until`).
        if let Some(last) = request.at.iter().copied().reduce(f64::max) {
            scene.until = scene.until.max(last);
        }
        self.runs += 1;
        run_read(&read, &self.path, &mut self.models, request)
    }
}

/// `text` as a key the file did not hold (it has no place in it).
fn unplaced(text: &str) -> Spanned<String> {
    Spanned::new(0..0, text.to_string())
}
