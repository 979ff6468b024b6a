//! Rigid bodies in the model (docs/dsl.md#rigid, docs/mechanics.md#rigid-bodies): the
//! `rigid` statement lowered into a [`Body`] whose position is its centre of mass and whose
//! [`Rigid`] part holds R, ω, the inertia and the centre offset; loads and flows at body
//! points; torques.

use super::build::Builder;
use super::linear::{mat_vec, Matrix};
use super::model::{Body, Load, LoadKind, LoadTarget, Rigid};
use super::rotation;
use crate::expr::{ExprPool, Id, SymbolKind};
use crate::parse::ast::{
    Attitude, ExprNode, Frame, InertiaValue, LoadValue, RigidDecl, VectorNode,
};
use crate::parse::{keywords, Diagnostic, Span};

/// The attitude of a rigid body, lowered: R and ω in body components.
struct Turned {
    rotation: Matrix,
    angular_velocity: Vec<Id>,
    euler_middle: Option<(Id, bool)>,
    /// A quaternion's (q·q̇, |q|²), for the gauge term of T ([`gauge_term`]).
    radial: Option<(Id, Id)>,
    /// A quaternion's components.
    quaternion: Option<[Id; 4]>,
}

impl Builder {
    /// `rigid b: …`: checks the dimensions (2 with `angle`, 3 with `orientation`), lowers
    /// every part, and adds the body with its centre of mass r_c = r_O + R c as position.
    pub(super) fn lower_rigid(&mut self, decl: &RigidDecl, span: Span) {
        // Every part is lowered (and reports its own mistakes) before any failure ends the
        // statement, so one compile shows them all.
        let mass = self.body_mass(&decl.mass);
        let dimension = match decl.attitude {
            Attitude::Angle(_) => 2,
            Attitude::Orientation { .. } => 3,
        };
        let name = &decl.name.node;
        let origin = self.rigid_origin(decl, dimension);
        let turned = self.lower_attitude(decl);
        let inertia = self.lower_inertia(decl, dimension);
        let centre = match &decl.centre {
            Some(centre) => self.frozen_vector(centre, dimension, name, "centre"),
            None => Some(vec![self.model.pool.int(0); dimension]),
        };
        let (Some(mass), Some(origin), Some(turned), Some(inertia), Some(centre)) =
            (mass, origin, turned, inertia, centre)
        else {
            return;
        };
        let pool = &mut self.model.pool;
        let gauge = turned
            .radial
            .map(|radial| gauge_term(pool, radial, &inertia));
        let offset = mat_vec(pool, &turned.rotation, &centre);
        let position = origin
            .iter()
            .zip(&offset)
            .map(|(r, c)| pool.add(&[*r, *c]))
            .collect();
        self.model.bodies.push(Body {
            name: name.clone(),
            mass,
            position,
            rigid: Some(Rigid {
                origin,
                rotation: turned.rotation,
                angular_velocity: turned.angular_velocity,
                euler_middle: turned.euler_middle,
                gauge,
                quaternion: turned.quaternion,
                inertia,
                centre,
            }),
            span,
        });
    }

    /// r_O of `position [..]`: as many components as the attitude turns in (2 with
    /// `angle`, 3 with `orientation`), each a function of q and t.
    fn rigid_origin(&mut self, decl: &RigidDecl, dimension: usize) -> Option<Vec<Id>> {
        let name = &decl.name.node;
        if decl.position.node.len() != dimension {
            let message = format!(
                "rigid body `{name}` is {}, so its position has {dimension} components, found {}",
                if dimension == 2 {
                    "planar (`angle`)"
                } else {
                    "spatial (`orientation`)"
                },
                decl.position.node.len()
            );
            let help = if dimension == 2 {
                "a body turning in space takes `orientation zyx(psi, th, phi)` and `inertia [A, B, C]`"
            } else {
                "a body turning in the plane takes `angle th` and one moment, `inertia J`"
            };
            self.errors
                .push(Diagnostic::new(decl.position.span, message).with_help(help));
            return None;
        }
        let origin = self.lower_vector(&decl.position)?;
        let what = format!("the position of rigid body `{name}`");
        origin
            .iter()
            .all(|p| self.require_configuration(*p, decl.position.span, &what))
            .then_some(origin)
    }

