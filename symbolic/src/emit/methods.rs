//! The trait methods, one generator each.

use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};

use super::factor::ldlt_solve;
use super::signature::Method;
use super::system::{count_and_names, method_item, Emitter, Input};
use crate::expr::Id;
use crate::mechanics::{Of, TimeTable, VelocitySolve};
use crate::quantity::Quantity;

impl Emitter<'_> {
    /// `mass(index, t, state)`: a state mass is read from the state, a law is evaluated.
    pub(crate) fn mass(&self) -> TokenStream {
        let n = self.sizes().coordinates;
        let mut arms = Vec::new();
        let mut docs = Vec::new();
        for (i, (m, law)) in self.d.masses.iter().zip(&self.d.closed_laws).enumerate() {
            let index = Literal::usize_unsuffixed(i);
            match law {
                None => {
                    let slot = Literal::usize_unsuffixed(2 * n + i);
                    let unit = self.d.unit_suffix(Of::Mass(i));
                    docs.push(format!(
                        "{} = state[{}] (state mass){unit}",
                        m.name,
                        2 * n + i
                    ));
                    arms.push(quote!(#index => state[#slot],));
                }
                Some(law) => {
                    docs.push(self.doc_line(&m.name, *law, Of::Mass(i)));
                    let body = self.body(Input::Configuration, &[*law], |mut outs| {
                        outs.pop().unwrap_or_default()
                    });
                    arms.push(quote!(#index => { #body },));
                }
            }
        }
        let title = "The masses and inertias, state masses first.";
        self.indexed_method(Method::Mass, title, docs, arms)
    }

    /// A method taking a mass `index`: one `match` arm per mass, NaN past the last (the
    /// trait's contract for an index out of range).
    fn indexed_method(
        &self,
        method: Method,
        title: &str,
        docs: Vec<String>,
        arms: Vec<TokenStream>,
    ) -> TokenStream {
        let docs = self.docs(title, docs);
        let body = quote! {
            match index {
                #(#arms)*
                _ => f64::NAN,
            }
        };
        method_item(docs, self.signature(method), body)
    }

    /// `mass_rate(index, t, velocity_state)`.
    pub(crate) fn mass_rate(&self) -> TokenStream {
        let mut arms = Vec::new();
        let mut docs = Vec::new();
        for (i, (m, rate)) in self.d.masses.iter().zip(&self.d.mass_rates).enumerate() {
            let index = Literal::usize_unsuffixed(i);
            let label = Quantity::MassRates.text_label(&m.name);
            docs.push(self.doc_line(&label, *rate, Of::Quantity(Quantity::MassRates, i)));
            if self.d.pool.is_zero(*rate) {
                arms.push(quote!(#index => 0.0,));
            } else {
                let body = self.body(Input::VelocityState, &[*rate], |mut outs| {
                    outs.pop().unwrap_or_default()
                });
                arms.push(quote!(#index => { #body },));
            }
        }
        let title = title(Quantity::MassRates);
        self.indexed_method(Method::MassRate, title, docs, arms)
    }

    /// `mass_matrix(t, state)`.
    pub(crate) fn mass_matrix(&self) -> TokenStream {
        let runtime = &self.target.runtime;
        let sizes = self.sizes();
        let (n, n_lit) = (sizes.coordinates, sizes.coordinates_literal());
        let entries: Vec<Id> = self.d.mass_matrix.iter().flatten().copied().collect();
        let docs = self.docs(
            "The mass matrix M = ∂²L/∂q̇² (masses frozen), row by row.",
            (0..n).map(|a| {
                let row: Vec<String> = (0..n)
                    .map(|b| self.display(self.d.mass_matrix[a][b]))
                    .collect();
                format!("[{}]", row.join(", "))
            }),
        );
        let body = self.body(Input::Configuration, &entries, |outs| {
            quote!(#runtime::nalgebra::SMatrix::<f64, #n_lit, #n_lit>::from_row_slice(&[#(#outs),*]))
        });
        let signature = self.signature(Method::MassMatrix);
        method_item(docs, signature, body)
    }

    /// `lagrangian(t, velocity_state)`.
    pub(crate) fn lagrangian(&self) -> TokenStream {
        let lagrangian = (Quantity::Lagrangian, self.d.lagrangian);
        self.quantity_method(Method::Lagrangian, Input::VelocityState, lagrangian, false)
    }

    /// A method whose value is the scalar `quantity`'s expression `root` of `input`,
    /// documented by the quantity's registry entry (see [`Self::scalar_method`]).
    fn quantity_method(
        &self,
        method: Method,
        input: Input,
        (quantity, root): (Quantity, Id),
        fallible: bool,
    ) -> TokenStream {
        let lines = self.quantity_lines(quantity, &[root]);
        let docs = self.docs(title(quantity), lines);
        self.scalar_method(method, docs, (input, root), fallible)
    }

    /// A method whose value is the one expression `root` of its input, returned as it is or
    /// (`fallible`) as `Ok`.
    fn scalar_method(
        &self,
        method: Method,
        docs: TokenStream,
        (input, root): (Input, Id),
        fallible: bool,
    ) -> TokenStream {
        let body = self.body(input, &[root], |mut o| {
            let value = o.pop().unwrap_or_default();
            if fallible {
                quote!(Ok(#value))
            } else {
                value
            }
        });
        method_item(docs, self.signature(method), body)
    }

    /// `accelerations(t, velocity_state)`: q̈ in closed form, or M q̈ = rhs solved by the
    /// closed form of M⁻¹ (a lone quaternion body) or the straight-line LDLᵀ of `factor.rs`.
    pub(crate) fn accelerations(&self) -> TokenStream {
        let (docs, body) = match &self.d.accelerations {
            Some(acc) => (
                self.docs(
                    "Lagrange-form accelerations q̈(q, q̇, t) (eq. 6, masses frozen).",
                    self.quantity_lines(Quantity::Accelerations, acc),
                ),
                self.body(Input::VelocityState, acc, |outs| {
                    let v = self.vector(outs);
                    quote!(Ok(#v))
                }),
            ),
            None => match self.rigid_acceleration_body() {
                Some(body) => (self.rigid_acceleration_docs(), body),
                None => self.ldlt_accelerations(),
            },
        };
        let signature = self.signature(Method::Accelerations);
        method_item(docs, signature, body)
    }

    /// The docs of q̈ as the rate of the closed form of q̇ (a lone quaternion body).
    fn rigid_acceleration_docs(&self) -> TokenStream {
        let line = "q'' = d/dt q'(q, p, t, m) along the motion = Σ ∂q'/∂q_j q'_j + q'(q, ṗ) \
             + ∂q'/∂t + Σ ∂q'/∂m_k ṁ_k, q' in closed form (velocities), p = M q'";
        self.docs(
            "Lagrange-form accelerations (eq. 6): the rate of q̇ in closed form, equal to M⁻¹ rhs.",
            [line.to_string()],
        )
    }

    /// The docs and body of q̈ from M q̈ = rhs by the straight-line LDLᵀ.
    fn ldlt_accelerations(&self) -> (TokenStream, TokenStream) {
        let runtime = &self.target.runtime;
        let n_lit = self.sizes().coordinates_literal();
        let mut roots: Vec<Id> = self.d.mass_matrix.iter().flatten().copied().collect();
        let m = roots.len();
        roots.extend(&self.d.acceleration_rhs);
        let docs = self.docs(
            "Lagrange-form accelerations: solves M q̈ = rhs (eq. 6, masses frozen) with",
            self.quantity_lines(Quantity::AccelerationRhs, &self.d.acceleration_rhs),
        );
        let zero = self.zero_pattern();
        let body = self.body(Input::VelocityState, &roots, |outs| {
            let (matrix, rhs) = outs.split_at(m);
            let names: Vec<Ident> = (0..rhs.len())
                .map(|i| format_ident!("__ldl_x{}", i))
                .collect();
            let solve = ldlt_solve(matrix, &zero, rhs, &names, runtime);
            quote! {
                #solve
                Ok(#runtime::nalgebra::SVector::<f64, #n_lit>::from([#(#names),*]))
            }
        });
        (docs, body)
    }

    /// `velocities(t, state)`: q̇(q, p), overridden only when it is in closed form: solved
    /// symbolically, or a lone body turned by a quaternion (`mechanics/rigid_solve.rs`; the
    /// trait's default would factor its 7×7 M at every call, docs/bench/calisto.md).
    pub(crate) fn velocities(&self) -> TokenStream {
        let quaternion = (self.d.rigid_velocities.as_ref()).is_some_and(|r| r.quaternion);
        let (v, lines) = match &self.d.velocities {
            VelocitySolve::Symbolic(v) => (v.clone(), self.velocity_lines(v)),
            VelocitySolve::Numeric if quaternion => (self.velocity_roots(), self.velocity_docs()),
            VelocitySolve::Numeric => return TokenStream::new(),
        };
        let docs = self.docs("q̇(q, p, t) = M⁻¹ (p − b), in closed form.", lines);
        let body = self.body(Input::State, &v, |outs| {
            let v = self.vector(outs);
            quote!(Ok(#v))
        });
        let signature = self.signature(Method::Velocities);
        method_item(docs, signature, body)
    }

    /// `hamiltonian(t, state)`.
    pub(crate) fn hamiltonian(&self) -> TokenStream {
        let energy = Of::Quantity(Quantity::Energy, 0);
        let (root, line) = match self.d.hamiltonian {
            Some(h) => (h, self.doc_line("H", h, energy)),
            None => (
                self.d.energy,
                format!(
                    "H = {}   (q̇ from M q̇ = p − b){}",
                    self.display(self.d.energy),
                    self.d.unit_suffix(energy)
                ),
            ),
        };
        let docs = self.docs(title(Quantity::Energy), [line]);
        self.scalar_method(Method::Hamiltonian, docs, (Input::State, root), true)
    }

    /// `canonical_rates(t, state)`: (q̇, d*p/dt) of eq. 14.
    pub(crate) fn canonical_rates(&self) -> TokenStream {
        let n = self.sizes().coordinates;
        let velocities: Vec<Id> = self.velocity_roots();
        let mut roots = velocities.clone();
        roots.extend(&self.d.frozen_momentum_rate);
        let mut lines = self.velocity_docs();
        let frozen = &self.d.frozen_momentum_rate;
        lines.extend(self.quantity_lines(Quantity::FrozenMomentumRate, frozen));
        let docs = self.docs(
            "The canonical equations (eq. 14): q̇ = ∂*H/∂p, d*p/dt = −∂*H/∂q + Q* − R1 + R2.",
            lines,
        );
        let body = self.body(Input::State, &roots, |outs| {
            let (v, dp) = outs.split_at(n);
            let (v, dp) = (self.vector(v.to_vec()), self.vector(dp.to_vec()));
            quote!(Ok((#v, #dp)))
        });
        let signature = self.signature(Method::CanonicalRates);
        method_item(docs, signature, body)
    }

    /// The velocity symbols as expressions (q̇ itself, bound by the prologue).
    fn velocity_roots(&self) -> Vec<Id> {
        self.velocity_ids.clone()
    }

    /// Doc lines for q̇: the closed form, or the linear solve.
    fn velocity_docs(&self) -> Vec<String> {
        match &self.d.velocities {
            VelocitySolve::Symbolic(v) => self.velocity_lines(v),
            // A lone spatial rigid body: the closed form through E⁻¹ and I⁻¹
            // (`mechanics/rigid_solve.rs`), not the LDLᵀ.
            VelocitySolve::Numeric
                if self
                    .d
                    .rigid_velocities
                    .as_ref()
                    .is_some_and(|r| r.quaternion) =>
            {
                vec!["q' from p in closed form: ω = I⁻¹(½ G p_q − c × P), \
                 ṙ = R(P/m − ω × c), q̇ = ½ Gᵀ ω + (qᵀ p_q/λ) q"
                    .to_string()]
            }
            VelocitySolve::Numeric if self.d.rigid_velocities.is_some() => {
                vec!["q' from p in closed form: ω = I⁻¹(E⁻ᵀ p_η − c × P), \
                 ṙ = R(P/m − ω × c), η̇ = E⁻¹ ω"
                    .to_string()]
            }
            VelocitySolve::Numeric => vec!["q' from M q' = p - b (LDLᵀ)".to_string()],
        }
    }

    /// `state_rate(t, state)`: [q̇, ṗ, ṁ_s], the integration hot path, fused.
    pub(crate) fn state_rate(&self) -> TokenStream {
        let k = self.sizes().state_masses;
        let roots = self.state_rate_roots();
        let mut lines = self.velocity_docs();
        lines.extend(self.quantity_lines(Quantity::MomentumRate, &self.d.momentum_rate));
        let state_masses = self.d.masses.iter().zip(&self.d.mass_rates).take(k);
        for (i, (m, rate)) in state_masses.enumerate() {
            let label = Quantity::MassRates.text_label(&m.name);
            lines.push(self.doc_line(&label, *rate, Of::Quantity(Quantity::MassRates, i)));
        }
        let docs = self.docs(
            "The state rate [q̇, ṗ, ṁ_s] with the true ṗ = d*p/dt + Σ ṁᵢ ∂*p/∂mᵢ.",
            lines,
        );
        let held = self.d.held().len();
        let body = self.body(Input::State, &roots, |mut outs| {
            // A held value is constant between samples: its rate is 0.
            outs.extend((0..held).map(|_| quote!(0.0)));
            let v = self.vector(outs);
            quote!(Ok(#v))
        });
        let signature = self.signature(Method::StateRate);
        method_item(docs, signature, body)
    }

    /// `power(t, state)`: the energy-budget dH/dt.
    pub(crate) fn power(&self) -> TokenStream {
        let power = (Quantity::Power, self.d.power);
        self.quantity_method(Method::Power, Input::State, power, true)
    }

    /// `jacobian(t, state)` from the derivation's blocks, combined with M⁻¹ numerically.
    pub(crate) fn jacobian(&self) -> TokenStream {
        let runtime = &self.target.runtime;
        let sizes = self.sizes();
        let (n, k) = (sizes.coordinates, sizes.state_masses);
        let (n_lit, s) = (sizes.coordinates_literal(), sizes.state_literal());
        let Some(j) = &self.d.jacobian else {
            // Not derived: the trait's finite-difference default serves.
            return TokenStream::new();
        };
        let blocks: [&Vec<Vec<Id>>; 6] = [
            &j.rate_wrt_q,
            &j.rate_wrt_velocity,
            &j.rate_wrt_state_mass,
            &j.momentum_wrt_q,
            &j.momentum_wrt_state_mass,
            &self.d.mass_matrix,
        ];
        let mut roots = Vec::new();
        let mut sizes = Vec::new();
        for b in blocks {
            let entries: Vec<Id> = b.iter().flatten().copied().collect();
            sizes.push(entries.len());
            roots.extend(entries);
        }
        let nk = Literal::usize_unsuffixed(n + k);
        // The state masses' columns, then the held inputs' (rate 0: no rows of their own).
        let columns = k + self.d.held().len();
        let k_lit = Literal::usize_unsuffixed(columns);
        let docs = self.docs(
            "The Jacobian ∂[q̇, ṗ, ṁ_s]/∂[q, p, m_s]: J_q = F_q − F_v M⁻¹ P_q, J_p = F_v M⁻¹, J_m = F_m − F_v M⁻¹ P_m.",
            Vec::<String>::new(),
        );
        let body = self.body(Input::State, &roots, |outs| {
            let mut rest: &[TokenStream] = &outs;
            let mut take = |len: usize| {
                let (head, tail) = rest.split_at(len);
                rest = tail;
                head.to_vec()
            };
            let (fq, fv, fm, pq, pm, mm) = (take(sizes[0]), take(sizes[1]), take(sizes[2]), take(sizes[3]), take(sizes[4]), take(sizes[5]));
            let na = quote!(#runtime::nalgebra);
            let state_mass_blocks = if columns == 0 {
                TokenStream::new()
            } else {
                quote! {
                    let __fm = #na::SMatrix::<f64, #nk, #k_lit>::from_row_slice(&[#(#fm),*]);
                    let __pm = #na::SMatrix::<f64, #n_lit, #k_lit>::from_row_slice(&[#(#pm),*]);
                    let __dv_dm = -(__inverse * __pm);
                    __jacobian.fixed_view_mut::<#n_lit, #k_lit>(0, 2 * #n_lit).copy_from(&__dv_dm);
                    __jacobian.fixed_view_mut::<#nk, #k_lit>(#n_lit, 2 * #n_lit).copy_from(&(__fm + __fv * __dv_dm));
                }
            };
            quote! {
                let __fq = #na::SMatrix::<f64, #nk, #n_lit>::from_row_slice(&[#(#fq),*]);
                let __fv = #na::SMatrix::<f64, #nk, #n_lit>::from_row_slice(&[#(#fv),*]);
                let __pq = #na::SMatrix::<f64, #n_lit, #n_lit>::from_row_slice(&[#(#pq),*]);
                let __mass_matrix = #na::SMatrix::<f64, #n_lit, #n_lit>::from_row_slice(&[#(#mm),*]);
                let __inverse = __mass_matrix
                    .cholesky()
                    .ok_or(#runtime::SystemError::SingularMassMatrix)?
                    .inverse();
                let __dv_dq = -(__inverse * __pq);
                let mut __jacobian = #na::SMatrix::<f64, #s, #s>::zeros();
                __jacobian.fixed_view_mut::<#n_lit, #n_lit>(0, 0).copy_from(&__dv_dq);
                __jacobian.fixed_view_mut::<#n_lit, #n_lit>(0, #n_lit).copy_from(&__inverse);
                __jacobian.fixed_view_mut::<#nk, #n_lit>(#n_lit, 0).copy_from(&(__fq + __fv * __dv_dq));
                __jacobian.fixed_view_mut::<#nk, #n_lit>(#n_lit, #n_lit).copy_from(&(__fv * __inverse));
                #state_mass_blocks
                Ok(__jacobian)
            }
        });
        let signature = self.signature(Method::Jacobian);
        method_item(docs, signature, body)
    }

    /// `parameter_jacobian(t, state, out)` and `parameter_names()` (`emit = [...,
    /// "sensitivities"]`): ∂[q̇, ṗ, ṁ_s, held]/∂θ at a fixed state [q, p, m_s], row-major
    /// S × P into `out`, θ the parameters in `PARAMETERS` order. q̇ = M⁻¹ (p − b(q, θ)) moves
    /// with θ at fixed p: J_θ = F_θ − F_v M⁻¹ P_θ, F_θ and P_θ at fixed q̇ (mass laws
    /// followed), the q̇ rows −M⁻¹ P_θ, the held inputs' rows 0.
    pub(crate) fn parameter_jacobian(&self, time_tables: &[TimeTable]) -> TokenStream {
        let runtime = &self.target.runtime;
        let sizes = self.sizes();
        let (n, k) = (sizes.coordinates, sizes.state_masses);
        let Some(j) = &self.d.jacobian else {
            return TokenStream::new();
        };
        let p = self.d.parameters.len();
        let names: Vec<&str> = self
            .d
            .parameters
            .iter()
            .map(|(name, _)| name.as_str())
            .collect();
        let blocks: [&Vec<Vec<Id>>; 4] = [
            &j.rate_wrt_parameter,
            &j.rate_wrt_velocity,
            &j.momentum_wrt_parameter,
            &self.d.mass_matrix,
        ];
        let lens: Vec<usize> = blocks.iter().map(|b| b.iter().flatten().count()).collect();
        let roots: Vec<Id> = blocks
            .iter()
            .flat_map(|b| b.iter().flatten().copied())
            .collect();
        let (n_lit, nk) = (
            Literal::usize_unsuffixed(n),
            Literal::usize_unsuffixed(n + k),
        );
        let (p_lit, s) = (Literal::usize_unsuffixed(p), sizes.state_literal());
        let docs = self.docs(
            "∂[q̇, ṗ, ṁ_s, held]/∂θ at a fixed state, row-major S × P into `out` (θ in \
             `PARAMETERS` order): J_θ = F_θ − F_v M⁻¹ P_θ.",
            Vec::<String>::new(),
        );
        let body = self.body(Input::State, &roots, |outs| {
            let (ft, rest) = outs.split_at(lens[0]);
            let (fv, rest) = rest.split_at(lens[1]);
            let (pt, mm) = rest.split_at(lens[2]);
            let na = quote!(#runtime::nalgebra);
            quote! {
                let __ft = #na::SMatrix::<f64, #nk, #p_lit>::from_row_slice(&[#(#ft),*]);
                let __fv = #na::SMatrix::<f64, #nk, #n_lit>::from_row_slice(&[#(#fv),*]);
                let __pt = #na::SMatrix::<f64, #n_lit, #p_lit>::from_row_slice(&[#(#pt),*]);
                let __mass_matrix = #na::SMatrix::<f64, #n_lit, #n_lit>::from_row_slice(&[#(#mm),*]);
                let __dv_dt = -(__mass_matrix
                    .cholesky()
                    .ok_or(#runtime::SystemError::SingularMassMatrix)?
                    .solve(&__pt));
                let mut __j = #na::SMatrix::<f64, #s, #p_lit>::zeros();
                __j.fixed_view_mut::<#n_lit, #p_lit>(0, 0).copy_from(&__dv_dt);
                __j.fixed_view_mut::<#nk, #p_lit>(#n_lit, 0).copy_from(&(__ft + __fv * __dv_dt));
                for (slot, value) in out.iter_mut().zip(__j.transpose().iter()) {
                    *slot = *value;
                }
                Ok(true)
            }
        });
        let signature = quote! {
            fn parameter_jacobian(
                &self,
                t: f64,
                state: &#runtime::nalgebra::SVector<f64, #s>,
                out: &mut [f64],
            ) -> ::core::result::Result<bool, #runtime::SystemError>
        };
        let mut code = method_item(docs, signature, body);
        code.extend(self.sensitivity_names(&names, time_tables));
        code
    }

    /// `parameter_names` and `sensitivity_obstacle`, beside `parameter_jacobian`.
    fn sensitivity_names(&self, names: &[&str], time_tables: &[TimeTable]) -> TokenStream {
        let obstacle = match crate::mechanics::sensitivity_obstacle(self.d, time_tables) {
            Some(reason) => quote!(::core::option::Option::Some(#reason)),
            None => quote!(::core::option::Option::None),
        };
        quote! {
            fn parameter_names(&self) -> &'static [&'static str] {
                &[#(#names),*]
            }
            fn sensitivity_obstacle(&self) -> ::core::option::Option<&'static str> {
                #obstacle
            }
        }
    }
}

impl Emitter<'_> {
    /// `flow_count`, `flow_name` and `flow_rate(index, t, velocity_state)`: each flow's rate
    /// (Q1 of an outflow, Q2 of an inflow, eqs. 15–16), which a run checks is ≥ 0 at every
    /// point. Nothing when there are no flows (the trait's defaults).
    pub(crate) fn flow_rates(&self) -> TokenStream {
        let d = self.d;
        if d.flow_rates.is_empty() {
            return TokenStream::new();
        }
        let docs = self.docs(
            "The flows' rates, ≥ 0 by definition: a run ends where one is negative.",
            d.flow_names
                .iter()
                .zip(&d.flow_rates)
                .map(|(name, rate)| format!("{name}: {}", self.display(*rate))),
        );
        let arms = d.flow_rates.iter().enumerate().map(|(i, rate)| {
            let index = Literal::usize_unsuffixed(i);
            let body = self.body(Input::VelocityState, &[*rate], |mut outs| {
                outs.pop().unwrap_or_default()
            });
            quote!(#index => { #body },)
        });
        let mut code = count_and_names("flow", d.flow_rates.len(), &d.flow_names);
        let body = quote!(match index {
            #(#arms)*
            _ => f64::NAN,
        });
        code.extend(method_item(docs, self.signature(Method::FlowRate), body));
        code
    }

    /// `singular_attitude_distance(t, state)`: the angle from gimbal lock of the spatial
    /// rigid bodies' Euler sequences, from their middle angles (nothing without them: the
    /// trait's `None`).
    pub(crate) fn singular_attitude_distance(&self) -> TokenStream {
        let d = self.d;
        if d.euler_middles.is_empty() {
            return TokenStream::new();
        }
        let runtime = &self.target.runtime;
        let docs = self.docs(
            "The angle from gimbal lock: the Euler middle angles' distance to π/2 + kπ \
             (Tait–Bryan) or kπ (proper).",
            d.euler_middles.iter().map(|(angle, proper)| {
                format!(
                    "{} ({})",
                    self.display(*angle),
                    match proper {
                        true => "proper",
                        false => "Tait–Bryan",
                    }
                )
            }),
        );
        let angles: Vec<Id> = d.euler_middles.iter().map(|(angle, _)| *angle).collect();
        let propers = d.euler_middles.iter().map(|(_, proper)| *proper);
        let body = self.body(Input::Configuration, &angles, |outs| {
            quote!(Some(#runtime::math::singular_attitude_distance(&[#((#outs, #propers)),*])))
        });
        let signature = self.signature(Method::SingularAttitudeDistance);
        method_item(docs, signature, body)
    }
}

/// The doc comment's title of the method that carries `quantity` ([`Method::carrying`]);
/// every caller passes a quantity that one carries.
fn title(quantity: Quantity) -> &'static str {
    Method::carrying(quantity).map_or("", |(_, title)| title)
}
