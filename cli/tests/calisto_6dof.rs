//! RocketPy's getting-started Calisto in six degrees of freedom (issue 36's first item):
//! the scene `flights/calisto/calisto.toml` (model `calisto.vms`: from the rail to apogee, a
//! quaternion attitude, the propellant a state mass at the grains, the exhaust an outflow
//! at the nozzle, the 1976 air, a constant wind, the Barrowman airframe, axial power-on and
//! power-off drag) run by the tool, against RocketPy 1.13 run by
//! `benches/peers/rocketpy/calisto.py` (row `all` of calisto.csv: its known differences
//! corrected, rtol 1e-9) and `calisto_6dof.py` (calisto_6dof.csv: the same flight with
//! pieces switched). docs/validation.md#calisto-in-six-degrees-of-freedom has the figures.
//!
//! What the gap to `all` is (+14.1 m of apogee, 0.44 %): RocketPy 1.13's
//! `Flight.u_dot_generalized` takes `Rocket.com_to_cdm_function` and `nozzle_to_cdm` — the
//! vectors FROM the centre of mass (the nozzle) TO the centre of dry mass — as r_CM and
//! r_NOZ, the positions OF them, in the body frame where it places the aerodynamic surfaces
//! the right way round: it flies the propellant 0.753 m forward of the dry centre instead of
//! 0.753 m aft, so the aerodynamic forces' moments are taken about a centre of mass
//! 2 z_g m_p/m (0.232 m, 1.83 calibers at ignition; 0.213 m at rail exit) too far forward:
//! a stiffer weathercock into the wind (its pitch rate 1.74 times ours just off the rail).
//! One term of its translation equation, −(r_CM × ω̇), is written for the opposite
//! convention, so that the two errors cancel there as RocketPy ships it; correcting the
//! offsets' sign needs that term as −(ω̇ × r_CM) too (review of session 36). Measured below:
//! RocketPy with both corrected, its remaining spurious axial force −m r̈_CM − 2ṁ ṙ_CM
//! (= −m̈ (z_g − r_CM), the kind `all` removes) dropped, and its internal-flow Coriolis force
//! 2ṁ (r_NOZ − r_CM) halved to Thomson's ṁ (r_NOZ − r_CM) — this model's physics
//! (docs/mechanics.md: internal flow of negligible momentum), a difference of model and not
//! an error — meets this model to 8.2e-7 of apogee (calisto_6dof.py's
//! `cm_sign_vdot_axial_thomson`); and this model with the propellant and nozzle mirrored
//! (RocketPy's error put in) meets `all` to 1.7e-4.

mod common;

use common::{column, csv, root, scratch, scratch_file, varmass};

use std::collections::HashMap;

/// One flight's figures: apogee height (m above the pad, of the reference point) and time,
/// rail-exit speed, max speed, static margin at t = 0 and at rail exit (calibers).
#[derive(Debug, Clone, Copy)]
struct Figures {
    apogee: f64,
    apogee_time: f64,
    rail_exit_speed: f64,
    max_speed: f64,
    margin_0: f64,
    margin_exit: f64,
}