    /// R and ω from `angle θ` (R(θ), ω = θ̇) or `orientation seq(φ1, φ2, φ3)`.
    fn lower_attitude(&mut self, decl: &RigidDecl) -> Option<Turned> {
        let name = &decl.name.node;
        let (nodes, axes) = match &decl.attitude {
            Attitude::Angle(angle) => (vec![angle], None),
            Attitude::Orientation { sequence, angles } => (
                angles.iter().collect(),
                rotation::sequence_axes(&sequence.node),
            ),
        };
        let mut angles = Vec::with_capacity(4);
        let mut rates = Vec::with_capacity(4);
        for node in &nodes {
            let angle = self.lower(node)?;
            let what = format!("an angle of rigid body `{name}`");
            if !self.require_configuration(angle, node.span, &what) {
                return None;
            }
            match self.model.pool.time_derivative(angle) {
                Ok(rate) => rates.push(rate),
                Err(e) => {
                    let message = format!("cannot differentiate an angle of `{name}`: {e}");
                    self.errors.push(Diagnostic::new(node.span, message));
                    return None;
                }
            }
            angles.push(angle);
        }
        if angles.len() == 4 && !self.quaternion_coordinates(name, &nodes, &angles) {
            return None;
        }
        let pool = &mut self.model.pool;
        match (axes, angles.as_slice(), rates.as_slice()) {
            (None, [angle], [rate]) => Some(Turned {
                rotation: rotation::planar(pool, *angle),
                angular_velocity: vec![*rate],
                euler_middle: None,
                radial: None,
                quaternion: None,
            }),
            (None, [a, b, c, d], [da, db, dc, dd]) => {
                let (e, rates) = ([*a, *b, *c, *d], [*da, *db, *dc, *dd]);
                let products: Vec<Id> = e
                    .iter()
                    .zip(&rates)
                    .map(|(x, y)| pool.mul(&[*x, *y]))
                    .collect();
                let along = pool.add(&products);
                Some(Turned {
                    rotation: rotation::quaternion_rotation(pool, &e),
                    angular_velocity: rotation::quaternion_rates(pool, &e, &rates),
                    euler_middle: None,
                    radial: Some((along, rotation::quaternion_norm(pool, &e))),
                    quaternion: Some(e),
                })
            }
            (Some(axes), [a, b, c], [da, db, dc]) => {
                let angles = [*a, *b, *c];
                Some(Turned {
                    rotation: rotation::spatial(pool, axes, &angles),
                    angular_velocity: rotation::body_rates(pool, axes, &angles, &[*da, *db, *dc]),
                    euler_middle: Some((*b, axes[0] == axes[2])),
                    radial: None,
                    quaternion: None,
                })
            }
            _ => None,
        }
    }

    /// A quaternion's components must be distinct coordinates or `0`: then q is homogeneous
    /// of degree 1 in its coordinates, scaling them is a direction of motion that turns
    /// nothing, and the gauge term is zero on every motion (docs/mechanics.md#quaternions).
    /// Any other expression (`quaternion(1, g1, g2, g3)`, a law of t) would give the gauge
    /// term a value on real motions and change them, so it is refused.
    fn quaternion_coordinates(&mut self, name: &str, nodes: &[&ExprNode], values: &[Id]) -> bool {
        let pool = &self.model.pool;
        let mut seen = Vec::with_capacity(4);
        let wrong = nodes.iter().zip(values).find(|(_, value)| {
            if pool.is_zero(**value) {
                return false;
            }
            let symbol = pool.as_symbol(**value);
            let coordinate = symbol
                .filter(|s| matches!(pool.symbols().kind(*s), SymbolKind::Coordinate))
                .filter(|s| !seen.contains(s));
            seen.extend(coordinate);
            coordinate.is_none()
        });
        let Some((node, _)) = wrong else {
            return true;
        };
        let message = format!(
            "a component of the quaternion of rigid body `{name}` is a coordinate (each \
             once) or 0, found another expression"
        );
        let help = "declare four coordinates, `coordinates …, e0, e1, e2, e3`, and write \
                    `orientation quaternion(e0, e1, e2, e3)`; a body turning about one axis may \
                    write `quaternion(e0, 0, 0, e3)`";
        self.errors
            .push(Diagnostic::new(node.span, message).with_help(help));
        false
    }

