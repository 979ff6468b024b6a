//! Calisto's full flight in six degrees of freedom (issue 36): `flights/calisto/
//! calisto_flight.toml` — calisto.toml's ascent from the rail, the drogue 1.5 s after apogee,
//! the main 1.5 s after the 800 m crossing on the way down (the drogue cut away), to landing,
//! at tol 1e-8 — against the closed-form terminal speeds and against RocketPy 1.13's descent
//! (benches/peers/rocketpy/calisto_descent.py, row `cm_sign_vdot_axial_thomson` of
//! calisto_descent.csv: the ascent with RocketPy's sign errors corrected, which this model
//! meets to 8.2e-7 of apogee in cli/tests/calisto_6dof.rs, the parachutes' noise off, LSODA
//! at rtol 1e-9). docs/validation.md#calistos-full-flight has the figures.
//!
//! Under a canopy calisto.vms flies RocketPy's Flight.u_dot_parachute: the canopies' drag
//! D = -1/2 rho CdS |V| V with V the free-stream airspeed at the reference point, the
//! airframe's own forces off, and the canopy's added mass m_a = k rho (2/3) pi R^2 h (k =
//! 1.068 (1 - 1.465 p - 0.25975 p^2 + 1.2626 p^3) = 1.0000 at the porosity p = 0.0432, R = h =
//! 1.5 m): (m + m_a) a = D + W. After burnout the reference point is the centre of mass, so
//! this is the particle's motion exactly, whatever the attitude does (RocketPy freezes it;
//! here the riser damps the rotation to rest with a time constant of 1 s).
//!
//! Terminal speed, derived by hand: the horizontal airspeed decays (the canopy drags the
//! rocket to the wind's speed), and the vertical descent speed v obeys
//! (m + m_a) dv/dt = m g - 1/2 rho CdS v^2. At a fixed density it tends to
//! v_t = sqrt(2 m g / (rho CdS)). The density rises as the rocket descends, so v_t falls, at
//! dv_t/dt = -(v_t / (2 rho)) d(rho)/dt = -v_t^2 / (2 H) with H = -rho / (d rho / dz) the
//! density's scale height (d rho/dt = -v d rho/dz, v ≈ v_t); the speed follows it with a lag:
//! writing v = v_t (1 + e), the equation to first order in e gives (m + m_a) dv_t/dt =
//! -2 m g e, so e = (m + m_a) v_t^2 / (4 m g H). In the 1976 atmosphere's troposphere rho ∝
//! (T/T0)^(g M0/(R* L) - 1), T = T0 - L h, so 1/H = (g M0/(R* L) - 1) L / T (h the altitude
//! above sea level, geopotential; the factor (r0/(r0 + h))^2 between geopotential and
//! geometric height left out of 1/H makes e 4.3e-4 of itself too large: 4.7e-8 at landing, so
//! the main's residual is within that, not the next order; review of session 37).
//! Under the drogue (CdS 1 m^2) at the main's trigger, 800 m above the pad: v_t = 17.970 m/s,
//! e = 1.19e-3, and the run's v / v_t - 1 - e = 4.1e-6 (the next order, e^2 and the change
//! of dv_t/dt; bound 2e-5, against e 60 times larger). Under the main (CdS 10 m^2) at landing:
//! v_t = 5.4596 m/s, e = 1.10e-4, residual -1.4e-8 (bound 1e-7).
//!
//! RocketPy checks its triggers at the sampling instants k/105 s: the drogue's at the first
//! instant after apogee (6.30 ms after it), the main's at the first after the 800 m crossing
//! (4.85 ms after it, the height there 799.9128 m at 17.991 m/s down); the run here adds those
//! delays to the lags, and then meets RocketPy's landing: measured -0.26 ms of landing time
//! (-9e-7), +1.7 mm East and +7.9 mm North of the landing point (the apogee's place differs
//! by as much: the ascent's 8.2e-7), the 800 m crossing -0.21 ms, the landing speed 3.5e-7 faster
//! (RocketPy's air constant 287.05287 against the 1976 R*/M0 = 287.05307 of ours: its
//! density 7.0e-7 higher, its terminal speed 3.5e-7 lower)
//! (bounds 2 ms, 3 cm, 1 ms, 2e-6). With the triggers continuous (the scene as it is) it
//! lands 13.6 ms later (drogue 6.3 ms earlier, main 4.85 ms earlier: 11 ms of it), not
//! asserted.

mod common;

use common::{column, csv, root, scratch, scratch_file, varmass};

use std::collections::HashMap;

/// RocketPy's row `config` of calisto_descent.csv, by column name.
fn rocketpy(config: &str) -> HashMap<String, f64> {
    let path = root("benches/peers/rocketpy/calisto_descent.csv");
    let text = std::fs::read_to_string(path).expect("RocketPy's stored descent");
    let mut lines = text.lines();
    let names: Vec<&str> = lines.next().expect("a header").split(',').collect();
    let row: Vec<&str> = lines
        .map(|l| l.split(',').collect::<Vec<_>>())
        .find(|f| f[0] == config)
        .unwrap_or_else(|| panic!("no row {config}"));
    names
        .iter()
        .zip(row)
        .skip(1)
        .map(|(n, v)| (n.to_string(), v.parse().expect("a number")))
        .collect()
}

