//! `varmass run SCENE.toml --sensitivity NAME` (docs/sensitivities.md#scenes): a scene's
//! derivative columns through its rail and its changes, against closed forms derived by hand,
//! and the refusals of what a scene's sensitivities do not follow yet.

#[path = "../../tests/rail_support/mod.rs"]
mod rail_support;

mod common;

use common::{csv, model, scratch, scratch_file, varmass};
use rail_support::{flight, richardson, G, MU, M_D, M_P, U_E};

/// The columns `names` of the last row of the CSV at `path`.
fn last_row(path: &std::path::Path, names: &[String]) -> Vec<f64> {
    let (header, rows) = csv(path);
    let row = rows.last().expect("a row");
    let at = |name: &String| {
        let i = header.iter().position(|h| h == name);
        row[i.unwrap_or_else(|| panic!("{name} in {header:?}"))]
    };
    names.iter().map(at).collect()
}

/// The six-degree-of-freedom rocket of models/rocket_on_rail.toml (its reference point the
/// centre of mass, so the rail couples with nothing): on the rail's bottom until 6.49 s, up
/// the rail to its exit at 13.26 s, free to 16 s. Its ∂(x, z, x', z')/∂(m0, μ, g, u_e) at
/// 16 s against the point rocket's closed form (tests/rail_support's `flight`, derived
/// there; the attitude held on the rail and the thrust along the axis afterwards make the
/// 6-dof flight the point rocket's), m0 = m_d + m_p(0) moved by `init:m_p`.
#[test]
fn a_scene_on_its_rail_has_the_closed_forms_derivatives() {
    let table = scratch("rail_sensitivities.csv");
    let path = model("rocket_on_rail.toml");
    let columns = ["init:m_p", "mu", "g", "u_e"];
    let mut args = vec!["run", &path, "--csv"];
    let table_name = table.display().to_string();
    args.push(&table_name);
    for c in columns {
        args.extend(["--sensitivity", c]);
    }
    varmass(&args, 0);
    let p = [M_D + M_P, MU, G, U_E];
    let mut worst: f64 = 0.0;
    for (i, c) in columns.iter().enumerate() {
        let names = ["x", "z", "x'", "z'"].map(|x| format!("d({x})/d({c})"));
        let run = last_row(&table, &names);
        let by_hand = richardson(|p| flight(p, 16.0), &p, i);
        eprintln!("{c}: run {run:?}\n  by hand {by_hand:?}");
        for (a, b) in run.iter().zip(by_hand) {
            worst = worst.max((a - b).abs() / (b.abs() + 1.0));
        }
    }
    eprintln!("worst {worst:e}");
    // Measured 4.5e-10 (∂x'/∂μ); bound 2e-9 (tests/sensitivities_supports.rs's).
    assert!(worst < 2e-9, "{worst:e}");
}

/// A column that does not move the body along its rail — the aerodynamic damping k_a of a
/// flight without rotation — has velocities of rounding alone on the rail (refused there
/// before the rail's check had an absolute floor: the review of this change), and no
/// effect on the flight: every derivative 0 (the closed form does not hold k_a).
#[test]
fn a_scene_column_that_does_not_move_the_body_passes_its_rail() {
    let table = scratch("rail_damping.csv");
    let path = model("rocket_on_rail.toml");
    let table_name = table.display().to_string();
    varmass(
        &["run", &path, "--csv", &table_name, "--sensitivity", "k_a"],
        0,
    );
    let names = ["x", "z", "x'", "z'", "m_p"].map(|x| format!("d({x})/d(k_a)"));
    let largest = last_row(&table, &names)
        .iter()
        .fold(0.0_f64, |m, d| m.max(d.abs()));
    // Measured 0 exactly; bound 1e-12.
    assert!(largest < 1e-12, "{largest:e}");
}

