//! Sampled inputs in the command line tool are sampled on their own grid only
//! (docs/inputs.md#sampled-inputs), as in generated code (`tests/inputs_sampled_grid.rs`):
//! the review's reproductions (round 5) ran `sampled_two.vms`, whose `w` of period 0.03 was
//! sampled again every 0.01, and `sampled_knot.vms`, whose `u` took u(0.015) at a table's
//! knot. With u(t) = t and w(t) = t the held values are the sample times themselves.

mod common;

use common::{csv, data, varmass, written};

/// The tool's rows (t, then the `--record`ed columns) for `model` with `args`.
fn tool(model: &str, args: &[&str], record: &str, name: &str) -> Vec<Vec<f64>> {
    let model = data(model);
    let mut all = vec!["run", &model, "--init", "y=0", "--tol", "1e-12"];
    all.extend(["--record", record]);
    all.extend(args);
    csv(&written(&all, &format!("{name}.csv"))).1
}

/// The times at which column `column` changed, with its value after (between two rows at
/// the same time: the one before the sample and the one after).
fn changes(rows: &[Vec<f64>], column: usize) -> Vec<(f64, f64)> {
    let pairs = rows.iter().zip(rows.iter().skip(1));
    pairs
        .filter(|(a, b)| a[column] != b[column])
        .map(|(a, b)| {
            assert_eq!(a[0], b[0], "a held value changes only at a sample");
            (b[0], b[column])
        })
        .collect()
}

#[test]
fn each_input_of_the_tool_is_sampled_on_its_own_period() {
    let args = ["--input", "u=t", "--input", "w=t", "--until", "0.1"];
    let rows = tool("sampled_two.vms", &args, "y,y',u,w", "grid_two");
    let u: Vec<(f64, f64)> = (1..=10)
        .map(|k| (k as f64 * 0.01, k as f64 * 0.01))
        .collect();
    assert_eq!(changes(&rows, 3), u);
    // Before the fix: w changed at every k·0.01.
    let w: Vec<(f64, f64)> = (1..=3)
        .map(|j| (j as f64 * 0.03, j as f64 * 0.03))
        .collect();
    assert_eq!(changes(&rows, 4), w);
    // The end state against the held motion (ÿ = u_k + w_⌊k/3⌋ on each 10 ms; see
    // tests/inputs_sampled_grid.rs): y = 2.415e-4, ẏ = 8.1e-3. Measured 0 and 0 relative
    // (the text of the CSV round-trips); bound 1e-13.
    let end = rows.last().unwrap();
    let (y, v) = (2.415e-4, 8.1e-3);
    let errors = [(end[1] - y).abs() / y, (end[2] - v).abs() / v];
    println!("two periods: {errors:?}");
    assert!(errors.iter().all(|e| *e <= 1e-13), "{errors:?}");
}

#[test]
fn a_table_knot_or_an_output_time_between_samples_does_not_sample() {
    let args = ["--input", "u=t", "--until", "0.03"];
    let rows = tool("sampled_knot.vms", &args, "u", "grid_knot");
    assert!(
        rows.iter().any(|r| r[0] == 0.015),
        "the run lands on the knot"
    );
    // Before the fix: u became 0.015 at the knot.
    let u: Vec<(f64, f64)> = (1..=3)
        .map(|k| (k as f64 * 0.01, k as f64 * 0.01))
        .collect();
    assert_eq!(changes(&rows, 1), u);
    // `--every 0.005` ends a run at the knot (0.015) and starts the next there: neither
    // samples (before the fix, the end on the knot did). One row per output time.
    let every = [&args[..], &["--every", "0.005"]].concat();
    let rows = tool("sampled_knot.vms", &every, "u", "grid_knot_every");
    let held: Vec<(f64, f64)> = rows.iter().map(|r| (r[0], r[1])).collect();
    let expected = [
        (0.0, 0.0),
        (0.005, 0.0),
        (0.01, 0.01),
        (0.015, 0.01),
        (0.02, 0.02),
        (0.025, 0.02),
        (0.03, 0.03),
    ];
    assert_eq!(held, expected);
}

#[test]
fn a_switch_crossed_just_before_a_sample_time_does_not_skip_it_in_the_tool() {
    // The kink of |t − c| at c = 0.01 − 1e-16 is crossed with a restart past 0.01: the
    // sample is taken there, a few roundings late (before the fix: u(0) held to 0.02).
    let args = [
        "--input",
        "u=t",
        "--set",
        "c=0.0099999999999999",
        "--until",
        "0.025",
    ];
    let rows = tool("sampled_switch.vms", &args, "u", "grid_switch");
    let changes = changes(&rows, 1);
    let (first, value) = changes[0];
    // Measured 7.9e-16 late; bound 1e6 roundings of t (8.9e-10).
    assert!(
        first >= 0.01 && first - 0.01 <= 1e6 * 4.0 * f64::EPSILON,
        "{first}"
    );
    assert_eq!(value, first);
    assert_eq!(changes[1..], [(0.02, 0.02)]);
}

#[test]
fn a_law_without_a_value_at_a_sample_names_the_input_and_the_time() {
    // √(0.015 − t) is NaN at the sample 0.02 (before: "the state became non-finite" and
    // help about a fixed step past the stability limit). A run that fails exits 1.
    let model = data("sampled_knot.vms");
    let args = ["run", &model, "--init", "y=0", "--until", "0.05"];
    let (_, stderr) = varmass(&[&args[..], &["--input", "u=sqrt(0.015 - t)"]].concat(), 1);
    assert!(
        stderr.contains("at t = 0.02: the sampled input `u` is not finite at its sample (NaN)"),
        "{stderr}"
    );
    assert!(
        stderr.contains("the --input law of `u` has no value"),
        "{stderr}"
    );
    assert!(!stderr.contains("stability limit"), "{stderr}");
}
