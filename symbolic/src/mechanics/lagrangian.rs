//! L = T − V, the momenta p = ∂*L/∂q̇ (eq. 8) and the mass matrix M = ∂²L/∂q̇², with the
//! checks that make the Legendre transform possible (L at most quadratic in q̇, M regular).

use super::linear::Matrix;
use super::model::{Model, Term, TermKind};
use crate::expr::{ExprPool, Id, Rational, SamplePoints, Symbol};
use crate::parse::Diagnostic;

/// The kinetic and potential parts and their sum.
pub(crate) struct Energies {
    pub kinetic: Id,
    pub potential: Id,
    pub lagrangian: Id,
    /// ṙ for every body (d*/dt of its position).
    pub body_velocities: Vec<Vec<Id>>,
}

/// Builds T (½ m |ṙ|² per body plus `kinetic` terms), V and L, checking that each
/// contribution is at most quadratic in the velocities.
pub(crate) fn energies(
    model: &mut Model,
    velocities: &[Symbol],
) -> Result<Energies, Vec<Diagnostic>> {
    let mut errors = Vec::new();
    let (mut kinetic_terms, body_velocities) = body_kinetic_terms(model, &mut errors);
    let mut potential_terms = Vec::new();
    let mut lagrangian_terms = Vec::new();
    let pool = &mut model.pool;
    for term in &model.terms {
        if let Some(offender) = non_quadratic_term(pool, term.value, velocities) {
            errors.push(non_quadratic_diagnostic(pool, term, offender));
            continue;
        }
        match term.kind {
            TermKind::Kinetic => kinetic_terms.push(term.value),
            TermKind::Potential => potential_terms.push(term.value),
            TermKind::Lagrangian => lagrangian_terms.push(term.value),
        }
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    // Expanded and trigonometrically reduced, so that a linkage's T reads as in a textbook
    // (sin² + cos² = 1, cos a cos b + sin a sin b = cos(a − b)) and every quantity derived
    // from L starts from its simplest form.
    let kinetic = pool.add(&kinetic_terms);
    let kinetic = pool.reduce_trig(kinetic);
    let potential = pool.add(&potential_terms);
    let potential = pool.reduce_trig(potential);
    let minus_v = pool.neg(potential);
    lagrangian_terms.push(kinetic);
    lagrangian_terms.push(minus_v);
    let lagrangian = pool.add(&lagrangian_terms);
    let lagrangian = pool.reduce_trig(lagrangian);
    Ok(Energies {
        kinetic,
        potential,
        lagrangian,
        body_velocities,
    })
}

/// ½ m |ṙ|² (and ½ ωᵀ I ω for a rigid body) and ṙ for every body; a position that cannot be differentiated is a diagnostic.
fn body_kinetic_terms(model: &mut Model, errors: &mut Vec<Diagnostic>) -> (Vec<Id>, Vec<Vec<Id>>) {
    let pool = &mut model.pool;
    let half = pool.rational(Rational::HALF);
    let mut kinetic_terms = Vec::new();
    let mut body_velocities = Vec::with_capacity(model.bodies.len());
    for body in &model.bodies {
        let mut v = Vec::with_capacity(body.position.len());
        for r in &body.position {
            match pool.time_derivative(*r) {
                Ok(d) => v.push(d),
                Err(e) => {
                    errors.push(Diagnostic::new(
                        body.span,
                        format!("cannot differentiate the position of `{}`: {e}", body.name),
                    ));
                    v.push(*r);
                }
            }
        }
        let mass = pool.sym(model.masses[body.mass].symbol);
        let squares: Vec<Id> = v
            .iter()
            .map(|c| {
                let two = pool.int(2);
                pool.pow(*c, two)
            })
            .collect();
        let speed_squared = pool.add(&squares);
        kinetic_terms.push(pool.mul(&[half, mass, speed_squared]));
        if let Some(rigid) = &body.rigid {
            kinetic_terms.push(super::rigid_forces::rotational_kinetic(pool, rigid));
        }
        body_velocities.push(v);
    }
    (kinetic_terms, body_velocities)
}

/// A term of T, V or L beyond quadratic in the velocities, which the Legendre transform
/// cannot take.
fn non_quadratic_diagnostic(pool: &ExprPool, term: &Term, offender: Id) -> Diagnostic {
    let what = match term.kind {
        TermKind::Kinetic => "kinetic energy",
        TermKind::Potential => "potential",
        TermKind::Lagrangian => "Lagrangian",
    };
    Diagnostic::new(
        term.span,
        format!(
            "L must be at most quadratic in the velocities, but the {what} term `{}` is not",
            pool.display(offender)
        ),
    )
    .with_help("the Legendre transform p = ∂*L/∂q̇ needs L = ½ q̇ᵀ M q̇ + b·q̇ + L₀")
}

/// The first term of `e` (as a sum) that is not a polynomial of degree ≤ 2 in `velocities`.
fn non_quadratic_term(pool: &mut ExprPool, e: Id, velocities: &[Symbol]) -> Option<Id> {
    if pool.degree(e, velocities).is_some_and(|d| d <= 2) {
        return None;
    }
    let expanded = pool.expand(e);
    let terms = pool.terms(expanded);
    terms
        .into_iter()
        .find(|t| pool.degree(*t, velocities).is_none_or(|d| d > 2))
        .or(Some(e))
}

/// p = ∂*L/∂q̇, M = ∂p/∂q̇ and b = p|_{q̇=0}, so that p = M q̇ + b.
pub(crate) struct Momenta {
    pub momenta: Vec<Id>,
    pub mass_matrix: Matrix,
    pub offset: Vec<Id>,
}

pub(crate) fn momenta(pool: &mut ExprPool, lagrangian: Id, velocities: &[Symbol]) -> Momenta {
    let momenta: Vec<Id> = velocities
        .iter()
        .map(|v| pool.diff(lagrangian, *v))
        .collect();
    let mass_matrix: Matrix = momenta
        .iter()
        .map(|p| velocities.iter().map(|v| pool.diff(*p, *v)).collect())
        .collect();
    let zero = pool.int(0);
    let at_rest = velocities.iter().map(|v| (*v, zero)).collect();
    let offset = momenta
        .iter()
        .map(|p| pool.substitute(*p, &at_rest))
        .collect();
    Momenta {
        momenta,
        mass_matrix,
        offset,
    }
}

/// Whether M is singular at every one of `samples` random points (masses and parameters
/// positive). A matrix singular only on a set of measure zero (a pendulum at θ = 0 in some
/// coordinates) passes; one singular everywhere cannot give q̇ from p.
pub(crate) fn singular_everywhere(
    pool: &ExprPool,
    mass_matrix: &Matrix,
    symbol_count: usize,
) -> bool {
    let n = mass_matrix.len();
    let mut points = SamplePoints::new(0x9e37_79b9_7f4a_7c15);
    let mut env = vec![f64::NAN; symbol_count];
    let mut usable = 0;
    for _ in 0..16 {
        points.fill(&mut env, pool.symbols().iter());
        let mut a: Vec<Vec<f64>> = mass_matrix
            .iter()
            .map(|row| row.iter().map(|e| pool.eval(*e, &env)).collect())
            .collect();
        if a.iter().flatten().any(|x| !x.is_finite()) {
            continue;
        }
        usable += 1;
        if !is_singular(&mut a, n) {
            return false;
        }
    }
    usable > 0
}

/// Gaussian elimination with partial pivoting; singular when a pivot falls below a relative
/// 1e-10 of the matrix's largest entry (well above round-off for the small matrices here).
fn is_singular(a: &mut [Vec<f64>], n: usize) -> bool {
    let scale = a.iter().flatten().fold(0.0_f64, |m, x| m.max(x.abs()));
    if scale == 0.0 {
        return true;
    }
    for col in 0..n {
        let Some(pivot) = (col..n).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))
        else {
            return true;
        };
        if a[pivot][col].abs() <= 1e-10 * scale {
            return true;
        }
        a.swap(col, pivot);
        let (upper, lower) = a.split_at_mut(col + 1);
        let pivot_row = &upper[col];
        for row in lower.iter_mut() {
            let factor = row[col] / pivot_row[col];
            for (entry, above) in row.iter_mut().zip(pivot_row).skip(col) {
                *entry -= factor * above;
            }
        }
    }
    false
}

