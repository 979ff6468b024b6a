//! q̇ from p in closed form for a lone spatial rigid body: the body's own metric instead of a
//! 6×6 LDLᵀ of M (docs/mechanics.md#rigid-bodies, "q̇ from p").
//!
//! With q = [r_O, η] (the origin's world components and three Euler angles), ω = E(η) η̇ in
//! body axes, R(η) body → world, the centre c and the inertia I about it (body axes, frozen),
//! T = ½ m |w|² + ½ ωᵀ I ω with w = Rᵀ ṙ_O + ω × c the centre's velocity in body axes, so
//!
//! ```text
//! p_r = ∂T/∂ṙ_O = m R w,     p_η = ∂T/∂η̇ = Eᵀ h,   h = I ω + m c × w
//! ```
//!
//! and backwards, with P = Rᵀ p_r = m w:
//!
//! ```text
//! h = E⁻ᵀ p_η,   ω = I⁻¹ (h − c × P),   ṙ_O = R (P/m − ω × c),   η̇ = E⁻¹ ω
//! ```
//!
//! E⁻¹ = adj(E)/det E, each entry trigonometrically reduced: det E is ± the cosine (or, for
//! the symmetric sequences `zyz` …, the sine) of the middle angle, zero at the sequence's
//! gimbal lock, where M's Schur complement on the angles, Eᵀ I E, is singular as det E².
//! The generated code refuses that attitude with the typed singular-mass-matrix error below
//! the same relative floor as the LDLᵀ pivots (det E² ≤ `RELATIVE_PIVOT_FLOOR`; E's entries
//! are sines and cosines, so det E² is already relative), and a mass or inertia that is not
//! positive (m ≤ 0 or a pivot of I ≤ 0: M not positive definite) the same way.
//!
//! A quaternion q = (e0, e1, e2, e3) in place of η (docs/mechanics.md#quaternions): with
//! n = qᵀq and G(q) = [[−e1, e0, e3, −e2], [−e2, −e3, e0, e1], [−e3, e2, −e1, e0]],
//! ω = (2/n) G q̇, G q = 0 and G Gᵀ = n I₃; T gains the gauge term ½ λ s²/n² (s = q·q̇,
//! λ = (4/3) tr I), so p_q = (2/n) Gᵀ h + λ s q/n², whence G p_q = 2 h and qᵀ p_q = λ s/n:
//!
//! ```text
//! h = ½ G p_q,   q̇ = ½ Gᵀ ω + (qᵀ p_q / λ) q
//! ```
//!
//! (the first part gives (2/n) G q̇ = ω, the second qᵀ q̇ = s), ω and ṙ_O as above. The
//! state is refused at n ≤ √ε (|q| ≤ 1.2e-4: `RELATIVE_PIVOT_FLOOR`), besides m and I's
//! pivots.
//!
//! Only where this is M's exact inverse: one body, rigid and spatial, whose position and
//! angles (or the four components of its quaternion) are the coordinates themselves (each
//! once, all of them) and no other term of L with a velocity in it. Everywhere else q̇
//! comes from the LDLᵀ of `emit/factor.rs`.

use super::lagrangian::Momenta;
use super::linear::{cofactor, determinant, dot, mat_vec, Matrix};
use super::model::Model;
use super::rotation::transpose;
use crate::expr::{ExprPool, Id, Rational, Symbol};

/// q̇(q, p) for a lone spatial rigid body, and when it holds.
#[derive(Clone, Debug)]
pub struct RigidVelocities {
    /// q̇ in coordinate order, in the momentum symbols (`p_x`), q and the masses.
    pub velocities: Vec<Id>,
    /// `(value, relative)`: the state is refused unless each value is above 0, or above
    /// `RELATIVE_PIVOT_FLOOR` when `relative` (m and I's pivots absolute; det E² for Euler
    /// angles and n = |q|² for a quaternion relative, both dimensionless: an n below the
    /// floor, |q| ≤ 1.2e-4, is refused — q̈'s 1/n³ would overflow for n below about 1e-100
    /// — and an n that overflowed to infinity would pass, which a run cannot reach, |q|
    /// drifting by rounding only).
    pub guards: Vec<(Id, bool)>,
    /// Whether the attitude is a quaternion (q̇ = ½ Gᵀ ω + (qᵀ p_q/λ) q), not Euler angles.
    pub quaternion: bool,
    /// q̈ of a quaternion body (`quaternion_accelerations`), in q, q̇, p, t and the masses
    /// (p = M q̇ bound by the generated code); empty for Euler angles.
    pub accelerations: Vec<Id>,
    /// p = M q̇ of a quaternion body in closed form, in q, q̇ and the masses, coordinate
    /// order (`quaternion_momenta`; a third of the derived momenta's operations): what
    /// its `accelerations` binds p from. Empty for Euler angles.
    pub momenta: Vec<Id>,
}