impl Figures {
    /// The figures in calisto.csv's order, with their names.
    fn named(&self) -> [(&'static str, f64); 6] {
        [
            ("apogee", self.apogee),
            ("apogee_time", self.apogee_time),
            ("rail_exit_speed", self.rail_exit_speed),
            ("max_speed", self.max_speed),
            ("static_margin_0", self.margin_0),
            ("static_margin_rail_exit", self.margin_exit),
        ]
    }
}

/// The row `config` of RocketPy's stored output `file` (benches/peers/rocketpy/).
fn rocketpy(file: &str, config: &str) -> Figures {
    let text = std::fs::read_to_string(root(&format!("benches/peers/rocketpy/{file}")))
        .expect("RocketPy's stored output");
    let mut lines = text.lines();
    let names: Vec<&str> = lines.next().expect("a header").split(',').collect();
    let row: HashMap<&str, f64> = lines
        .map(|l| l.split(',').collect::<Vec<_>>())
        .find(|f| f[0] == config)
        .unwrap_or_else(|| panic!("no row {config} in {file}"))
        .iter()
        .zip(&names)
        .skip(1)
        .filter_map(|(v, n)| v.parse().ok().map(|v| (*n, v)))
        .collect();
    Figures {
        apogee: row["apogee"],
        apogee_time: row["apogee_time"],
        rail_exit_speed: row["rail_exit_speed"],
        max_speed: row["max_speed"],
        margin_0: row["static_margin_0"],
        margin_exit: row["static_margin_rail_exit"],
    }
}

/// The vertex of the parabola through three points (t, v): a sampled maximum refined.
/// Newton's form p(t) = v0 + d1 (t - t0) + a (t - t0)(t - t1), p'(tm) = 0.
fn vertex(t: [f64; 3], v: [f64; 3]) -> f64 {
    let d1 = (v[1] - v[0]) / (t[1] - t[0]);
    let d2 = (v[2] - v[1]) / (t[2] - t[1]);
    let a = (d2 - d1) / (t[2] - t[0]);
    let tm = (t[0] + t[1]) / 2.0 - d1 / (2.0 * a);
    v[0] + d1 * (tm - t[0]) + a * (tm - t[0]) * (tm - t[1])
}

/// Runs the Calisto scene with `set` appended as its `[set]` table (parameters of
/// calisto.vms changed), written beside nothing: the model path made absolute.
fn fly(name: &str, set: &str) -> Figures {
    let scene = root("flights/calisto/calisto.toml");
    let text = std::fs::read_to_string(&scene).expect("the scene");
    let model = root("flights/calisto/calisto.vms");
    let text = text.replace("model = \"calisto.vms\"", &format!("model = {model:?}"));
    let path = scratch_file(&format!("{name}.toml"), &format!("{text}\n{set}"));
    let table = scratch(format!("{name}.csv"));
    let _ = std::fs::remove_file(&table);
    let (summary, _) = varmass(&["run", &path, "--csv", table.to_str().unwrap()], 0);
    let exit = summary
        .lines()
        .find_map(|l| l.strip_prefix("left its rail at t = "))
        .unwrap_or_else(|| panic!("no rail exit in\n{summary}"));
    let (t_exit, rest) = exit.split_once(", at ").unwrap();
    let t_exit: f64 = t_exit.parse().unwrap();
    let rail_exit_speed: f64 = rest.trim_end_matches(" m/s").parse().unwrap();
    let (names, rows) = csv(&table);
    let col = |n: &str| -> Vec<f64> { rows.iter().map(|r| r[column(&names, n)]).collect() };
    let (t, z, speed, margin) = (col("t"), col("z"), col("speed"), col("static_margin_0"));
    let last = rows.len() - 1;
    let i = (1..last)
        .max_by(|&a, &b| speed[a].total_cmp(&speed[b]))
        .unwrap();
    let k = t
        .iter()
        .position(|&s| s == t_exit)
        .expect("a row at the exit");
    Figures {
        // stopped where z' falls through 0: the apogee, located
        apogee: z[last],
        apogee_time: t[last],
        rail_exit_speed,
        max_speed: vertex(
            [t[i - 1], t[i], t[i + 1]],
            [speed[i - 1], speed[i], speed[i + 1]],
        ),
        margin_0: margin[0],
        margin_exit: margin[k],
    }
}

/// Asserts the first `bounds.len()` figures of `ours` within `bounds` (relative) of
/// `theirs`, printing both.
fn within(what: &str, ours: Figures, theirs: Figures, bounds: &[f64]) {
    for (((name, a), (_, b)), bound) in ours
        .named()
        .iter()
        .zip(theirs.named())
        .zip(bounds.iter().copied())
    {
        let rel = (a - b) / b;
        println!("{what}: {name} ours {a:.7} RocketPy {b:.7} ({rel:+.2e})");
        assert!(
            rel.abs() < bound,
            "{what}: {name} {a} against {b}: {rel:e} relative, bound {bound:e}"
        );
    }
}

/// The acceptance: every figure within 0.5 % of RocketPy's `all` row, and the
/// bounds near what was measured (apogee +0.4376 %, its time +0.236 %, rail-exit speed
/// -1.5e-7, max speed +2.5e-5, margins 1.8e-10 and -7.4e-9 — the exit margin read 6.4e-8 s
/// before RocketPy's exit, the margin rising 0.2/s): the apogee's +14.1 m is RocketPy's sign of
/// r_CM (the module's doc). Then RocketPy with this model's physics
/// (`cm_sign_vdot_axial_thomson`: the offsets' sign and the −ω̇ × r_CM term corrected, the
/// spurious axial force dropped, Thomson's internal flow): measured −8.2e-7 of apogee
/// (−0.0027 m), −1.0e-6 of its time, −9.5e-8 of max speed (docs/validation.md); bounds 3e-6,
/// 3e-6, 3e-7.
#[test]
fn calisto_meets_rocketpy_all_within_half_a_percent_and_its_corrected_flight_closely() {
    let ours = fly("calisto_6dof", "");
    let all = rocketpy("calisto.csv", "all");
    within("all", ours, all, &[5e-3; 6]);
    let rel = |a: f64, b: f64| (a - b) / b;
    let apogee = rel(ours.apogee, all.apogee);
    assert!((apogee - 4.376e-3).abs() < 2e-5, "apogee {apogee:e}");
    let time = rel(ours.apogee_time, all.apogee_time);
    assert!((time - 2.36e-3).abs() < 2e-5, "apogee time {time:e}");
    within(
        "all, tight",
        ours,
        all,
        &[5e-3, 3e-3, 1e-6, 5e-5, 1e-9, 2e-8],
    );
    let fixed = rocketpy("calisto_6dof.csv", "cm_sign_vdot_axial_thomson");
    within("fixed", ours, fixed, &[3e-6, 3e-6, 1e-6, 3e-7, 1e-9, 2e-8]);
}

/// This model with RocketPy's error put in — the grains and the nozzle mirrored about the
/// reference point, z_g = +0.753 m and z_nozzle = +1.150 m in the equations of motion (the
/// thrust stays along the axis, the jet damping's (l - z_c)^2 is unchanged) — meets `all`:
/// measured +1.7e-4 of apogee (+0.56 m: the r_CM' terms it keeps), +9e-5 of its time; the
/// static margin is then the mirrored rocket's, not compared.
#[test]
fn calisto_with_rocketpys_sign_meets_rocketpy_all() {
    let set = "[set]\nz_g = 0.753174558217\nz_nozzle = 1.150174558217\n";
    let ours = fly("calisto_6dof_mirrored", set);
    let all = rocketpy("calisto.csv", "all");
    within("mirrored", ours, all, &[3e-4, 2e-4, 1e-6, 5e-5]);
}
