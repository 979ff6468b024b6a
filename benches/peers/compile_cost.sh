#!/usr/bin/env bash
# Our construction cost for the heyoka comparison (issue 38): the release build of a crate
# holding the bench's four systems (the sled, Kepler with its head, the rocket, the 3-link
# pendulum, emitted with the Taylor recurrences as benches/peers/ours.rs uses them) and one function
# that runs each with the Taylor stepper, against the same crate without them (the function
# empty). Each build is `cargo rustc --release --lib` after touching the crate, so only the
# crate itself is rebuilt (its dependencies, varmass included, are built once before): wall
# seconds of the whole build (cargo's own start included), and the macro's expansion inside
# it (`expand_crate` of `-Z time-passes`, on stable through RUSTC_BOOTSTRAP=1); the fastest
# of 3 builds each way.
#
#   bash benches/peers/compile_cost.sh      # from the repository root
#
# The crate is made in target/peers-compile-cost and uses this repository's Cargo.lock and
# target directory, so the dependencies the peers bench built in release are reused.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
crate="$root/target/peers-compile-cost"
mkdir -p "$crate/src"
cp "$root/Cargo.lock" "$crate/Cargo.lock"
cat > "$crate/Cargo.toml" <<TOML
[package]
name = "peers-compile-cost"
version = "0.0.0"
edition = "2021"
publish = false

[dependencies]
varmass = { path = "$root", features = ["parallel"] }

[workspace]
TOML
with_systems() {
    cat > "$crate/src/lib.rs" <<'RUST'
use varmass::core::nalgebra::SVector;
use varmass::core::steppers::{Taylor, TaylorControl};
use varmass::core::{StepOutcome, Stepper};
use varmass::prelude::*;

#[variable_mass_system(
    "
    coordinates x
    mass m = m0 + c*x
    body sled: mass m, position [x]
    potential -m*g*x*sin(theta)
    force sled: [-f_d*m*g*cos(theta)]
    inflow sled: velocity [0]
",
    emit = ["taylor"]
)]
pub struct Sled {
    pub m0: f64,
    pub c: f64,
    pub g: f64,
    pub theta: f64,
    pub f_d: f64,
}

#[variable_mass_system(
    "
    coordinates r, th
    mass m = m1
    body planet: mass m, position [r*cos(th), r*sin(th)]
    potential -k*m/r
",
    emit = ["taylor", "head"]
)]
pub struct Kepler {
    pub m1: f64,
    pub k: f64,
}

#[variable_mass_system(
    "
    coordinates y
    mass m: state, rate -mu
    body rocket: mass m, position [y]
    potential m*g*y
    outflow rocket: rate mu, relative_velocity [-u_e]
",
    emit = ["taylor"]
)]
pub struct Rocket {
    pub mu: f64,
    pub u_e: f64,
    pub g: f64,
}

#[variable_mass_system(
    "
    coordinates a1, a2, a3
    mass m1 = m
    mass m2 = m
    mass m3 = m
    body bob1: mass m1, position [l*sin(a1), -l*cos(a1)]
    body bob2: mass m2, position [l*sin(a1) + l*sin(a2), -l*cos(a1) - l*cos(a2)]
    body bob3: mass m3, position [l*sin(a1) + l*sin(a2) + l*sin(a3), -l*cos(a1) - l*cos(a2) - l*cos(a3)]
    potential -m*g*l*(3*cos(a1) + 2*cos(a2) + cos(a3))
",
    emit = ["taylor"]
)]
pub struct Pendulum3 {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

fn final_state<Sys: VariableMassSystem<N, S>, const N: usize, const S: usize>(
    system: &Sys,
    y0: SVector<f64, S>,
    end: f64,
    tolerance: f64,
) -> SVector<f64, S> {
    let control = TaylorControl::adaptive(Tolerance::new(tolerance, tolerance).unwrap());
    let mut stepper = Taylor::new(system, 0.0, y0, control).unwrap();
    stepper.set_stop_time(end).unwrap();
    while stepper.step().unwrap() != StepOutcome::ReachedStopTime {}
    *stepper.state()
}

/// Each system run by the Taylor stepper (the code the bench times).
pub fn run(tolerance: f64) -> f64 {
    let sled = Sled { m0: 20.0, c: 4.0, g: 9.81, theta: 0.5, f_d: 0.1 };
    let kepler = Kepler { m1: 1.5, k: 1.0 };
    let rocket = Rocket { mu: 0.05, u_e: 300.0, g: 9.81 };
    let pendulum = Pendulum3 { m: 1.0, l: 1.0, g: 9.81 };
    let a = final_state(&sled, SVector::<f64, 2>::zeros(), 4.0, tolerance);
    let b = final_state(&kepler, SVector::<f64, 4>::new(0.5, 0.0, 0.0, 1.3), 18.8, tolerance);
    let y0 = SVector::<f64, 6>::from_column_slice(&[0.6, -0.4, 0.3, 0.0, 0.0, 0.0]);
    let c = final_state(&pendulum, y0, 10.0, tolerance);
    let d = final_state(&rocket, SVector::<f64, 3>::new(0.0, 0.0, 1.0), 15.0, tolerance);
    a[0] + b[0] + c[0] + d[0]
}
RUST
}
without_systems() {
    cat > "$crate/src/lib.rs" <<'RUST'
#[allow(unused_imports)]
use varmass::prelude::*;

/// The same entry point with nothing to run.
pub fn run(tolerance: f64) -> f64 {
    tolerance
}
RUST
}
cd "$crate"
export CARGO_TARGET_DIR="$root/target" CARGO_INCREMENTAL=0
with_systems
cargo build --release --lib

# "wall seconds, expand_crate seconds" of the fastest of 3 rebuilds of the crate as it stands.
fastest() {
    for _ in 1 2 3; do
        touch src/lib.rs
        began=$(date +%s.%N)
        expand=$(RUSTC_BOOTSTRAP=1 cargo rustc --quiet --release --lib -- -Z time-passes 2>&1 |
            awk '$NF == "expand_crate" { sub(";", "", $2); print $2 }')
        ended=$(date +%s.%N)
        echo "$(awk -v a="$began" -v b="$ended" 'BEGIN { printf "%.2f", b - a }') $expand"
    done | sort -g | head -1
}
read -r wall expand < <(fastest)
without_systems
read -r base_wall base_expand < <(fastest)
with_systems
# Also kept for benches/peers/heyoka.py, which puts these lines on docs/bench/heyoka.md.
{
    echo "with the four systems: build ${wall} s, expand_crate ${expand} s"
    echo "without them: build ${base_wall} s, expand_crate ${base_expand} s"
    echo "load average $(cut -d' ' -f1-3 /proc/loadavg), $(date -u +%Y-%m-%d)"
} | tee "$crate/result.txt"
