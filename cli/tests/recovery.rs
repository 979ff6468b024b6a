//! Recovery (docs/scenes.md#a-recovery): a payload under `models/lib/parachute_1d.vms`
//! canopies, deployed by a scene's `[[phase]]` that sets a canopy's opening time to the
//! time of its change plus a lag (`set = { drogue_t_open = "t + 1.5" }`), against the
//! closed forms of a fall under a constant drag area in air of constant density.
//!
//! The fall (z up, v = ż < 0, mass m, drag area C = Cd·S, density ρ): the canopy's force is
//! −½ρC|v|v = +½ρC v², so m v̇ = −m g + ½ρC v², i.e. v̇ = −g (1 − v²/v_t²) with the
//! terminal speed v_t = √(2 m g/(ρ C)). Separating, dv/(1 − v²/v_t²) = −g dt; for |v| < v_t
//! the left side integrates to v_t atanh(v/v_t), so from v(t₁) = v₁
//!
//!   v(t) = −v_t tanh(a + g (t − t₁)/v_t),   a = atanh(−v₁/v_t),
//!   z(t) = z₁ − (v_t²/g) [ln cosh(a + g (t − t₁)/v_t) − ln cosh a]
//!
//! (z by integrating v: ∫ tanh = ln cosh). From rest (t₁ = 0, v₁ = 0, a = 0) that is
//! v = −v_t tanh(g t/v_t), z = z₀ − (v_t²/g) ln cosh(g t/v_t). Faster than v_t
//! (|v₁| > v_t, a main opening under a drogue) the left side integrates to v_t acoth(v/v_t)
//! and tanh becomes coth, ln cosh becomes ln sinh, b = acoth(−v₁/v_t) = atanh(−v_t/v₁)
//! (d/dx coth x = −csch² x and 1 − coth² = −csch², so v̇ = −g (1 − v²/v_t²) holds). The time
//! to fall Δz from (t₁, v₁) inverts z: x = acosh(cosh a · e^{gΔz/v_t²}) − a (asinh and
//! sinh for coth), t − t₁ = x v_t/g. Before its canopy opens the body falls freely:
//! z = v₀ t − g t²/2, v = v₀ − g t from the launch, and the apogee is at t_a = v₀/g.

mod common;

use std::path::Path;

use common::{model, scratch, scratch_file, varmass as run};
use varmass_cli::scene::{run_file, SceneRun};

const G: f64 = 9.81;
const RHO: f64 = 1.225;
const M0: f64 = 2.0;

/// The terminal speed under the drag area `cds`.
fn terminal(cds: f64) -> f64 {
    (2.0 * M0 * G / (RHO * cds)).sqrt()
}

/// The fall under a constant drag area of terminal speed `vt` from `(t1, z1, v1)`: (z, v)
/// at `t` (the closed forms of the header, tanh below v_t and coth above).
fn fall(vt: f64, (t1, z1, v1): (f64, f64, f64), t: f64) -> (f64, f64) {
    let x = G * (t - t1) / vt;
    let h = vt * vt / G;
    if v1.abs() < vt {
        let a = (-v1 / vt).atanh();
        let drop = (a + x).cosh().ln() - a.cosh().ln();
        (z1 - h * drop, -vt * (a + x).tanh())
    } else {
        let b = (-vt / v1).atanh();
        let drop = (b + x).sinh().ln() - b.sinh().ln();
        (z1 - h * drop, -vt / (b + x).tanh())
    }
}

/// The time at which the fall of [`fall`] from `(t1, z1, v1)` reaches the height `z`.
fn time_to(vt: f64, (t1, z1, v1): (f64, f64, f64), z: f64) -> f64 {
    let e = (G * (z1 - z) / (vt * vt)).exp();
    let x = if v1.abs() < vt {
        let a = (-v1 / vt).atanh();
        (a.cosh() * e).acosh() - a
    } else {
        let b = (-vt / v1).atanh();
        (b.sinh() * e).asinh() - b
    };
    t1 + x * vt / G
}

/// The scene `text` (its model `models/recovery_descent.vms`) written to the scratch file
/// `name` and run by the tool's library.
fn scene(name: &str, text: &str) -> SceneRun {
    let model = model("recovery_descent.vms");
    let path = scratch_file(name, &format!("model = {model:?}\n{text}"));
    let done = run_file(Path::new(&path)).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        done.failure.is_none(),
        "{:?}",
        done.failure.map(|e| e.to_string())
    );
    done
}

