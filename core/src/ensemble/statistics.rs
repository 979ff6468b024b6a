//! Statistics of one observable over the members that completed: count, mean, standard
//! deviation, extremes, quantiles and a confidence interval of the mean.
//!
//! Everything is computed from the values in member-index order, so it depends only on which
//! members were run, never on threads or shards. Sums are compensated (Neumaier), the variance
//! is the two-pass one, and the quantiles are exact: they sort a copy of all the values (8
//! bytes per member, on top of the 8 bytes per member and observable a [`Partial`] keeps).
//!
//! [`Partial`]: super::Partial

use alloc::vec::Vec;

/// What to compute besides count, mean, standard deviation and extremes.
#[derive(Clone, Debug, PartialEq)]
pub struct SummaryConfig {
    /// Probabilities in [0, 1] of the quantiles wanted.
    pub quantiles: Vec<f64>,
    /// Confidence level of the interval of the mean, in (0, 1).
    pub confidence: f64,
}

impl Default for SummaryConfig {
    /// The 5 %, 25 %, 50 %, 75 % and 95 % quantiles and a 95 % interval.
    fn default() -> Self {
        Self {
            quantiles: alloc::vec![0.05, 0.25, 0.5, 0.75, 0.95],
            confidence: 0.95,
        }
    }
}

/// The statistics of one observable.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Summary {
    /// How many members contributed a value.
    pub count: u64,
    /// The sample mean.
    pub mean: f64,
    /// The sample standard deviation (divisor n − 1).
    pub standard_deviation: f64,
    /// The smallest value.
    pub min: f64,
    /// The largest value.
    pub max: f64,
    /// `(probability, quantile)` pairs, in the order asked for. The quantile interpolates
    /// linearly between the order statistics at rank (n − 1)·probability (Hyndman–Fan type 7,
    /// the default of R and NumPy).
    pub quantiles: Vec<(f64, f64)>,
    /// The confidence level of `confidence_interval`.
    pub confidence: f64,
    /// The interval mean ± z·s/√n, with z the standard normal quantile of (1 + level)/2: the
    /// large-sample interval, good once n is in the tens.
    pub confidence_interval: (f64, f64),
}

impl Summary {
    /// Half the width of the confidence interval, z·s/√n.
    pub fn half_width(&self) -> f64 {
        0.5 * (self.confidence_interval.1 - self.confidence_interval.0)
    }
}

/// Why statistics could not be computed.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum StatisticsError {
    /// A standard deviation needs two values.
    #[error("statistics need at least two values, {count} completed")]
    TooFewValues {
        /// The values available.
        count: u64,
    },
    /// A quantile probability outside [0, 1] or a confidence level outside (0, 1).
    #[error("the probability {value} is out of range")]
    InvalidProbability {
        /// The offending probability.
        value: f64,
    },
    /// A value is NaN or infinite (the ensemble never stores one: it reports the member as
    /// failed instead).
    #[error("value {index} is not finite")]
    NonFiniteValue {
        /// Its position in the values.
        index: usize,
    },
    /// No observable has this name or index.
    #[error("no such observable")]
    UnknownObservable,
}

/// The statistics of `values` (finite, in member-index order).
pub fn summarize(values: &[f64], config: &SummaryConfig) -> Result<Summary, StatisticsError> {
    let (mean, standard_deviation) = mean_and_deviation(values)?;
    let half_width = half_width_from(standard_deviation, values.len(), config.confidence)?;
    let mut sorted = values.to_vec();
    sorted.sort_unstable_by(f64::total_cmp);
    let quantiles = config
        .quantiles
        .iter()
        .map(|&probability| Ok((probability, quantile(&sorted, probability)?)))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Summary {
        count: values.len() as u64,
        mean,
        standard_deviation,
        min: sorted[0],
        max: sorted[sorted.len() - 1],
        quantiles,
        confidence: config.confidence,
        confidence_interval: (mean - half_width, mean + half_width),
    })
}

/// Half the width of the `confidence` interval of the mean of `values`, z·s/√n: what the stop
/// rule compares with its target, without sorting.
pub fn half_width(values: &[f64], confidence: f64) -> Result<f64, StatisticsError> {
    let (_, standard_deviation) = mean_and_deviation(values)?;
    half_width_from(standard_deviation, values.len(), confidence)
}