/// q̈ of a lone body turned by a quaternion from its closed-form q̇ = F(q, p, t, m): the
/// total derivative along the motion,
///
/// ```text
/// q̈ = Σ_j ∂F/∂q_j q̇_j + F(q, ṗ) + ∂F/∂t + Σ_k ∂F/∂m_k ṁ_k
/// ```
///
/// (F is linear in p: ∂F/∂p ṗ = F(q, ṗ)), with ṗ the true momentum rate and ṁ the masses'
/// rates. It equals eq. 6's M⁻¹ rhs — both are the motion's acceleration: for Calisto 4 118
/// operations (ṗ's 2 339 among them) where rhs alone, d*p/dt − (d*p/dt at q̈ = 0) expanded,
/// takes 56 829 (docs/bench/calisto.md). Empty for Euler angles, whose q̈ stays eq. 6's
/// LDLᵀ.
pub(crate) fn quaternion_accelerations(
    model: &mut Model,
    rigid: &RigidVelocities,
    momentum_rate: &[Id],
    mass_rates: &[Id],
) -> Vec<Id> {
    if !rigid.quaternion {
        return Vec::new();
    }
    let pool = &mut model.pool;
    let time = model.time;
    let along_rates: std::collections::HashMap<Symbol, Id> = (model.coordinates.iter())
        .map(|c| c.momentum)
        .zip(momentum_rate.iter().copied())
        .collect();
    let mut out = Vec::with_capacity(rigid.velocities.len());
    for &f in &rigid.velocities {
        let mut terms = vec![pool.substitute(f, &along_rates), pool.diff(f, time)];
        for c in &model.coordinates {
            let slope = pool.diff(f, c.q);
            let rate = pool.sym(c.velocity);
            terms.push(pool.mul(&[slope, rate]));
        }
        for (mass, rate) in model.masses.iter().zip(mass_rates) {
            let slope = pool.diff(f, mass.symbol);
            terms.push(pool.mul(&[slope, *rate]));
        }
        out.push(pool.add(&terms));
    }
    out
}

/// The closed form above when the model is a lone spatial rigid body in its own
/// coordinates (see the module's comment), `None` otherwise.
pub(crate) fn rigid_velocities(model: &mut Model, momenta: &Momenta) -> Option<RigidVelocities> {
    let slots = own_coordinates(model)?;
    if !momenta.offset.iter().all(|b| model.pool.is_zero(*b)) {
        return None;
    }
    // w and h as functions of q and q̇, for a quaternion body's momenta forwards.
    let motion = match model.bodies[0].rigid.as_ref()?.quaternion {
        Some(_) => Some(super::rigid_rates::motion(model, &slots)?),
        None => None,
    };
    let body = &model.bodies[0];
    let rigid = body.rigid.as_ref()?;
    let velocities: Vec<Symbol> = model.coordinates.iter().map(|c| c.velocity).collect();
    let (rotation, omega, inertia, centre) = (
        rigid.rotation.clone(),
        rigid.angular_velocity.clone(),
        rigid.inertia.clone(),
        rigid.centre.clone(),
    );
    let mass = model.pool.sym(model.masses[body.mass].symbol);
    let momentum: Vec<Id> = slots
        .iter()
        .map(|&i| model.pool.sym(model.coordinates[i].momentum))
        .collect();
    let angle_rates: Vec<Symbol> = slots[3..].iter().map(|&i| velocities[i]).collect();
    let pool = &mut model.pool;
    let metric = match rigid.quaternion {
        Some(e) => Metric::quaternion(pool, &e, &inertia),
        None => Metric::euler(pool, &omega, &angle_rates)?,
    };
    let (origin_rates, angle_rates) =
        solve(pool, &metric, &rotation, &inertia, &centre, mass, &momentum);
    let momenta = match &motion {
        Some(motion) => {
            let rates: Vec<Id> = slots[3..]
                .iter()
                .map(|&i| pool.sym(velocities[i]))
                .collect();
            let (linear, turning) =
                quaternion_momenta(pool, &metric, (&rotation, mass), motion, &rates);
            let mut out = vec![pool.int(0); slots.len()];
            for (slot, p) in slots.iter().zip(linear.into_iter().chain(turning)) {
                out[*slot] = p;
            }
            out
        }
        None => Vec::new(),
    };
    let mut out = vec![pool.int(0); slots.len()];
    for (slot, rate) in slots
        .iter()
        .zip(origin_rates.into_iter().chain(angle_rates))
    {
        out[*slot] = rate;
    }
    let mut guards = vec![(mass, false)];
    guards.extend(pivots(pool, &inertia).into_iter().map(|m| (m, false)));
    guards.push(metric.guard(pool));
    Some(RigidVelocities {
        velocities: out,
        guards,
        quaternion: rigid.quaternion.is_some(),
        accelerations: Vec::new(),
        momenta,
    })
}

