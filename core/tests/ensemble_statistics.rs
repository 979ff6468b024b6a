//! The ensemble's statistics against values computed by hand, and partials read back from
//! JSON that were tampered with.

use varmass_core::ensemble::rand::RngExt;
use varmass_core::ensemble::{
    standard_normal_quantile, summarize, Ensemble, MemberRng, Partial, StatisticsError,
    SummaryConfig,
};
use varmass_core::{StepError, StepErrorKind};

#[test]
fn summary_of_a_small_sample_matches_hand_computation() {
    // 1..=5 in a scrambled order: mean 3, s² = 10/4, type-7 quantiles interpolate ranks.
    let values = [4.0, 1.0, 5.0, 2.0, 3.0];
    let config = SummaryConfig {
        quantiles: vec![0.0, 0.1, 0.25, 0.5, 1.0],
        confidence: 0.95,
    };
    let summary = summarize(&values, &config).unwrap();
    assert_eq!(summary.count, 5);
    assert_eq!(summary.mean, 3.0);
    assert_eq!(summary.standard_deviation, 2.5f64.sqrt());
    assert_eq!((summary.min, summary.max), (1.0, 5.0));
    // Rank (n − 1)p: 0 → 1; 0.4 → 1.4; 1 → 2; 2 → 3; 4 → 5 (1e-15: one rounding of 1.4).
    let expected = [1.0, 1.4, 2.0, 3.0, 5.0];
    for ((_, quantile), want) in summary.quantiles.iter().zip(expected) {
        assert!((quantile - want).abs() < 1e-15, "{quantile} vs {want}");
    }
    // Half-width 1.959963984540054 · √2.5 / √5, to the accuracy of the normal quantile
    // (z(0.975) is off by 4.1e-10 relative; bound 1e-9).
    let half_width = 1.959_963_984_540_054 * (2.5f64 / 5.0).sqrt();
    assert!((summary.half_width() - half_width).abs() < 1e-9 * half_width);
}

#[test]
fn the_normal_quantile_matches_tabulated_values() {
    // Tabulated Φ⁻¹ to 16 digits; Acklam's approximation is published as good to 1.15e-9
    // relative (measured here at most 1.12e-9, at p = 0.995).
    let table = [
        (0.5, 0.0),
        (0.975, 1.959_963_984_540_054),
        (0.995, 2.575_829_303_548_901),
        (0.841_344_746_068_542_9, 1.0),
        (0.01, -2.326_347_874_040_841),
        (1e-6, -4.753_424_308_822_899),
    ];
    for (p, z) in table {
        let got = standard_normal_quantile(p);
        assert!(
            (got - z).abs() <= 1.2e-9 * z.abs().max(1.0),
            "Φ⁻¹({p}) = {got}, not {z}"
        );
    }
}

#[test]
fn statistics_refuse_what_they_cannot_compute() {
    let config = SummaryConfig::default();
    assert_eq!(
        summarize(&[1.0], &config),
        Err(StatisticsError::TooFewValues { count: 1 })
    );
    assert_eq!(
        summarize(&[1.0, f64::NAN, 2.0], &config),
        Err(StatisticsError::NonFiniteValue { index: 1 })
    );
    let bad_quantile = SummaryConfig {
        quantiles: vec![1.5],
        ..SummaryConfig::default()
    };
    assert_eq!(
        summarize(&[1.0, 2.0], &bad_quantile),
        Err(StatisticsError::InvalidProbability { value: 1.5 })
    );
    let bad_level = SummaryConfig {
        confidence: 1.0,
        ..SummaryConfig::default()
    };
    assert_eq!(
        summarize(&[1.0, 2.0], &bad_level),
        Err(StatisticsError::InvalidProbability { value: 1.0 })
    );
}

fn small_partial() -> Partial<f64, String> {
    let ensemble = Ensemble::new(
        3,
        ["x"],
        |rng: &mut MemberRng| rng.random_range(0.0..1.0),
        |x: &f64| {
            if *x < 0.2 {
                Err(String::from("too small"))
            } else {
                Ok([*x])
            }
        },
    );
    ensemble.run(0..20)
}

#[test]
fn a_tampered_partial_is_refused_when_read_back() {
    let partial = small_partial();
    assert!(!partial.failures().is_empty() && !partial.completed().is_empty());
    let json = serde_json::to_value(&partial).unwrap();
    let back: Partial<f64, String> = serde_json::from_value(json.clone()).unwrap();
    assert_eq!(back, partial);

    let tampered = |edit: &dyn Fn(&mut serde_json::Value)| {
        let mut value = json.clone();
        edit(&mut value);
        let error = serde_json::from_value::<Partial<f64, String>>(value).unwrap_err();
        assert!(error.to_string().contains("inconsistent"), "{error}");
    };
    // A value dropped, a failure dropped, an extra covered member, overlapping ranges.
    tampered(&|v| {
        v["values"][0].as_array_mut().unwrap().pop();
    });
    tampered(&|v| {
        v["failures"].as_array_mut().unwrap().pop();
    });
    tampered(&|v| v["covered"][0]["end"] = 21.into());
    tampered(&|v| {
        v["covered"] = serde_json::json!([{"start": 0, "end": 12}, {"start": 10, "end": 20}])
    });
}

#[test]
fn step_errors_become_records_with_their_time() {
    let error = StepError::<3>::new(
        2.5,
        Default::default(),
        StepErrorKind::TooManySteps { max_steps: 7 },
    );
    let record = varmass_core::ensemble::ErrorRecord::from(error);
    assert_eq!(record.time, 2.5);
    assert_eq!(record.message, error.to_string());
}
