//! Tables: the three interpolants' defining properties (closed forms by hand, continuity,
//! end conditions), derivatives as tables, the outside rules, and the remembered interval.

use proptest::prelude::*;
use varmass_table::{
    Cursor, Interpolation, InvalidPoints, LookupError, Outside, Piecewise, Points, Table,
};

fn points(x: &[f64], y: &[f64]) -> Points {
    Points::new(x.to_vec(), y.to_vec()).unwrap()
}

/// Uneven knots, a turn, a flat run: (0, 1), (1, 3), (2.5, 2), (3, 2), (5, 6).
fn data() -> Points {
    points(&[0.0, 1.0, 2.5, 3.0, 5.0], &[1.0, 3.0, 2.0, 2.0, 6.0])
}

#[test]
fn linear_is_the_chords_and_its_slope_jumps_to_the_right_one_at_a_knot() {
    let table = Table::new(&data(), Interpolation::Linear, Outside::Error);
    let mut cursor = Cursor::default();
    // On [1, 2.5]: 3 − (x − 1)·2/3; at 2: 3 − 2/3.
    assert_eq!(table.value_at(2.0, &mut cursor), Ok(3.0 - 2.0 / 3.0));
    // At the knot 1 the slope is the chord's on its right, −2/3 (left: 2).
    assert_eq!(table.slope_at(1.0, &mut cursor), Ok(-2.0 / 3.0));
    // The last knot belongs to the last interval: slope (6 − 2)/2.
    assert_eq!(table.slope_at(5.0, &mut cursor), Ok(2.0));
    assert_eq!(table.value_at(5.0, &mut cursor), Ok(6.0));
}

#[test]
fn every_interpolant_passes_through_the_points() {
    for interpolation in [
        Interpolation::Linear,
        Interpolation::Pchip,
        Interpolation::Spline,
    ] {
        let table = Table::new(&data(), interpolation, Outside::Error);
        for (&x, &y) in data().arguments().iter().zip(data().values()) {
            let value = table.value(x).unwrap();
            // Measured 0; 4e-15 allows a few ulps of the end piece summed at h.
            assert!(
                (value - y).abs() <= 4e-15,
                "{interpolation:?} at {x}: {value}"
            );
        }
    }
}

#[test]
fn pchip_is_flat_where_the_data_turn_or_stay() {
    let table = Table::new(&data(), Interpolation::Pchip, Outside::Error);
    let mut cursor = Cursor::default();
    // The chords turn at x = 1 (up, then down) and are flat on [2.5, 3]: slope 0 at 1, 2.5, 3.
    for knot in [1.0, 2.5, 3.0] {
        assert_eq!(table.slope_at(knot, &mut cursor), Ok(0.0), "at {knot}");
    }
    // And the flat run stays flat: no overshoot between equal values.
    assert_eq!(table.value_at(2.75, &mut cursor), Ok(2.0));
}

#[test]
fn pchips_end_slope_is_the_three_point_formula() {
    // At x = 0: h0 = 1, h1 = 1.5, m0 = 2, m1 = −2/3: d = ((2h0 + h1)m0 − h0 m1)/(h0 + h1)
    // = (7 + 2/3)/2.5 = 46/15, same sign as m0; the chords turn and |d| ≤ 3|m0| = 6: kept.
    let table = Table::new(&data(), Interpolation::Pchip, Outside::Error);
    let slope = table.slope_at(0.0, &mut Cursor::default()).unwrap();
    // Measured 0; the bound allows 1 ulp of rounding in the formula's steps.
    assert!(
        (slope - 46.0 / 15.0).abs() <= 1e-15 * 46.0 / 15.0,
        "{slope}"
    );
}

#[test]
fn the_natural_spline_is_c2_with_zero_curvature_at_the_ends() {
    let table = Table::new(&data(), Interpolation::Spline, Outside::Error);
    let second = table.derivative().derivative();
    let (first, last) = (0.0, 5.0);
    // Measured |y''| 0 at the start and 8.9e-16 at the end (y'' at the knots up to 3.9).
    assert!(second.value(first).unwrap().abs() <= 1e-14);
    assert!(second.value(last).unwrap().abs() <= 1e-14);
    // C²: the second derivative from the left equals the one from the right at every
    // interior knot (left: the previous piece evaluated at the knot).
    let curve = second.curve();
    for (i, &knot) in curve.knots().iter().enumerate().take(4).skip(1) {
        let left = curve.value_on(i - 1, knot);
        let right = curve.value_on(i, knot);
        // Measured ≤ 1.3e-15 (y'' ≈ 3.9 there); 1e-14 allows 7×.
        assert!((left - right).abs() <= 1e-14, "at {knot}: {left} {right}");
    }
}

