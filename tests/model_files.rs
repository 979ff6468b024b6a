//! Every model file in `models/` parses, composes (its components of `models/lib/`
//! expanded) and derives (its `check`s pass) for every choice of its tags, and tag
//! selection follows its documented rule.

use std::path::PathBuf;

use varmass::symbolic::compose::compose;
use varmass::symbolic::parse::{known_tags, parse_system, select_tags};
use varmass::symbolic::{
    derive_in,
    mechanics::{Outputs, Parameters},
};

fn models() -> Vec<(PathBuf, String)> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("models");
    let mut files: Vec<(PathBuf, String)> = std::fs::read_dir(&dir)
        .expect("models/ exists")
        .map(|entry| entry.expect("a directory entry").path())
        .filter(|path| path.extension().is_some_and(|e| e == "vms"))
        .map(|path| {
            let text = std::fs::read_to_string(&path).expect("a model file is readable");
            (path, text)
        })
        .collect();
    files.sort();
    files
}

/// Every subset of `tags`.
fn subsets(tags: &[String]) -> Vec<Vec<String>> {
    (0..1u32 << tags.len())
        .map(|mask| {
            tags.iter()
                .enumerate()
                .filter(|(i, _)| mask & (1 << i) != 0)
                .map(|(_, t)| t.clone())
                .collect()
        })
        .collect()
}

#[test]
fn every_model_derives_with_every_choice_of_tags() {
    let files = models();
    assert!(files.len() >= 8, "found {} model files", files.len());
    for (path, text) in files {
        let parsed = parse_system(&text).unwrap_or_else(|e| panic!("{}: {e:?}", path.display()));
        let composed = compose(&text, parsed, &path);
        let ast = composed
            .unwrap_or_else(|e| panic!("{}: {e:?}", path.display()))
            .ast;
        for with in subsets(&known_tags(&ast)) {
            let selected = select_tags(&ast, &with).expect("known tags");
            // Table files are read next to the model file.
            let base = path.parent().expect("a model file has a directory");
            if let Err(errors) = derive_in(&selected, Parameters::Inferred, Outputs::FULL, base) {
                let rendered: Vec<String> = errors
                    .iter()
                    .map(|e| e.render_in_file(&text, &path.display().to_string()))
                    .collect();
                panic!("with {with:?}:\n{}", rendered.join("\n"));
            }
        }
    }
}
