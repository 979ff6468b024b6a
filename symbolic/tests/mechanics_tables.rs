//! `table` statements end to end in the symbolic engine (docs/tables.md): parsing (options
//! in any order, defaults, every malformed statement a diagnostic at its text), files read
//! relative to the model's directory (missing and malformed files at the file's name, with
//! the file's line), calls lowered, differentiated through the derivative table, checked
//! by `check`s and by the units check.
//!
//! `tests/data/tables/ramp.csv`: knots 0, 1, 2, 4 s, thrust 0, 2, 3, 1 N.

use std::path::{Path, PathBuf};

use varmass_symbolic::expr::Identity;
use varmass_symbolic::parse::ast::StatementKind;
use varmass_symbolic::parse::parse_system;
use varmass_symbolic::Diagnostic;
use varmass_symbolic::{
    derive_in,
    mechanics::{Outputs, Parameters},
};
use varmass_table::{Interpolation, Outside};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/tables")
}

fn derive(source: &str) -> Result<varmass_symbolic::mechanics::Derivation, Vec<Diagnostic>> {
    let ast = parse_system(source)?;
    derive_in(&ast, Parameters::Inferred, Outputs::FULL, &data())
}

#[track_caller]
fn error(source: &str, message: &str, line: u32, column: u32) {
    let errors = match derive(source) {
        Ok(_) => panic!("expected a diagnostic for:\n{source}"),
        Err(e) => e,
    };
    let found = errors.iter().find(|e| e.message.contains(message));
    let Some(found) = found else {
        let all: Vec<String> = errors.iter().map(|e| e.render(source)).collect();
        panic!(
            "no diagnostic containing {message:?}; got:\n{}",
            all.join("\n")
        );
    };
    assert_eq!(
        (found.span.line, found.span.column),
        (line, column),
        "{}",
        found.render(source)
    );
}

#[test]
fn options_come_in_any_order_with_defaults() {
    let cases = [
        (
            r#"table F(t) = "motors/M1670.eng", outside zero"#,
            Interpolation::Linear,
            Outside::Zero,
        ),
        (
            r#"table rho(y) = "atmosphere/density.csv", pchip"#,
            Interpolation::Pchip,
            Outside::Error,
        ),
        (
            r#"table cd(M) = "cd.csv", outside hold, spline"#,
            Interpolation::Spline,
            Outside::Hold,
        ),
        (
            r#"table G(t) = "g.csv""#,
            Interpolation::Linear,
            Outside::Error,
        ),
    ];
    for (statement, interpolation, outside) in cases {
        let ast = parse_system(&format!("coordinates x\n{statement}")).unwrap();
        let StatementKind::Table(decl) = &ast.statements[1].kind else {
            panic!("not a table: {statement}");
        };
        assert_eq!((decl.interpolation, decl.outside), (interpolation, outside));
    }
    let ast =
        parse_system("coordinates x\ntable rho(y) = \"atmosphere/density.csv\", pchip").unwrap();
    let StatementKind::Table(decl) = &ast.statements[1].kind else {
        panic!()
    };
    assert_eq!(decl.name.node, "rho");
    assert_eq!(decl.parameter.node, "y");
    assert_eq!(decl.file.node, "atmosphere/density.csv");
    // The file's span covers the quotes: line 2, column 16.
    assert_eq!((decl.file.span.line, decl.file.span.column), (2, 16));
}

#[track_caller]
fn parse_error(source: &str, message: &str, line: u32, column: u32) -> Diagnostic {
    let errors = parse_system(source).expect_err(source);
    let found = errors.iter().find(|e| e.message.contains(message));
    let Some(found) = found else {
        let all: Vec<String> = errors.iter().map(|e| e.render(source)).collect();
        panic!(
            "no diagnostic containing {message:?}; got:\n{}",
            all.join("\n")
        );
    };
    assert_eq!((found.span.line, found.span.column), (line, column));
    found.clone()
}

#[test]
fn malformed_statements_are_diagnostics_at_their_text() {
    let d = parse_error(
        "coordinates x\ntable F(t) = \"f.csv\", pchip, spline",
        "`spline` contradicts or repeats `pchip`",
        2,
        30,
    );
    assert!(d.help.as_deref().unwrap_or_default().contains("2:23"));
    parse_error(
        "coordinates x\ntable F(t) = \"f.csv\", outside zero, outside hold",
        "`outside` contradicts or repeats `outside`",
        2,
        37,
    );
    let d = parse_error(
        "coordinates x\ntable F(t) = \"f.csv\", pchp",
        "unknown option `pchp` for table `F`",
        2,
        23,
    );
    assert_eq!(d.help.as_deref(), Some("did you mean `pchip`?"));
    let d = parse_error(
        "coordinates x\ntable F(t) = \"f.csv\", outside zeros",
        "unknown rule `zeros` after `outside`",
        2,
        31,
    );
    assert_eq!(d.help.as_deref(), Some("did you mean `zero`?"));
    parse_error(
        "coordinates x\ntable F(t) = f.csv",
        "expected a file name in double quotes",
        2,
        14,
    );
    parse_error(
        "coordinates x\ntable F(t) = \"f.csv\ny",
        "no closing `\"`",
        2,
        14,
    );
    parse_error("coordinates x\ntable F = \"f.csv\"", "expected `(`", 2, 9);
}

