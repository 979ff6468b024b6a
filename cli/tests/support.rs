//! A scene's `support` (docs/scenes.md, docs/mechanics.md#a-support-that-holds-until-lifted):
//! the M1670 rocket of `models/motor_rocket.vms` held on its pad by the tool until its thrust
//! exceeds its weight, against the lift-off time solved by hand on the thrust table's
//! pieces (`tests/pad_support/mod.rs`, derivation there).

#[path = "../../tests/pad_support/mod.rs"]
mod pad_support;

mod common;

use common::{csv, model, scratch, scratch_file, varmass as run};
use pad_support::{mass, motor, speed, thrust_equals_weight, G};

/// The rocket's scene from rest on its pad at `from` with `m0`, `support` its key line;
/// returns the summary and the CSV rows (t, phase, y, y', m).
fn fly(name: &str, support: &str, from: f64, m0: f64) -> (String, Vec<Vec<f64>>) {
    let model = model("motor_rocket.vms");
    let table = scratch(format!("{name}.csv"));
    let text = format!(
        "model = {model:?}\n{support}\nfrom = {from:?}\nuntil = 6.0\nmethod = \"dop853\"\n\
         tol = 1e-12\nrecord = [\"y\", \"y'\", \"m\"]\ncsv = {:?}\n\
         [set]\nu_e = {:?}\ng = {G:?}\n[init]\ny = 0.0\nm = {m0:?}\n",
        table.display().to_string(),
        motor().exhaust_speed(),
    );
    let path = scratch_file(&format!("{name}.toml"), &text);
    let (stdout, _) = run(&["run", &path], 0);
    (stdout, csv(&table).1)
}

/// The lift-off time the summary prints.
fn lift_off(summary: &str) -> f64 {
    let line = summary
        .lines()
        .find(|l| l.starts_with("lifted off its support (y) at t = "))
        .unwrap_or_else(|| panic!("no lift-off in\n{summary}"));
    line.rsplit(' ').next().unwrap().parse().unwrap()
}

#[test]
fn the_scene_lifts_off_where_the_thrust_equals_the_weight() {
    let exact = thrust_equals_weight(20.0).unwrap();
    let (summary, rows) = fly("pad", "support = \"y\"", 0.0, 20.0);
    let t_l = lift_off(&summary);
    // Located to 1e-12 in t (the event tolerance, the bound); measured 1.3e-14.
    assert!(
        (t_l - exact).abs() < 1e-12,
        "lift-off at {t_l}, exact {exact}"
    );
    let mut worst = 0.0_f64;
    for row in &rows {
        let (t, phase, y, v, m) = (row[0], row[1], row[2], row[3], row[4]);
        assert_eq!(phase, 1.0, "the hold is part of the first phase");
        assert!(y >= 0.0, "y = {y} < 0 at t = {t}");
        if t <= t_l {
            // Held: at rest exactly, the motor burning.
            assert_eq!((y, v), (0.0, 0.0), "moved on the pad at t = {t}");
            assert!(
                (m - mass(20.0, t)).abs() < 1e-12 * 20.0,
                "m = {m} at t = {t}"
            );
        } else {
            assert!(v > 0.0, "not climbing at t = {t}");
        }
        if t >= t_l {
            worst = worst.max((v - speed(20.0, t_l, t)).abs() / 290.0);
        }
    }
    // Measured 5.7e-15 (DOP853 at 1e-12); bound 18× that.
    assert!(worst < 1e-13, "v off the closed form by {worst:e}");
    let at_lift = rows.iter().filter(|r| r[0] == t_l).count();
    assert_eq!(at_lift, 1, "the lift-off is one row");
}

