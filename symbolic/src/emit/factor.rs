//! Straight-line solves of M x = b for the mass matrix when q̇ or q̈ is not in closed form:
//! the LDLᵀ factorisation written out for the system's size, so that the generated code
//! has no loops, no generic matrix type and no square roots.
//!
//! For a symmetric positive definite M, column by column (k < j < i):
//!
//! ```text
//! d_j = m_jj − Σ_k l_jk u_jk,   u_ij = m_ij − Σ_k l_ik u_jk,   l_ij = u_ij / d_j
//! z_i = b_i − Σ_{k<i} l_ik z_k          (L z = b)
//! x_i = z_i / d_i − Σ_{k>i} l_ki x_k    (D Lᵀ x = z, from the last row up)
//! ```
//!
//! u_ij = l_ij d_j is the entry of L before its division by the pivot, kept rather than
//! recomputed as a product: each pivot costs one division, and no multiplication undoes it.
//! A pivot d_j that is not positive (or NaN) means M is not positive definite there, and one
//! at or below `RELATIVE_PIVOT_FLOOR` (√ε) of m_jj leaves the rates without half their digits
//! (a rigid body at the gimbal lock of its Euler sequence; the reasoning is at the constant,
//! in the core's `system.rs`): the code returns the given error, as the interpreter's and the
//! core's Cholesky factorisations do.

use proc_macro2::{Ident, TokenStream, TokenTree};
use quote::{format_ident, quote};

fn l(i: usize, j: usize) -> Ident {
    format_ident!("__ldl_l{}_{}", i, j)
}

fn u(i: usize, j: usize) -> Ident {
    format_ident!("__ldl_u{}_{}", i, j)
}

fn inverse_pivot(j: usize) -> Ident {
    format_ident!("__ldl_inv{}", j)
}

fn z(i: usize) -> Ident {
    format_ident!("__ldl_z{}", i)
}

/// `let`s that bind `solution[i]` to x_i of M x = b, with M given row-major (`matrix`, only
/// its lower triangle is read; `zero[i * n + j]` when that entry is identically zero) and b
/// as `rhs`; `SystemError::SingularMassMatrix` of the `runtime` crate is returned when M is
/// not positive definite or a pivot falls below the relative floor.
/// Entries of L that are zero whatever the state (no fill-in reaches them) are left out.
pub(crate) fn ldlt_solve(
    matrix: &[TokenStream],
    zero: &[bool],
    rhs: &[TokenStream],
    solution: &[Ident],
    runtime: &TokenStream,
) -> TokenStream {
    let n = solution.len();
    let lower = structure(zero, n);
    let mut out = factorisation(matrix, &lower, n, runtime);
    out.extend(substitution(rhs, solution, &lower));
    out
}

/// Which l_ij (i > j, row-major) can be nonzero: m_ij is, or some k < j has both l_ik and
/// l_jk nonzero (fill-in).
fn structure(zero: &[bool], n: usize) -> Vec<bool> {
    let mut nonzero = vec![false; n * n];
    for j in 0..n {
        for i in j + 1..n {
            let fill = (0..j).any(|k| nonzero[i * n + k] && nonzero[j * n + k]);
            nonzero[i * n + j] = !zero.get(i * n + j).copied().unwrap_or(false) || fill;
        }
    }
    nonzero
}

/// L (with its undivided entries u) and the inverse pivots 1/d_j.
fn factorisation(
    matrix: &[TokenStream],
    nonzero: &[bool],
    n: usize,
    runtime: &TokenStream,
) -> TokenStream {
    let error = quote!(#runtime::SystemError::SingularMassMatrix);
    let entry = |i: usize, j: usize| matrix.get(i * n + j).cloned().unwrap_or_default();
    let used = |i: usize, j: usize| nonzero[i * n + j];
    // u_ij as the code names it: the entry itself when it is one token, else a local.
    let mut undivided: Vec<TokenStream> = vec![TokenStream::new(); n * n];
    let mut out = TokenStream::new();
    for j in 0..n {
        let (m, d, inv) = (entry(j, j), format_ident!("__ldl_d{}", j), inverse_pivot(j));
        let minus = (0..j).filter(|k| used(j, *k)).map(|k| {
            let (ljk, ujk) = (l(j, k), &undivided[j * n + k]);
            quote!(- #ljk * #ujk)
        });
        let minus: Vec<TokenStream> = minus.collect();
        // d_0 = m_00: positive is the whole test. Later pivots are compared with m_jj.
        let floor = if minus.is_empty() {
            quote!(0.0)
        } else {
            let diagonal = if is_single_token(&m) {
                m.clone()
            } else {
                quote!((#m))
            };
            quote!(#runtime::system::RELATIVE_PIVOT_FLOOR * #diagonal)
        };
        let pivot = minus_terms(m, minus.into_iter());
        out.extend(quote! {
            let #d = #pivot;
            if !(#d > #floor) {
                return Err(#error);
            }
            let #inv = 1.0 / #d;
        });
        for i in (j + 1..n).filter(|i| used(*i, j)) {
            let minus: Vec<TokenStream> = (0..j)
                .filter(|k| used(i, *k) && used(j, *k))
                .map(|k| {
                    let (lik, ujk) = (l(i, k), &undivided[j * n + k]);
                    quote!(- #lik * #ujk)
                })
                .collect();
            let m = entry(i, j);
            let uij = if minus.is_empty() && is_single_token(&m) {
                m
            } else {
                let (name, value) = (u(i, j), minus_terms(m, minus.into_iter()));
                out.extend(quote!(let #name = #value;));
                quote!(#name)
            };
            let lij = l(i, j);
            out.extend(quote!(let #lij = #uij * #inv;));
            undivided[i * n + j] = uij;
        }
    }
    out
}

/// Whether `tokens` is a single name or literal (needs no parentheses as an operand).
fn is_single_token(tokens: &TokenStream) -> bool {
    let mut trees = tokens.clone().into_iter();
    matches!(
        (trees.next(), trees.next()),
        (Some(TokenTree::Ident(_) | TokenTree::Literal(_)), None)
    )
}

/// L z = b forward, then D Lᵀ x = z backward into the solution's names.
fn substitution(rhs: &[TokenStream], solution: &[Ident], nonzero: &[bool]) -> TokenStream {
    let n = solution.len();
    let used = |i: usize, j: usize| nonzero[i * n + j];
    let mut out = TokenStream::new();
    for i in 0..n {
        let (zi, b) = (z(i), rhs.get(i).cloned().unwrap_or_default());
        let minus = (0..i).filter(|k| used(i, *k)).map(|k| {
            let (lik, zk) = (l(i, k), z(k));
            quote!(- #lik * #zk)
        });
        let value = minus_terms(b, minus);
        out.extend(quote!(let #zi = #value;));
    }
    for i in (0..n).rev() {
        let (xi, zi, inv) = (&solution[i], z(i), inverse_pivot(i));
        let minus = (i + 1..n).filter(|k| used(*k, i)).map(|k| {
            let (lki, xk) = (l(k, i), &solution[k]);
            quote!(- #lki * #xk)
        });
        out.extend(quote!(let #xi = #zi * #inv #(#minus)*;));
    }
    out
}

/// `first`, or `(first) - t₁ - t₂ …` when there are terms to subtract.
fn minus_terms(first: TokenStream, terms: impl Iterator<Item = TokenStream>) -> TokenStream {
    let terms: Vec<TokenStream> = terms.collect();
    if terms.is_empty() {
        first
    } else if is_single_token(&first) {
        quote!(#first #(#terms)*)
    } else {
        quote!((#first) #(#terms)*)
    }
}
