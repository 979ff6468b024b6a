//! A scene whose phase change moves the mass against its `carry` rule is refused at the
//! change with its time (docs/scenes.md): before, it ran with a negative "kinetic energy
//! removed" and exit 0.

mod common;

use common::{root, scratch_file, varmass};

/// `models/two_stage_rocket.toml` with its separation's `carry` and stage 2's mass
/// replaced, expecting exit `code`; returns stderr.
fn fly(carry: &str, mass: &str, code: i32) -> String {
    let scene = std::fs::read_to_string(root("models/two_stage_rocket.toml"))
        .expect("the scene is read")
        .replace("two_stage_rocket.vms", &root("models/two_stage_rocket.vms"))
        .replace("carry = \"separation\"", &format!("carry = \"{carry}\""))
        .replace("m = 300.0 }", &format!("m = {mass} }}"));
    let path = scratch_file(&format!("scene_carry_{carry}_{mass}.toml"), &scene);
    varmass(&["run", &path], code).1
}

/// Stage 1 burns from 1000 kg at 10 kg/s to 500 kg at t = 50 s; entering stage 2 with
/// 300 kg by a capture (mass lost at the same p: T rises by p²/2·(1/300 − 1/500)) or with
/// 700 kg by a separation (mass gained at the same q̇) is refused at t = 50 s, exit 1, with
/// the rule to use. The scene as written (separation to 300 kg) runs.
#[test]
fn a_change_against_its_carry_rule_is_refused_with_its_time() {
    for (carry, mass) in [("capture", "300.0"), ("separation", "700.0")] {
        let stderr = fly(carry, mass, 1);
        let prefix = "the run failed at t = ";
        let time: f64 = stderr
            .lines()
            .find_map(|l| l.split_once(prefix))
            .and_then(|(_, rest)| rest.split(':').next()?.parse().ok())
            .unwrap_or_else(|| panic!("no time: {stderr}"));
        assert!((time - 50.0).abs() < 1e-9, "{time}");
        assert!(
            stderr.contains("a separation must not add mass"),
            "{stderr}"
        );
        assert!(stderr.contains("carry = \"capture\""), "{stderr}");
    }
    fly("separation", "300.0", 0);
}
