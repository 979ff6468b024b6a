//! The RASP `.eng` reader: the two motors of `models/motors/`, and every malformed input as a
//! typed error at its line and column.

use varmass_table::{Motor, ReadError, ReadErrorKind};

fn motor(file: &str) -> Motor {
    let path = format!("{}/../models/motors/{file}", env!("CARGO_MANIFEST_DIR"));
    Motor::parse(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn error(text: &str) -> ReadError {
    Motor::parse(text).unwrap_err()
}

#[test]
fn the_m1670_header_and_curve_from_ignition() {
    let m1670 = motor("Cesaroni_M1670.eng");
    assert_eq!(m1670.name, "M1670-BS");
    assert_eq!((m1670.diameter_mm, m1670.length_mm), (75.0, 757.0));
    assert_eq!(m1670.delays, "0");
    assert_eq!((m1670.propellant_kg, m1670.total_kg), (3.101, 5.231));
    assert_eq!(m1670.maker, "CTI");
    // 15 listed points after ignition, and (0, 0) in front.
    assert_eq!(m1670.thrust.len(), 16);
    assert_eq!(m1670.thrust.arguments()[..2], [0.0, 0.055]);
    assert_eq!(m1670.thrust.values()[..2], [0.0, 100.0]);
    assert_eq!(m1670.burn_time(), 3.9);
}

#[test]
fn the_m1670_total_impulse_by_exact_trapezoids_is_6026_35() {
    // Exact in rationals (Python's fractions over the file's decimals): 120527/20 =
    // 6026.35 N·s, as the data's README states. Measured |error| 0 (the K828FJ's 4.5e-13:
    // rounded products summed); 1e-11 leaves 20× the latter, and a curve read without
    // (0, 0) is off by 2.75 N·s.
    let impulse = motor("Cesaroni_M1670.eng").total_impulse();
    assert!((impulse - 6026.35).abs() <= 1e-11, "{impulse}");
}

#[test]
fn the_k828fj_with_comments_and_four_delays() {
    let k828 = motor("AeroTech_K828FJ.eng");
    assert_eq!(
        (k828.name.as_str(), k828.delays.as_str()),
        ("K828FJ", "6-10-14-18")
    );
    assert_eq!(
        (k828.propellant_kg, k828.total_kg, k828.maker.as_str()),
        (1.45, 2.255, "AT")
    );
    // Exact: 20721023/10000 N·s (the README rounds to 2072.10). Measured |error| 4.5e-13.
    let impulse = k828.total_impulse();
    assert!((impulse - 2072.1023).abs() <= 1e-11, "{impulse}");
    // u_e = I/m_p, the rocketry tools' exhaust speed.
    assert!((k828.exhaust_speed() - 2072.1023 / 1.45).abs() <= 1e-11);
}

#[test]
fn a_curve_listing_ignition_is_not_given_a_second_zero() {
    let motor = Motor::parse("A 1 2 P 0.1 0.2 X\n0 5\n1 0\n").unwrap();
    assert_eq!(motor.thrust.arguments(), [0.0, 1.0]);
    assert_eq!(motor.thrust.values(), [5.0, 0.0]);
}

#[test]
fn a_number_that_is_not_one_names_its_line_and_column() {
    let e = error("; comment\nA 1 2 0 0.1 0.2 X\n0.5  100\n1.0  1OO\n");
    assert_eq!((e.line, e.column), (4, 6));
    assert_eq!(
        e.kind,
        ReadErrorKind::NotANumber {
            field: "1OO".into()
        }
    );
    assert_eq!(e.to_string(), "line 4, column 6: `1OO` is not a number");
}

#[test]
fn a_header_number_that_is_not_one_names_its_column() {
    let e = error("A 1 2mm 0 0.1 0.2 X\n1 1\n");
    assert_eq!((e.line, e.column), (1, 5));
    assert_eq!(
        e.kind,
        ReadErrorKind::NotANumber {
            field: "2mm".into()
        }
    );
}

#[test]
fn an_infinite_thrust_is_refused() {
    let e = error("A 1 2 0 0.1 0.2 X\n1 inf\n");
    assert_eq!((e.line, e.column), (2, 3));
    assert_eq!(
        e.kind,
        ReadErrorKind::NotFinite {
            field: "inf".into()
        }
    );
}

#[test]
fn times_that_do_not_increase_name_the_line() {
    let e = error("A 1 2 0 0.1 0.2 X\n0.5 10\n0.5 20\n");
    assert_eq!((e.line, e.column), (3, 1));
    assert_eq!(
        e.kind,
        ReadErrorKind::NotIncreasing {
            previous: 0.5,
            knot: 0.5
        }
    );
}

#[test]
fn a_negative_time_is_before_ignition() {
    let e = error("A 1 2 0 0.1 0.2 X\n  -0.5 10\n");
    assert_eq!((e.line, e.column), (2, 3));
    assert_eq!(e.kind, ReadErrorKind::NegativeTime { time: -0.5 });
}

#[test]
fn a_data_line_needs_two_fields() {
    let e = error("A 1 2 0 0.1 0.2 X\n0.5 10 3\n");
    assert_eq!(e.line, 2);
    assert!(
        matches!(e.kind, ReadErrorKind::FieldCount { found: 3, .. }),
        "{e}"
    );
}

#[test]
fn a_short_header_is_refused() {
    let e = error("\n\nA 1 2 0 0.1 0.2\n1 1\n");
    assert_eq!(e.line, 3);
    assert!(
        matches!(e.kind, ReadErrorKind::FieldCount { found: 6, .. }),
        "{e}"
    );
}

#[test]
fn a_second_motor_in_the_file_is_refused() {
    let e = error("A 1 2 0 0.1 0.2 X\n1 1\nB 1 2 0 0.1 0.2 Y\n1 1\n");
    assert_eq!((e.line, e.kind), (3, ReadErrorKind::SecondMotor));
}

#[test]
fn only_comments_is_a_missing_header() {
    let e = error(";\n; nothing\n");
    assert_eq!(e.line, 2);
    assert!(matches!(e.kind, ReadErrorKind::MissingHeader { .. }), "{e}");
}

#[test]
fn a_header_without_points_has_too_few() {
    let e = error("A 1 2 0 0.1 0.2 X\n; no data\n");
    assert_eq!(
        (e.line, e.kind),
        (1, ReadErrorKind::TooFewPoints { found: 0 })
    );
    // Ignition listed and nothing after it: one point.
    let e = error("A 1 2 0 0.1 0.2 X\n0 0\n");
    assert_eq!(
        (e.line, e.kind),
        (2, ReadErrorKind::TooFewPoints { found: 1 })
    );
}

#[test]
fn a_negative_thrust_is_refused_where_it_is_written() {
    // A motor only pushes: -3 N on line 3 would become a negative flow rate ṁ = −F/u_e
    // only when a run reached it. Refused at the thrust's field (line 3, column 5).
    let e = error("A 1 2 0 0.1 0.2 X\n0.1 10\n0.2 -3\n0.3 0\n");
    assert_eq!((e.line, e.column), (3, 5));
    assert_eq!(e.kind, ReadErrorKind::NegativeThrust { thrust: -3.0 });
    // Zero thrust stays valid (the burn's end).
    assert!(Motor::parse("A 1 2 0 0.1 0.2 X\n0.1 10\n0.2 0\n").is_ok());
}