    /// Every `potential` term homogeneous of degree 0 in each quaternion's coordinates:
    /// Σ e_i ∂V/∂e_i = 0, so V depends on q/|q| as R does (docs/mechanics.md#quaternions).
    /// A potential written with the unit quaternion's formula and no /|q|² drives the
    /// radial equation and lets |q| run away: refused at the term when the identity is
    /// refuted at a point (a proof or numerical agreement lets it pass).
    pub(super) fn check_quaternion_potentials(&mut self) {
        for e in self.quaternion_coordinates_of_bodies() {
            for (value, span) in self.potential_terms() {
                let pool = &mut self.model.pool;
                let inlined = pool.inline_definitions(value);
                let terms: Vec<Id> = (e.iter())
                    .map(|c| {
                        let (q, rate) = (pool.sym(*c), pool.diff(inlined, *c));
                        pool.mul(&[q, rate])
                    })
                    .collect();
                let radial = pool.add(&terms);
                let zero = pool.int(0);
                if let crate::expr::Identity::Refuted { .. } = pool.identical(radial, zero) {
                    let message = "this potential changes with the length of a quaternion, which \
                                   turns nothing: write it in q/|q|";
                    let help = "divide each product of two components by e0^2 + e1^2 + e2^2 + \
                                e3^2, as R does (R33 = (e0^2 - e1^2 - e2^2 + e3^2)/n)";
                    self.errors
                        .push(Diagnostic::new(span, message).with_help(help));
                }
            }
        }
    }

    /// The coordinates of each quaternion (the rate-carrying ones of a body with a gauge).
    fn quaternion_coordinates_of_bodies(&self) -> Vec<Vec<crate::expr::Symbol>> {
        let pool = &self.model.pool;
        let rigid = self.model.bodies.iter().filter_map(|b| b.rigid.as_ref());
        rigid
            .filter(|r| r.gauge.is_some())
            .map(|r| {
                let moving = |c: &&super::model::Coordinate| {
                    (r.angular_velocity.iter()).any(|w| pool.contains(*w, c.velocity))
                };
                (self.model.coordinates.iter())
                    .filter(moving)
                    .map(|c| c.q)
                    .collect()
            })
            .collect()
    }

    fn potential_terms(&self) -> Vec<(Id, Span)> {
        let potential = |t: &&super::model::Term| t.kind == super::model::TermKind::Potential;
        (self.model.terms.iter())
            .filter(potential)
            .map(|t| (t.value, t.span))
            .collect()
    }

    /// `inertia J` in the plane; `[A, B, C]` or the full symmetric tensor in space. Frozen.
    fn lower_inertia(&mut self, decl: &RigidDecl, dimension: usize) -> Option<Matrix> {
        let name = &decl.name.node;
        let mismatch = |span: Span, found: &str| {
            let expected = if dimension == 2 {
                "a planar body has one moment, `inertia J`"
            } else {
                "a spatial body has `inertia [A, B, C]` (principal) or a 3×3 symmetric tensor"
            };
            Diagnostic::new(span, format!("{expected}; found {found} for `{name}`"))
        };
        match (&decl.inertia, dimension) {
            (InertiaValue::Scalar(e), 2) => {
                let value = self.lower(e)?;
                self.require_frozen(value, e.span, name, "inertia")
                    .then(|| vec![vec![value]])
            }
            (InertiaValue::Principal(v), 3) => {
                let moments = self.frozen_vector(v, 3, name, "inertia")?;
                let zero = self.model.pool.int(0);
                Some(
                    (0..3)
                        .map(|i| {
                            (0..3)
                                .map(|j| if i == j { moments[i] } else { zero })
                                .collect()
                        })
                        .collect(),
                )
            }
            (InertiaValue::Tensor(rows), 3) if rows.node.len() == 3 => {
                let mut tensor = Vec::with_capacity(3);
                for row in &rows.node {
                    tensor.push(self.frozen_vector(row, 3, name, "inertia")?);
                }
                self.require_symmetric(&tensor, rows.span, name)
                    .then_some(tensor)
            }
            (InertiaValue::Scalar(e), _) => {
                self.errors.push(mismatch(e.span, "one moment"));
                None
            }
            (InertiaValue::Principal(v), _) => {
                self.errors.push(mismatch(v.span, "a vector"));
                None
            }
            (InertiaValue::Tensor(rows), _) => {
                self.errors.push(mismatch(rows.span, "a tensor"));
                None
            }
        }
    }

    fn require_symmetric(&mut self, tensor: &Matrix, span: Span, name: &str) -> bool {
        let pairs = [(1, 0), (2, 0), (2, 1)];
        let asymmetric = pairs.into_iter().find(|&(i, j)| {
            let verdict = self.model.pool.identical(tensor[i][j], tensor[j][i]);
            matches!(verdict, crate::expr::Identity::Refuted { .. })
        });
        let Some((i, j)) = asymmetric else {
            return true;
        };
        let message = format!(
            "the inertia tensor of `{name}` is not symmetric: entry ({}, {}) differs from ({}, {})",
            i + 1,
            j + 1,
            j + 1,
            i + 1
        );
        self.errors.push(Diagnostic::new(span, message));
        false
    }

