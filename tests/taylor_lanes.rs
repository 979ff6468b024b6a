//! Taylor's method in lanes (`emit = [..., "taylor", "lanes"]`): the generated recurrences
//! instantiated over `Lanes<W>` give, lane by lane, the scalar `taylor_coefficients` of the
//! system in that lane, bit for bit, to order 20 (models with a state mass, abs, sin and
//! cos, √ and the closed-form inverse of a 2 × 2 mass matrix), and truncated at any order.

use varmass::core::lanes::{LaneSystem, Lanes};
use varmass::core::steppers::taylor::series::Scratch;
use varmass::prelude::*;

#[variable_mass_system(file = "models/rocket.vms", with = ["drag"], emit = ["taylor", "lanes"])]
#[derive(Clone, Copy)]
struct DragRocket {
    mu: f64,
    u_e: f64,
    g: f64,
    k_d: f64,
}

#[variable_mass_system(file = "models/leaking_spring_pendulum.vms", emit = ["taylor", "lanes"])]
#[derive(Clone, Copy)]
struct LeakingSpringPendulum {
    mu: f64,
    u_e: f64,
    k: f64,
    l0: f64,
    g: f64,
}

#[variable_mass_system(file = "models/double_pendulum.vms", emit = ["taylor", "lanes"])]
#[derive(Clone, Copy)]
#[allow(non_snake_case)] // the model's names
struct DoublePendulum {
    M1: f64,
    M2: f64,
    l1: f64,
    l2: f64,
    g: f64,
}

/// A deterministic stream in [−1, 1) (a 64-bit LCG, Knuth's MMIX constants).
struct Stream(u64);

impl Stream {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

const ORDER: usize = 20;

/// Lane by lane, `taylor_coefficients_lanes` to `ORDER` against the scalar
/// `taylor_coefficients` of each lane's system, to `ORDER` and truncated at 7 (the lanes
/// expand to the largest order any lane needs, each lane keeping its own).
fn check<Sys, const N: usize, const S: usize>(
    systems: [Sys; 4],
    mut state: impl FnMut(&mut Stream) -> SVector<f64, S>,
) where
    Sys: LaneSystem<N, S, 4>,
{
    let mut stream = Stream(2015);
    let mut parameters = Sys::splat(&systems[0]);
    for (lane, system) in systems.iter().enumerate() {
        Sys::set_lane(&mut parameters, lane, system);
    }
    let mut lanes_scratch = Scratch::<Lanes<4>>::default();
    let mut scalar_scratch = Scratch::new();
    for round in 0..50 {
        let states: [SVector<f64, S>; 4] = core::array::from_fn(|_| state(&mut stream));
        let times = Lanes::from_fn(|_| 10.0 * stream.next().abs());
        let lanes: [Lanes<4>; S] = core::array::from_fn(|j| Lanes::from_fn(|i| states[i][j]));
        let mut series = [[Lanes::splat(f64::NAN); S]; ORDER + 1];
        Sys::taylor_coefficients_lanes(&parameters, times, &lanes, &mut series, &mut lanes_scratch)
            .expect("emitted")
            .expect("lanes never fail");
        for (lane, system) in systems.iter().enumerate() {
            for order in [ORDER, 7] {
                let mut scalar = [SVector::<f64, S>::repeat(f64::NAN); ORDER + 1];
                let t = times.0[lane];
                system
                    .taylor_coefficients(
                        t,
                        &states[lane],
                        &mut scalar[..=order],
                        &mut scalar_scratch,
                    )
                    .expect("emitted")
                    .expect("a regular state");
                for k in 0..=order {
                    for j in 0..S {
                        let (a, b) = (series[k][j].0[lane], scalar[k][j]);
                        assert!(
                            a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan()),
                            "round {round}, lane {lane}, order {order}: y[{k}][{j}] {a:e} vs {b:e}"
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn the_lanes_expansion_is_the_scalar_expansion_in_every_lane() {
    let rocket = |mu: f64, u_e: f64, k_d: f64| DragRocket {
        mu,
        u_e,
        g: 9.81,
        k_d,
    };
    check::<_, 1, 3>(
        [
            rocket(9.7, 2450.0, 0.3),
            rocket(10.3, 2590.0, 0.0),
            rocket(0.0, 2500.0, 1.2),
            rocket(12.0, 2000.0, 0.05),
        ],
        |s| SVector::from([3e4 * s.next(), 4e5 * s.next(), 600.0 + 300.0 * s.next()]),
    );
    let pendulum = |mu: f64, k: f64| LeakingSpringPendulum {
        mu,
        u_e: 3.0,
        k,
        l0: 1.0,
        g: 9.81,
    };
    check::<_, 2, 5>(
        [
            pendulum(0.01, 40.0),
            pendulum(0.0, 10.0),
            pendulum(0.1, 200.0),
            pendulum(0.02, 1.0),
        ],
        |s| {
            SVector::from([
                1.0 + 0.3 * s.next(),
                3.0 * s.next(),
                2.0 * s.next(),
                0.5 * s.next(),
                1.5 + s.next(),
            ])
        },
    );
    let double = |l2: f64| DoublePendulum {
        M1: 1.0,
        M2: 0.7,
        l1: 1.0,
        l2,
        g: 9.81,
    };
    check::<_, 2, 4>([double(1.0), double(0.5), double(2.0), double(1.3)], |s| {
        SVector::from([
            3.0 * s.next(),
            3.0 * s.next(),
            2.0 * s.next(),
            2.0 * s.next(),
        ])
    });
}
