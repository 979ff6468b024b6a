//! `taylor_coefficients(t, state, coefficients, scratch)` (`emit = [..., "taylor"]`): the
//! Taylor recurrences of the state rate as straight-line Rust, one statement per instruction
//! of the [`TaylorTape`]s of the three stages (the law masses; q̇, in closed form or solved
//! order by order; ṗ and ṁ of the state masses, over the slots of q̇'s stage), inside one
//! loop over the order k. Every subexpression is a row of coefficients of the caller's
//! scratch (`series::Scratch`, kept between expansions, never cleared: see there why it
//! need not be), bound to a local by name, shared subexpressions computed once;
//! each statement calls the runtime's recurrence for its operation
//! (`steppers::taylor::series`), so the formulas live in one place at run time and generated
//! code stays small. The stages and the loop are those of `varmass::interpret`'s Taylor
//! program (Jorba & Zou 2005, §2: y\[k+1\] = f\[k\]/(k+1)).

use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::{format_ident, quote};

use crate::expr::{Func, Instr, Op, TaylorTape};
use crate::mechanics::{Derivation, TaylorLayout, TaylorStages};

/// Names the arrays of one tape: its input slots are the shared `i<n>`, the rest
/// `<prefix><slot>`.
struct Names<'a> {
    tape: &'a TaylorTape,
    prefix: &'static str,
}

impl Names<'_> {
    /// The field of the jet holding `slot`'s coefficients.
    fn field(&self, slot: usize) -> Ident {
        match self.tape.input_slots().iter().position(|s| *s == slot) {
            Some(i) => input(i),
            None => format_ident!("{}{}", self.prefix, slot),
        }
    }

    /// `slot`'s coefficient array: the local bound to its row of the jet.
    fn of(&self, slot: usize) -> TokenStream {
        let field = self.field(slot);
        quote!(#field)
    }

    fn output(&self, i: usize) -> TokenStream {
        self.of(self
            .tape
            .output_slots()
            .get(i)
            .copied()
            .unwrap_or(usize::MAX))
    }

    /// The fields of the slots this tape's instructions write (inputs excluded).
    fn fields(&self) -> Vec<Ident> {
        self.fields_of(self.tape.written_slots())
    }

    /// The fields of the slots written at every order (inputs excluded).
    fn series_fields(&self) -> Vec<Ident> {
        self.fields_of(self.tape.series_written_slots())
    }

    /// The fields of `slots`, inputs left out (they are the shared `i<n>`, declared once).
    fn fields_of(&self, slots: Vec<usize>) -> Vec<Ident> {
        let inputs = self.tape.input_slots();
        slots
            .into_iter()
            .filter(|s| !inputs.contains(s))
            .map(|s| self.field(s))
            .collect()
    }
}

/// Orders 0 … `steppers::taylor::MAX_ORDER`: one instance of the per-order function each.
const ORDERS: usize = 33;

/// The row of the jet holding Taylor input `i` ([`TaylorLayout`]).
fn input(i: usize) -> Ident {
    format_ident!("i{}", i)
}

/// What the parts of the method read: the derivation, its stages and their inputs' layout,
/// the names of the three tapes' rows, and the runtime's path.
struct Method<'a> {
    d: &'a Derivation,
    st: &'a TaylorStages,
    layout: TaylorLayout,
    laws: Names<'a>,
    velocities: Names<'a>,
    rates: Names<'a>,
    runtime: &'a TokenStream,
    /// Each row's degree in t ([`degrees`]).
    degrees: &'a Degrees,
    /// Whether the per-order function is generic over the coefficient (`T`: `f64` for the
    /// scalar method, `Lanes<W>` for the lanes', `emit = [..., "taylor", "lanes"]`) and an
    /// inherent function of the system (`__taylor_order`), or the scalar method's own.
    generic: bool,
}