#[test]
fn derivatives_lower_the_degree_down_to_zero() {
    let table = Table::new(&data(), Interpolation::Spline, Outside::Error);
    let degrees: Vec<usize> = std::iter::successors(Some(table), |t| Some(t.derivative()))
        .take(6)
        .map(|t| t.curve().degree())
        .collect();
    assert_eq!(degrees, [3, 2, 1, 0, 0, 0]);
    // The third derivative is constant on each piece; the fourth is zero.
    let fourth = Table::new(&data(), Interpolation::Spline, Outside::Error)
        .derivative()
        .derivative()
        .derivative()
        .derivative();
    assert!(fourth.curve().coefficients().iter().all(|&c| c == 0.0));
}

#[test]
fn the_derivative_table_is_the_slope() {
    for interpolation in [
        Interpolation::Linear,
        Interpolation::Pchip,
        Interpolation::Spline,
    ] {
        let table = Table::new(&data(), interpolation, Outside::Error);
        let derivative = table.derivative();
        let mut cursor = Cursor::default();
        for k in 0..=50 {
            let x = 0.1 * k as f64;
            let slope = table.slope_at(x, &mut cursor).unwrap();
            // The same terms, rounded as (k·cₖ)·sᵏ⁻¹ here and (cₖ·sᵏ⁻¹)·k there (SciPy's
            // order): measured ≤ 4.4e-16 apart (slopes up to ≈ 4); 1e-15 allows 4 ulps.
            let difference = (derivative.value(x).unwrap() - slope).abs();
            assert!(
                difference <= 1e-15,
                "{interpolation:?} at {x}: {difference:e}"
            );
        }
    }
}

#[test]
fn outside_error_carries_the_argument_and_the_range() {
    let table = Table::new(&data(), Interpolation::Pchip, Outside::Error);
    let expected = LookupError::Outside {
        argument: 5.5,
        first: 0.0,
        last: 5.0,
    };
    assert_eq!(table.value(5.5), Err(expected));
    assert_eq!(table.derivative().value(5.5), Err(expected));
    assert_eq!(
        expected.to_string(),
        "the argument 5.5 is outside the data [0, 5]"
    );
}

#[test]
fn an_ulp_past_an_end_is_on_the_end_piece() {
    // A step landed on a knot by a stop time evaluates its last stage at t + h, an ulp or
    // so *of t* past the knot: within END_SLACK of the span (here 5e-10; t may be far larger
    // than the knots) of an end, the end's value and slope, and beyond it the rule — where
    // the table is continuous there (`error`, `hold`, `zero` after a zero). Where it jumps
    // (`zero` after a value that is not zero: the data end at 1 and 6), only the knot's
    // roundings (4 ε·5 = 4.4e-15) are taken back: a run restarting just past the knot must
    // read the value after the jump.
    let ends_at_zero = points(&[0.0, 1.0, 5.0], &[0.0, 3.0, 0.0]);
    for (points, outside) in [
        (data(), Outside::Error),
        (data(), Outside::Zero),
        (data(), Outside::Hold),
        (ends_at_zero, Outside::Zero),
    ] {
        for interpolation in [Interpolation::Linear, Interpolation::Spline] {
            let table = Table::new(&points, interpolation, outside);
            let jumps = table.jumps_at(5.0);
            assert_eq!(jumps, table.jumps_at(0.0));
            let mut cursor = Cursor::default();
            for (x, end) in [
                (f64::next_up(5.0), 5.0),
                (5.0 + 4e-15, 5.0),
                (f64::next_down(0.0), 0.0),
                (-4e-15, 0.0),
                (5.0 + 4.9e-10, 5.0),
                (-4.9e-10, 0.0),
            ] {
                let snapped = !jumps || (x - end).abs() < 1e-14;
                let expected = match snapped {
                    true => table.value(end),
                    false => Ok(0.0),
                };
                assert_eq!(table.value(x), expected, "{outside:?} at {x:e}");
                let slope = table.slope_at(x, &mut cursor);
                let expected = match snapped {
                    true => table.slope_at(end, &mut cursor),
                    false => Ok(0.0),
                };
                assert_eq!(slope, expected, "{outside:?} at {x:e}");
            }
            let beyond = table.value(5.0 + 5.1e-10);
            assert_eq!(beyond.is_err(), outside == Outside::Error, "{outside:?}");
            if outside == Outside::Zero {
                assert_eq!(beyond, Ok(0.0));
            }
        }
    }
}

