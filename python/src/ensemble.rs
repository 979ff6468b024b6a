//! Ensembles of runs with the tool's semantics on the core's ensemble: member `i` draws its
//! sampled parameters from `member_rng(seed, i)` in the order given, runs the model with
//! them (and the fixed ones) as `varmass run` would, and reports the observables at the
//! end of its run (`t` or any recordable quantity). Results, merges and statistics are the
//! core's: bit-identical for any thread count and any split into shards.

use std::collections::BTreeSet;
use std::ops::Range;
use std::sync::Mutex;

use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use varmass::core::ensemble::rayon::ThreadPoolBuilder;
use varmass::core::ensemble::{member_rng, Ensemble, Partial, Shard, SummaryConfig};
use varmass_cli::args::RunArgs;
use varmass_cli::error::CliError;
use varmass_cli::model::LoadedModel;
use varmass_cli::run::{column_name, Compiled};

use crate::errors::{to_py, value_error};
use crate::model::NativeModel;
use crate::run::{bytes, run_args, Options};
use crate::sample::Distribution;

/// The most observables an ensemble reports (the core's ensemble has their count as a
/// compile-time constant: one monomorphization per count).
const MAX_OBSERVABLES: usize = 8;

/// A partial result: sampled parameters per failure, the tool's message as the error.
type NativeResult = Partial<Vec<f64>, String>;

/// Where an observable's value comes from at the end of a member's run.
#[derive(Clone, Copy, Debug)]
enum Source {
    /// The end time.
    Time,
    /// A recorded column.
    Column(usize),
}

/// Everything a member needs, shared by the threads.
struct Spec {
    seed: u64,
    /// The derived model, copied into a new [`Compiled`] when every one is in use.
    model: LoadedModel,
    /// The compiled models not in use: a member takes one, runs, gives it back, so the
    /// ensemble compiles the model once per thread, not once per member (a reused model
    /// gives the bits of a fresh one: `cli/tests/compiled.rs`).
    idle: Mutex<Vec<Compiled>>,
    fixed: Vec<(String, f64)>,
    sampled: Vec<(String, Distribution)>,
    args: RunArgs,
    names: Vec<&'static str>,
    sources: Vec<Source>,
}

impl Spec {
    /// Member parameters in the order given (sampled ones by their draw).
    fn sample(&self, rng: &mut varmass::core::ensemble::MemberRng) -> Vec<f64> {
        self.sampled.iter().map(|(_, d)| d.draw(rng)).collect()
    }

    /// One member's run: its observables, or the tool's message.
    fn fly(&self, drawn: &[f64]) -> Result<Vec<f64>, CliError> {
        let fixed = self.fixed.iter().map(|(n, v)| (n.as_str(), *v));
        let sampled = self.sampled.iter().map(|(n, _)| n.as_str());
        let parameters: Vec<(&str, f64)> =
            fixed.chain(sampled.zip(drawn.iter().copied())).collect();
        let mut compiled = self.take();
        let done = compiled.run_to_end(&parameters, &self.args);
        self.idle().push(compiled);
        let (time, row) = done?;
        Ok(self
            .sources
            .iter()
            .map(|s| match s {
                Source::Time => time,
                Source::Column(k) => row[*k],
            })
            .collect())
    }

    /// An idle compiled model, or a new one.
    fn take(&self) -> Compiled {
        let idle = self.idle().pop();
        idle.unwrap_or_else(|| Compiled::new(self.model.clone()))
    }