/// The slots of a lone spatial rigid body's own coordinates, the origin's three then the
/// three angles or the quaternion's four (indices into the coordinates), when the model is that body alone: its
/// position and angles are the coordinates themselves (each once, all of them), and no
/// other term of L has a velocity in it, so p = ∂T_b/∂q̇ is the body's own momentum.
pub(crate) fn own_coordinates(model: &Model) -> Option<Vec<usize>> {
    let [body] = model.bodies.as_slice() else {
        return None;
    };
    let rigid = body.rigid.as_ref()?;
    if rigid.origin.len() != 3 {
        return None;
    }
    let velocities: Vec<Symbol> = model.coordinates.iter().map(|c| c.velocity).collect();
    let pool = &model.pool;
    let moving_term = (model.terms.iter()).any(|t| pool.degree(t.value, &velocities) != Some(0));
    // The origin's components are coordinates; ω is a function of the other three's rates.
    let index_of = |e: &Id| {
        let s = pool.as_symbol(*e)?;
        model.coordinates.iter().position(|c| c.q == s)
    };
    let origin: Option<Vec<usize>> = rigid.origin.iter().map(index_of).collect();
    // A quaternion's four components in order, each a coordinate (a partial one,
    // `quaternion(e0, 0, 0, e3)`, is left to the LDLᵀ); Euler angles in coordinate order.
    let (angles, turning): (Vec<usize>, usize) = match &rigid.quaternion {
        Some(q) => (q.iter().map(index_of).collect::<Option<_>>()?, 4),
        None => {
            let moves = |i: &usize| {
                (rigid.angular_velocity.iter()).any(|w| pool.contains(*w, velocities[*i]))
            };
            ((0..model.coordinates.len()).filter(moves).collect(), 3)
        }
    };
    let mut slots = origin?;
    slots.extend(&angles);
    let mut seen = slots.clone();
    seen.sort_unstable();
    seen.dedup();
    let count = 3 + turning;
    if moving_term || angles.len() != turning || seen.len() != count {
        return None;
    }
    if model.coordinates.len() != count {
        return None;
    }
    Some(slots)
}

/// How the attitude's rates and momenta meet ω and h.
enum Metric {
    /// Euler angles: E = ∂ω/∂η̇ and E⁻¹ = adj(E)/det E, reduced.
    Euler { inverse: Matrix, det: Id },
    /// A quaternion q: G(q) (ω = (2/n) G q̇), q, n = |q|² and λ = (4/3) tr I.
    Quaternion {
        g: Matrix,
        q: Vec<Id>,
        norm: Id,
        lambda: Id,
    },
}

