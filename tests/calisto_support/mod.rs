//! Calisto's full flight (`flights/calisto/calisto_flight.toml`) driven by the core's Rust
//! API for any system of the model `flights/calisto/calisto.vms` — the macro's compiled
//! struct or the interpreter's `TapeSystem` — so that both fly the same phases: the rail
//! (`rail::phases`: the pad, the slide to the exit travel, free), the ascent to apogee (z'
//! falling through 0), the drogue open from apogee + 1.5 s to the 800 m crossing + 1.5 s,
//! the main from then to landing (z falling through 0), DOP853 at rtol = atol = `tol` (the
//! scene's `tol`, the tool's rule). Shared by tests/calisto_compiled.rs and the benches'
//! `calisto` bench (benches/calisto.rs).

#![allow(dead_code)] // each includer uses its part

use varmass::core::nalgebra::SVector;
use varmass::core::rail;
use varmass::core::steppers::{AdaptiveControl, Dop853, StepControl};
use varmass::core::{
    continue_phases, run_phases, Carry, Direction, Event, EventAction, EventCondition, Phase,
    PhasedSolution, RunConfig, Statistics, StepError, Supported, VariableMassSystem,
};

/// The coordinates x, y, z, e0, e1, e2, e3; the state [q, p, m_s].
pub const N: usize = 7;
/// The state's length.
pub const S: usize = 15;
/// The delay from each trigger to its canopy's opening, s (flight.toml).
pub const LAG: f64 = 1.5;
/// The main's trigger, m above the pad on the way down.
pub const MAIN_HEIGHT: f64 = 800.0;
/// The rail: 85° above the horizontal toward North; the reference point's travel to the exit.
pub const INCLINATION: f64 = 85.0;
pub const EXIT_TRAVEL: f64 = 3.8632;

/// When each canopy opens and the drogue is cut away (s; 1e30 = never): the parameters the
/// scene's phases set.
#[derive(Clone, Copy, Debug)]
pub struct Canopies {
    pub drogue_t_open: f64,
    pub drogue_t_cut: f64,
    pub main_t_open: f64,
}

/// Both closed: the ascent.
pub const CLOSED: Canopies = Canopies {
    drogue_t_open: 1e30,
    drogue_t_cut: 1e30,
    main_t_open: 1e30,
};

/// The start at rest on the rail (calisto_flight.toml's [init]): attitude on the rail with
/// RocketPy's roll angle, the propellant plus the 1 kg held.
pub fn start() -> SVector<f64, S> {
    let mut state = SVector::<f64, S>::zeros();
    let q = [
        0.9230002039112792,
        -0.04029905920751535,
        0.01669241687462921,
        0.38231920253318413,
    ];
    state.fixed_rows_mut::<4>(3).copy_from_slice(&q);
    state[14] = 3.955911961392;
    state
}

/// What a flight gives: the solution of every phase and the counters of each stage
/// (ascent with the rail, drogue, main).
pub struct Flown {
    pub phased: PhasedSolution<N, S>,
    pub stages: [Statistics; 3],
}

impl Flown {
    /// The time and state where stage `k` (0 ascent, 1 drogue, 2 main) ended.
    pub fn end_of(&self, k: usize) -> (f64, SVector<f64, S>) {
        let changes = &self.phased.changes;
        let last = changes.len();
        let time = match k {
            0 => changes[last - 2].time,
            1 => changes[last - 1].time,
            _ => *self.phased.solution.times.last().unwrap(),
        };
        let i = self
            .phased
            .solution
            .times
            .iter()
            .position(|&t| t == time)
            .unwrap();
        (time, self.phased.solution.states[i])
    }
}

/// The counters `after` less `before`.
fn less(after: Statistics, before: Statistics) -> Statistics {
    Statistics {
        accepted_steps: after.accepted_steps - before.accepted_steps,
        rejected_steps: after.rejected_steps - before.rejected_steps,
        rate_evaluations: after.rate_evaluations - before.rate_evaluations,
        ..after
    }
}

/// A phase of the free system `system` ended by `g` falling through 0.
fn falling<'a, Sys>(
    system: Sys,
    g: &'a dyn Fn(f64, &SVector<f64, S>) -> f64,
) -> Phase<'a, Supported<Sys>, S> {
    Phase {
        system: Supported::free(system),
        carry: Carry::Separation,
        state_masses: &[],
        until: Some(Event {
            condition: EventCondition::Function(g),
            direction: Direction::Falling,
            action: EventAction::Stop,
        }),
    }
}

/// Flies Calisto from the rail to landing at tolerance `tol`, `make` building the system
/// with the canopies' times. `Err` is the core's error of the stage that failed.
pub fn fly<Sys, Make>(make: Make, tol: f64) -> Result<Flown, StepError<S>>
where
    Sys: VariableMassSystem<N, S>,
    Make: Fn(Canopies) -> Sys,
{
    let control = StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: tol,
        absolute_tolerance: tol,
        ..AdaptiveControl::dop853()
    });
    let stepper = |system, t, state| Dop853::new(system, t, state, control);
    let config = RunConfig::until(600.0);
    let ascent = make(CLOSED);
    let incline = INCLINATION.to_radians();
    let direction = [0.0, incline.cos(), incline.sin()];
    let vz = |t: f64, s: &SVector<f64, S>| ascent.velocities(t, s).map_or(f64::NAN, |v| v[2]);
    let z = |_: f64, s: &SVector<f64, S>| s[2];
    let above_main = |_: f64, s: &SVector<f64, S>| s[2] - MAIN_HEIGHT;
    let start = start();
    // rail::phases's phases, each system made anew (an interpreted one is not Clone)
    let (on, pad) = rail::on_rail(&ascent, ([0, 1, 2], direction), EXIT_TRAVEL, (0.0, &start))?;
    let mut ascent_phases = Vec::new();
    if pad {
        ascent_phases.push(rail::pad_phase(make(CLOSED), on));
    }
    ascent_phases.push(rail::slide_phase(make(CLOSED), on, EXIT_TRAVEL));
    ascent_phases.push(Phase {
        carry: Carry::Capture,
        ..falling(make(CLOSED), &vz)
    });
    let phased = run_phases(&ascent_phases, (0.0, start), stepper, &config)?;
    let s0 = phased.solution.statistics;
    let apogee = phased.solution.times.last().copied().unwrap_or(0.0);
    let drogue = make(Canopies {
        drogue_t_open: apogee + LAG,
        ..CLOSED
    });
    let drogue_phase = [falling(drogue, &above_main)];
    let last = &ascent_phases[ascent_phases.len() - 1].system;
    let phased = continue_phases(phased, last, &drogue_phase, stepper, &config)?;
    let s1 = phased.solution.statistics;
    let crossing = phased.solution.times.last().copied().unwrap_or(0.0);
    let main = make(Canopies {
        drogue_t_open: apogee + LAG,
        drogue_t_cut: crossing + LAG,
        main_t_open: crossing + LAG,
    });
    let main_phase = [falling(main, &z)];
    let phased = continue_phases(
        phased,
        &drogue_phase[0].system,
        &main_phase,
        stepper,
        &config,
    )?;
    let s2 = phased.solution.statistics;
    Ok(Flown {
        phased,
        stages: [s0, less(s1, s0), less(s2, s1)],
    })
}