    /// The idle compiled models (a poisoned lock is only a panic's leftover).
    fn idle(&self) -> std::sync::MutexGuard<'_, Vec<Compiled>> {
        self.idle.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Runs `members` on `threads` threads (all of rayon's global pool if `None`).
    fn run(&self, members: Range<u64>, threads: Option<usize>) -> Result<NativeResult, String> {
        macro_rules! by_count {
            ($($k:literal),*) => {
                match self.names.len() {
                    $($k => self.run_k::<$k>(members, threads),)*
                    n => Err(format!("{n} observables: at most {MAX_OBSERVABLES}")),
                }
            };
        }
        by_count!(1, 2, 3, 4, 5, 6, 7, 8)
    }

    fn run_k<const K: usize>(
        &self,
        members: Range<u64>,
        threads: Option<usize>,
    ) -> Result<NativeResult, String> {
        let names: [&'static str; K] = std::array::from_fn(|k| self.names[k]);
        let member = |drawn: &Vec<f64>| -> Result<[f64; K], String> {
            let values = self.fly(drawn).map_err(|e| e.to_string())?;
            Ok(std::array::from_fn(|k| values[k]))
        };
        let ensemble = Ensemble::new(self.seed, names, |rng| self.sample(rng), member);
        match threads {
            None => Ok(ensemble.run(members)),
            Some(1) => Ok(ensemble.serial().run(members)),
            Some(n) => {
                let pool = ThreadPoolBuilder::new()
                    .num_threads(n)
                    .build()
                    .map_err(|e| e.to_string())?;
                Ok(pool.install(|| ensemble.run(members)))
            }
        }
    }
}

/// A `&'static str` for `name`, each distinct name leaked once (the core's ensemble names
/// its observables with static strings; a session makes few distinct names).
fn intern(name: &str) -> &'static str {
    static NAMES: Mutex<BTreeSet<&'static str>> = Mutex::new(BTreeSet::new());
    let mut names = NAMES.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(known) = names.get(name) {
        return known;
    }
    let leaked: &'static str = Box::leak(name.to_string().into_boxed_str());
    names.insert(leaked);
    leaked
}

/// The native half of `varmass.Ensemble`.
#[pyclass(module = "varmass._native", frozen)]
pub struct NativeEnsemble {
    spec: Spec,
}

#[pymethods]
impl NativeEnsemble {
    /// Checks the specification: options, distributions, observables, and that member 0's
    /// input is accepted (an unknown name or a missing value is a `ValueError` now, not a
    /// failure of every member later; member 0's *run* may still fail).
    #[new]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        seed: u64,
        model: &NativeModel,
        file: String,
        with: Vec<String>,
        set: Vec<(String, f64)>,
        sample: Vec<(String, String, f64, f64)>,
        options: Options,
        observables: Vec<String>,
    ) -> PyResult<Self> {
        if observables.is_empty() || observables.len() > MAX_OBSERVABLES {
            return Err(value_error(format!(
                "observables: give 1 to {MAX_OBSERVABLES} names, not {}",
                observables.len()
            )));
        }
        let sampled = sample
            .iter()
            .map(|(name, kind, a, b)| {
                Distribution::new(name, kind, *a, *b).map(|d| (name.clone(), d))
            })
            .collect::<Result<Vec<_>, _>>()
            .map_err(value_error)?;
        let mut args = run_args(&file, &with, options).map_err(|e| to_py(py, e))?;
        let recorded = observables.iter().filter(|o| *o != "t").cloned();
        args.record.extend(recorded);
        // Keep only the end point: one output interval, the whole run (the same steps).
        if let Some(until) = args.until.filter(|&until| until > args.from) {
            args.every = Some(until - args.from);
        }
        let mut next = 0;
        let sources = observables
            .iter()
            .map(|o| match o.as_str() {
                "t" => Source::Time,
                _ => {
                    next += 1;
                    Source::Column(next - 1)
                }
            })
            .collect();
        let spec = Spec {
            seed,
            model: model.loaded(),
            idle: Mutex::new(Vec::new()),
            fixed: set,
            sampled,
            args,
            names: observables.iter().map(|o| intern(column_name(o))).collect(),
            sources,
        };
        let drawn = spec.sample(&mut member_rng(seed, 0));
        match py.detach(|| spec.fly(&drawn)) {
            Err(e @ (CliError::Input(_) | CliError::Model { .. } | CliError::Read { .. })) => {
                Err(to_py(py, e))
            }
            _ => Ok(Self { spec }),
        }
    }

    /// Runs members `start..end` on `threads` threads (all cores if `None`).
    #[pyo3(signature = (start, end, threads=None))]
    fn run(
        &self,
        py: Python<'_>,
        start: u64,
        end: u64,
        threads: Option<usize>,
    ) -> PyResult<NativePartial> {
        if start > end {
            return Err(value_error(format!(
                "members {start}..{end}: start after end"
            )));
        }
        if threads == Some(0) {
            return Err(value_error("threads: at least 1"));
        }
        let partial = py
            .detach(|| self.spec.run(start..end, threads))
            .map_err(value_error)?;
        Ok(NativePartial { partial })
    }

    /// Member `index` alone: its sampled parameters and its observables (a failed run is
    /// its exception).
    fn member(&self, py: Python<'_>, index: u64) -> PyResult<(Vec<f64>, Vec<f64>)> {
        let drawn = self.spec.sample(&mut member_rng(self.spec.seed, index));
        let values = py
            .detach(|| self.spec.fly(&drawn))
            .map_err(|e| to_py(py, e))?;
        Ok((drawn, values))
    }