/// The `taylor_coefficients` method of `d`'s system `name`, with the runtime at `runtime`.
///
/// Every coefficient array is a field of one local struct, the jet, and the work of one
/// order k is a function generic over `const K: usize`, instantiated for each k and
/// dispatched by a `match` in the loop over the orders. With k a constant, every
/// recurrence's sum over j has a known length, so the compiler unrolls it into
/// straight-line code with constant offsets and no bounds checks (heyoka compiles one
/// function per order for the same reason); the arithmetic, and so every bit of the result,
/// is that of the loop over a run-time k (`tests/taylor_emitted.rs`).
///
/// With `generic` (the Taylor method in lanes is emitted too, [`taylor_lanes`]) the
/// per-order function is generic over the coefficient as well and lives beside the impl,
/// where both methods call it: one set of recurrences for `f64` and for `Lanes<W>`.
pub(crate) fn taylor_method(
    d: &Derivation,
    runtime: &TokenStream,
    name: &Ident,
    generic: bool,
) -> TokenStream {
    let st = d.taylor_stages();
    let degrees = degrees(&st);
    let m = Method::new(d, &st, runtime, &degrees, generic);
    let (ts, system, vector) = m.paths();
    let body = m.expansion(name, quote!(self), quote!(f64));
    quote! {
        /// The Taylor coefficients y[k] = y⁽ᵏ⁾(t)/k! of the solution through `(t, state)`
        /// (k ≤ `steppers::taylor::MAX_ORDER`), by the recurrences of automatic
        /// differentiation over the state rate (Jorba & Zou 2005).
        #[allow(unused_mut, unused_assignments, unused_variables, clippy::all)]
        fn taylor_coefficients(
            &self,
            t: f64,
            state: &#vector,
            coefficients: &mut [#vector],
            scratch: &mut #ts::Scratch,
        ) -> ::core::option::Option<::core::result::Result<(), #system>> {
            #body
        }
    }
}

