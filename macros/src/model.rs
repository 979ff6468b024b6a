//! The DSL text of a system, inline or read from a model file, and how a diagnostic about
//! it is shown: positions in the Rust file for an inline system, in the model file for a
//! file, always on the attribute's string literal (the only span a stable proc macro has).

use std::path::PathBuf;

use proc_macro2::TokenStream;
use quote::quote;
use syn::LitStr;
use varmass_symbolic::compose::Composition;
use varmass_symbolic::mechanics::Derivation;
use varmass_symbolic::parse::Origin;
use varmass_symbolic::Diagnostic;

use crate::ast::Source;
use crate::ctxt::Ctxt;

/// The text of a system and where it came from.
pub struct ModelText {
    /// The DSL.
    pub text: String,
    /// The literal diagnostics are reported on (the system, or the file's path).
    pub literal: LitStr,
    /// The file, as written in the attribute and resolved, for a model file.
    pub file: Option<(String, PathBuf)>,
}

impl ModelText {
    /// The text of `source`: the literal's value, or the file it names read from disk (path
    /// relative to `CARGO_MANIFEST_DIR`); a file that cannot be read is an error on its path.
    pub fn load(source: &Source) -> syn::Result<ModelText> {
        match source {
            Source::Inline(literal) => Ok(ModelText {
                text: literal.value(),
                literal: literal.clone(),
                file: None,
            }),
            Source::File(literal) => {
                let written = literal.value();
                let base = std::env::var_os("CARGO_MANIFEST_DIR").unwrap_or_default();
                let resolved = PathBuf::from(base).join(&written);
                let text = std::fs::read_to_string(&resolved).map_err(|error| {
                    syn::Error::new(
                        literal.span(),
                        format!(
                            "cannot read the model file `{written}` (paths are relative to the \
                             crate's directory, CARGO_MANIFEST_DIR): {error}"
                        ),
                    )
                })?;
                Ok(ModelText {
                    text,
                    literal: literal.clone(),
                    file: Some((written, resolved)),
                })
            }
        }
    }

    /// The directory `table` files are read from: the model file's, or for an inline
    /// system the crate's (`CARGO_MANIFEST_DIR`).
    pub fn base(&self) -> PathBuf {
        match &self.file {
            Some((_, resolved)) => resolved.parent().map(PathBuf::from).unwrap_or_default(),
            None => PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").unwrap_or_default()),
        }
    }

    /// Makes cargo rebuild the crate when a table's data change: an `include_bytes!` of
    /// each table file.
    pub fn table_tracking(&self, d: &Derivation) -> TokenStream {
        let paths = d
            .tables
            .iter()
            .filter(|t| !t.runtime)
            .map(|t| t.path.to_string_lossy().into_owned());
        quote!(#(const _: &[u8] = ::core::include_bytes!(#paths);)*)
    }

    /// The model file, or for an inline system a name in the crate's directory: where the
    /// paths of its components start (docs/components.md).
    pub fn path(&self) -> PathBuf {
        match &self.file {
            Some((_, resolved)) => resolved.clone(),
            None => self.base().join("(inline system)"),
        }
    }

    /// Makes cargo rebuild the crate when the model file or one of its components changes:
    /// an `include_bytes!` of each (nothing for an inline system without components).
    pub fn tracking(&self, composition: Option<&Composition>) -> TokenStream {
        let model = self.file.iter().map(|(_, resolved)| resolved.as_path());
        let components = composition.into_iter().flat_map(Composition::files);
        let paths = model
            .chain(components)
            .map(|p| p.to_string_lossy().into_owned());
        quote!(#(const _: &[u8] = ::core::include_bytes!(#paths);)*)
    }

    /// Each diagnostic as a compile error on the literal, with the line:column (in the Rust
    /// file or in the model file) and a caret under the offending DSL text in the message. (A
    /// span inside the literal needs the unstable `Literal::subspan`; the message carries the
    /// exact position instead.)
    pub fn report(&self, cx: &Ctxt, errors: &[Diagnostic]) {
        for d in errors {
            let rendered = match &self.file {
                Some((written, _)) => d.render_in_file(&self.text, written),
                None => d.render_at(&self.text, origin(&self.literal)),
            };
            // `render` starts with "error: <message>"; the compiler prints its own "error: ".
            let body: Vec<&str> = rendered.lines().skip(1).collect();
            cx.error_at(
                self.literal.span(),
                format!("{}\n{}", d.message, body.join("\n")),
            );
        }
    }
}

/// Where the literal's text starts in the file, when its value is its text verbatim (no
/// escapes), so DSL positions map to file positions; otherwise positions stay relative to
/// the DSL text (line 1 is the first line of the string).
fn origin(literal: &LitStr) -> Origin {
    let token = literal.token().to_string();
    let prefix = token.find('"').map_or(0, |i| i + 1);
    let suffix = token.len() - token.rfind('"').unwrap_or(token.len());
    let verbatim = token
        .get(prefix..token.len() - suffix)
        .is_some_and(|inner| inner == literal.value());
    let start = literal.span().start();
    if verbatim && start.line > 0 {
        Origin {
            line: start.line as u32,
            // `start.column` is 0-based and points at the literal's first character.
            column: (start.column + prefix + 1) as u32,
        }
    } else {
        Origin::default()
    }
}