    /// The observables' column names, as `--record` names them (`MU` for `"MU=mu"`).
    #[getter]
    fn columns(&self) -> Vec<&'static str> {
        self.spec.names.clone()
    }

    /// The members of shard `index` of `count` in an ensemble of `total`.
    #[staticmethod]
    fn shard_members(index: u64, count: u64, total: u64) -> PyResult<(u64, u64)> {
        let shard = Shard::new(index, count).map_err(|e| value_error(format!("shard: {e}")))?;
        let members = shard.members(total);
        Ok((members.start, members.end))
    }
}

/// The native half of `varmass.EnsembleResult`: the core's `Partial`.
#[pyclass(module = "varmass._native", frozen)]
pub struct NativePartial {
    partial: NativeResult,
}

#[pymethods]
impl NativePartial {
    /// The partial of the members of both (exact; refuses overlaps and another seed).
    fn merge(&self, other: &NativePartial) -> PyResult<NativePartial> {
        let merged = self
            .partial
            .clone()
            .merge(other.partial.clone())
            .map_err(|e| value_error(format!("merge: {e}")))?;
        Ok(NativePartial { partial: merged })
    }

    /// JSON that keeps every value's bits.
    fn to_json(&self, py: Python<'_>) -> PyResult<String> {
        py.detach(|| serde_json::to_string(&self.partial))
            .map_err(|e| value_error(e.to_string()))
    }

    /// Reads [`NativePartial::to_json`]'s text back, checked.
    #[staticmethod]
    fn from_json(py: Python<'_>, text: &str) -> PyResult<NativePartial> {
        let partial = py
            .detach(|| serde_json::from_str(text))
            .map_err(|e| value_error(format!("not a partial ensemble result: {e}")))?;
        Ok(NativePartial { partial })
    }

    #[getter]
    fn seed(&self) -> u64 {
        self.partial.seed()
    }

    #[getter]
    fn observables(&self) -> Vec<String> {
        self.partial.observables().to_vec()
    }

    #[getter]
    fn member_count(&self) -> u64 {
        self.partial.member_count()
    }

    #[getter]
    fn covered(&self) -> Vec<(u64, u64)> {
        self.partial
            .covered()
            .iter()
            .map(|r| (r.start, r.end))
            .collect()
    }

    /// Completed members' indices as little-endian `u64` bytes.
    fn completed<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        let raw: Vec<u8> = self
            .partial
            .completed()
            .iter()
            .flat_map(|i| i.to_le_bytes())
            .collect();
        PyBytes::new(py, &raw)
    }

    /// Observable `k` of the completed members, in index order, as little-endian `f64` bytes.
    fn values<'py>(&self, py: Python<'py>, k: usize) -> PyResult<Bound<'py, PyBytes>> {
        let values = self
            .partial
            .values(k)
            .ok_or_else(|| value_error(format!("no observable {k}")))?;
        Ok(bytes(py, values.iter().copied()))
    }

    /// Every failure: (index, sampled parameters, message).
    fn failures(&self) -> Vec<(u64, Vec<f64>, String)> {
        self.partial
            .failures()
            .iter()
            .map(|f| (f.index, f.params.clone(), f.error.to_string()))
            .collect()
    }

    /// The core's statistics of observable `name`.
    fn summary<'py>(
        &self,
        py: Python<'py>,
        name: &str,
        quantiles: Vec<f64>,
        confidence: f64,
    ) -> PyResult<Bound<'py, PyDict>> {
        let config = SummaryConfig {
            quantiles,
            confidence,
        };
        let s = self
            .partial
            .summary(name, &config)
            .map_err(|e| value_error(format!("summary of `{name}`: {e}")))?;
        let out = PyDict::new(py);
        out.set_item("count", s.count)?;
        out.set_item("mean", s.mean)?;
        out.set_item("standard_deviation", s.standard_deviation)?;
        out.set_item("min", s.min)?;
        out.set_item("max", s.max)?;
        out.set_item("quantiles", s.quantiles)?;
        out.set_item("confidence", s.confidence)?;
        out.set_item("confidence_interval", s.confidence_interval)?;
        Ok(out)
    }

    fn __eq__(&self, other: &NativePartial) -> bool {
        self.partial == other.partial
    }
}