#[test]
fn a_scene_whose_thrust_exceeds_the_weight_lifts_at_once() {
    // From t = 0.1 s, F = 2000 N > m g; m as burnt since 0, so that the reference holds.
    let (summary, rows) = fly("pad_at_once", "support = \"y\"", 0.1, mass(20.0, 0.1));
    assert_eq!(lift_off(&summary), 0.1);
    assert!(rows[1..].iter().all(|r| r[2] > 0.0 && r[3] > 0.0));
    let worst = (rows.iter())
        .map(|r| (r[3] - speed(20.0, 0.1, r[0])).abs() / 290.0)
        .fold(0.0, f64::max);
    // Measured 6.5e-15; bound 15× that.
    assert!(worst < 1e-13, "v off the closed form by {worst:e}");
}

#[test]
fn a_scene_too_heavy_to_lift_stays_on_its_pad() {
    let (summary, rows) = fly("pad_heavy", "support = \"y\"", 0.0, 300.0);
    assert!(
        summary.contains("never lifted off its support (y)"),
        "{summary}"
    );
    assert!(rows.iter().all(|r| r[2] == 0.0 && r[3] == 0.0));
    let last = rows.last().unwrap();
    assert!((last[4] - mass(300.0, 6.0)).abs() < 1e-12 * 300.0);
}

#[test]
fn a_support_on_no_coordinate_is_refused() {
    let model = model("motor_rocket.vms");
    let text = format!(
        "model = {model:?}\nsupport = \"x\"\nuntil = 1.0\n[set]\nu_e = 2000.0\ng = 9.8\n\
         [init]\ny = 0.0\nm = 20.0\n"
    );
    let path = scratch_file("pad_no_coordinate.toml", &text);
    let (_, stderr) = run(&["run", &path], 2);
    assert!(stderr.contains("pad_no_coordinate.toml:2:11"), "{stderr}");
    assert!(
        stderr.contains("`support = \"x\"` names no coordinate"),
        "{stderr}"
    );
    assert!(stderr.contains("its coordinates are y"), "{stderr}");
}

#[test]
fn a_body_moving_along_its_support_is_refused() {
    let model = model("motor_rocket.vms");
    let text = format!(
        "model = {model:?}\nsupport = \"y\"\nuntil = 1.0\n[set]\nu_e = 2000.0\ng = 9.8\n\
         [init]\ny = 0.0\n\"y'\" = -1.0\nm = 20.0\n"
    );
    let path = scratch_file("pad_moving.toml", &text);
    let (_, stderr) = run(&["run", &path], 2);
    assert!(stderr.contains("must start at rest along it"), "{stderr}");
}

#[test]
fn a_held_phase_with_taylor_is_refused_with_the_reason() {
    let model = model("motor_rocket.vms");
    let text = format!(
        "model = {model:?}\nsupport = \"y\"\nuntil = 1.0\nmethod = \"taylor\"\n[set]\n\
         u_e = 2000.0\ng = 9.8\n[init]\ny = 0.0\nm = 20.0\n"
    );
    let path = scratch_file("pad_taylor.toml", &text);
    let (_, stderr) = run(&["run", &path], 2);
    assert!(
        stderr.contains("the held phase has no Taylor coefficients"),
        "{stderr}"
    );
}