/// What `emit = [..., "taylor", "lanes"]` adds: the per-order function generic over the
/// coefficient (`.0`, an inherent function of `name`, which [`taylor_method`] calls with
/// `f64`), and `LaneSystem::taylor_coefficients_lanes` (`.1`), the same expansion with
/// `Lanes<W>` coefficients and the lanes' parameters.
pub(crate) fn taylor_lanes(
    d: &Derivation,
    runtime: &TokenStream,
    name: &Ident,
) -> (TokenStream, TokenStream) {
    let st = d.taylor_stages();
    let degrees = degrees(&st);
    let m = Method::new(d, &st, runtime, &degrees, true);
    let (ts, system, _) = m.paths();
    let lane = quote!(#runtime::lanes::Lanes<W>);
    let s = Literal::usize_unsuffixed(m.layout.state_len());
    let body = m.expansion(name, quote!(parameters), lane.clone());
    let method = quote! {
        #[allow(unused_mut, unused_assignments, unused_variables, clippy::all)]
        fn taylor_coefficients_lanes(
            parameters: &Self::Parameters,
            t: #lane,
            state: &[#lane; #s],
            coefficients: &mut [[#lane; #s]],
            scratch: &mut #ts::Scratch<#lane>,
        ) -> ::core::option::Option<::core::result::Result<(), #system>> {
            #body
        }
    };
    (order_helper(d, runtime, name), method)
}

/// `impl name { __taylor_order }`: the per-order function generic over the coefficient,
/// which the scalar method, the lanes' and the tangents' call.
pub(crate) fn order_helper(d: &Derivation, runtime: &TokenStream, name: &Ident) -> TokenStream {
    let st = d.taylor_stages();
    let degrees = degrees(&st);
    let m = Method::new(d, &st, runtime, &degrees, true);
    let fields = m.fields();
    let (solve, _) = m.velocity_solve();
    let order_k = m.order_k(name, &fields, solve);
    quote! {
        #[allow(unused_mut, unused_assignments, unused_variables, clippy::all)]
        impl #name {
            #order_k
        }
    }
}

/// `taylor_coefficients_tangents` (`emit = [..., "taylor", "sensitivities"]`): the
/// expansion over `Tangent<W>` coefficients, t a constant and the parameters the tangents'
/// companion struct `tangents` seeded as the state rate over tangents seeds them; the
/// per-order function is the generic one ([`order_helper`]).
pub(crate) fn taylor_tangents(
    d: &Derivation,
    runtime: &TokenStream,
    (name, tangents): (&Ident, &Ident),
) -> TokenStream {
    let st = d.taylor_stages();
    let degrees = degrees(&st);
    let m = Method::new(d, &st, runtime, &degrees, true);
    let (ts, system, _) = m.paths();
    let tangent = quote!(#runtime::tangent::Tangent<W>);
    let s = Literal::usize_unsuffixed(m.layout.state_len());
    let body = m.expansion(name, quote!(parameters), tangent.clone());
    quote! {
        /// The Taylor coefficients over tangents (`emit = [..., "taylor", "sensitivities"]`).
        #[allow(unused_mut, unused_assignments, unused_variables, clippy::all)]
        fn taylor_coefficients_tangents<const W: usize>(
            &self,
            t: f64,
            state: &[#tangent; #s],
            seeds: &[::core::option::Option<usize>; W],
            coefficients: &mut [[#tangent; #s]],
            scratch: &mut #ts::Scratch<#tangent>,
        ) -> ::core::option::Option<::core::result::Result<(), #system>> {
            let parameters = #tangents::<W>::seeded(self, seeds);
            let t = #runtime::tangent::Tangent::<W>::constant(t);
            #body
        }
    }
}

impl<'a> Method<'a> {
    fn new(
        d: &'a Derivation,
        st: &'a TaylorStages,
        runtime: &'a TokenStream,
        degrees: &'a Degrees,
        generic: bool,
    ) -> Self {
        let names = |tape, prefix| Names { tape, prefix };
        Method {
            generic,
            degrees,
            d,
            st,
            layout: st.layout,
            laws: names(&st.laws, "l"),
            // q̇ and the rates share their slots (`ExprPool::compile_taylor_stages`): one
            // name each, declared once.
            velocities: names(&st.velocities, "v"),
            rates: names(&st.rates, "v"),
            runtime,
        }
    }

    /// The body of an expansion over coefficients `element`, the parameters read from
    /// `this` (the system, or the lanes' parameters): order 0, the loop over the orders,
    /// the state's coefficients out.
    fn expansion(&self, name: &Ident, this: TokenStream, element: TokenStream) -> TokenStream {
        let fields = self.fields();
        let (solve, factor_size) = self.velocity_solve();
        let factor_size = factor_size.unwrap_or_else(|| Literal::usize_unsuffixed(0));
        let start = self.start(&fields);
        let same_constants = self.same_constants();
        let out = (0..self.layout.state_len()).map(|j| {
            let from = input(self.layout.state(j));
            quote!(c[#j] = #from[k];)
        });
        let orders = (0..ORDERS).map(Literal::usize_unsuffixed);
        let orders_len = Literal::usize_unsuffixed(ORDERS);
        let rows = Literal::usize_unsuffixed(fields.len());
        let (ts, ..) = self.paths();
        // Generic: the system's `__taylor_order` (the state a slice of the lanes' array or
        // of the vector); otherwise the method's own `order_k` over its `Jet`.
        let (order_k, arms): (TokenStream, Vec<TokenStream>) = if self.generic {
            let state = match element.to_string() == "f64" {
                true => quote!(state.as_slice()),
                false => quote!(&state[..]),
            };
            let arms = orders.map(
                |k| quote!(#k => #name::__taylor_order::<#element, #k>(jet, factor, #state, last),),
            );
            (TokenStream::new(), arms.collect())
        } else {
            let order_k = self.order_k(name, &fields, solve);
            let arms = orders.map(|k| quote!(#k => order_k::<#k>(this, jet, factor, state, last),));
            let jet = quote! {
                /// One row of coefficients per subexpression, bound by name below.
                type Jet = [[f64; #ts::LEN]; #rows];
            };
            (quote!(#jet #order_k), arms.collect())
        };
        quote! {
            const _: () = assert!(#ts::LEN == #orders_len, "one instance per order");
            #order_k
            let order = coefficients.len().checked_sub(1)?.min(#ts::LEN - 1);
            let this = #this;
            /// This code's own type: the scratch knows whether this code used it last.
            struct Owner;
            let owner = ::core::any::TypeId::of::<Owner>();
            #same_constants
            let (jet, factor, fresh) = scratch.parts::<#rows>(#factor_size, owner);
            {
                #start
            }
            for k in 0..=order {
                let last = k == order;
                let failed = match k {
                    #(#arms)*
                    _ => None,
                };
                if failed.is_some() {
                    return failed;
                }
            }
            let [#(#fields),*] = &*jet;
            for (k, c) in coefficients.iter_mut().enumerate().take(order + 1) {
                #(#out)*
            }
            Some(Ok(()))
        }
    }

    /// The paths of the series module, of `SystemError` and of the state's vector type.
    fn paths(&self) -> (TokenStream, TokenStream, TokenStream) {
        let runtime = self.runtime;
        let s = Literal::usize_unsuffixed(self.layout.state_len());
        (
            quote!(#runtime::steppers::taylor::series),
            quote!(#runtime::SystemError),
            quote!(#runtime::nalgebra::SVector<f64, #s>),
        )
    }

    /// Every row of the jet: the inputs, then the rows each tape writes.
    fn fields(&self) -> Vec<Ident> {
        (0..self.layout.len())
            .map(input)
            .chain(self.laws.fields())
            .chain(self.velocities.fields())
            .chain(self.rates.fields())
            .collect()
    }

    /// The rows written at every order of an expansion before they are read: the series
    /// instructions' results, the state, q̇ and the law masses. Every other row (time, held
    /// inputs, constants) is set at order 0 alone: zeroed when the scratch is new to this
    /// code, so that a higher coefficient read from it is 0 whatever the scratch held
    /// (`series::Scratch`).
    fn written(&self) -> Vec<Ident> {
        let l = self.layout;
        (self.laws.series_fields().into_iter())
            .chain(self.velocities.series_fields())
            .chain(self.rates.series_fields())
            .chain((0..2 * l.n + l.state_masses).map(|j| input(l.state(j))))
            .chain((0..l.n).map(|a| input(l.velocity(a))))
            .chain(self.st.law_masses.iter().map(|mass| input(l.mass(*mass))))
            .collect()
    }

    /// The statements of the three tapes: their fixed instructions at order 0 (`fixed`), or
    /// their series instructions at order k.
    fn stages(&self, fixed: bool) -> [TokenStream; 3] {
        let k = if fixed { quote!(0) } else { quote!(k) };
        [&self.laws, &self.velocities, &self.rates]
            .map(|names| ops((self.d, self.degrees), names, fixed, &k, self.runtime))
    }

    /// Order 0 of the jet: the rows no series writes zeroed if the scratch is new to this
    /// code, t and the state into their inputs, then the fixed instructions.
    fn start(&self, fields: &[Ident]) -> TokenStream {
        let written = self.written();
        let zeroed = fields.iter().filter(|f| !written.contains(f));
        let (ts, ..) = self.paths();
        let state = (0..self.layout.state_len()).map(|j| {
            let name = input(self.layout.state(j));
            quote!(#name[0] = state[#j];)
        });
        let time = input(TaylorLayout::TIME);
        let fixed = self.stages(true);
        quote! {
            let [#(#fields),*] = &mut *jet;
            if fresh {
                #(*#zeroed = [#ts::splat(0.0f64); #ts::LEN];)*
            }
            #time[0] = t;
            #time[1] = #ts::splat(1.0f64);
            #(#state)*
            if fresh || !same {
                #(#fixed)*
            }
        }
    }

    /// `same`: whether the rows of the order-0 instructions still hold what they compute
    /// (`series::Scratch::same_constants`, keyed on the parameters they read); always
    /// `false` when one of them reads a table (its key would be the table itself).
    fn same_constants(&self) -> TokenStream {
        let fixed = || {
            [&self.laws, &self.velocities, &self.rates]
                .into_iter()
                .flat_map(|names| names.tape.fixed_instructions())
        };
        if fixed().any(|i| matches!(i.op, Op::Table { .. })) {
            return quote!(let same = false;);
        }
        let mut read: Vec<usize> = fixed()
            .filter_map(|i| match i.op {
                Op::Param(index) => Some(index),
                _ => None,
            })
            .collect();
        read.sort_unstable();
        read.dedup();
        let (ts, ..) = self.paths();
        let key = read.iter().map(|index| {
            let field = self.d.parameters.iter().find(|(_, s)| s.index() == *index);
            match field {
                Some((name, _)) => {
                    let field = Ident::new(name, Span::call_site());
                    quote!(this.#field)
                }
                None => quote!(#ts::splat(f64::NAN)),
            }
        });
        quote!(let same = scratch.same_constants(&[#(#key),*]);)
    }

    /// `order_k::<K>`, order K of every stage, then coefficient K + 1 of the state from
    /// the rates: y\[k+1\] = f\[k\]/(k+1) (q from q̇; a held input's higher coefficients stay
    /// 0: it is constant between samples).
    fn order_k(&self, name: &Ident, fields: &[Ident], solve: TokenStream) -> TokenStream {
        let l = self.layout;
        let [law_series, velocity_series, rate_series] = self.stages(false);
        let law_copies = self.st.law_masses.iter().enumerate().map(|(i, mass)| {
            let (to, from) = (input(l.mass(*mass)), self.laws.output(i));
            quote!(#to[k] = #from[k];)
        });
        let next = (0..2 * l.n + l.state_masses).map(|j| {
            let to = input(l.state(j));
            let from = if j < l.n {
                let velocity = input(l.velocity(j));
                quote!(#velocity)
            } else {
                self.rates.output(j - l.n)
            };
            quote!(#to[k + 1] = #from[k] * next;)
        });
        let (ts, system, vector) = self.paths();
        let signature = if self.generic {
            let rows = Literal::usize_unsuffixed(fields.len());
            quote! {
                #[doc(hidden)]
                #[inline]
                fn __taylor_order<T: #ts::Coefficient, const K: usize>(
                    jet: &mut [[T; #ts::LEN]; #rows],
                    factor: &mut [f64],
                    state: &[T],
                    last: bool,
                ) -> ::core::option::Option<::core::result::Result<(), #system>>
            }
        } else {
            quote! {
                fn order_k<const K: usize>(
                    this: &#name,
                    jet: &mut Jet,
                    factor: &mut [f64],
                    state: &#vector,
                    last: bool,
                ) -> ::core::option::Option<::core::result::Result<(), #system>>
            }
        };
        quote! {
            /// Order `K` of every stage; `Some` ends the expansion with an error.
            #[allow(unused_mut, unused_assignments, unused_variables, clippy::all)]
            #signature {
                let [#(#fields),*] = jet;
                let k = K;
                #law_series
                #(#law_copies)*
                #velocity_series
                #solve
                if last || K + 1 >= #ts::LEN {
                    return None;
                }
                #rate_series
                let next = 1.0 / (k + 1) as f64;
                #(#next)*
                None
            }
        }
    }

    /// Coefficient k of q̇ into its inputs: copied from the closed form (a non-finite value
    /// at order 0 is a singular M), or solved with M\[0\]'s factor, the scratch's `factor` of
    /// the size returned.
    fn velocity_solve(&self) -> (TokenStream, Option<Literal>) {
        let (l, names, runtime) = (self.layout, &self.velocities, self.runtime);
        let velocity = |a: usize| input(l.velocity(a));
        let singular = quote!(return Some(Err(#runtime::SystemError::SingularMassMatrix)););
        let state = match self.generic {
            true => quote!(state),
            false => quote!(state.as_slice()),
        };
        if !self.st.numeric {
            let copies = (0..l.n).map(|a| {
                let (to, from) = (velocity(a), names.output(a));
                quote! {
                    #to[k] = #from[k];
                    if k == 0 && #runtime::steppers::taylor::series::Coefficient::singular(#to[0], #state) {
                        #singular
                    }
                }
            });
            return (quote!(#(#copies)*), None);
        }
        let n = l.n;
        let matrix = (0..n * n).map(|e| names.output(e));
        let offset = (0..n).map(|a| names.output(n * n + a));
        let momenta = (0..n).map(|a| input(l.momentum(a)));
        let velocities = (0..n).map(velocity);
        let size = Literal::usize_unsuffixed(n * n);
        let solve = quote! {
            if !#runtime::steppers::taylor::series::solve_velocities(
                #n,
                (&[#(&*#matrix),*], &[#(&*#offset),*], &[#(&*#momenta),*]),
                &mut [#(&mut *#velocities),*],
                factor,
                k,
            ) {
                #singular
            }
        };
        (solve, Some(size))
    }
}

/// The statements of one tape's fixed (order-0) or series instructions at order `k`.
fn ops(
    (d, degrees): (&Derivation, &Degrees),
    names: &Names,
    fixed: bool,
    k: &TokenStream,
    runtime: &TokenStream,
) -> TokenStream {
    let list = if fixed {
        names.tape.fixed_instructions()
    } else {
        names.tape.series_instructions()
    };
    let statements = list.iter().map(|i| op((d, degrees), names, i, k, runtime));
    quote!(#(#statements)*)
}

fn number(x: f64) -> TokenStream {
    if x.is_nan() {
        quote!(f64::NAN)
    } else if x.is_infinite() {
        if x > 0.0 {
            quote!(f64::INFINITY)
        } else {
            quote!(f64::NEG_INFINITY)
        }
    } else {
        let lit = Literal::f64_unsuffixed(x.abs());
        if x.is_sign_negative() {
            quote!((-#lit))
        } else {
            quote!(#lit)
        }
    }
}

/// The value f(x) of a one-argument function as generated code writes it.
fn value(f: Func, x: TokenStream, runtime: &TokenStream) -> TokenStream {
    match f {
        Func::Sign => quote!(#runtime::math::sign(#x)),
        Func::Atan2 | Func::Min | Func::Max => quote!(f64::NAN),
        f => {
            let method = Ident::new(f.name(), Span::call_site());
            quote!(#x.#method())
        }
    }
}

fn op(
    (d, degrees): (&Derivation, &Degrees),
    names: &Names,
    instr: &Instr,
    k: &TokenStream,
    rt: &TokenStream,
) -> TokenStream {
    let ts = quote!(#rt::steppers::taylor::series);
    if let Some(statement) = bounded(degrees, names, instr, k, &ts) {
        return statement;
    }
    let w = names.of(instr.out);
    let n = |s: usize| names.of(s);
    // `w[k] = series::f(operands…, [w,] k)`: the recurrences whose only result is w, some
    // reading w's own lower coefficients.
    let call = |f: &str, operands: &[usize], own: bool| {
        let f = Ident::new(f, Span::call_site());
        let operands = operands.iter().map(|s| n(*s));
        let own = own.then(|| quote!(&*#w,));
        quote!(#w[#k] = #ts::#f(#(&*#operands,)* #own #k);)
    };
    match instr.op {
        Op::Const(c) => {
            let c = number(c);
            quote!(#w[0] = #ts::splat(#c);)
        }
        Op::Param(index) => parameter(d, &w, index, &ts),
        Op::Add { start, len } => {
            let terms = names.tape.operand_slots(start, len).iter().map(|s| n(*s));
            quote!(#w[#k] = #ts::add([#(#terms[#k]),*]);)
        }
        Op::Scale(c, a) => call("scale", &[c, a], false),
        Op::Affine { a, scale, offset } => {
            let (a, scale, offset) = (n(a), number(scale), number(offset));
            quote!(#w[#k] = #ts::affine(&*#a, #k, (#scale, #offset));)
        }
        Op::Mul(a, b) => call("mul", &[a, b], false),
        Op::Square(a) => call("square", &[a], false),
        Op::Recip(a) => call("recip", &[a], true),
        Op::Div(a, den) => call("div", &[a, den], true),
        Op::Sqrt(a) => call("sqrt_of", &[a], true),
        Op::Pow(a, e) => call("pow", &[a, e], true),
        Op::Exp(a) => call("exp", &[a], true),
        Op::SinCos { a, cos: c } | Op::SinhCosh { a, cosh: c } => {
            let (a, c, hyperbolic) = (n(a), n(c), matches!(instr.op, Op::SinhCosh { .. }));
            quote!(#ts::sin_cos(&*#a, &mut *#w, &mut *#c, #k, #hyperbolic);)
        }
        Op::Tan { a, v, f, .. } => {
            let (a, v, hyperbolic) = (n(a), n(v), f == Func::Tanh);
            quote!(#ts::tan(&*#a, &mut *#w, &mut *#v, #k, #hyperbolic);)
        }
        Op::Quotient { a, d: den, sign, f } => quotient(&ts, (&w, n(a), n(den)), (sign, f), k, rt),
        Op::Atan2 { y, x, d: den } if den == usize::MAX => {
            let (y, x) = (n(y), n(x));
            quote!(#w[0] = #ts::atan2_value(#y[0], #x[0]);)
        }
        Op::Atan2 { y, x, d: den } => {
            let (y, x, den) = (n(y), n(x), n(den));
            quote!(#w[#k] = #ts::atan2(&*#y, &*#x, &*#den, &*#w, #k);)
        }
        Op::Abs(a) => call("abs", &[a], false),
        Op::Sign(a) => call("sign", &[a], false),
        Op::Min(a, b) | Op::Max(a, b) => {
            let (a, b, larger) = (n(a), n(b), matches!(instr.op, Op::Max(..)));
            quote!(#w[#k] = #ts::min_max(&*#a, &*#b, #k, #larger);)
        }
        Op::Table {
            a,
            table,
            order,
            h,
            piece,
            ..
        } => table_op(d, (w, n(a), n(h)), (table, order), piece, names, k, rt),
    }
}

/// The recurrences that would read a polynomial operand's coefficients above its degree
/// ([`Degrees`]), with those terms left out: a sum's as an exact −0, which the compiler
/// drops (the constant m0 of m = m0 + c x is no addition at k ≥ 1), a product's and a
/// quotient's by `series::mul_bounded` and `series::div_bounded`; `None` when no operand
/// is a polynomial.
fn bounded(
    degrees: &Degrees,
    names: &Names,
    instr: &Instr,
    k: &TokenStream,
    ts: &TokenStream,
) -> Option<TokenStream> {
    let (w, n) = (names.of(instr.out), |s: usize| names.of(s));
    let degree = |s: usize| degrees.of(names, s);
    let literal = Literal::usize_unsuffixed;
    match instr.op {
        Op::Add { start, len } => {
            let slots = names.tape.operand_slots(start, len);
            if slots.iter().all(|s| degree(*s) >= FULL) {
                return None;
            }
            let terms = slots.iter().map(|s| {
                let t = n(*s);
                match degree(*s) {
                    FULL => quote!(#t[#k]),
                    d => {
                        let d = literal(d);
                        quote!(if #k <= #d { #t[#k] } else { #ts::splat(-0.0f64) })
                    }
                }
            });
            Some(quote!(#w[#k] = #ts::add([#(#terms),*]);))
        }
        Op::Mul(a, b) if degree(a).min(degree(b)) < FULL => {
            let (da, db) = (literal(degree(a)), literal(degree(b)));
            let (a, b) = (n(a), n(b));
            Some(quote!(#w[#k] = #ts::mul_bounded(&*#a, &*#b, #k, (#da, #db));))
        }
        Op::Div(a, den) if degree(den) < FULL => {
            let (a, den, dd) = (n(a), n(den), literal(degree(den)));
            Some(quote!(#w[#k] = #ts::div_bounded(&*#a, &*#den, &*#w, #k, #dd);))
        }
        _ => None,
    }
}

/// A parameter's value at order 0 (`this.field`; NaN for a slot that names none).
fn parameter(d: &Derivation, w: &TokenStream, index: usize, ts: &TokenStream) -> TokenStream {
    let field = d
        .parameters
        .iter()
        .find(|(_, s)| s.index() == index)
        .map(|(name, _)| Ident::new(name, Span::call_site()));
    match field {
        Some(field) => quote!(#w[0] = this.#field;),
        None => quote!(#w[0] = #ts::splat(f64::NAN);),
    }
}

/// w = f(a) by the quotient recurrence w′ den = sign·a′ (`Op::Quotient`: ln, asin, acos,
/// atan), its value at order 0 f(a\[0\]) (a closure over `f64`, applied lane by lane).
fn quotient(
    ts: &TokenStream,
    (w, a, den): (&TokenStream, TokenStream, TokenStream),
    (sign, f): (f64, Func),
    k: &TokenStream,
    rt: &TokenStream,
) -> TokenStream {
    let sign = number(sign);
    let at_zero = value(f, quote!(x), rt);
    let slope = slope(f);
    quote! {
        #w[#k] = #ts::quotient(
            &*#a, &*#den, &*#w, #k,
            (#sign, |x: f64| #at_zero, |x: f64, w: f64| #slope),
        );
    }
}

/// f′(x) written with x and w = f(x), for a tangent's derivative at order 0 (`quotient`:
/// ln, asin, acos, atan of the state, and any one-argument function of constants but exp,
/// abs and sign, which have ops of their own); NaN for any other, which never reaches it (a
/// tangent through NaN would be a non-finite coefficient, not a wrong one).
fn slope(f: Func) -> TokenStream {
    match f {
        Func::Sin => quote!(x.cos()),
        Func::Cos => quote!(-x.sin()),
        Func::Tan => quote!(1.0 + w * w),
        Func::Exp => quote!(w),
        Func::Ln => quote!(1.0 / x),
        Func::Tanh => quote!(1.0 - w * w),
        Func::Sinh => quote!(x.cosh()),
        Func::Cosh => quote!(x.sinh()),
        Func::Asin => quote!(1.0 / (1.0 - x * x).sqrt()),
        Func::Acos => quote!(-1.0 / (1.0 - x * x).sqrt()),
        Func::Atan => quote!(1.0 / (1.0 + x * x)),
        _ => quote!(f64::NAN),
    }
}

/// A table call (docs/tables.md#taylor-series): the piece holding a\[0\] looked up at
/// order 0 into the `piece` slots, then the series by the same function the tapes call.
fn table_op(
    d: &Derivation,
    (w, a, h): (TokenStream, TokenStream, TokenStream),
    (table, order): (u16, u8),
    piece: usize,
    names: &Names,
    k: &TokenStream,
    rt: &TokenStream,
) -> TokenStream {
    // Inside the per-order function the system is `this` (`self` is not in scope there).
    let reference = super::tables::reference(&d.pool, table, order).replace("self.", "this.");
    let reference = super::expression::tokens(&reference);
    let [p0, p1, p2, p3, p4] = [0, 1, 2, 3, 4].map(|i| names.of(piece + i));
    quote! {{
        let __local = if #k == 0 {
            let __l = #rt::table::local_or_nan(&#reference, #a[0]);
            #p0[0] = __l.knot;
            #p1[0] = __l.coefficients[0];
            #p2[0] = __l.coefficients[1];
            #p3[0] = __l.coefficients[2];
            #p4[0] = __l.coefficients[3];
            __l
        } else {
            #rt::table::Local {
                knot: #p0[0],
                coefficients: [#p1[0], #p2[0], #p3[0], #p4[0]],
                value: f64::NAN,
            }
        };
        let (__h, __w) = #rt::table::series_coefficient(&__local, |j| #a[j], |j| #h[j], #k);
        #h[#k] = __h;
        #w[#k] = __w;
    }}
}

/// A row's degree in t that stands for "a full series" (any degree from the highest order
/// up: no coefficient is known to vanish).
const FULL: usize = ORDERS;

/// Each row's degree in t over a step, by name: every coefficient above it is 0, exactly.
/// A product's convolution leaves out the terms that read one of those
/// (`series::mul_bounded`, `series::div_bounded`): the rocket's m = m0 − μt, or its state
/// mass at the constant rate −μ, is of degree 1, so p/m at order k is one product, not k
/// (issue 38).
struct Degrees(std::collections::HashMap<String, usize>);

impl Degrees {
    /// The degree of `slot` of the tape `names` names ([`FULL`] when unknown).
    fn of(&self, names: &Names, slot: usize) -> usize {
        let name = names.field(slot).to_string();
        self.0.get(&name).copied().unwrap_or(FULL)
    }
}

/// The degree of an instruction's result from its operands' (`of`): sums and constant
/// multiples keep it, products add, a quotient by a constant keeps the numerator's, abs
/// and sign (on one branch over the step) keep it or make it 0, min and max take one
/// argument's series; everything else is a full series unless every operand is constant.
fn op_degree(tape: &TaylorTape, op: &Op, of: impl Fn(usize) -> usize) -> usize {
    let full_unless_constant = |slots: &[usize]| {
        if slots.iter().all(|s| of(*s) == 0) {
            0
        } else {
            FULL
        }
    };
    let degree = match *op {
        Op::Const(_) | Op::Param(_) | Op::Sign(_) => 0,
        Op::Add { start, len } => (tape.operand_slots(start, len).iter())
            .map(|s| of(*s))
            .max()
            .unwrap_or(0),
        Op::Scale(_, a) | Op::Affine { a, .. } | Op::Abs(a) => of(a),
        Op::Mul(a, b) => of(a) + of(b),
        Op::Square(a) => 2 * of(a),
        Op::Div(a, d) if of(d) == 0 => of(a),
        Op::Min(a, b) | Op::Max(a, b) => of(a).max(of(b)),
        Op::Div(a, d) => full_unless_constant(&[a, d]),
        Op::Recip(a) | Op::Sqrt(a) | Op::Exp(a) => full_unless_constant(&[a]),
        Op::Pow(a, e) => full_unless_constant(&[a, e]),
        _ => FULL,
    };
    degree.min(FULL)
}

/// Every row's degree ([`Degrees`]): t is of degree 1, a constant row 0; a state
/// component's degree is its rate's plus one, q's its velocity's plus one, a law mass's
/// its law's, q̇ solved numerically a full series. The state's degrees are unknown before
/// the rates are, so they start at 0 and the three stages are evaluated again until no
/// degree grows (at most [`FULL`] times: each pass raises one at least, and a degree stops
/// at [`FULL`]): the least fixed point, which bounds the true degrees (by induction on
/// the order, every coefficient above a row's degree is computed from coefficients above
/// its operands' degrees, 0).
fn degrees(st: &TaylorStages) -> Degrees {
    let l = st.layout;
    let names = [
        Names {
            tape: &st.laws,
            prefix: "l",
        },
        Names {
            tape: &st.velocities,
            prefix: "v",
        },
        Names {
            tape: &st.rates,
            prefix: "v",
        },
    ];
    let mut degree: std::collections::HashMap<String, usize> = Default::default();
    let set = |degree: &mut std::collections::HashMap<String, usize>, name: Ident, d: usize| {
        degree.insert(name.to_string(), d.min(FULL));
    };
    for i in 0..l.len() {
        set(&mut degree, input(i), FULL);
    }
    set(&mut degree, input(TaylorLayout::TIME), 1);
    for j in 0..l.state_len() {
        set(&mut degree, input(l.state(j)), 0);
    }
    for _ in 0..=FULL + 1 {
        let before = degree.clone();
        for names in &names {
            for instr in names.tape.fixed_instructions() {
                set(&mut degree, names.field(instr.out), 0);
            }
            for instr in names.tape.series_instructions() {
                let of = |slot: usize| degree.get(&names.field(slot).to_string()).copied();
                let d = op_degree(names.tape, &instr.op, |slot| of(slot).unwrap_or(FULL));
                set(&mut degree, names.field(instr.out), d);
            }
            if std::ptr::eq(names.tape, &st.laws) {
                for (i, mass) in st.law_masses.iter().enumerate() {
                    let d = degree.get(&names.output(i).to_string()).copied();
                    set(&mut degree, input(l.mass(*mass)), d.unwrap_or(FULL));
                }
            }
            if std::ptr::eq(names.tape, &st.velocities) {
                for a in 0..l.n {
                    let d = degree.get(&names.output(a).to_string()).copied();
                    let d = if st.numeric { FULL } else { d.unwrap_or(FULL) };
                    set(&mut degree, input(l.velocity(a)), d);
                }
            }
        }
        for j in 0..2 * l.n + l.state_masses {
            let rate = if j < l.n {
                input(l.velocity(j)).to_string()
            } else {
                names[2].output(j - l.n).to_string()
            };
            let d = degree.get(&rate).copied().unwrap_or(FULL);
            set(&mut degree, input(l.state(j)), d.saturating_add(1));
        }
        if degree == before {
            return Degrees(degree);
        }
    }
    // No fixed point reached (it always is): no row is known to be a polynomial.
    Degrees(std::collections::HashMap::new())
}