/// A body falling under gravity and the ramp's thrust F(t), mass m0: y'' = F(t)/m0 − g.
const RAMP: &str = "coordinates y
table F(t) = \"ramp.csv\"
mass m = m0
kinetic 1/2*m*y'^2
potential m*g*y
force y: F(t)
check y'' = F(t)/m - g
";

#[test]
fn a_table_of_t_derives_and_its_checks_hold() {
    let d = derive(RAMP).unwrap();
    assert_eq!(d.tables.len(), 1);
    assert_eq!(d.tables[0].name, "F");
    assert_eq!(d.tables[0].path, data().join("ramp.csv"));
    assert_eq!(d.checks.len(), 1);
    assert!(!matches!(
        d.checks[0].verdict,
        Identity::Refuted { .. } | Identity::Undecided
    ));
    // A check that is false at the random points (F is not F + 1) fails: the checks
    // evaluate table calls.
    let wrong = RAMP.replace("check y'' = F(t)/m - g", "check y'' = (F(t) + 1)/m - g");
    error(&wrong, "check", 7, 1);
}

#[test]
fn a_table_of_the_state_is_differentiated_through_its_derivative_table() {
    // force y: F(2*y): the Jacobian's ∂y''/∂y = 2 F'(2y)/m0.
    let source = RAMP
        .replace("force y: F(t)", "force y: F(2*y)")
        .replace("check y'' = F(t)/m - g", "check y'' = F(2*y)/m - g");
    let d = derive(&source).unwrap();
    let jacobian = d.jacobian.as_ref().expect("the Jacobian");
    let printed: Vec<String> = jacobian
        .rate_wrt_q
        .iter()
        .flatten()
        .map(|e| d.pool.display(*e).to_string())
        .collect();
    assert!(printed.iter().any(|p| p.contains("F'(2*y)")), "{printed:?}");
    // And only there: no second derivative table was needed for a first-order Jacobian.
    assert!(!printed.iter().any(|p| p.contains("F''")), "{printed:?}");
}

#[test]
fn a_table_that_cannot_be_read_is_one_diagnostic() {
    // Not also "unknown function `F`" at its call.
    let source = "coordinates y\ntable F(t) = \"missing.csv\"\nkinetic y'^2\nforce y: F(t)";
    let errors = derive(source).expect_err("a diagnostic");
    assert_eq!(errors.len(), 1, "{errors:?}");
}

#[test]
fn files_are_read_relative_to_the_model_and_their_errors_carry_the_line() {
    error(
        "coordinates y\ntable F(t) = \"missing.csv\"\nkinetic y'^2",
        "cannot read the table file `missing.csv`",
        2,
        14,
    );
    error(
        "coordinates y\ntable F(t) = \"bad.eng\"\nkinetic y'^2",
        "bad.eng:4:5: `1OO` is not a number",
        2,
        14,
    );
    error(
        "coordinates y\ntable F(t) = \"ramp.txt\"\nkinetic y'^2",
        "a RASP motor (`.eng`) or a CSV table (`.csv`)",
        2,
        14,
    );
}

#[test]
fn a_motor_with_negative_thrust_is_refused_at_its_file_line_and_value() {
    // negative.eng, line 4: `0.3 -4.5`; before, it was read and a run failed later with a
    // negative flow rate (ṁ = −F/u_e).
    error(
        "coordinates y\ntable F(t) = \"negative.eng\"\nkinetic y'^2",
        "negative.eng:4:5: the thrust -4.5 N is negative",
        2,
        14,
    );
}

#[test]
fn a_pchip_or_spline_table_whose_interpolant_overflows_is_a_diagnostic_at_its_file() {
    // peaks.csv: 0, 1.5e308, 0, 1.5e308 at t = 0…3. The chords' slopes are finite, so a
    // linear table is taken; the cubics' coefficients hold 2·1.5e308 on the first piece
    // (lines 2–3 of the file), so pchip and spline are refused there, at the file's name
    // (before, they were taken and the run failed at t = 0 with "non-finite state").
    assert!(
        derive("coordinates y\ntable F(t) = \"peaks.csv\"\nkinetic y'^2\nforce y: F(t)").is_ok()
    );
    for interpolation in ["pchip", "spline"] {
        error(
            &format!("coordinates y\ntable F(t) = \"peaks.csv\", {interpolation}\nkinetic y'^2"),
            &format!(
                "peaks.csv:3:1: the {interpolation} interpolant from (0.0, 0.0) (line 2) to \
                 (1.0, 1.5e308) is not finite"
            ),
            2,
            14,
        );
    }
}

