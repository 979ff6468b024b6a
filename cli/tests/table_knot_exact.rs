//! A knot of a table of the state reached exactly at the end of a step, by `varmass run`
//! (the interpreter's switches; the generated code's are `tests/table_knot_exact.rs`, which
//! names the cause): before the fix the run went round at t = 1 until `--max-steps`
//! ("more than --max-steps 10000 steps were needed", exit 1); now it crosses the knot.

mod common;

use common::{data, varmass};

#[test]
fn a_knot_reached_exactly_is_crossed_by_every_fixed_step_method() {
    let model = data("tables/two_knots.vms");
    for method in ["euler", "rk4", "dormand-prince"] {
        let (stdout, stderr) = varmass(
            &[
                "run",
                &model,
                "--set",
                "m0=1",
                "--init",
                "x=999",
                "--init",
                "x'=1",
                "--until",
                "2",
                "--step",
                "0.25",
                "--max-steps",
                "10000",
                "--method",
                method,
            ],
            0,
        );
        // x = 999 + 2 exactly (sums of quarters, the crossing's sliver rounding away).
        let text = format!("{stdout}{stderr}");
        assert!(text.contains("  x = 1001\n"), "{method}: {text}");
        assert!(text.contains("steps: 9 accepted"), "{method}: {text}");
    }
}
