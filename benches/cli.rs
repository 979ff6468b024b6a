//! What `varmass run` costs against compiled code: the paper's sled (m0 = 10, c = 2,
//! θ = 30°, f_d = 0.1) from rest to x = 50 m with Dormand–Prince at tol 1e-12, integrated
//! once as the macro's generated system and once as the run-time [`TapeSystem`] the command
//! line tool builds from a model file, with the same stepper and the same event. Also the
//! fixed cost the tool pays before it steps: parse, derive and compile the tapes.
//!
//! ```sh
//! cargo bench -p varmass-benches --bench cli
//! ```

mod common;

use criterion::Criterion;
use varmass::core::nalgebra::SVector;
use varmass::core::steppers::{AdaptiveControl, DormandPrince, StepControl};
use varmass::core::{run, Direction, Event, RunConfig, VariableMassSystem};
use varmass::interpret::{Program, TapeSystem};
use varmass::symbolic::{derive_source, mechanics::Parameters};

use common::generated::Sled;
use common::timing::fastest;
use common::workloads::sled_parameters;

const SLED: Sled = Sled {
    m0: 10.0,
    c: 2.0,
    g: 9.81,
    theta: 0.523_598_775_598_298_8,
    f_d: 0.1,
};

/// Runs `system` from rest to x = 50 m; returns the accepted steps.
fn to_50_m<Sys: VariableMassSystem<1, 2>>(system: &Sys) -> usize {
    let control = StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-12,
        absolute_tolerance: 1e-12,
        ..AdaptiveControl::default()
    });
    let start = SVector::<f64, 2>::zeros();
    let mut stepper = DormandPrince::new(system, 0.0, start, control).expect("starts");
    let at_50 = Event::state_reaches(0, 50.0, Direction::Either);
    let solution = run(&mut stepper, &RunConfig::until(100.0), &[at_50]).expect("runs");
    solution.statistics.accepted_steps
}

fn tape_sled() -> TapeSystem<1, 2> {
    let derivation = derive_source(Sled::SOURCE, Parameters::Inferred).expect("derives");
    let program = Program::new(derivation, &sled_parameters(&SLED)).expect("parameters fit");
    TapeSystem::new(program).expect("one coordinate, no state mass")
}

fn main() {
    let tape = tape_sled();
    let (generated_time, steps) = fastest(|| to_50_m(&SLED));
    let (tape_time, tape_steps) = fastest(|| to_50_m(&tape));
    let (setup_time, _) = fastest(tape_sled);
    println!("sled to x = 50 m, Dormand–Prince tol 1e-12 (fastest of interleaved runs):");
    println!("  generated code:        {generated_time:>10.1?} ({steps} steps)");
    println!(
        "  run-time tapes (CLI):  {tape_time:>10.1?} ({tape_steps} steps), {:.1}× generated",
        tape_time.as_secs_f64() / generated_time.as_secs_f64()
    );
    println!("  parse + derive + compile tapes: {setup_time:.1?}");

    let mut criterion = Criterion::default().configure_from_args();
    let mut group = criterion.benchmark_group("cli_sled_to_50_m");
    group.bench_function("generated", |b| b.iter(|| to_50_m(&SLED)));
    group.bench_function("tape", |b| b.iter(|| to_50_m(&tape)));
    group.bench_function("derive_and_compile", |b| b.iter(tape_sled));
    group.finish();
    criterion.final_summary();
}
