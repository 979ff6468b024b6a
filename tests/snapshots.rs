//! Snapshots (insta) of the full expansion of every example system (the model files of
//! `models/`), formatted with prettyplease, and of its derivation text: any change to
//! generated code or to the derivation shows up for review.

use quote::format_ident;
use varmass::symbolic::emit::{emit_system, Target};
use varmass::symbolic::parse::ast::SystemAst;
use varmass::symbolic::parse::{parse_system, select_tags};
use varmass::symbolic::{derive, mechanics::Parameters};

fn fields(names: &[&str]) -> Parameters {
    Parameters::Declared(names.iter().map(|s| s.to_string()).collect())
}

/// A model file of `models/` and the system it gives with the tags `with`.
fn model(file: &str, with: &[&str]) -> (String, SystemAst) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("models")
        .join(file);
    let source = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{file}: {e}"));
    let ast = parse_system(&source).unwrap_or_else(|e| panic!("{e:?}"));
    let with: Vec<String> = with.iter().map(|s| s.to_string()).collect();
    let selected = select_tags(&ast, &with).unwrap_or_else(|e| panic!("{e:?}"));
    (source, selected)
}

/// The formatted expansion and the derivation text of a model file.
fn expand(name: &str, file: &str, with: &[&str], parameters: &[&str]) -> (String, String) {
    let (source, ast) = model(file, with);
    let mut d = derive(&ast, fields(parameters)).unwrap_or_else(|e| panic!("{e:?}"));
    let target = Target {
        name: format_ident!("{}", name),
        runtime: quote::quote!(::varmass::core),
    };
    let tokens = emit_system(&mut d, &source, &target);
    let file: syn::File = syn::parse2(tokens).expect("generated code parses as Rust");
    (prettyplease::unparse(&file), d.to_text())
}

macro_rules! snapshot_system {
    ($test:ident, $name:literal, $file:literal, $with:expr, $parameters:expr) => {
        #[test]
        fn $test() {
            let (code, text) = expand($name, $file, $with, $parameters);
            insta::assert_snapshot!(concat!(stringify!($test), "_expansion"), code);
            insta::assert_snapshot!(concat!(stringify!($test), "_derivation"), text);
        }
    };
}

snapshot_system!(
    sled_paper_form,
    "Sled",
    "sled_paper_form.vms",
    &[],
    &["m0", "c", "g", "theta", "f_d"]
);

snapshot_system!(
    sled_body_form,
    "Sled",
    "sled.vms",
    &["impact"],
    &["m0", "c", "g", "theta", "f_d"]
);

snapshot_system!(
    vertical_rocket,
    "Rocket",
    "rocket.vms",
    &[],
    &["mu", "u_e", "g"]
);

snapshot_system!(
    double_pendulum,
    "DoublePendulum",
    "double_pendulum.vms",
    &[],
    &["M1", "M2", "l1", "l2", "g"]
);

snapshot_system!(
    swinging_tank,
    "SwingingTank",
    "swinging_tank.vms",
    &[],
    &["mu", "M0", "J0", "l", "g", "K", "u_e"]
);