impl Metric {
    fn euler(pool: &mut ExprPool, omega: &[Id], rates: &[Symbol]) -> Option<Metric> {
        let e: Matrix = omega
            .iter()
            .map(|w| rates.iter().map(|r| pool.diff(*w, *r)).collect())
            .collect();
        let det = determinant(pool, &e)?;
        let det = pool.reduce_trig(det);
        if pool.is_zero(det) {
            return None;
        }
        let minus_one = pool.int(-1);
        let inverse_det = pool.pow(det, minus_one);
        let mut inverse = vec![vec![det; 3]; 3];
        for (i, row) in inverse.iter_mut().enumerate() {
            for (j, entry) in row.iter_mut().enumerate() {
                let adjugate = cofactor(pool, &e, j, i)?;
                let adjugate = pool.reduce_trig(adjugate);
                *entry = pool.mul(&[adjugate, inverse_det]);
            }
        }
        Some(Metric::Euler { inverse, det })
    }

    /// G = [[−e1, e0, e3, −e2], [−e2, −e3, e0, e1], [−e3, e2, −e1, e0]] of
    /// `rotation::quaternion_rates`, and λ of the gauge term (`rigid.rs`, `gauge_term`).
    fn quaternion(pool: &mut ExprPool, e: &[Id; 4], inertia: &Matrix) -> Metric {
        let m: Vec<Id> = e.iter().map(|x| pool.neg(*x)).collect();
        let g = vec![
            vec![m[1], e[0], e[3], m[2]],
            vec![m[2], m[3], e[0], e[1]],
            vec![m[3], e[2], m[1], e[0]],
        ];
        let trace: Vec<Id> = (0..3).map(|i| inertia[i][i]).collect();
        let trace = pool.add(&trace);
        let (four, three) = (pool.int(4), pool.int(3));
        let factor = pool.div(four, three);
        let lambda = pool.mul(&[factor, trace]);
        let norm = super::rotation::quaternion_norm(pool, e);
        Metric::Quaternion {
            g,
            q: e.to_vec(),
            norm,
            lambda,
        }
    }

    /// h from p_η: E⁻ᵀ p_η, or ½ G p_q (E p_q = (4/n) h, E = (2/n) G, E q = 0).
    fn angular(&self, pool: &mut ExprPool, momentum: &[Id]) -> Vec<Id> {
        match self {
            Metric::Euler { inverse, .. } => mat_vec(pool, &transpose(inverse), momentum),
            Metric::Quaternion { g, .. } => {
                let half = pool.rational(Rational::HALF);
                let gp = mat_vec(pool, g, momentum);
                gp.iter().map(|x| pool.mul(&[half, *x])).collect()
            }
        }
    }

    /// η̇ from ω: E⁻¹ ω, or q̇ = ½ Gᵀ ω + (qᵀ p_q / λ) q (qᵀ p_q = λ (q·q̇)/n).
    fn rates(&self, pool: &mut ExprPool, omega: &[Id], momentum: &[Id]) -> Vec<Id> {
        match self {
            Metric::Euler { inverse, .. } => mat_vec(pool, inverse, omega),
            Metric::Quaternion { g, q, lambda, .. } => {
                let half = pool.rational(Rational::HALF);
                let turned = mat_vec(pool, &transpose(g), omega);
                let along = dot(pool, q, momentum);
                let radial = pool.div(along, *lambda);
                (turned.iter().zip(q))
                    .map(|(t, e)| {
                        let a = pool.mul(&[half, *t]);
                        let b = pool.mul(&[radial, *e]);
                        pool.add(&[a, b])
                    })
                    .collect()
            }
        }
    }

    /// The attitude's guard: det E² above the relative floor (gimbal lock), or n = |q|²
    /// above it too (n is dimensionless; q̈ holds 1/n³, which overflows to ∞ and, times a
    /// zero, to NaN for n below about 1e-100).
    fn guard(&self, pool: &mut ExprPool) -> (Id, bool) {
        match self {
            Metric::Euler { det, .. } => {
                let two = pool.int(2);
                (pool.pow(*det, two), true)
            }
            Metric::Quaternion { norm, .. } => (*norm, true),
        }
    }
}

