//! Where a table jumps at an end (`outside zero` after a value that is not zero), the two
//! stop times of a table of t and the switch of a table of the state say exactly which side
//! of the jump a lookup reads (docs/tables.md#outside-the-data): the properties the runs of
//! `tests/table_ends.rs` and `tests/table_state_ends.rs` rest on, checked argument by
//! argument. The table is the box G = 1 on [1, 2] (`tests/data/box_1_2.csv`), 0 outside.

use varmass::core::table::{knot_bracket_read, knot_gap_read, next_knot_time, Table};
use varmass_table::{CsvTable, Interpolation, Outside};

fn boxed() -> Table {
    let text = std::fs::read_to_string("tests/data/box_1_2.csv").unwrap();
    let points = CsvTable::parse(&text).unwrap().points;
    Table::new(&points, Interpolation::Linear, Outside::Zero)
}

/// The value the table reads at the argument `slope·t + offset`, as the generated code's
/// lookup computes it.
fn read(table: &Table, slope: f64, offset: f64, t: f64) -> f64 {
    table.value(slope * t + offset).unwrap()
}

#[test]
fn a_jump_of_a_table_of_t_has_a_stop_on_either_side() {
    let table = boxed();
    // Rising and falling arguments, slopes that do and do not round, offsets up to 10³
    // (where an ulp of t is 16 times an ulp of the knot 2): 4 × 200 runs through the box.
    for slope in [1.0, 0.37, -1.0, -3.1] {
        for i in 0..200 {
            let offset = if slope > 0.0 {
                -5.0 * f64::from(i)
            } else {
                3.0 + 5.0 * f64::from(i)
            };
            // From the argument 0 rising, 3 falling: through both ends of the box.
            let start = if slope > 0.0 { 0.0 } else { 3.0 };
            let mut after = (start - offset) / slope;
            let mut stops = Vec::new();
            loop {
                let stop = next_knot_time(&table, slope, offset, after);
                if !stop.is_finite() {
                    break;
                }
                assert!(
                    stop > after,
                    "slope {slope} offset {offset}: {stop} ≤ {after}"
                );
                stops.push(stop);
                after = stop;
            }
            // The box's two knots both jump: T₁ and T₂ at each.
            let case = format!("slope {slope}, offset {offset}, stops {stops:?}");
            assert_eq!(stops.len(), 4, "{case}");
            for pair in stops.chunks(2) {
                let (arrival, restart) = (pair[0], pair[1]);
                let before = read(&table, slope, offset, arrival);
                let after = read(&table, slope, offset, restart);
                assert_ne!(before, after, "{case}");
                // The arriving step's stages round t + h by an ulp or two of t: the side
                // before holds there (and the whole way up from a step's start).
                let mut t = arrival;
                for _ in 0..3 {
                    assert_eq!(read(&table, slope, offset, t), before, "{case}");
                    t = t.next_up();
                }
                // The tiny step between the two stops: measured ≤ 7.5 ε (1.7e-15) relative to
                // max(|t|, the knot and the offset in time); bound 32 ε (7.1e-15).
                let scale = restart
                    .abs()
                    .max(2.0 / slope.abs())
                    .max(offset.abs() / slope.abs());
                let gap = (restart - arrival) / scale;
                assert!(gap <= 32.0 * f64::EPSILON, "{case}: {gap:e}");
            }
        }
    }
}

#[test]
fn a_jump_of_a_table_of_the_state_is_switched_where_the_lookup_jumps() {
    let table = boxed();
    let (from, to) = table.data_edges();
    // The edges are a few roundings beyond the knots (the band of 4 ε·2 the lookups snap
    // onto the ends) and the value jumps there.
    assert!(
        (1.0 - from) > 0.0 && (1.0 - from) <= 4.0 * f64::EPSILON * 2.0,
        "{from}"
    );
    assert!(
        (to - 2.0) > 0.0 && (to - 2.0) <= 4.0 * f64::EPSILON * 2.0,
        "{to}"
    );
    assert_eq!(
        (table.value(from), table.value(from.next_down())),
        (Ok(1.0), Ok(0.0))
    );
    assert_eq!(
        (table.value(to), table.value(to.next_up())),
        (Ok(1.0), Ok(0.0))
    );
    // Every argument within 40 ulps of either knot: the bracket says which side the lookup
    // reads (bracket 0 the data, −1 and 1 outside), the gap is ≥ 0 in its own bracket, and
    // zero only on the last argument of a side.
    for knot in [1.0f64, 2.0] {
        let mut x = knot;
        for _ in 0..40 {
            x = x.next_down();
        }
        for _ in 0..80 {
            let bracket = knot_bracket_read(&[&table], x);
            let reads = table.value(x).unwrap();
            assert_eq!(reads == 1.0, bracket == 0.0, "{x}: bracket {bracket}");
            let gap = knot_gap_read(&[&table], x, bracket);
            assert!(gap >= 0.0, "{x}: gap {gap}");
            let last_of_its_side = knot_bracket_read(&[&table], x.next_up()) != bracket
                || knot_bracket_read(&[&table], x.next_down()) != bracket;
            assert_eq!(gap == 0.0, last_of_its_side, "{x}: gap {gap}");
            x = x.next_up();
        }
    }
}
