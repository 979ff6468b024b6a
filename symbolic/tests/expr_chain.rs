//! A 6-link planar pendulum: the size of Lagrangian the mechanics stage meets (many
//! sin/cos products, hundreds of terms). Its mass matrix has a closed form to check
//! against: M_ij = l_i l_j cos(θ_i − θ_j) Σ_{k ≥ max(i,j)} m_k.

use varmass_symbolic::expr::{ExprPool, Func, Id, Identity, Symbol, SymbolKind};

const LINKS: usize = 6;

struct Chain {
    pool: ExprPool,
    angles: Vec<Symbol>,
    rates: Vec<Symbol>,
    lengths: Vec<Id>,
    masses: Vec<Id>,
    lagrangian: Id,
}

fn chain() -> Chain {
    let mut pool = ExprPool::new();
    let angles: Vec<Symbol> = (0..LINKS)
        .map(|i| pool.symbols_mut().add_coordinate(&format!("theta{i}")))
        .collect();
    let rates: Vec<Symbol> = angles
        .iter()
        .map(|q| pool.symbols().velocity_of(*q).unwrap())
        .collect();
    let g = pool.symbols_mut().add("g", SymbolKind::Parameter);
    let lengths: Vec<Id> = (0..LINKS)
        .map(|i| {
            let s = pool
                .symbols_mut()
                .add(&format!("l{i}"), SymbolKind::Parameter);
            pool.sym(s)
        })
        .collect();
    let masses: Vec<Id> = (0..LINKS)
        .map(|i| {
            let s = pool.symbols_mut().add(&format!("m{i}"), SymbolKind::Frozen);
            pool.sym(s)
        })
        .collect();
    let g = pool.sym(g);
    let half = pool.rational(varmass_symbolic::expr::Rational::HALF);
    let two = pool.int(2);
    let (mut x, mut y) = (pool.int(0), pool.int(0));
    let mut terms = Vec::new();
    for i in 0..LINKS {
        let q = pool.sym(angles[i]);
        let (s, c) = (pool.call(Func::Sin, &[q]), pool.call(Func::Cos, &[q]));
        let dx = pool.mul(&[lengths[i], s]);
        let dy = pool.mul(&[lengths[i], c]);
        let dy = pool.neg(dy);
        x = pool.add(&[x, dx]);
        y = pool.add(&[y, dy]);
        // T_i = ½ m_i (ẋ_i² + ẏ_i²), V_i = m_i g y_i.
        let vx = pool.time_derivative(x).unwrap();
        let vy = pool.time_derivative(y).unwrap();
        let (vx2, vy2) = (pool.pow(vx, two), pool.pow(vy, two));
        let speed2 = pool.add(&[vx2, vy2]);
        let kinetic = pool.mul(&[half, masses[i], speed2]);
        let potential = pool.mul(&[masses[i], g, y]);
        terms.push(kinetic);
        terms.push(pool.neg(potential));
    }
    let lagrangian = pool.add(&terms);
    Chain {
        pool,
        angles,
        rates,
        lengths,
        masses,
        lagrangian,
    }
}

#[test]
fn the_mass_matrix_matches_its_closed_form() {
    let Chain {
        mut pool,
        angles,
        rates,
        lengths,
        masses,
        lagrangian,
    } = chain();
    let v: Vec<Id> = rates.iter().map(|r| pool.sym(*r)).collect();
    assert_eq!(pool.degree(lagrangian, &rates), Some(2));
    let momenta: Vec<Id> = rates.iter().map(|r| pool.diff(lagrangian, *r)).collect();
    for i in 0..LINKS {
        for j in 0..LINKS {
            let entry = pool.diff(momenta[i], rates[j]);
            let (qi, qj) = (pool.sym(angles[i]), pool.sym(angles[j]));
            let gap = pool.sub(qi, qj);
            let cos = pool.call(Func::Cos, &[gap]);
            let tail: Vec<Id> = masses[i.max(j)..].to_vec();
            let mass = pool.add(&tail);
            let want = pool.mul(&[lengths[i], lengths[j], cos, mass]);
            let verdict = pool.identical(entry, want);
            assert!(
                matches!(verdict, Identity::Proven | Identity::Numerical { .. }),
                "M[{i}][{j}]: {verdict:?}"
            );
        }
        // Euler's theorem for a quadratic form: Σ_j v_j ∂p_i/∂v_j = p_i.
        let mut sum = Vec::new();
        for j in 0..LINKS {
            let d = pool.diff(momenta[i], rates[j]);
            sum.push(pool.mul(&[d, v[j]]));
        }
        let euler = pool.add(&sum);
        assert_eq!(
            pool.identical(euler, momenta[i]),
            Identity::Proven,
            "row {i}"
        );
    }
}

#[test]
fn the_lagrange_equations_compile_to_one_tape() {
    let Chain {
        mut pool,
        angles,
        rates,
        lagrangian,
        ..
    } = chain();
    // d/dt ∂L/∂θ̇ − ∂L/∂θ for every link: the residuals of the equations of motion.
    let mut residuals = Vec::new();
    for (q, v) in angles.iter().zip(&rates) {
        let p = pool.diff(lagrangian, *v);
        let dp = pool.time_derivative(p).unwrap();
        let force = pool.diff(lagrangian, *q);
        residuals.push(pool.sub(dp, force));
    }
    let tape = pool.compile(&residuals);
    let cse = pool.cse(&residuals);
    assert!(
        !cse.shared.is_empty(),
        "the links share their sines and cosines"
    );
    let env: Vec<f64> = (0..pool.symbols().len())
        .map(|i| 0.3 + 0.1 * (i % 13) as f64)
        .collect();
    let mut out = vec![0.0; residuals.len()];
    tape.eval(&env, &mut out);
    for (r, got) in residuals.iter().zip(&out) {
        assert_eq!(got.to_bits(), pool.eval(*r, &env).to_bits());
    }
}