/// Rejects a mass matrix that is singular at every state, naming a coordinate without
/// kinetic energy when there is one.
pub(crate) fn require_regular(model: &Model, mass_matrix: &Matrix) -> Result<(), Vec<Diagnostic>> {
    let symbol_count = model.pool.symbols().len();
    if singular_everywhere(&model.pool, mass_matrix, symbol_count) {
        return Err(vec![singular_diagnostic(model, mass_matrix)]);
    }
    Ok(())
}

fn singular_diagnostic(model: &Model, mass_matrix: &Matrix) -> Diagnostic {
    // A coordinate whose row of M is identically zero has no kinetic energy at all.
    let idle = mass_matrix
        .iter()
        .position(|row| row.iter().all(|e| model.pool.is_zero(*e)));
    match idle {
        Some(a) => {
            let c = &model.coordinates[a];
            Diagnostic::new(
                c.span,
                format!(
                    "the mass matrix is singular: no term of T depends on the velocity `{}'`",
                    c.name
                ),
            )
            .with_help("every coordinate needs kinetic energy, or q̇ cannot be recovered from p")
        }
        None => Diagnostic::new(
            model
                .coordinates
                .first()
                .map_or_else(Default::default, |c| c.span),
            "the mass matrix ∂²L/∂q̇² is singular at every state: q̇ cannot be recovered from p",
        )
        .with_help("the coordinates may not be independent (e.g. two coordinates for one motion)"),
    }
}
