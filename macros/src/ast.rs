//! The typed view of the macro's input: the attribute's arguments and the struct they are on.
//!
//! ```text
//! #[variable_mass_system("coordinates x …")]                     the system inline
//! #[variable_mass_system(file = "models/sled.vms")]              the system in a file
//! #[variable_mass_system(file = "models/rocket.vms", with = ["drag"])]
//! #[variable_mass_system(file = "models/sled.vms", emit = [])]    only what steppers need
//! ```

use proc_macro2::{Span, TokenStream};
use syn::parse::{Parse, ParseStream};
use syn::punctuated::Punctuated;
use syn::{bracketed, Ident, LitStr, Token};

/// The options after the inline system or in place of it.
const OPTIONS: &str = "`file = \"…\"`, `with = [\"…\", …]` or `emit = [\"…\", …]`";

/// Where the DSL text is.
pub enum Source {
    /// Written in the attribute.
    Inline(LitStr),
    /// In a file, path relative to `CARGO_MANIFEST_DIR`.
    File(LitStr),
}

/// The attribute's arguments.
pub struct Attribute {
    /// The system, inline or in a file.
    pub source: Source,
    /// The tags asked for with `with = [...]`; empty without it.
    pub with: Vec<LitStr>,
    /// The optional outputs asked for with `emit = [...]`; `None` (all of them) without it.
    pub emit: Option<Vec<LitStr>>,
}

/// The attribute's arguments: the system (inline or `file = …`) and its options.
pub fn parse_attribute(attr: TokenStream) -> syn::Result<Attribute> {
    if attr.is_empty() {
        return Err(no_system(Span::call_site()));
    }
    syn::parse2::<Attribute>(attr)
}

fn no_system(span: Span) -> syn::Error {
    syn::Error::new(
        span,
        "expected the system as one string literal, e.g. \
         #[variable_mass_system(\"coordinates x\\nmass m = m0 + c*x\\n…\")], \
         or a model file, #[variable_mass_system(file = \"models/sled.vms\")]",
    )
}

impl Parse for Attribute {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let mut source = None;
        let mut with = None;
        let mut emit = None;
        if input.peek(LitStr) {
            source = Some(Source::Inline(input.parse()?));
        } else if !input.peek(Ident) || !input.peek2(Token![=]) {
            return Err(no_system(input.span()));
        }
        while !input.is_empty() {
            if source.is_some() || with.is_some() || emit.is_some() {
                input.parse::<Token![,]>()?;
                if input.is_empty() {
                    break;
                }
            }
            let option: Ident = input.parse()?;
            input.parse::<Token![=]>()?;
            match option.to_string().as_str() {
                "file" => {
                    if let Some(previous) = &source {
                        return Err(twice(&option, previous));
                    }
                    source = Some(Source::File(input.parse()?));
                }
                "with" if with.is_none() => with = Some(tag_list(input)?),
                "emit" if emit.is_none() => emit = Some(tag_list(input)?),
                "with" | "emit" => {
                    return Err(syn::Error::new(
                        option.span(),
                        format!("`{option}` given twice"),
                    ))
                }
                other => {
                    return Err(syn::Error::new(
                        option.span(),
                        format!("unknown option `{other}`; expected {OPTIONS}"),
                    ))
                }
            }
        }
        let source = source.ok_or_else(|| no_system(Span::call_site()))?;
        let with = with.unwrap_or_default();
        Ok(Attribute { source, with, emit })
    }
}

/// `file = …` after the system was already given.
fn twice(option: &Ident, previous: &Source) -> syn::Error {
    let message = match previous {
        Source::Inline(_) => "the system is given both inline and as `file`; give one",
        Source::File(_) => "`file` given twice",
    };
    syn::Error::new(option.span(), message)
}

/// A list of strings, `["drag", "wind"]`.
fn tag_list(input: ParseStream) -> syn::Result<Vec<LitStr>> {
    let content;
    bracketed!(content in input);
    let tags = Punctuated::<LitStr, Token![,]>::parse_terminated(&content)?;
    Ok(tags.into_iter().collect())
}

/// The item the attribute is on, which must be a struct.
pub fn parse_struct(item: TokenStream) -> syn::Result<syn::ItemStruct> {
    match syn::parse2::<syn::Item>(item)? {
        syn::Item::Struct(s) => Ok(s),
        syn::Item::Enum(e) => Err(syn::Error::new_spanned(
            e.enum_token,
            "#[variable_mass_system] goes on a struct whose named `f64` fields are the parameters, not on an enum",
        )),
        other => Err(syn::Error::new_spanned(
            other,
            "#[variable_mass_system] goes on a struct whose named `f64` fields are the parameters",
        )),
    }
}