/// The columns `names` of a run's table, with t first: one `Vec` per row.
fn rows(done: &SceneRun, names: &[&str]) -> Vec<Vec<f64>> {
    let table = &done.table;
    let index: Vec<usize> = (names.iter())
        .map(|n| table.names.iter().position(|c| c == n).expect(n))
        .collect();
    (0..table.len())
        .map(|i| {
            let (t, values) = table.row(i);
            std::iter::once(t)
                .chain(index.iter().map(|&k| values[k]))
                .collect()
        })
        .collect()
}

/// The first row at or after `t` (a kink the run lands on: within a few roundings of t).
fn row_at(rows: &[Vec<f64>], t: f64) -> (f64, f64, f64) {
    let row = rows.iter().find(|r| r[0] >= t - 1e-12).expect("a row");
    assert!(
        (row[0] - t).abs() < 1e-12 * t.max(1.0),
        "no point at {t}: {}",
        row[0]
    );
    (row[0], row[1], row[2])
}

const SETTINGS: &str = "method = \"dop853\"\ntol = 1e-12\n\
    record = [\"z\", \"z'\", \"drogue_cds\", \"main_cds\", \"T_OPEN=drogue_t_open\"]\n";

fn set(m_drogue: f64, m_main: f64, fill: (f64, f64)) -> String {
    format!(
        "[set]\nm0 = {M0:?}\ng = {G:?}\nrho = {RHO:?}\nCdS_drogue = {m_drogue:?}\n\
         CdS_main = {m_main:?}\ndrogue_t_fill = {:?}\nmain_t_fill = {:?}\n",
        fill.0, fill.1
    )
}

#[test]
fn an_open_canopy_falls_as_the_closed_form_from_rest() {
    // Opened before the start (t_open = −1 s, at once): a constant drag area throughout.
    let cds = 0.1;
    let vt = terminal(cds);
    let text = format!(
        "until = 30.0\n{SETTINGS}{}drogue_t_open = -1.0\n[init]\nz = 1000.0\n",
        set(cds, 1.0, (0.0, 0.0))
    );
    let done = scene("open.toml", &text);
    let mut worst = (0.0_f64, 0.0_f64);
    for row in rows(&done, &["z", "z'", "drogue_cds"]) {
        let (t, z, v, c) = (row[0], row[1], row[2], row[3]);
        assert_eq!(c, cds, "the drag area at t = {t}");
        let (z_exact, v_exact) = fall(vt, (0.0, 1000.0, 0.0), t);
        worst.0 = worst.0.max((z - z_exact).abs() / 1000.0);
        worst.1 = worst.1.max((v - v_exact).abs() / vt);
    }
    println!(
        "open canopy from rest: worst |Δz|/z0 {:.2e}, |Δv|/v_t {:.2e}",
        worst.0, worst.1
    );
    // Measured 1.3e-14 and 7.5e-13 (DOP853 at 1e-12): 1e-10.
    assert!(worst.0 < 1e-10 && worst.1 < 1e-10, "{worst:?}");
}

#[test]
fn the_drogue_opens_a_lag_after_apogee_and_descends_as_the_closed_form() {
    let (v0, lag, fill) = (50.0, 1.5, 0.5);
    let cds = 0.0356;
    let vt = terminal(cds);
    let text = format!(
        "until = 40.0\nstop_when = \"z < 0\"\n{SETTINGS}{}[init]\nz = 0.0\n\"z'\" = {v0:?}\n\
         [[phase]]\nwhen = \"z' < 0\"\nset = {{ drogue_t_open = \"t + {lag:?}\" }}\n",
        set(cds, 1.0, (fill, 0.0))
    );
    let done = scene("apogee.toml", &text);
    let apogee = v0 / G;
    let change = &done.changes[0];
    // The apogee located against t_a = v₀/g: measured 8.9e-16 s (one ulp); 1e-13 s.
    println!("apogee at {} (exact {apogee})", change.time);
    assert!((change.time - apogee).abs() < 1e-13, "{}", change.time);
    let t_open = change.time + lag;
    assert_eq!(change.set, [("drogue_t_open".to_string(), t_open)]);
    let rows = rows(&done, &["z", "z'", "drogue_cds", "T_OPEN", "phase"]);
    let (mut free, mut open) = (0.0_f64, 0.0_f64);
    for row in &rows {
        let (t, z, v, c, recorded) = (row[0], row[1], row[2], row[3], row[4]);
        // The recorded expression reads the value set at the change (phase 2 on), the
        // default (1e30 s, never) before.
        let expected = if row[5] == 2.0 { t_open } else { 1e30 };
        assert_eq!(recorded, expected, "at {t}");
        if t <= t_open {
            assert_eq!(c, 0.0, "closed at {t}");
            free = free.max((z - (v0 * t - G * t * t / 2.0)).abs() + (v - (v0 - G * t)).abs());
        } else if t < t_open + fill {
            assert!(
                (c - cds * (t - t_open) / fill).abs() <= 1e-15,
                "inflating at {t}: {c}"
            );
        } else {
            assert_eq!(c, cds, "open at {t}");
        }
    }
    let t1 = row_at(&rows, t_open + fill);
    assert!(
        t1.2.abs() < vt,
        "v₁ = {} is below v_t = {vt}: the tanh form",
        t1.2
    );
    for row in rows.iter().filter(|r| r[0] > t1.0) {
        let (z, v) = fall(vt, t1, row[0]);
        open = open
            .max((row[1] - z).abs() / 127.0)
            .max((row[2] - v).abs() / vt);
    }
    println!("free fall to the opening: {free:.2e} m; open: {open:.2e}");
    // Measured 4.1e-13 (m plus m/s) and 4.2e-13 (relative to the apogee height, v_t).
    assert!(free < 1e-11 && open < 1e-10, "{free:e} {open:e}");
}

