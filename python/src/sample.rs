//! The distributions a member's parameters are drawn from (`varmass.uniform`,
//! `varmass.normal`), each drawn from the member's own stream in the order given.

use rand_distr::{Distribution as _, Normal, Uniform};
use varmass::core::ensemble::MemberRng;

/// One parameter's distribution, checked when built.
#[derive(Clone, Copy, Debug)]
pub enum Distribution {
    /// Uniform on [low, high).
    Uniform(Uniform<f64>),
    /// Normal with this mean and standard deviation.
    Normal(Normal<f64>),
}

impl Distribution {
    /// `kind` is "uniform" (a, b: low, high) or "normal" (a, b: mean, standard deviation);
    /// an unusable one is a message naming the parameter.
    pub fn new(name: &str, kind: &str, a: f64, b: f64) -> Result<Self, String> {
        let bad = |why: &str| format!("sample[{name:?}]: {kind}({a}, {b}) {why}");
        if !a.is_finite() || !b.is_finite() {
            return Err(bad("needs finite numbers"));
        }
        match kind {
            "uniform" if a < b => Uniform::new(a, b)
                .map(Distribution::Uniform)
                .map_err(|e| bad(&e.to_string())),
            "uniform" => Err(bad("needs low < high")),
            "normal" if b >= 0.0 => Normal::new(a, b)
                .map(Distribution::Normal)
                .map_err(|e| bad(&e.to_string())),
            "normal" => Err(bad("needs a standard deviation ≥ 0")),
            _ => Err(format!(
                "sample[{name:?}]: unknown distribution `{kind}` (uniform or normal)"
            )),
        }
    }

    /// One draw.
    pub fn draw(&self, rng: &mut MemberRng) -> f64 {
        match self {
            Distribution::Uniform(d) => d.sample(rng),
            Distribution::Normal(d) => d.sample(rng),
        }
    }
}