#[test]
fn outside_zero_and_hold() {
    let zero = Table::new(&data(), Interpolation::Spline, Outside::Zero);
    assert_eq!((zero.value(-1.0), zero.value(7.0)), (Ok(0.0), Ok(0.0)));
    let hold = Table::new(&data(), Interpolation::Spline, Outside::Hold);
    assert_eq!(hold.value(-1e300), Ok(1.0));
    // The end piece at its knot: measured exactly 6.
    let end = hold.value(f64::INFINITY).unwrap();
    assert!((end - 6.0).abs() <= 4e-15, "{end}");
    // A held value has zero slope: the derivative table is zero outside.
    let mut cursor = Cursor::default();
    assert_eq!(hold.slope_at(7.0, &mut cursor), Ok(0.0));
    assert_eq!(hold.derivative().outside(), Outside::Zero);
    assert_eq!(hold.derivative().value(7.0), Ok(0.0));
}

#[test]
fn a_nan_argument_is_an_error_under_every_rule() {
    for outside in [Outside::Error, Outside::Zero, Outside::Hold] {
        let table = Table::new(&data(), Interpolation::Linear, outside);
        assert_eq!(table.value(f64::NAN), Err(LookupError::NotANumber));
    }
}

#[test]
fn points_are_checked() {
    let new = |x: &[f64], y: &[f64]| Points::new(x.to_vec(), y.to_vec()).unwrap_err();
    assert_eq!(
        new(&[0.0], &[1.0]),
        InvalidPoints::TooFewPoints { found: 1 }
    );
    assert_eq!(
        new(&[0.0, 1.0], &[1.0]),
        InvalidPoints::LengthMismatch {
            arguments: 2,
            values: 1
        }
    );
    assert_eq!(
        new(&[0.0, 1.0, 1.0], &[1.0; 3]),
        InvalidPoints::NotIncreasing { index: 2 }
    );
    assert_eq!(
        new(&[0.0, f64::NAN], &[1.0; 2]),
        InvalidPoints::NotFinite { index: 1 }
    );
    assert_eq!(
        new(&[0.0, 1.0], &[1.0, f64::INFINITY]),
        InvalidPoints::NotFinite { index: 1 }
    );
    // Finite values whose chord overflows (−1e308 − 1e308 = −∞): the value at
    // the knot would have been c₀ + ∞·0 = NaN, returned as Ok.
    assert_eq!(
        new(&[0.0, 1.0, 2.0], &[0.0, 1e308, -1e308]),
        InvalidPoints::SlopeNotFinite { index: 2 }
    );
    assert_eq!(
        new(&[0.0, 5e-324], &[0.0, 1.0]),
        InvalidPoints::SlopeNotFinite { index: 1 }
    );
}

/// A table built over static arrays at compile time, as the macro will embed one: the
/// linear curve (0, 0), (1, 2), (3, 0).
static EMBEDDED: Table = Table::from_piecewise(
    Piecewise::from_static(&[0.0, 1.0, 3.0], &[0.0, 2.0, 2.0, -1.0], 1),
    Outside::Zero,
);

#[test]
fn a_static_table_is_shared_between_threads() {
    fn shared<T: Send + Sync>(_: &T) {}
    shared(&EMBEDDED);
    let values: Vec<f64> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..4)
            .map(|k| scope.spawn(move || EMBEDDED.value(0.5 + 0.5 * k as f64).unwrap()))
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    assert_eq!(values, [1.0, 2.0, 1.5, 1.0]);
    assert_eq!(EMBEDDED.knots(), [0.0, 1.0, 3.0]);
}

proptest! {
    /// The remembered interval changes nothing: from any previous argument, a lookup gives
    /// what a fresh binary search gives, bit for bit.
    #[test]
    fn the_remembered_interval_never_changes_a_value(
        previous in -1.0..6.0f64,
        x in 0.0..=5.0f64,
        interpolation in prop_oneof![
            Just(Interpolation::Linear), Just(Interpolation::Pchip), Just(Interpolation::Spline)
        ],
    ) {
        let table = Table::new(&data(), interpolation, Outside::Hold);
        let mut cursor = Cursor::default();
        table.value_at(previous, &mut cursor).unwrap();
        table.value(previous).unwrap();
        let fresh = table.curve().value(x);
        prop_assert_eq!(table.value_at(x, &mut cursor), Ok(fresh));
        prop_assert_eq!(table.value(x), Ok(fresh));
    }

    /// pchip never overshoots: between two knots its value stays between their values.
    #[test]
    fn pchip_stays_between_neighbouring_values(x in 0.0..=5.0f64) {
        let table = Table::new(&data(), Interpolation::Pchip, Outside::Error);
        let knots = data();
        let i = table.curve().interval(x, 0);
        let (a, b) = (knots.values()[i], knots.values()[i + 1]);
        let value = table.value(x).unwrap();
        prop_assert!(a.min(b) - 1e-15 <= value && value <= a.max(b) + 1e-15);
    }
}