#[test]
fn a_drogue_then_a_main_land_where_the_closed_forms_say() {
    // models/recovery_descent.toml: 120 m/s up, the drogue (v_t 30.0 m/s, 0.5 s to fill)
    // 1.5 s after apogee, the main (v_t 5.0 m/s, 1 s to fill) 1 s after z = 450 on the way
    // down, the drogue cut away as the main opens; the landing at z = 0.
    let done = run_file(Path::new(&model("recovery_descent.toml"))).expect("runs");
    assert!(done.failure.is_none());
    assert_eq!(done.stopped_by.as_deref(), Some("z < 0"));
    let (drogue, main) = (terminal(0.0356), terminal(1.28));
    let rows = rows(&done, &["z", "z'", "drogue_cds", "main_cds"]);
    let [apogee, below] = &done.changes[..] else {
        panic!("{:?}", done.changes)
    };
    assert!((apogee.time - 120.0 / G).abs() < 1e-13, "{}", apogee.time);
    // The drogue fully open 2 s after apogee; its closed form to z = 450.
    let d1 = row_at(&rows, apogee.time + 2.0);
    let predicted = time_to(drogue, d1, 450.0);
    println!("main's trigger at {} (closed form {predicted})", below.time);
    // Measured 6.7e-14 s; 1e-10 s.
    assert!((below.time - predicted).abs() < 1e-10, "{}", below.time);
    let t_main = below.time + 1.0;
    let set: Vec<(String, f64)> = ["drogue_t_cut", "main_t_open"]
        .map(|n| (n.to_string(), t_main))
        .to_vec();
    assert_eq!(below.set, set);
    // The drogue's value set at phase 2 carries into phase 3: open through the main's lag.
    let mut lag = 0.0_f64;
    for row in rows.iter().filter(|r| r[0] > below.time && r[0] <= t_main) {
        assert_eq!((row[3], row[4]), (0.0356, 0.0), "at {}", row[0]);
        let (z, v) = fall(drogue, d1, row[0]);
        lag = lag
            .max((row[1] - z).abs() / 450.0)
            .max((row[2] - v).abs() / drogue);
    }
    // The main fully open 1 s after the drogue is cut: its closed form to the ground.
    let m1 = row_at(&rows, t_main + 1.0);
    assert!(
        m1.2.abs() > main,
        "v = {} is faster than the main's v_t: the coth form",
        m1.2
    );
    let (t_land, state) = done.end.clone().expect("an end");
    let landing = time_to(main, m1, 0.0);
    let (_, v_land) = fall(main, m1, t_land);
    println!(
        "lag {lag:.2e}; landing at {t_land} (closed form {landing}), {} m/s (closed form \
         {v_land}, v_t {main})",
        state[1] / M0
    );
    // Measured 5.8e-14 (relative), 5.4e-13 s and 1.1e-11 m/s.
    assert!(lag < 1e-11, "{lag:e}");
    assert!(
        (t_land - landing).abs() < 1e-10,
        "{t_land} against {landing}"
    );
    assert!((state[1] / M0 - v_land).abs() < 1e-10);
    assert!(state[0].abs() < 1e-9, "z = {} at the landing", state[0]);
    // 81 s under the main: coth has reached 1, the landing speed is the main's terminal
    // speed (measured 2.2e-12 relative).
    let speed = (state[1] / M0).abs();
    assert!(
        (speed - main).abs() < 1e-10 * main,
        "{speed} against {main}"
    );
}