    /// A body-frame vector of `dimension` frozen components (an inertia or a centre).
    fn frozen_vector(
        &mut self,
        vector: &VectorNode,
        dimension: usize,
        name: &str,
        what: &str,
    ) -> Option<Vec<Id>> {
        if vector.node.len() != dimension {
            let message = format!(
                "the {what} of rigid body `{name}` has {dimension} components here, found {}",
                vector.node.len()
            );
            self.errors.push(Diagnostic::new(vector.span, message));
            return None;
        }
        let values = self.lower_vector(vector)?;
        let frozen = vector
            .node
            .iter()
            .zip(&values)
            .all(|(node, value)| self.require_frozen(*value, node.span, name, what));
        frozen.then_some(values)
    }

    /// An inertia or a centre offset is frozen like a mass (why: the frozen-mass rule holds
    /// every such quantity fixed under ∂* and d*/dt, and its change enters only through
    /// Σ φ̇ ∂*p/∂φ): it may name masses, inertias and parameters, not q, q̇ or t directly.
    fn require_frozen(&mut self, value: Id, span: Span, name: &str, what: &str) -> bool {
        let pool = &self.model.pool;
        let moving = pool.free_symbols(value).into_iter().find(|s| {
            matches!(
                pool.symbols().kind(*s),
                SymbolKind::Coordinate | SymbolKind::Velocity { .. } | SymbolKind::Time
            )
        });
        let Some(symbol) = moving else {
            return true;
        };
        let message = format!(
            "the {what} of rigid body `{name}` depends on `{}`; it is frozen like a mass",
            pool.symbols().name(symbol)
        );
        let help = format!(
            "declare its law, e.g. `{} J = …` or `{} m_p = …`, and write it in terms of those names",
            keywords::INERTIA,
            keywords::MASS
        );
        self.errors
            .push(Diagnostic::new(span, message).with_help(help));
        false
    }

    /// A vector in the frame it was written in, as world components.
    pub(super) fn in_world_axes(&mut self, body: usize, frame: Frame, vector: Vec<Id>) -> Vec<Id> {
        match (frame, &self.model.bodies[body].rigid) {
            (Frame::Body, Some(rigid)) => {
                let rotation = rigid.rotation.clone();
                mat_vec(&mut self.model.pool, &rotation, &vector)
            }
            _ => vector,
        }
    }

    /// The body-frame point `at [..]` of rigid body `body` (the reference point without one).
    pub(super) fn body_point(&mut self, body: usize, at: Option<&VectorNode>) -> Option<Vec<Id>> {
        let dimension = self.model.bodies[body].position.len();
        let Some(at) = at else {
            return Some(vec![self.model.pool.int(0); dimension]);
        };
        let point = self.lower_vector(at)?;
        if !self.check_dimension(body, point.len(), at.span) {
            return None;
        }
        let what = format!("the point `at` on `{}`", self.model.bodies[body].name);
        point
            .iter()
            .all(|p| self.require_configuration(*p, at.span, &what))
            .then_some(point)
    }

    /// A particle has no frame and no points: `body [..]` and `at [..]` need a rigid body.
    pub(super) fn particle_plain(
        &mut self,
        body: usize,
        frame: Frame,
        at: Option<&VectorNode>,
    ) -> bool {
        let name = &self.model.bodies[body].name;
        let (span, what) = match (frame, at) {
            (_, Some(at)) => (at.span, "a point `at [..]`"),
            (Frame::Body, None) => (
                self.model.bodies[body].span,
                "a body-frame vector `body [..]`",
            ),
            (Frame::World, None) => return true,
        };
        let message = format!("`{name}` is a particle: {what} needs a rigid body");
        let help = format!(
            "declare it with `{} {name}: …` to give it axes and points",
            keywords::RIGID
        );
        self.errors
            .push(Diagnostic::new(span, message).with_help(help));
        false
    }