/// The 1976 atmosphere's density scale height (m) in its troposphere at `h` m above sea
/// level: 1/H = (g M0/(R* L) - 1) L / T, T = T0 - L h.
fn scale_height(h: f64) -> f64 {
    let (g, m0, r_star, lapse, t0) = (9.80665, 0.0289644, 8.3144598, 0.0065, 288.15);
    let exponent = g * m0 / (r_star * lapse) - 1.0;
    (t0 - lapse * h) / (exponent * lapse)
}

/// The descent speed's excess over the local terminal speed, v / v_t - 1 - e (the module's
/// doc), at a row: `cds` the open canopy's drag area.
fn terminal_residual(row: &[f64], col: &dyn Fn(&str) -> usize, cds: f64) -> f64 {
    let (g, porosity, r, h): (f64, f64, f64, f64) = (9.80665, 0.0432, 1.5, 1.5);
    let rho = row[col("air_rho")];
    let m = 16.241 + row[col("m_s")] - 1.0;
    let v = -row[col("z'")];
    let v_t = (2.0 * m * g / (rho * cds)).sqrt();
    let k =
        1.068 * (1.0 - 1.465 * porosity - 0.25975 * porosity.powi(2) + 1.2626 * porosity.powi(3));
    let m_a = k * rho * (2.0 / 3.0) * std::f64::consts::PI * r * r * h;
    let e = (m + m_a) * v_t * v_t / (4.0 * m * g * scale_height(1400.0 + row[col("z")]));
    println!(
        "v {v:.6} v_t {v_t:.6} e {e:.3e} residual {:.2e}",
        v / v_t - 1.0 - e
    );
    v / v_t - 1.0 - e
}

#[test]
fn calisto_lands_at_the_terminal_speeds_and_where_rocketpy_lands() {
    let rp = rocketpy("cm_sign_vdot_axial_thomson");
    let drogue_delay = rp["drogue_trigger"] - rp["apogee_time"];
    let main_delay = (800.0 - rp["main_trigger_height"]) / -rp["main_trigger_vz"];
    let main_crossing = rp["main_trigger"] - main_delay;
    let text = std::fs::read_to_string(root("flights/calisto/calisto_flight.toml")).unwrap();
    let model = root("flights/calisto/calisto.vms");
    let text = text
        .replace("model = \"calisto.vms\"", &format!("model = {model:?}"))
        .replace(
            "drogue_t_open = \"t + 1.5\"",
            &format!("drogue_t_open = \"t + {}\"", 1.5 + drogue_delay),
        )
        .replace("\"t + 1.5\"", &format!("\"t + {}\"", 1.5 + main_delay));
    let path = scratch_file("calisto_flight.toml", &text);
    let table = scratch("calisto_flight.csv");
    let _ = std::fs::remove_file(&table);
    let (summary, _) = varmass(&["run", &path, "--csv", table.to_str().unwrap()], 0);
    assert!(
        summary.contains("in phase 3 of 3 (stop_when 'z < 0')"),
        "{summary}"
    );
    let (names, rows) = csv(&table);
    let col = |n: &str| column(&names, n);
    let phase = |r: &Vec<f64>| r[col("phase")] as usize;
    let apogee = rows.iter().rfind(|r| phase(r) == 1).expect("an ascent");
    let crossing = rows
        .iter()
        .rfind(|r| phase(r) == 2)
        .expect("a drogue phase");
    let landing = rows.last().unwrap();
    let near = |what: &str, ours: f64, theirs: f64, bound: f64| {
        println!(
            "{what}: ours {ours:.7} RocketPy {theirs:.7} ({:+.2e})",
            ours - theirs
        );
        assert!(
            (ours - theirs).abs() < bound,
            "{what}: {ours} against {theirs}"
        );
    };
    near(
        "apogee (m)",
        apogee[col("z")],
        rp["apogee"],
        3e-6 * rp["apogee"],
    );
    near(
        "800 m crossing (s)",
        crossing[col("t")],
        main_crossing,
        1e-3,
    );
    near(
        "landing time (s)",
        landing[col("t")],
        rp["landing_time"],
        2e-3,
    );
    near("landing x (m)", landing[col("x")], rp["landing_x"], 0.03);
    near("landing y (m)", landing[col("y")], rp["landing_y"], 0.03);
    let vz = rp["landing_vz"];
    near(
        "landing speed (m/s)",
        landing[col("z'")],
        vz,
        2e-6 * vz.abs(),
    );
    // under the drogue, at the main's trigger; under the main, at landing
    assert!(terminal_residual(crossing, &col, 1.0).abs() < 2e-5);
    assert!(terminal_residual(landing, &col, 10.0).abs() < 1e-7);
    // the canopy has brought the rocket to the wind's speed (3, -4) m/s
    assert!((landing[col("x'")] - 3.0).abs() < 1e-6 && (landing[col("y'")] + 4.0).abs() < 1e-6);
}
