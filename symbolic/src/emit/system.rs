//! The `VariableMassSystem` impl for a derivation (ARCHITECTURE.md#stage-4-emit): one straight-line function per
//! trait method, each with its formula in a doc comment.

use std::collections::BTreeSet;

use proc_macro2::{Delimiter, Group, Ident, Literal, Punct, Spacing, TokenStream, TokenTree};
use quote::{format_ident, quote};

use super::expression::{block, staged_block, symbol_ident, Lookups, Stage};
use super::factor::ldlt_solve;
use super::signature::Method;
use crate::expr::{Id, Symbol, SymbolKind};
use crate::mechanics::{Derivation, Of, VelocitySolve};
use crate::quantity::{Named, Quantity};

/// Where the generated code finds the runtime.
#[derive(Clone, Debug)]
pub struct Target {
    /// The struct the impl is for.
    pub name: Ident,
    /// A path to `varmass_core` (e.g. `::varmass::core`).
    pub runtime: TokenStream,
}

/// How a method on `input` calls tables: the methods on the canonical state (velocities,
/// H, the state rate, the power, the Jacobian) return a `Result`; the others cannot fail,
/// and the run only calls them where the state rate succeeded.
fn lookups(input: Input) -> Lookups {
    match input {
        Input::State => Lookups::Fallible,
        Input::Configuration | Input::VelocityState => Lookups::Nan,
    }
}

/// Turns the rendered first-stage values into the `let`s that bind q̇.
type Bridge<'a> = Box<dyn FnOnce(Vec<TokenStream>) -> Vec<TokenStream> + 'a>;