/// The tool on a scene whose phase 2 sets `drogue_t_open` to `value`: exit `code`, stderr.
fn refused(name: &str, value: &str, code: i32) -> String {
    let model = model("recovery_descent.vms");
    let csv = scratch(format!("{name}.csv"));
    let _ = std::fs::remove_file(&csv);
    let text = format!(
        "model = {model:?}\nuntil = 40.0\ncsv = {:?}\n{}[init]\nz = 0.0\n\"z'\" = 50.0\n\
         [[phase]]\nwhen = \"z' < 0\"\nset = {{ drogue_t_open = {value} }}\n",
        csv.display().to_string(),
        set(0.0356, 1.0, (0.5, 0.0))
    );
    let path = scratch_file(&format!("{name}.toml"), &text);
    let (_, stderr) = run(&["run", &path], code);
    stderr
}

#[test]
fn a_bad_value_set_at_a_change_is_a_message() {
    let unknown = refused("unknown", "\"t + lagg\"", 2);
    assert!(
        unknown.contains("`lagg` is not a parameter") && unknown.contains(":17:"),
        "{unknown}"
    );
    let malformed = refused("malformed", "\"t + * 2\"", 2);
    assert!(
        malformed.contains("`t + * 2`") && malformed.contains("drogue_t_open"),
        "{malformed}"
    );
    let infinite = refused("infinite", "\"t + 1/0\"", 2);
    assert!(
        infinite.contains("inf") && infinite.contains("finite"),
        "{infinite}"
    );
    let motion = refused("motion", "\"z' + 1\"", 2);
    assert!(motion.contains("quantity of the motion"), "{motion}");
    let boolean = refused("boolean", "true", 2);
    assert!(boolean.contains("a number, or an expression"), "{boolean}");
    // Finite until the run reaches the change, where √(t − 100) is NaN: exit 1 there, the
    // points so far written.
    let late = refused("late", "\"t + sqrt(t - 100)\"", 1);
    assert!(
        late.contains("phase 2") && late.contains("NaN at the change"),
        "{late}"
    );
    let text = std::fs::read_to_string(scratch("late.csv")).expect("the points so far");
    assert!(text.lines().count() > 2, "{text}");
}

#[test]
fn the_three_dimensional_canopy_slows_a_body_along_its_line() {
    // lib/parachute.vms on a body moving in three dimensions without gravity: the force
    // −½ρC|V|V is along −V, so the direction û of V stays and the speed s obeys
    // m ṡ = −½ρC s², s = s₀/(1 + k s₀ τ) with k = ρC/(2m) and τ = t − t_open; the position
    // moves along û by ∫ s dτ = ln(1 + k s₀ τ)/k. Before t_open (1 s) the body coasts.
    let path = common::data("recovery/coast_3d.vms");
    let (cds, v0) = (0.5, [3.0, -4.0, 12.0]);
    let sets = [
        "m0=2",
        "g=0",
        "rho=1.225",
        "CdS=0.5",
        "chute_t_open=1",
        "chute_t_fill=0",
    ];
    let mut args = vec!["run", path.as_str(), "--until", "10", "--method", "dop853"];
    args.extend(["--tol", "1e-12", "--record", "x,y,z,x',y',z'"]);
    let init: Vec<String> = (["x'", "y'", "z'"].iter().zip(v0))
        .map(|(n, v)| format!("{n}={v:?}"))
        .chain(["x=0".to_string(), "y=0".to_string(), "z=0".to_string()])
        .collect();
    for i in &init {
        args.extend(["--init", i.as_str()]);
    }
    for s in &sets {
        args.extend(["--set", s]);
    }
    let table = common::written(&args, "coast_3d.csv");
    let (_, rows) = common::csv(&table);
    let s0 = 13.0_f64;
    let k = RHO * cds / (2.0 * M0);
    let mut worst = 0.0_f64;
    for row in &rows {
        let tau = (row[0] - 1.0).max(0.0);
        let along = (1.0 + k * s0 * tau).ln() / k + row[0].min(1.0) * s0;
        let speed = s0 / (1.0 + k * s0 * tau);
        for i in 0..3 {
            let u = v0[i] / s0;
            worst = worst.max((row[1 + i] - u * along).abs() / along.max(1.0));
            worst = worst.max((row[4 + i] - u * speed).abs() / s0);
        }
    }
    println!("3-D canopy: worst {worst:.2e}");
    // Measured 1.0e-14 (DOP853 at 1e-12); 1e-11.
    assert!(worst < 1e-11, "{worst:e}");
}