#[test]
fn a_table_is_a_function_and_its_name_is_taken() {
    error(
        "coordinates y\ntable F(t) = \"ramp.csv\"\nkinetic y'^2\nforce y: F",
        "`F` is a table, a function of one argument",
        4,
        10,
    );
    error(
        "coordinates y\ntable F(t) = \"ramp.csv\"\nkinetic y'^2\nforce y: F(t, y)",
        "`F` takes 1 argument, found 2",
        4,
        10,
    );
    error(
        "coordinates y\ntable y(t) = \"ramp.csv\"\nkinetic y'^2",
        "`y`",
        2,
        7,
    );
}

#[test]
fn units_give_the_value_and_infer_the_argument() {
    let ok = "coordinates y
table F(t) = \"ramp.csv\"
units y: m, m0: kg, g: m/s^2, F: N
mass m = m0
kinetic 1/2*m*y'^2
potential m*g*y
force y: F(t)
";
    derive(ok).unwrap();
    // F in a force is N; as a velocity it is not.
    error(
        &ok.replace("force y: F(t)", "force y: F(t)*y'"),
        "generalized force",
        7,
        10,
    );
    // Once an argument in s, always in s.
    error(
        &ok.replace("force y: F(t)", "force y: F(t) + F(y)"),
        "the argument of table `F`, y, has m, but at 7:12 it has s",
        7,
        19,
    );
}

#[test]
fn a_runtime_table_derives_over_a_placeholder_and_its_checks_hold() {
    // `= runtime` then options: no file read; the derivation's checks evaluate the
    // placeholder (they test algebra), so a true check holds and a false one fails.
    let source = RAMP.replace(r#""ramp.csv""#, "runtime, pchip, outside hold");
    let ast = parse_system(&source).unwrap();
    let decl = ast
        .statements
        .iter()
        .find_map(|s| match &s.kind {
            StatementKind::Table(t) => Some(t.clone()),
            _ => None,
        })
        .unwrap();
    assert!(decl.runtime);
    assert_eq!(
        (decl.interpolation, decl.outside),
        (Interpolation::Pchip, Outside::Hold)
    );
    let d = derive(&source).unwrap();
    assert!(d.tables[0].runtime);
    assert_eq!(d.tables[0].path, PathBuf::new());
    assert!(d.pool.is_runtime_table(d.tables[0].index));
    assert!(!matches!(
        d.checks[0].verdict,
        Identity::Refuted { .. } | Identity::Undecided
    ));
    let wrong = source.replace("check y'' = F(t)/m - g", "check y'' = (F(t) + 1)/m - g");
    error(&wrong, "check", 7, 1);
    // A misspelt `runtime` is a file name expected, with `runtime` in the help.
    let misspelt = RAMP.replace(r#""ramp.csv""#, "runtim");
    let d = parse_error(&misspelt, "expected a file name in double quotes", 2, 14);
    assert!(
        d.help.iter().any(|h| h.contains("= runtime")),
        "{:?}",
        d.help
    );
}

/// A bead on a track y = h(x) given by a table: T = ½ m (1 + h′²) ẋ², so ṗ needs h″. A
/// `linear` table's h″ is an impulse at each knot that the piecewise derivative (≡ 0)
/// drops — across a 0 → 1 change of slope p is kept and ẋ halves, losing half of T without
/// a trace in the energy budget — so it is refused at the table's file; `pchip` (C¹) and
/// `spline` (C²) derive.
#[test]
fn a_linear_table_in_a_position_is_refused() {
    let track = |options: &str| {
        format!(
            "coordinates x\ntable h(x) = \"ramp.csv\"{options}\nmass m = m0\n\
             body bead: mass m, position [x, h(x)]\npotential m*g*h(x)"
        )
    };
    error(&track(""), "differentiate table `h` 2 times", 2, 14);
    error(
        &track(""),
        "`linear` tables have an impulse in derivative 2",
        2,
        14,
    );
    for smooth in [", pchip", ", spline"] {
        assert!(derive(&track(smooth)).is_ok(), "{smooth}");
    }
    // A linear table in a force is differentiated by the Jacobian only: derives.
    assert!(derive(RAMP).is_ok());
}