#[test]
fn the_antiderivative_of_a_linear_thrust_curve_is_the_trapezoid_impulse() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../models/motors/Cesaroni_M1670.eng"
    );
    let motor = varmass_table::Motor::parse(&std::fs::read_to_string(path).unwrap()).unwrap();
    let thrust = Interpolation::Linear.interpolate(&motor.thrust);
    let impulse = thrust.antiderivative();
    assert_eq!(impulse.degree(), 2);
    assert_eq!(impulse.value(0.0), 0.0);
    // At the knots: the partial trapezoid sums (6026.35 at the end). Measured 0 (the same
    // halves and products, added in the same order); 4e-12 allows a few ulps of 6026.
    let (x, y) = (motor.thrust.arguments(), motor.thrust.values());
    let mut trapezoids = 0.0;
    for i in 1..x.len() {
        trapezoids += 0.5 * (y[i] + y[i - 1]) * (x[i] - x[i - 1]);
        let difference = (impulse.value(x[i]) - trapezoids).abs();
        assert!(difference <= 4e-12, "at {}: {difference:e}", x[i]);
    }
    // Between knots, on the piece from (1, 2034) to (1.5, 2000): I(1) + ∫ 2034 − 68 s ds
    // = I(1) + 2034·0.25 − 34·0.0625 at t = 1.25.
    let at_one = impulse.value(1.0);
    let expected = at_one + 2034.0 * 0.25 - 34.0 * 0.0625;
    // Measured 0.
    assert!((impulse.value(1.25) - expected).abs() <= 4e-12);
}

#[test]
fn differentiating_the_antiderivative_gives_the_curve_back() {
    let spline = Interpolation::Spline.interpolate(&data());
    let back = spline.antiderivative().derivative();
    assert_eq!(back.degree(), 3);
    for (a, b) in back.coefficients().iter().zip(spline.coefficients()) {
        // (c/(k+1))·(k+1): measured 0; 2e-15 allows 4 ulps of the largest |c| = 3.
        assert!((a - b).abs() <= 2e-15, "{a} {b}");
    }
}

#[test]
fn a_stretched_thrust_curve_scales_the_impulse_by_both_factors() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../models/motors/Cesaroni_M1670.eng"
    );
    let thrust = varmass_table::Motor::parse(&std::fs::read_to_string(path).unwrap())
        .unwrap()
        .thrust;
    // 10 % slower, 10 % weaker: ∫ 0.9 F(t/1.1) dt = 0.99 I. Measured 0 against
    // 0.99 · 6026.35; 1e-11 allows the rounding of 16 scaled products (≈ 1e-12).
    let dispersed = thrust.stretched(1.1, 0.9).unwrap();
    let impulse = dispersed.trapezoid_integral();
    assert!((impulse - 0.99 * 6026.35).abs() <= 1e-11, "{impulse}");
    assert_eq!(dispersed.arguments()[15], 1.1 * 3.9);
    // A factor that is not positive and finite is refused by the same checks as any data.
    assert_eq!(
        thrust.stretched(0.0, 1.0),
        Err(InvalidPoints::NotIncreasing { index: 1 })
    );
    assert_eq!(
        thrust.stretched(-1.0, 1.0),
        Err(InvalidPoints::NotIncreasing { index: 1 })
    );
    assert_eq!(
        thrust.stretched(f64::NAN, 1.0),
        Err(InvalidPoints::NotFinite { index: 0 })
    );
    assert_eq!(
        thrust.stretched(1.0, f64::INFINITY),
        Err(InvalidPoints::NotFinite { index: 0 })
    );
}

#[test]
fn a_file_with_an_overflowing_slope_names_its_line() {
    // 1e308 to −1e308 over 1e-308: the chord overflows. The message named "2 point(s); a
    // table needs at least two" before (every refusal of the points read as a count).
    let text = "x,F\n0,1e308\n1e-308,-1e308\n";
    let error = varmass_table::CsvTable::parse(text).unwrap_err();
    assert_eq!(error.line, 3, "{error}");
    assert!(
        matches!(
            error.kind,
            varmass_table::ReadErrorKind::SlopeNotFinite { .. }
        ),
        "{error}"
    );
}