/// A phase condition met while the body is held is refused, not skipped: the rocket lifts
/// off at t_L ≈ 0.0575 s (`the_scene_lifts_off_where_the_thrust_equals_the_weight`), so a
/// stage change at t = 0.03 falls inside the hold; a change at t = 1 (after t_L) flies.
#[test]
fn a_phase_condition_met_on_the_pad_is_refused() {
    let model = format!("{}/../models/motor_rocket.vms", env!("CARGO_MANIFEST_DIR"));
    let scene = |when: f64| {
        format!(
            "model = {model:?}\nsupport = \"y\"\nuntil = 2.0\nmethod = \"dop853\"\n\
             [set]\nu_e = {:?}\ng = {G:?}\n[init]\ny = 0.0\nm = 20.0\n\
             [[phase]]\nwhen = \"t = {when:?}\"\ncarry = \"separation\"\nmasses = {{ m = 19.0 }}\n",
            motor().exhaust_speed(),
        )
    };
    let path = scratch("pad_phase_on_pad.toml");
    std::fs::write(&path, scene(0.03)).expect("writable");
    let (_, stderr) = run(&["run", path.to_str().unwrap()], 2);
    assert!(
        stderr.contains("`t = 0.03` (the end of phase 1) was met while the body was held"),
        "{stderr}"
    );
    // Too heavy to lift (300 kg: the thrust never passes the weight), held to the end: a
    // stop at t = 0.5 falls inside the hold too.
    let heavy = scene(1.0).replace("m = 20.0", "m = 300.0").replace(
        "[[phase]]\nwhen = \"t = 1.0\"\ncarry = \"separation\"\nmasses = { m = 19.0 }\n",
        "",
    );
    let heavy = heavy.replace("until = 2.0\n", "until = 2.0\nstop_when = \"t = 0.5\"\n");
    let path = scratch("pad_stop_while_held.toml");
    std::fs::write(&path, heavy).expect("writable");
    let (_, stderr) = run(&["run", path.to_str().unwrap()], 2);
    assert!(
        stderr.contains("`t = 0.5` (the end of phase 1) was met while the body was held"),
        "{stderr}"
    );
    let path = scratch("pad_phase_after_lift_off.toml");
    std::fs::write(&path, scene(1.0)).expect("writable");
    let (stdout, _) = run(&["run", path.to_str().unwrap()], 0);
    assert!(stdout.contains("lifted off its support"), "{stdout}");
}

/// A held coordinate that starts uncoupled but couples as the others move ends the run there
/// (exit 1), rather than hold it by clamping p_y, a wrong motion: the pitching rocket's
/// M_yθ = g_c m_p sin θ is 0 at θ = 0 only, and its gimballed thrust turns θ at once.
/// Before (review of session 33) the run ended with exit 0, θ 0.8 rad off at 3 s.
#[test]
fn a_coupling_that_appears_while_held_ends_the_run() {
    let scene = common::data("support/pitching_on_pad.toml");
    let (_, stderr) = run(&["run", &scene], 1);
    assert!(
        stderr.contains("the coordinate `y` held on its support couples here with another"),
        "{stderr}"
    );
}

/// A first phase's condition met and unmet again during the hold is refused, not skipped:
/// the oscillator z (ω = 2π, from z = 0 at 3 m/s, amplitude 3/2π) passes z = 0.4 at
/// t = asin(0.8π/3)/2π ≈ 0.158 s and is back below it at the lift-off (F = 200 t equals
/// the weight 196.2 N at t ≈ 0.98 s). Before, phase 2 began at the first crossing after the
/// lift-off (1.158 s), exit 0.
#[test]
fn a_condition_met_and_unmet_while_held_is_refused() {
    let scene = common::data("support/held_oscillator.toml");
    let (_, stderr) = run(&["run", &scene], 2);
    assert!(
        stderr.contains("`z = 0.4` (the end of phase 1) was met while the body was held"),
        "{stderr}"
    );
}

/// After the lift-off the support is gone: a thrust that dips below the weight (150 N
/// against 196.2 N from 0.1 s to 0.3 s) brings the rocket back below its pad, and the summary
/// says so (before, nothing did).
#[test]
fn a_body_that_comes_back_below_its_support_is_warned_of() {
    let scene = common::data("support/dipping_thrust.toml");
    let (stdout, stderr) = run(&["run", &scene], 0);
    let all = format!("{stdout}{stderr}");
    assert!(
        all.contains("warning: after the lift-off y went below its support"),
        "{all}"
    );
    // And the unwarned case: the M1670 rocket climbs for good.
    let (summary, _) = fly("climbs_for_good", "support = \"y\"", 0.0, 20.0);
    assert!(!summary.contains("went below its support"), "{summary}");
}
