//! Jumps, failed runs and phases at the command line: a mass law that jumps is refused by
//! `check`, a failed run writes the points it computed and exits 1.

mod common;

use common::{data, model, scratch, varmass as run};

/// The 23 % example: stage separation as a `sign` in the mass law is refused at
/// `sign` (line 3, column 25 of the file), exit 1, with help pointing to phases.
#[test]
fn check_refuses_a_mass_law_that_jumps() {
    let file = data("staged_by_sign.vms");
    let (_, stderr) = run(&["check", &file], 1);
    assert!(stderr.contains("the law of `m` can jump"), "{stderr}");
    assert!(stderr.contains(&format!("--> {file}:3:25")), "{stderr}");
    assert!(stderr.contains("phases"), "{stderr}");
}

/// The rocket of `models/rocket.vms` (m0 = 1000 kg, μ = 10 kg/s) run past its burn-out at
/// t = 100 s: the run fails there (exit 1, the time and the state in the message) and the
/// CSV holds every point before it, each on m = 1000 − 10 t with m > 0.
#[test]
fn a_failed_run_writes_the_points_so_far_and_exits_1() {
    let csv = scratch("rocket_runs_out.csv");
    let model = model("rocket.vms");
    let (_, stderr) = run(
        &[
            "run",
            &model,
            "--set",
            "mu=10",
            "--set",
            "u_e=2500",
            "--set",
            "g=9.81",
            "--init",
            "y=0",
            "--init",
            "m=1000",
            "--until",
            "150",
            "--tol",
            "1e-10",
            "--record",
            "m",
            "--csv",
            csv.to_str().expect("a UTF-8 path"),
        ],
        1,
    );
    assert!(stderr.contains("the run failed at t = "), "{stderr}");
    assert!(stderr.contains("the mass `m` is not positive"), "{stderr}");
    assert!(stderr.contains("state there:"), "{stderr}");
    let text = std::fs::read_to_string(&csv).expect("the CSV was written");
    let rows: Vec<Vec<f64>> = text
        .lines()
        .skip(1)
        .map(|line| {
            line.split(',')
                .map(|v| v.parse().expect("a number"))
                .collect()
        })
        .collect();
    assert!(rows.len() > 10, "{} rows", rows.len());
    let last = rows.last().expect("rows");
    // The burn-out is at t = 100 s; the last point kept is the last one whose integrated m is
    // still positive, which rounding may put a few ulps either side of 100 (measured
    // 99.99999999999999 and 100.00000000000004 on two builds): 1e-12 is ~70 ulps of 100.
    assert!(
        last[0] < 100.0 + 1e-12 && last[0] > 99.9,
        "last row {last:?}"
    );
    for row in &rows {
        let (t, m) = (row[0], row[1]);
        assert!(m > 0.0, "{row:?}");
        // m is linear in t: integrated exactly up to rounding of 1000 (measured ≤ 5.7e-13).
        assert!((m - (1000.0 - 10.0 * t)).abs() < 1e-10, "{row:?}");
    }
}