/// p = ∂T/∂q̇ of a lone quaternion body forwards (the module's comment), from the body's
/// motion (w and h, `rigid_rates::motion`) and the quaternion's rates `rates`: p_r = R (m w)
/// and p_q = (2/n) Gᵀ h + λ s q/n² with s = q·q̇. Empty for Euler angles.
fn quaternion_momenta(
    pool: &mut ExprPool,
    metric: &Metric,
    (rotation, mass): (&Matrix, Id),
    motion: &super::rigid_rates::Motion,
    rates: &[Id],
) -> (Vec<Id>, Vec<Id>) {
    let Metric::Quaternion { g, q, norm, lambda } = metric else {
        return (Vec::new(), Vec::new());
    };
    let big_p: Vec<Id> = motion
        .centre
        .iter()
        .map(|w| pool.mul(&[mass, *w]))
        .collect();
    let linear = mat_vec(pool, rotation, &big_p);
    let turned = mat_vec(pool, &transpose(g), &motion.angular);
    let s = dot(pool, q, rates);
    let (two, minus_one, minus_two) = (pool.int(2), pool.int(-1), pool.int(-2));
    let (inverse, inverse_square) = (pool.pow(*norm, minus_one), pool.pow(*norm, minus_two));
    let two_over_n = pool.mul(&[two, inverse]);
    let gauge = pool.mul(&[*lambda, s, inverse_square]);
    let turning = (turned.iter().zip(q))
        .map(|(t, e)| {
            let a = pool.mul(&[two_over_n, *t]);
            let b = pool.mul(&[gauge, *e]);
            pool.add(&[a, b])
        })
        .collect();
    (linear, turning)
}

/// ṙ_O and η̇ from p_r and p_η (the formulas of the module's comment).
fn solve(
    pool: &mut ExprPool,
    metric: &Metric,
    rotation: &Matrix,
    inertia: &Matrix,
    centre: &[Id],
    mass: Id,
    momentum: &[Id],
) -> (Vec<Id>, Vec<Id>) {
    let big_p = mat_vec(pool, &transpose(rotation), &momentum[..3]);
    let h = metric.angular(pool, &momentum[3..]);
    let c_x_p = cross(pool, centre, &big_p);
    let excess: Vec<Id> = h
        .iter()
        .zip(&c_x_p)
        .map(|(a, b)| pool.sub(*a, *b))
        .collect();
    let inverse_inertia = super::linear::inverse(pool, inertia).unwrap_or_default();
    let omega = mat_vec(pool, &inverse_inertia, &excess);
    let minus_one = pool.int(-1);
    let inverse_mass = pool.pow(mass, minus_one);
    let w_x_c = cross(pool, &omega, centre);
    let velocity: Vec<Id> = big_p
        .iter()
        .zip(&w_x_c)
        .map(|(p, wc)| {
            let w = pool.mul(&[*p, inverse_mass]);
            pool.sub(w, *wc)
        })
        .collect();
    let origin_rates = mat_vec(pool, rotation, &velocity);
    let angle_rates = metric.rates(pool, &omega, &momentum[3..]);
    (origin_rates, angle_rates)
}

/// a × b.
pub(super) fn cross(pool: &mut ExprPool, a: &[Id], b: &[Id]) -> Vec<Id> {
    (0..3)
        .map(|i| {
            let (j, k) = ((i + 1) % 3, (i + 2) % 3);
            let plus = pool.mul(&[a[j], b[k]]);
            let minus = pool.mul(&[a[k], b[j]]);
            pool.sub(plus, minus)
        })
        .collect()
}

/// The pivots of I's LDLᵀ, each leading minor over the one before (Sylvester: all
/// positive ⇔ I positive definite), without repeats: A and C for `[A, A, C]`.
fn pivots(pool: &mut ExprPool, inertia: &Matrix) -> Vec<Id> {
    let mut pivots: Vec<Id> = Vec::with_capacity(3);
    let mut previous = pool.int(1);
    for n in 1..=3 {
        let block: Matrix = inertia[..n].iter().map(|row| row[..n].to_vec()).collect();
        let Some(minor) = determinant(pool, &block) else {
            continue;
        };
        let minus_one = pool.int(-1);
        let below = pool.pow(previous, minus_one);
        let pivot = pool.mul(&[minor, below]);
        if !pivots.contains(&pivot) {
            pivots.push(pivot);
        }
        previous = minor;
    }
    pivots
}