/// The two-stage rocket of models/two_stage_rocket.toml: stage 1 burns to m = 500 kg at
/// T₁ = (M₁ − 500)/μ₁ = 50 s, the separation sets m = 300 kg, stage 2 burns to 150 s. By
/// hand (tests/sensitivities_phases.rs derives the flight) v(150) = u₁ ln(M₁/500) − g T₁ +
/// u₂ ln(300/m₂) − g (150 − T₁) with m₂ = 300 − μ₂ (150 − T₁), so ∂v/∂g = −150 (T₁ does not
/// move with g), ∂v/∂M₁ = u₁/M₁ − u₂ μ₂/(μ₁ m₂) = −3.5, ∂v/∂v₀ = 1, ∂m/∂M₁ = μ₂/μ₁ = 0.2,
/// ∂m/∂g = 0; and the change's time moves with M₁ (the separation's own `d(t)` is not a
/// column: the last point is at a fixed time, d(t)/d(w) = 0 there).
#[test]
fn a_scene_carries_its_columns_across_a_separation() {
    let table = scratch("two_stage_sensitivities.csv");
    let path = model("two_stage_rocket.toml");
    let table_name = table.display().to_string();
    let args = [
        "run",
        &path,
        "--csv",
        &table_name,
        "--sensitivity",
        "g",
        "--sensitivity",
        "init:m",
        "--sensitivity",
        "init:y'",
    ];
    varmass(&args, 0);
    let names = [
        "d(y')/d(g)",
        "d(m)/d(g)",
        "d(y')/d(init:m)",
        "d(m)/d(init:m)",
        "d(y')/d(init:y')",
        "d(t)/d(init:m)",
    ]
    .map(String::from);
    let run = last_row(&table, &names);
    let by_hand = [-150.0, 0.0, -3.5, 0.2, 1.0, 0.0];
    let worst =
        (run.iter().zip(by_hand)).fold(0.0_f64, |m, (a, b)| m.max((a - b).abs() / (b.abs() + 1.0)));
    eprintln!("two stages: run {run:?}, by hand {by_hand:?}, worst {worst:e}");
    // Measured 1.2e-14 (∂v/∂g −149.99999999999915); bound 1e-9.
    assert!(worst < 1e-9, "{worst:e}");
}

/// The vertical rocket of two_stage_rocket.vms from m(0) = M, ẏ(0) = v₀: it burns μ = 10
/// kg/s at u_e until the fixed time t₁ = 30 s, where a change sets μ = 0 (the change's
/// time does not move: dτ/dw = 0); it coasts to its apogee, where the change on `y' < 0`
/// sets μ = 5 (the apogee's time t_a moves with every column: dτ/dw = −(∂ẏ/∂w)/ÿ), and
/// burns again to T = 100 s. By hand, with m₁ = M − 10 t₁:
///   v₁ = v₀ + u_e ln(M/m₁) − g t₁,  y₁ = v₀ t₁ + u_e (t₁ − (m₁/10) ln(M/m₁)) − ½ g t₁²;
///   t_a = t₁ + v₁/g,  y_a = y₁ + v₁²/(2g);
///   τ = T − t_a, m = m₁ − 5τ: v = u_e ln(m₁/m) − g τ, y = y_a + u_e (τ − (m/5) ln(m₁/m)) − ½ g τ².
fn apogee_flight(p: &[f64; 4], big_t: f64) -> [f64; 3] {
    let [g, u_e, big_m, v0] = *p;
    let t1 = 30.0;
    let m1 = big_m - 10.0 * t1;
    let v1 = v0 + u_e * (big_m / m1).ln() - g * t1;
    let y1 = v0 * t1 + u_e * (t1 - m1 / 10.0 * (big_m / m1).ln()) - 0.5 * g * t1 * t1;
    let t_a = t1 + v1 / g;
    let y_a = y1 + v1 * v1 / (2.0 * g);
    let tau = big_t - t_a;
    let m = m1 - 5.0 * tau;
    let v = u_e * (m1 / m).ln() - g * tau;
    let y = y_a + u_e * (tau - m / 5.0 * (m1 / m).ln()) - 0.5 * g * tau * tau;
    [y, v, m]
}

/// The derivatives of [`apogee_flight`]'s (y, v, m) at 100 s by (g, u_e, M, v₀) at (9.81,
/// 2500, 1000, 5), by mpmath at 40 digits (`mpmath.diff` of the same closed form written
/// in mpmath: `python3 -c` with mp.dps = 40, each rounded to f64). Richardson's central
/// differences of the f64 closed form (the rail test's reference) are only good to 1.5e-9
/// relative here (∂y/∂v₀: 83.854505179 for 83.854505047).
const APOGEE_DERIVATIVES: [[f64; 3]; 4] = [
    [-3524.213940603743, 77.26773642178078, -46.58788956778334],
    [24.51068577597606, -0.27169001850843966, 0.18179151067213678],
    [-72.85259296121764, 0.7728644770102198, 0.45391000436872],
    [83.85450504716574, -0.9393565384870808, 0.509683995922528],
];