fn half_width_from(deviation: f64, count: usize, confidence: f64) -> Result<f64, StatisticsError> {
    if !(confidence > 0.0 && confidence < 1.0) {
        return Err(StatisticsError::InvalidProbability { value: confidence });
    }
    let z = standard_normal_quantile(0.5 + 0.5 * confidence);
    Ok(z * deviation / (count as f64).sqrt())
}

/// The mean and the sample standard deviation, two-pass with compensated sums.
fn mean_and_deviation(values: &[f64]) -> Result<(f64, f64), StatisticsError> {
    let count = values.len();
    if count < 2 {
        return Err(StatisticsError::TooFewValues {
            count: count as u64,
        });
    }
    if let Some(index) = values.iter().position(|x| !x.is_finite()) {
        return Err(StatisticsError::NonFiniteValue { index });
    }
    let mean = compensated_sum(values.iter().copied()) / count as f64;
    let squares = compensated_sum(values.iter().map(|x| (x - mean) * (x - mean)));
    Ok((mean, (squares / (count - 1) as f64).sqrt()))
}

/// Σ values in the given order, with Neumaier's compensation.
fn compensated_sum(values: impl Iterator<Item = f64>) -> f64 {
    let (mut sum, mut compensation) = (0.0_f64, 0.0_f64);
    for x in values {
        let t = sum + x;
        compensation += if sum.abs() >= x.abs() {
            (sum - t) + x
        } else {
            (x - t) + sum
        };
        sum = t;
    }
    sum + compensation
}

/// The type-7 quantile of sorted, non-empty values.
fn quantile(sorted: &[f64], probability: f64) -> Result<f64, StatisticsError> {
    if !(0.0..=1.0).contains(&probability) {
        return Err(StatisticsError::InvalidProbability { value: probability });
    }
    let rank = (sorted.len() - 1) as f64 * probability;
    let below = rank.floor() as usize;
    let above = (below + 1).min(sorted.len() - 1);
    let fraction = rank - below as f64;
    Ok(sorted[below] + fraction * (sorted[above] - sorted[below]))
}

/// The standard normal quantile Φ⁻¹(p) for p in (0, 1), by Acklam's rational approximation
/// (relative error below 1.2e-9, far below the sampling error of any interval).
pub fn standard_normal_quantile(p: f64) -> f64 {
    const A: [f64; 6] = [
        -3.969_683_028_665_376e1,
        2.209_460_984_245_205e2,
        -2.759_285_104_469_687e2,
        1.383_577_518_672_69e2,
        -3.066_479_806_614_716e1,
        2.506_628_277_459_239,
    ];
    const B: [f64; 5] = [
        -5.447_609_879_822_406e1,
        1.615_858_368_580_409e2,
        -1.556_989_798_598_866e2,
        6.680_131_188_771_972e1,
        -1.328_068_155_288_572e1,
    ];
    const C: [f64; 6] = [
        -7.784_894_002_430_293e-3,
        -3.223_964_580_411_365e-1,
        -2.400_758_277_161_838,
        -2.549_732_539_343_734,
        4.374_664_141_464_968,
        2.938_163_982_698_783,
    ];
    const D: [f64; 4] = [
        7.784_695_709_041_462e-3,
        3.224_671_290_700_398e-1,
        2.445_134_137_142_996,
        3.754_408_661_907_416,
    ];
    let tail = |q: f64| {
        (((((C[0] * q + C[1]) * q + C[2]) * q + C[3]) * q + C[4]) * q + C[5])
            / ((((D[0] * q + D[1]) * q + D[2]) * q + D[3]) * q + 1.0)
    };
    const LOW: f64 = 0.024_25;
    if p < LOW {
        tail((-2.0 * p.ln()).sqrt())
    } else if p > 1.0 - LOW {
        -tail((-2.0 * (1.0 - p).ln()).sqrt())
    } else {
        let q = p - 0.5;
        let r = q * q;
        (((((A[0] * r + A[1]) * r + A[2]) * r + A[3]) * r + A[4]) * r + A[5]) * q
            / (((((B[0] * r + B[1]) * r + B[2]) * r + B[3]) * r + B[4]) * r + 1.0)
    }
}