/// The checks that refuse a state with `SingularMassMatrix` unless each guard's value is
/// above 0, or above the relative pivot floor where `relative`.
fn guard_checks(
    values: &[TokenStream],
    relative: &[bool],
    runtime: &TokenStream,
) -> Vec<TokenStream> {
    let checks = values.iter().zip(relative);
    checks
        .map(|(value, relative)| {
            let floor = if *relative {
                quote!(#runtime::system::RELATIVE_PIVOT_FLOOR)
            } else {
                quote!(0.0)
            };
            quote! {
                if !((#value) > #floor) {
                    return Err(#runtime::SystemError::SingularMassMatrix);
                }
            }
        })
        .collect()
}

/// Which vector a method receives.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Input {
    /// `state = [q, p, m_s]`
    State,
    /// `velocity_state = [q, q̇, m_s]`
    VelocityState,
    /// `state`, of which only q and m_s are read (mass laws, the mass matrix).
    Configuration,
}

/// What the generated code's vectors and matrices count: the state is `[q, p, m_s, held]`
/// (`velocity_state` has q̇ where `state` has p), its length S = 2N + K + the held inputs.
pub(crate) struct Sizes {
    /// N, the coordinates (as many velocities and momenta).
    pub coordinates: usize,
    /// K, the masses integrated in the state, after its 2N positions and momenta.
    pub state_masses: usize,
    /// S, the whole state.
    pub state: usize,
}

impl Sizes {
    /// The sizes of `d`'s system.
    pub(crate) fn of(d: &Derivation) -> Sizes {
        Sizes {
            coordinates: d.coordinates.len(),
            state_masses: d.state_mass_count(),
            state: d.state_len(),
        }
    }

    /// N as the literal of `SVector<f64, N>`.
    pub(crate) fn coordinates_literal(&self) -> Literal {
        Literal::usize_unsuffixed(self.coordinates)
    }

    /// S as the literal of `SVector<f64, S>`.
    pub(crate) fn state_literal(&self) -> Literal {
        Literal::usize_unsuffixed(self.state)
    }

    /// The state's index of the first held input (after q, p and m_s).
    pub(crate) fn first_held(&self) -> usize {
        2 * self.coordinates + self.state_masses
    }
}

pub(crate) struct Emitter<'a> {
    pub d: &'a Derivation,
    pub target: &'a Target,
    /// The velocity symbols as expressions, in coordinate order.
    pub velocity_ids: Vec<Id>,
    /// Expressions rewritten for evaluation (see `expand_trig_arguments`); others as is.
    pub for_code: rustc_hash::FxHashMap<Id, Id>,
    /// The DSL text of the expressions the doc comments show, printed in one walk.
    pub texts: rustc_hash::FxHashMap<Id, String>,
}

impl Emitter<'_> {
    /// The form of `e` that generated code evaluates.
    fn code(&self, e: Id) -> Id {
        self.for_code.get(&e).copied().unwrap_or(e)
    }

    /// [`Self::code`] of each.
    fn code_all(&self, es: &[Id]) -> Vec<Id> {
        es.iter().map(|e| self.code(*e)).collect()
    }

    /// The sizes the generated code is written for.
    pub(crate) fn sizes(&self) -> Sizes {
        Sizes::of(self.d)
    }

    /// The signature of `method` for this system (see `signature.rs`).
    pub(crate) fn signature(&self, method: Method) -> TokenStream {
        let sizes = self.sizes();
        method.signature(&self.target.runtime, sizes.coordinates, sizes.state)
    }

    /// `id` in DSL text, for a doc comment: from [`Self::texts`] when it is there.
    pub(crate) fn display(&self, id: Id) -> String {
        match self.texts.get(&id) {
            Some(text) => text.clone(),
            None => self.d.pool.display(id).to_string(),
        }
    }

    /// Symbols needed to evaluate `roots`, closed under the laws of the law masses.
    fn used(&self, roots: &[Id]) -> BTreeSet<Symbol> {
        // The free symbols of all roots from one walk (one per root repeats the shared parts).
        let pool = &self.d.pool;
        let reachable = pool.reachable(roots, true).into_iter();
        let mut used: BTreeSet<Symbol> = reachable.filter_map(|id| pool.as_symbol(id)).collect();
        // A law may name state masses and parameters, never other law masses (closed laws).
        for (m, law) in self.d.masses.iter().zip(&self.d.closed_laws) {
            if let (true, Some(law)) = (used.contains(&m.symbol), law) {
                used.extend(self.d.pool.free_symbols(*law));
            }
        }
        used
    }

    /// `let` bindings for every used symbol from the struct's fields, `t` and the input.
    fn prologue(&self, used: &BTreeSet<Symbol>, input: Input) -> TokenStream {
        let sizes = self.sizes();
        let n = sizes.coordinates;
        let vector = match input {
            Input::State | Input::Configuration => format_ident!("state"),
            Input::VelocityState => format_ident!("velocity_state"),
        };
        let mut out = TokenStream::new();
        for (name, s) in &self.d.parameters {
            if used.contains(s) {
                let local = symbol_ident(&self.d.pool, *s);
                let field = Ident::new(name, proc_macro2::Span::call_site());
                out.extend(quote!(let #local = self.#field;));
            }
        }
        for (a, c) in self.d.coordinates.iter().enumerate() {
            let q = symbol_ident(&self.d.pool, c.q);
            let second = Literal::usize_unsuffixed(n + a);
            let first = Literal::usize_unsuffixed(a);
            if used.contains(&c.q) {
                out.extend(quote!(let #q = #vector[#first];));
            }
            let second_symbol = match input {
                Input::State => c.momentum,
                Input::VelocityState => c.velocity,
                Input::Configuration => continue,
            };
            if used.contains(&second_symbol) {
                let local = symbol_ident(&self.d.pool, second_symbol);
                out.extend(quote!(let #local = #vector[#second];));
            }
        }
        for (k, m) in self.d.masses.iter().take(sizes.state_masses).enumerate() {
            if used.contains(&m.symbol) {
                let local = symbol_ident(&self.d.pool, m.symbol);
                let index = Literal::usize_unsuffixed(2 * n + k);
                out.extend(quote!(let #local = #vector[#index];));
            }
        }
        // The held values of the sampled inputs, after the state masses.
        for (j, held) in self.d.held().into_iter().enumerate() {
            if used.contains(&held) {
                let local = symbol_ident(&self.d.pool, held);
                let index = Literal::usize_unsuffixed(sizes.first_held() + j);
                out.extend(quote!(let #local = #vector[#index];));
            }
        }
        let laws: Vec<(Symbol, Id)> = self
            .d
            .masses
            .iter()
            .zip(&self.d.closed_laws)
            .filter_map(|(m, law)| {
                law.filter(|_| used.contains(&m.symbol))
                    .map(|l| (m.symbol, l))
            })
            .collect();
        if !laws.is_empty() {
            let roots: Vec<Id> = laws.iter().map(|(_, l)| self.code(*l)).collect();
            let b = block(
                &self.d.pool,
                &roots,
                "law",
                &self.target.runtime,
                lookups(input),
            );
            out.extend(b.lets);
            for ((symbol, _), value) in laws.iter().zip(b.outputs) {
                let local = symbol_ident(&self.d.pool, *symbol);
                out.extend(quote!(let #local = #value;));
            }
        }
        out
    }

    /// The first stage of a method on the state that needs q̇: the expressions to render
    /// and the bridge that binds `x_dot`, … from their values — q̇ = M⁻¹(p − b) in closed
    /// form, or an LDLᵀ solve of M q̇ = p − b from the entries of M and b.
    fn velocity_stage(&self) -> (Vec<Id>, Bridge<'_>) {
        let runtime = &self.target.runtime;
        let names: Vec<Ident> = self
            .d
            .coordinates
            .iter()
            .map(|c| symbol_ident(&self.d.pool, c.velocity))
            .collect();
        match &self.d.velocities {
            VelocitySolve::Symbolic(v) => {
                let bridge = move |values: Vec<TokenStream>| {
                    names
                        .iter()
                        .zip(values)
                        .map(|(name, value)| quote!(let #name = #value;))
                        .collect()
                };
                (self.code_all(v), Box::new(bridge))
            }
            VelocitySolve::Numeric if self.d.rigid_velocities.is_some() => {
                self.rigid_velocity_stage(names)
            }
            VelocitySolve::Numeric => {
                let mut first: Vec<Id> = self.code_all(&self.d.mass_matrix.concat());
                let entries = first.len();
                first.extend(self.code_all(&self.d.momentum_offset));
                let momenta: Vec<Ident> = self
                    .d
                    .coordinates
                    .iter()
                    .map(|c| symbol_ident(&self.d.pool, c.momentum))
                    .collect();
                let zero = self.zero_pattern();
                let no_offset: Vec<bool> = self
                    .d
                    .momentum_offset
                    .iter()
                    .map(|b| self.d.pool.is_zero(*b))
                    .collect();
                let bridge = move |values: Vec<TokenStream>| {
                    let (matrix, offset) = values.split_at(entries);
                    let excess: Vec<TokenStream> = momenta
                        .iter()
                        .zip(offset)
                        .zip(&no_offset)
                        .map(|((p, b), none)| if *none { quote!(#p) } else { quote!(#p - (#b)) })
                        .collect();
                    vec![ldlt_solve(matrix, &zero, &excess, &names, runtime)]
                };
                (first, Box::new(bridge))
            }
        }
    }

    /// q̇ of a lone spatial rigid body in closed form (`mechanics/rigid_solve.rs`): its
    /// guards first (`SystemError::SingularMassMatrix` unless each is above 0, or above the
    /// relative pivot floor: m, I's pivots, det E² at gimbal lock), then q̇.
    fn rigid_velocity_stage(&self, names: Vec<Ident>) -> (Vec<Id>, Bridge<'_>) {
        let runtime = &self.target.runtime;
        let Some(rigid) = &self.d.rigid_velocities else {
            return (Vec::new(), Box::new(|_| Vec::new()));
        };
        let mut first = self.code_all(&rigid.velocities);
        first.extend(rigid.guards.iter().map(|(value, _)| self.code(*value)));
        let relative: Vec<bool> = rigid.guards.iter().map(|(_, r)| *r).collect();
        let bridge = move |values: Vec<TokenStream>| {
            let (rates, guards) = values.split_at(names.len());
            let mut out = guard_checks(guards, &relative, runtime);
            out.extend(
                names
                    .iter()
                    .zip(rates)
                    .map(|(name, value)| quote!(let #name = #value;)),
            );
            out
        };
        (first, Box::new(bridge))
    }

    /// `accelerations(t, velocity_state)` of a lone body turned by a quaternion, `None`
    /// for any other system: q̈ as the total derivative of its closed-form q̇ = F(q, p, t, m)
    /// (`mechanics/rigid_solve.rs`, `quaternion_accelerations`), with p = M q̇ bound first
    /// from the body's closed form (`quaternion_momenta`, free of an offset). The same
    /// guards refuse the same states as `velocities` (m, I's pivots, n = |q|² ≤ √ε).
    pub(crate) fn rigid_acceleration_body(&self) -> Option<TokenStream> {
        let rigid = (self.d.rigid_velocities.as_ref()).filter(|r| r.quaternion)?;
        let runtime = &self.target.runtime;
        let momenta = self.code_all(&rigid.momenta);
        let mut roots = self.code_all(&rigid.accelerations);
        roots.extend(rigid.guards.iter().map(|(value, _)| self.code(*value)));
        let mut used = self.used(&momenta);
        used.extend(self.used(&roots));
        let bound: Vec<Symbol> = self.d.coordinates.iter().map(|c| c.momentum).collect();
        let names: Vec<Ident> = (bound.iter())
            .map(|p| symbol_ident(&self.d.pool, *p))
            .collect();
        let bridge = move |values: Vec<TokenStream>| {
            let lets = names.iter().zip(values);
            lets.map(|(name, value)| quote!(let #name = #value;))
                .collect()
        };
        let stage = Stage {
            first: &momenta,
            bound: &bound,
            bridge,
        };
        let lookups = lookups(Input::VelocityState);
        let b = staged_block(&self.d.pool, stage, &roots, "t", runtime, lookups);
        let relative: Vec<bool> = rigid.guards.iter().map(|(_, r)| *r).collect();
        let (rates, guards) = b.outputs.split_at(bound.len());
        let mut code = self.prologue(&used, Input::VelocityState);
        code.extend(b.lets);
        code.extend(guard_checks(guards, &relative, runtime));
        let v = self.vector(rates.to_vec());
        code.extend(quote!(Ok(#v)));
        Some(code)
    }

    /// Which entries of M (row-major) are identically zero.
    pub(crate) fn zero_pattern(&self) -> Vec<bool> {
        let entries = self.d.mass_matrix.iter().flatten();
        entries.map(|e| self.d.pool.is_zero(*e)).collect()
    }

    /// Whether evaluating `roots` needs any velocity.
    fn needs_velocities(&self, used: &BTreeSet<Symbol>) -> bool {
        used.iter()
            .any(|s| matches!(self.d.pool.symbols().kind(*s), SymbolKind::Velocity { .. }))
    }

    /// Prologue + shared subexpressions + the outputs, handed to `finish`. A method on the
    /// state that needs q̇ first solves it from p: in closed form inside the same CSE pass
    /// as the outputs, or by an LDLᵀ solve before them.
    pub(crate) fn body(
        &self,
        input: Input,
        roots: &[Id],
        finish: impl FnOnce(Vec<TokenStream>) -> TokenStream,
    ) -> TokenStream {
        let runtime = &self.target.runtime;
        let mut used = self.used(roots);
        let roots = &self.code_all(roots);
        let b = if input == Input::State && self.needs_velocities(&used) {
            let (first, bridge) = self.velocity_stage();
            used.extend(self.used(&first));
            used.extend(self.d.coordinates.iter().map(|c| c.momentum));
            let bound: Vec<Symbol> = self.d.coordinates.iter().map(|c| c.velocity).collect();
            let stage = Stage {
                first: &first,
                bound: &bound,
                bridge,
            };
            staged_block(&self.d.pool, stage, roots, "t", runtime, lookups(input))
        } else {
            block(&self.d.pool, roots, "t", runtime, lookups(input))
        };
        // Moved, not interpolated: `quote!` would clone every token of each part.
        let mut code = self.prologue(&used, input);
        code.extend(b.lets);
        code.extend(finish(b.outputs));
        code
    }

    pub(crate) fn vector(&self, values: Vec<TokenStream>) -> TokenStream {
        let runtime = &self.target.runtime;
        let len = Literal::usize_unsuffixed(values.len());
        let mut code = quote!(#runtime::nalgebra::SVector::<f64, #len>::from);
        let array = Group::new(Delimiter::Bracket, comma_separated(values));
        let call = TokenStream::from(TokenTree::Group(array));
        code.extend([TokenTree::Group(Group::new(Delimiter::Parenthesis, call))]);
        code
    }

    pub(crate) fn docs(&self, title: &str, lines: impl IntoIterator<Item = String>) -> TokenStream {
        let lines: Vec<String> = lines.into_iter().collect();
        let mut text = vec![title.to_string()];
        if !lines.is_empty() {
            text.extend([String::new(), "```text".to_string()]);
            text.extend(lines);
            text.push("```".to_string());
        }
        quote!(#(#[doc = #text])*)
    }

    /// `label = value   [unit]`, the unit from the derivation's units (see
    /// `Derivation::unit_suffix`).
    pub(crate) fn doc_line(&self, label: &str, value: Id, of: Of) -> String {
        let unit = self.d.unit_suffix(of);
        format!("{label} = {}{unit}", self.display(value))
    }

    /// One doc line per value of `quantity` (one per coordinate, or one for a scalar),
    /// labelled as the registry labels it in text.
    pub(crate) fn quantity_lines(&self, quantity: Quantity, values: &[Id]) -> Vec<String> {
        let scalar = matches!(quantity.spec().name, Named::Scalar(_));
        let names = self.d.coordinates.iter().map(|c| c.name.as_str());
        let names: Vec<&str> = if scalar { vec![""] } else { names.collect() };
        names
            .iter()
            .zip(values)
            .enumerate()
            .map(|(a, (name, v))| {
                self.doc_line(&quantity.text_label(name), *v, Of::Quantity(quantity, a))
            })
            .collect()
    }

    /// The doc lines of q̇ in closed form, `x' = …`.
    pub(crate) fn velocity_lines(&self, values: &[Id]) -> Vec<String> {
        let coordinates = self.d.coordinates.iter().zip(values).enumerate();
        coordinates
            .map(|(a, (c, v))| self.doc_line(&format!("{}'", c.name), *v, Of::Velocity(a)))
            .collect()
    }

    /// The method of a per-coordinate quantity of the registry, `fn name(&self, t,
    /// velocity_state) -> SVector<N>`, documented by its entry, returning zeros when every
    /// entry is identically zero. `None` for a quantity that no generated method carries.
    pub(crate) fn vector_method(&self, quantity: Quantity) -> TokenStream {
        let Some((method, doc)) = Method::carrying(quantity) else {
            return TokenStream::new();
        };
        let values = self.d.quantity(quantity);
        let runtime = &self.target.runtime;
        let n = self.sizes().coordinates_literal();
        let signature = self.signature(method);
        let docs = self.docs(doc, self.quantity_lines(quantity, &values));
        let all_zero = values.iter().all(|v| self.d.pool.is_zero(*v));
        let body = if all_zero {
            quote!(#runtime::nalgebra::SVector::<f64, #n>::zeros())
        } else {
            self.body(Input::VelocityState, &values, |outs| self.vector(outs))
        };
        method_item(docs, signature, body)
    }
}

/// `docs #[inline] signature { body }`, each part moved into place: `quote!` would clone
/// every token of the streams it interpolates, and a body is most of a method's tokens.
pub(crate) fn method_item(
    docs: TokenStream,
    signature: TokenStream,
    body: TokenStream,
) -> TokenStream {
    let mut code = docs;
    code.extend(quote!(#[inline]));
    code.extend(signature);
    code.extend([TokenTree::Group(Group::new(Delimiter::Brace, body))]);
    code
}

/// `<what>_count()` and `<what>_name(index)` of a list of `count` named items (the flows, the
/// switching functions), the names in their order.
pub(crate) fn count_and_names(what: &str, count: usize, names: &[String]) -> TokenStream {
    let (count_method, name_method) = (format_ident!("{what}_count"), format_ident!("{what}_name"));
    let count = Literal::usize_unsuffixed(count);
    let indices = (0..names.len()).map(Literal::usize_unsuffixed);
    quote! {
        #[inline]
        fn #count_method(&self) -> usize {
            #count
        }
        fn #name_method(&self, index: usize) -> ::core::option::Option<&str> {
            match index {
                #(#indices => ::core::option::Option::Some(#names),)*
                _ => ::core::option::Option::None,
            }
        }
    }
}

/// `a, b, c`, the parts moved into place (see [`method_item`]).
pub(crate) fn comma_separated(parts: Vec<TokenStream>) -> TokenStream {
    let mut list = TokenStream::new();
    for (i, part) in parts.into_iter().enumerate() {
        if i > 0 {
            list.extend([TokenTree::Punct(Punct::new(',', Spacing::Alone))]);
        }
        list.extend(part);
    }
    list
}