    /// `force b: [..] at [..]` (and `thrust`, `impact`) on a rigid body.
    pub(super) fn lower_rigid_load(
        &mut self,
        kind: LoadKind,
        body: usize,
        load: &crate::parse::ast::Load,
        span: Span,
    ) {
        let LoadValue::Vector(v) = &load.value else {
            let message = format!(
                "`{}` is a body, so its load is a vector `[...]` or `body [...]`; a torque is written `{} {}: …`",
                load.target.node,
                keywords::TORQUE,
                load.target.node
            );
            self.errors.push(Diagnostic::new(load.target.span, message));
            return;
        };
        let Some(value) = self.lower_vector(v) else {
            return;
        };
        if !self.check_dimension(body, value.len(), v.span) {
            return;
        }
        let vector = self.in_world_axes(body, load.frame, value);
        let Some(point) = self.body_point(body, load.at.as_ref()) else {
            return;
        };
        let target = LoadTarget::Point {
            body,
            vector,
            point,
        };
        self.model.loads.push(Load { kind, target, span });
    }

    /// `torque b: τ`: a scalar on a planar body, a vector (`[..]` world, `body [..]` body
    /// axes) on a spatial one; kept in body components.
    pub(super) fn lower_torque(&mut self, load: &crate::parse::ast::Load, span: Span) {
        let target = &load.target;
        let Some(body) = self
            .body_index(&target.node)
            .filter(|b| self.model.bodies[*b].rigid.is_some())
        else {
            if self.failed_bodies.contains(&target.node) {
                return;
            }
            let message = format!(
                "`{}` is not a rigid body; a torque turns a rigid body",
                target.node
            );
            let help = "on a coordinate, a generalized force is written `force th: …`";
            self.errors
                .push(Diagnostic::new(target.span, message).with_help(help));
            return;
        };
        if let Some(at) = &load.at {
            let message = "a torque has no point of application: a couple acts on the whole body";
            let name = &target.node;
            let help = format!(
                "a force at a point makes its own torque: write `force {name}: body [..] at [..]`"
            );
            self.errors
                .push(Diagnostic::new(at.span, message).with_help(help));
            return;
        }
        let planar = self.model.bodies[body].position.len() == 2;
        let torque = match (&load.value, planar) {
            (LoadValue::Scalar(e), true) => vec![self.lower(e)],
            (LoadValue::Vector(v), false) if v.node.len() == 3 => {
                v.node.iter().map(|e| self.lower(e)).collect()
            }
            (value, _) => {
                let span = match value {
                    LoadValue::Scalar(e) => e.span,
                    LoadValue::Vector(v) => v.span,
                };
                let name = &self.model.bodies[body].name;
                let expected = if planar {
                    format!("a planar body's torque is a scalar: `torque {name}: tau`")
                } else {
                    format!(
                        "a spatial body's torque is a vector of 3: `torque {name}: [..]` or \
                         `body [..]`"
                    )
                };
                self.errors.push(Diagnostic::new(span, expected));
                return;
            }
        };
        let Some(torque) = torque.into_iter().collect::<Option<Vec<Id>>>() else {
            return;
        };
        let torque = match (load.frame, &self.model.bodies[body].rigid) {
            (Frame::World, Some(rigid)) if !planar => {
                let back = rotation::transpose(&rigid.rotation);
                mat_vec(&mut self.model.pool, &back, &torque)
            }
            _ => torque,
        };
        let kind = LoadKind::Active;
        let target = LoadTarget::Torque(body, torque);
        self.model.loads.push(Load { kind, target, span });
    }
}

/// ½ λ (q·q̇)² / n² with λ = 4/3 tr I, the kinetic term of a quaternion's radial rate
/// (docs/mechanics.md#quaternions). R and ω depend on q/|q| only, so without it the
/// mass matrix is singular along q; with it, in the orthonormal frame of q/|q| and the
/// three rows of ω's Jacobian, the angular block of M is diag(4 I, λ)/n: positive definite
/// for every q ≠ 0 and as well conditioned as I. Its equation keeps q·q̇ = 0 (so |q| is
/// constant) when it starts there, where the term is zero: the motion and the energy are
/// those of the Euler angles' derivation.
fn gauge_term(pool: &mut ExprPool, (along, norm): (Id, Id), inertia: &Matrix) -> Id {
    let trace: Vec<Id> = (0..inertia.len()).map(|i| inertia[i][i]).collect();
    let trace = pool.add(&trace);
    let (two, minus_two) = (pool.int(2), pool.int(-2));
    let (two_, three) = (pool.int(2), pool.int(3));
    let factor = pool.div(two_, three);
    let squared = pool.pow(along, two);
    let over = pool.pow(norm, minus_two);
    pool.mul(&[factor, trace, squared, over])
}