/// [`apogee_flight`] as a scene with a change at a fixed time and one at the apogee: its
/// columns ∂(y, y', m)/∂(g, u_e, M, v₀) at 100 s against the closed form's
/// ([`APOGEE_DERIVATIVES`]; Richardson's differences of [`apogee_flight`] agree with those
/// to 1.5e-9). Before the core had velocity and time events the scene was refused (a
/// change's time needed its gradient).
#[test]
fn a_scene_carries_its_columns_across_a_fixed_time_and_an_apogee() {
    let scene = format!(
        "model = \"{}\"\nuntil = 100.0\nmethod = \"dop853\"\ntol = 1e-12\n\
         record = [\"y\", \"y'\", \"m\"]\n\
         [set]\nmu = 10.0\nu_e = 2500.0\ng = 9.81\n\
         [init]\ny = 0.0\n\"y'\" = 5.0\nm = 1000.0\n\
         [[phase]]\nwhen = \"t = 30\"\nset = {{ mu = 0.0 }}\n\
         [[phase]]\nwhen = \"y' < 0\"\nset = {{ mu = 5.0 }}\n",
        model("two_stage_rocket.vms")
    );
    let path = scratch_file("apogee_scene.toml", &scene);
    let table = scratch("apogee_scene.csv").display().to_string();
    let columns = ["g", "u_e", "init:m", "init:y'"];
    let mut args = vec!["run", &path, "--csv", &table];
    for c in columns {
        args.extend(["--sensitivity", c]);
    }
    let (stdout, _) = varmass(&args, 0);
    assert!(stdout.contains("phase 3 began"), "{stdout}");
    let p = [9.81, 2500.0, 1000.0, 5.0];
    let mut worst: f64 = 0.0;
    for (i, c) in columns.iter().enumerate() {
        let names = ["y", "y'", "m"].map(|x| format!("d({x})/d({c})"));
        let run = last_row(std::path::Path::new(&table), &names);
        let differences = richardson(|p| apogee_flight(p, 100.0), &p, i);
        let exact = APOGEE_DERIVATIVES[i];
        eprintln!("{c}: run {run:?}\n  exact {exact:?}");
        for ((a, b), d) in run.iter().zip(exact).zip(differences) {
            worst = worst.max((a - b).abs() / (b.abs() + 1.0));
            // The stored values are the closed form's: its own differences agree.
            assert!(
                (d - b).abs() <= 3e-9 * (b.abs() + 1.0),
                "{c}: {d} against {b}"
            );
        }
    }
    eprintln!("worst {worst:e}");
    assert!(worst < 1e-11, "{worst:e}");
}

/// What a scene's sensitivities do not follow is refused before the first step (exit 2): a
/// column of a parameter a later phase sets (stage 2's own μ; g set again to its own value:
/// the scene fixes it there), the initial position of a body on a rail (the rail is laid
/// from it), a phase ending on a quantity (`H > 1e9`: its gradient is not carried), a value
/// set at a change by an expression, an unknown name.
#[test]
fn what_a_scenes_sensitivities_do_not_follow_is_refused() {
    let two_stage = model("two_stage_rocket.toml");
    let (_, set) = varmass(&["run", &two_stage, "--sensitivity", "mu"], 2);
    assert!(set.contains("sets `mu`"), "{set}");
    let (_, unknown) = varmass(&["run", &two_stage, "--sensitivity", "u_d"], 2);
    assert!(unknown.contains("u_e"), "{unknown}");
    let rail = model("rocket_on_rail.toml");
    let (_, laid) = varmass(&["run", &rail, "--sensitivity", "init:x"], 2);
    assert!(laid.contains("`[rail]` fixes this initial value"), "{laid}");
    let text = std::fs::read_to_string(&two_stage).expect("the scene");
    let text = text.replace(
        "model = \"two_stage_rocket.vms\"",
        &format!("model = \"{}\"", model("two_stage_rocket.vms")),
    );
    // A change on a quantity (the energy H): its gradient is not carried.
    let energy = text.replace("when = \"m = 500\"", "when = \"H > 1e9\"");
    let energy = scratch_file("energy_two_stage.toml", &energy);
    let (_, on_energy) = varmass(&["run", &energy, "--sensitivity", "g"], 2);
    assert!(on_energy.contains("ends on `H > 1e9`"), "{on_energy}");
    let same = text.replace("u_e = 3000.0 }", "u_e = 3000.0, g = 9.81 }");
    let same = scratch_file("same_g_two_stage.toml", &same);
    let (_, set_again) = varmass(&["run", &same, "--sensitivity", "g"], 2);
    assert!(set_again.contains("sets `g`"), "{set_again}");
    let timed = text.replace("u_e = 3000.0 }", "u_e = \"3000 + 0*t\" }");
    let timed = scratch_file("timed_two_stage.toml", &timed);
    let (_, at_change) = varmass(&["run", &timed, "--sensitivity", "g"], 2);
    assert!(
        at_change.contains("sets a value at its change"),
        "{at_change}"
    );
}
