//! The state rate over lanes (`emit = [..., "lanes"]`) is the scalar state rate in every
//! lane, bit for bit, on models whose rate calls the real functions: the double pendulum
//! (sin and cos of both angles, the closed-form inverse of its 2 × 2 mass matrix) and the
//! leaking spring pendulum (a state mass, sin and cos, powers). 200 pseudo-random states each,
//! spread over several orders of magnitude, in 4 lanes with a different system per lane.

use varmass::core::lanes::{LaneSystem, Lanes};
use varmass::prelude::*;

#[variable_mass_system(file = "models/double_pendulum.vms", emit = ["lanes"])]
#[derive(Clone, Copy)]
#[allow(non_snake_case)] // the model's names
struct DoublePendulum {
    M1: f64,
    M2: f64,
    l1: f64,
    l2: f64,
    g: f64,
}

#[variable_mass_system(file = "models/leaking_spring_pendulum.vms", emit = ["lanes"])]
#[derive(Clone, Copy)]
struct LeakingSpringPendulum {
    mu: f64,
    u_e: f64,
    k: f64,
    l0: f64,
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

/// Lane by lane, `state_rate_lanes` against `state_rate` of each lane's system.
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
    for round in 0..200 {
        let states: [SVector<f64, S>; 4] = core::array::from_fn(|_| state(&mut stream));
        let times = Lanes::from_fn(|_| 10.0 * stream.next().abs());
        let lanes: [Lanes<4>; S] = core::array::from_fn(|j| Lanes::from_fn(|i| states[i][j]));
        let rates = Sys::state_rate_lanes(&parameters, times, &lanes);
        for (lane, system) in systems.iter().enumerate() {
            let scalar = system
                .state_rate(times.0[lane], &states[lane])
                .expect("a regular state");
            for j in 0..S {
                assert_eq!(
                    rates[j].0[lane].to_bits(),
                    scalar[j].to_bits(),
                    "round {round}, lane {lane}, component {j}"
                );
            }
        }
    }
}

#[test]
fn double_pendulum_lanes_are_its_scalar_rates() {
    let systems = [0.5, 1.0, 2.0, 7.5].map(|scale| DoublePendulum {
        M1: 1.0 * scale,
        M2: 0.3 + scale,
        l1: 0.7 * scale,
        l2: 1.1,
        g: 9.81,
    });
    check(systems, |s| {
        SVector::<f64, 4>::new(
            3.0 * s.next(),
            3.0 * s.next(),
            20.0 * s.next(),
            0.1 * s.next(),
        )
    });
}

#[test]
fn leaking_spring_pendulum_lanes_are_its_scalar_rates() {
    let systems = [0.0, 0.2, 1.0, 3.0].map(|mu| LeakingSpringPendulum {
        mu,
        u_e: 40.0 + 10.0 * mu,
        k: 80.0,
        l0: 1.0 + mu,
        g: 9.81,
    });
    check(systems, |s| {
        SVector::<f64, 5>::new(
            1.0 + 0.5 * s.next(),
            3.0 * s.next(),
            5.0 * s.next(),
            2.0 * s.next(),
            2.0 + s.next().abs(),
        )
    });
}
