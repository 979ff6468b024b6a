//! `Tabulated`: the derivative tables built once, and the dispersion helper
//! `transformed(k, s)`, which must be k·F(x/s) with derivatives (k/sʲ)·F⁽ʲ⁾(x/s) (the chain
//! rule, by hand), against the untransformed table evaluated at x/s.

use varmass_table::{Interpolation, LookupError, Outside, Points, Tabulated};

fn points() -> Points {
    // Turns, a flat run and uneven spacing, so that every cubic piece differs.
    let x = vec![0.0, 0.3, 0.7, 1.0, 1.6, 2.0, 2.9, 3.4];
    let y = vec![0.0, 2.0, 3.5, 3.5, 1.0, -0.5, 0.2, 0.0];
    Points::new(x, y).unwrap()
}

#[test]
fn transformed_is_the_scaled_and_stretched_function_with_its_derivatives() {
    let (k, s) = (1.07, 0.93);
    for interpolation in [
        Interpolation::Linear,
        Interpolation::Pchip,
        Interpolation::Spline,
    ] {
        let table = Tabulated::new(&points(), interpolation, Outside::Zero);
        let dispersed = table.transformed(k, s).unwrap();
        let mut worst = 0.0_f64;
        for i in 0..=3400 {
            let x = 3.4 * s * f64::from(i) / 3400.0;
            for order in 0..4 {
                let chain = k / s.powi(order as i32);
                let want = chain * table.order(order).value(x / s).unwrap();
                let got = dispersed.order(order).value(x).unwrap();
                worst = worst.max((got - want).abs() / want.abs().max(1.0));
            }
        }
        // Measured 7.8e-16 (linear), 2.9e-14 (pchip), 9.1e-15 (spline), relative to
        // max(|value|, 1): x − s·xᵢ rounds differently from x/s − xᵢ; bound 1e-12.
        assert!(worst <= 1e-12, "{interpolation:?}: {worst:e}");
    }
}

#[test]
fn orders_past_the_degree_are_the_zero_table_with_the_rule() {
    let linear = Tabulated::new(&points(), Interpolation::Linear, Outside::Error);
    // Degree 1: order 2 is zero inside, and stays an error outside, as every higher order.
    assert_eq!(linear.order(2).value(1.3), Ok(0.0));
    assert_eq!(linear.order(7), linear.order(2));
    assert!(matches!(
        linear.order(5).value(9.0),
        Err(LookupError::Outside { .. })
    ));
    let spline = Tabulated::new(&points(), Interpolation::Spline, Outside::Hold);
    assert_eq!(spline.order(4).value(1.3), Ok(0.0));
    assert_ne!(spline.order(3).value(1.3), Ok(0.0));
    // Held outside: the derivatives are zero there.
    assert_eq!(spline.order(1).value(-1.0), Ok(0.0));
}

#[test]
fn transformed_refuses_scales_that_break_the_data() {
    let table = Tabulated::new(&points(), Interpolation::Pchip, Outside::Zero);
    for (k, s) in [
        (1.0, 0.0),
        (1.0, -1.0),
        (f64::NAN, 1.0),
        (1.0, f64::INFINITY),
    ] {
        assert!(table.transformed(k, s).is_none(), "{k} {s}");
    }
    // s = 1e-320 makes the knots subnormal and equal: refused, not a division by zero.
    assert!(table.transformed(1.0, 1e-320).is_none());
}
