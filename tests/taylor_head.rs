//! The Taylor stepper's double-double head (`emit = [..., "taylor", "head"]`) on what
//! `tests/kepler_floor.rs` does not reach: square and cube roots (x^(±1/2), x^(−1/3)) and a
//! mass law in t, so that the head's time carries its ε. Its value part must be the double
//! state rate rounded, and its derivative part d f/dt = ∂f/∂y f + ∂f/∂t (the head evaluated
//! at y + ε f, t + ε) a central difference of the double rate along (f, 1).

use varmass::core::dd::{Dd, Dual};
use varmass::prelude::*;

#[variable_mass_system(
    "coordinates x
mass m = m0 + c*t
body b: mass m, position [x]
force b: [-k/sqrt(x) + k*x^(-1/3) - k*x^(1/2)]",
    emit = ["taylor", "head"]
)]
struct Rooted {
    m0: f64,
    c: f64,
    k: f64,
}

/// Measured at (t, x, p) = (0.4, 2.3, 0.7): the double-double rate's high part equals the
/// double rate to the last bit; the derivative part is 1.3e-12 and 1.7e-12 from the central
/// difference with h = 1e-5 (its own error, h² f‴/6 plus rounding 1e-16/h, is of that
/// size); bounds 1e-15 relative and 1e-9 (about 600×: a wrong term — a lost ∂f/∂t, the
/// mass law's rate, a root's derivative — moves it by 1e-2 or more).
#[test]
fn the_head_is_the_rate_and_its_derivative_through_roots_and_a_mass_law_in_t() {
    let rooted = Rooted {
        m0: 1.0,
        c: 0.1,
        k: 0.5,
    };
    let (t, y) = (0.4, SVector::from([2.3, 0.7]));
    let f = rooted.state_rate(t, &y).unwrap();
    let dd: [Dd; 2] = std::array::from_fn(|i| Dd::new(y[i]));
    let g = rooted.taylor_head_rate(t, &dd).expect("a head");
    let along: [Dual; 2] = std::array::from_fn(|i| Dual::new(dd[i], g[i]));
    let time = Dual::new(Dd::new(t), Dd::new(1.0));
    let d = rooted.taylor_head(time, &along).expect("a head");
    let h = 1e-5;
    let ahead = rooted.state_rate(t + h, &(y + f * h)).unwrap();
    let behind = rooted.state_rate(t - h, &(y - f * h)).unwrap();
    for i in 0..2 {
        let difference = (ahead[i] - behind[i]) / (2.0 * h);
        assert!(
            (f[i] - g[i].hi).abs() <= 1e-15 * f[i].abs(),
            "{i}: {} vs {}",
            f[i],
            g[i].hi
        );
        assert!(
            (difference - d[i].d.hi).abs() <= 1e-9,
            "{i}: {difference} vs {}",
            d[i].d.hi
        );
    }
}
