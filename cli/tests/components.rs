//! Composed models in the tool (docs/components.md): `varmass run` and a scene on a model
//! whose motor is the component `models/lib/motor_1d.vms` with its default exhaust speed,
//! `varmass derive` on two instances of it, and a bad use as a message at the use site.

use std::path::PathBuf;

mod common;

use common::output as varmass;

/// A file of `tests/data/components/`.
fn data(name: &str) -> String {
    format!(
        "{}/../tests/data/components/{name}",
        env!("CARGO_MANIFEST_DIR")
    )
}

/// The last value of each column `names` of a CSV the tool wrote.
fn final_values(csv: &PathBuf, names: &[&str]) -> Vec<f64> {
    let text = std::fs::read_to_string(csv).expect("the CSV was written");
    let header: Vec<&str> = text.lines().next().expect("a header").split(',').collect();
    let last: Vec<&str> = text.lines().last().expect("rows").split(',').collect();
    let column = |name: &&str| header.iter().position(|h| h == name).expect("recorded");
    let value = |name| last[column(name)].parse().expect("a number");
    names.iter().map(value).collect()
}

/// The rocket of `default_motor.vms` to burnout at t = 90 s (m = 1000 − 10 t reaches 100),
/// with `extra` settings: the final [t, y', m].
fn burnout(name: &str, extra: &[&str]) -> Vec<f64> {
    let csv = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let model = data("default_motor.vms");
    let mut args = vec!["run", &model, "--set", "mu=10", "--set", "g=9.81"];
    args.extend([
        "--init", "y=0", "--init", "m=1000", "--until", "90", "--tol", "1e-12",
    ]);
    args.extend([
        "--record",
        "y,y',m",
        "--csv",
        csv.to_str().expect("a UTF-8 path"),
    ]);
    args.extend(extra);
    let (code, stdout, stderr) = varmass(&args);
    assert_eq!(code, Some(0), "{stdout}\n{stderr}");
    final_values(&csv, &["t", "y'", "m"])
}

#[test]
fn a_component_default_needs_no_set_and_a_set_overrides_it() {
    // Tsiolkovsky with gravity loss at burnout: v = u_e ln(m0/m) − g t, u_e the default
    // 2500 m/s of the component, then 3000 m/s given by `--set main_u_e=3000`.
    let exact = |u_e: f64| u_e * 10f64.ln() - 9.81 * 90.0;
    for (u_e, extra) in [(2500.0, vec![]), (3000.0, vec!["--set", "main_u_e=3000"])] {
        let row = burnout(&format!("default_motor_{u_e}.csv"), &extra);
        assert!(
            (row[0] - 90.0).abs() < 1e-9 && (row[2] - 100.0).abs() < 1e-9,
            "{row:?}"
        );
        // Measured: 4.4e-14 relative for models/rocket.vms (cli/tests/run.rs); bound 1e-9.
        assert!(
            (row[1] - exact(u_e)).abs() < 1e-9 * exact(u_e),
            "{row:?} for u_e = {u_e}"
        );
    }
}

#[test]
fn a_scene_flies_a_composed_model() {
    let scene = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("default_motor.toml");
    let csv = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("default_motor_scene.csv");
    let text = format!(
        "model = {:?}\nuntil = 90.0\ntol = 1e-12\nrecord = [\"y'\", \"m\"]\n\
         [set]\nmu = 10.0\ng = 9.81\n[init]\ny = 0.0\nm = 1000.0\n",
        data("default_motor.vms")
    );
    std::fs::write(&scene, text).expect("writable");
    let scene = scene.to_str().expect("a UTF-8 path");
    let (code, stdout, stderr) = varmass(&["run", scene, "--csv", csv.to_str().expect("UTF-8")]);
    assert_eq!(code, Some(0), "{stdout}\n{stderr}");
    let v = final_values(&csv, &["y'"])[0];
    let exact = 2500.0 * 10f64.ln() - 9.81 * 90.0;
    assert!((v - exact).abs() < 1e-9 * exact, "{v} against {exact}");
}

#[test]
fn derive_shows_the_composed_model() {
    let (code, stdout, stderr) = varmass(&["derive", &data("twin_motor_rocket.vms")]);
    assert_eq!(code, Some(0), "{stdout}\n{stderr}");
    // The two motors' rates and thrusts, summed on the user's rocket.
    for line in ["dm/dt (state mass) = -2*mu", "R1_y = -2*mu*u_e"] {
        assert!(stdout.contains(line), "{line} in {stdout}");
    }
}

#[test]
fn a_bad_use_is_a_message_at_the_use_site() {
    let model = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bad_use.vms");
    std::fs::write(&model, "coordinates y\nuse \"lib/none.vms\" as gone\n").expect("writable");
    let (code, _, stderr) = varmass(&["derive", model.to_str().expect("UTF-8")]);
    // The tool's exit for a model that does not derive (no panic, whose code is 101).
    assert_eq!(code, Some(1), "{stderr}");
    assert!(
        stderr.contains("error: cannot read the component `lib/none.vms`"),
        "{stderr}"
    );
    assert!(stderr.contains("bad_use.vms:2:5"), "{stderr}");
}
