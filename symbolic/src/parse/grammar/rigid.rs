//! The rigid-body forms (docs/dsl.md#rigid): the `rigid` statement, vectors in a body's
//! frame (`body [..]`) and points on a body (`at [..]`), shared by loads and flows.

use super::{Grammar, PResult, STATEMENT_LEVEL};
use crate::parse::ast::{
    Attitude, Expr, ExprNode, Frame, InertiaValue, RigidDecl, StatementKind, VectorNode,
};
use crate::parse::keywords;
use crate::parse::span::{Diagnostic, Spanned};

/// What may follow a `rigid` statement.
const AFTER_LIST: &str = "`,`, `;` or a newline";

/// The options of a `rigid` statement as they are read, before the required ones are checked.
#[derive(Default)]
struct RigidOptions {
    mass: Option<Spanned<String>>,
    inertia: Option<InertiaValue>,
    position: Option<VectorNode>,
    attitude: Option<(Attitude, Spanned<String>)>,
    centre: Option<VectorNode>,
}

impl<'a> Grammar<'a> {
    /// `[..]` (world frame) or `body [..]` (the body's frame); backtracks when neither is
    /// here, so `body` stays a fine name in an expression (`force x: body*2`).
    pub(super) fn framed_vector(&self, input: &'a str) -> PResult<'a, (Frame, VectorNode)> {
        if let Ok((after, _)) = self.keyword(input, keywords::BODY) {
            match self.vector(after, STATEMENT_LEVEL) {
                Ok((rest, vector)) => return Ok((rest, (Frame::Body, vector))),
                Err(nom::Err::Error(_)) => {}
                Err(error) => return Err(error),
            }
        }
        let (rest, vector) = self.vector(input, STATEMENT_LEVEL)?;
        Ok((rest, (Frame::World, vector)))
    }

    /// An optional `at [..]` after a load's vector.
    pub(super) fn at_point(&self, input: &'a str) -> PResult<'a, Option<VectorNode>> {
        match self.keyword(input, keywords::AT) {
            Ok((after, _)) => {
                let (rest, point) = self.required(after, false, "a vector `[…]`", "at", |i| {
                    self.vector(i, STATEMENT_LEVEL)
                })?;
                Ok((rest, Some(point)))
            }
            Err(_) => Ok((input, None)),
        }
    }

    /// [`Self::at_point`] after a load; after a torque, its span covers `at [..]` (the
    /// derivation refuses it there: a couple has no point of application).
    pub(super) fn load_point(
        &self,
        input: &'a str,
        keyword: &str,
    ) -> PResult<'a, Option<VectorNode>> {
        let at = self.keyword(input, keywords::AT).ok().map(|(_, span)| span);
        let (rest, point) = self.at_point(input)?;
        let point = match (point, at) {
            (Some(mut point), Some(at)) if keyword == keywords::TORQUE => {
                point.span = at.join(point.span);
                Some(point)
            }
            (point, _) => point,
        };
        Ok((rest, point))
    }

    /// `rigid b: mass m, inertia …, position [..], angle e | orientation seq(a, b, c)
    /// [, centre [..]]`, options in any order, each at most once.
    pub(super) fn rigid(&self, input: &'a str) -> PResult<'a, (StatementKind, &'static str)> {
        let (after, name) = self.name_then(input, "a body name", keywords::RIGID, ':')?;
        let mut read = RigidOptions::default();
        let (rest, ()) = self.options(
            after,
            keywords::RIGID,
            &name,
            keywords::RIGID_OPTIONS,
            |option, at| self.rigid_option(option, at, &name, &mut read),
        )?;
        let help = format!(
            "a rigid body is written `{} {}: mass m, inertia J, position [x, y], angle th` \
             (planar) or `…, inertia [A, B, C], position [x, y, z], orientation \
             zyx(psi, th, phi)` (spatial)",
            keywords::RIGID,
            name.node
        );
        let missing = |option| self.missing_option(rest, ("rigid body", &name), option, &help);
        let Some(mass) = read.mass else {
            return Err(missing(keywords::MASS));
        };
        let Some(inertia) = read.inertia else {
            return Err(missing(keywords::INERTIA));
        };
        let Some(position) = read.position else {
            return Err(missing(keywords::POSITION));
        };
        let Some((attitude, _)) = read.attitude else {
            return Err(missing("angle` or `orientation"));
        };
        let decl = RigidDecl {
            name,
            mass,
            inertia,
            position,
            attitude,
            centre: read.centre,
        };
        Ok((rest, (StatementKind::Rigid(decl), AFTER_LIST)))
    }

    /// One option of a `rigid` statement, its value read after `at`.
    fn rigid_option(
        &self,
        option: &Spanned<String>,
        at: &'a str,
        name: &Spanned<String>,
        read: &mut RigidOptions,
    ) -> PResult<'a, ()> {
        match option.node.as_str() {
            keywords::MASS => {
                let (rest, mass) =
                    self.required(at, false, "a mass name", keywords::MASS, |i| self.name(i))?;
                read.mass = Some(mass);
                Ok((rest, ()))
            }
            keywords::INERTIA => {
                let (rest, inertia) = self.inertia_value(at)?;
                read.inertia = Some(inertia);
                Ok((rest, ()))
            }
            keywords::POSITION | keywords::CENTRE => {
                let (rest, vector) =
                    self.required(at, false, "a vector `[…]`", &option.node, |i| {
                        self.vector(i, STATEMENT_LEVEL)
                    })?;
                if option.node == keywords::POSITION {
                    read.position = Some(vector);
                } else {
                    read.centre = Some(vector);
                }
                Ok((rest, ()))
            }
            _ => {
                if let Some((_, first)) = &read.attitude {
                    let diagnostic = Diagnostic::new(
                        option.span,
                        format!(
                            "`{}` and `{}` cannot both be given for rigid body `{}`",
                            option.node, first.node, name.node
                        ),
                    )
                    .with_help(
                        "`angle` turns a body in the plane, `orientation` in space: give one",
                    );
                    return Err(self.fail(at, diagnostic));
                }
                let (rest, attitude) = if option.node == keywords::ANGLE {
                    let (rest, (angle, _)) =
                        self.required_expression(at, STATEMENT_LEVEL, keywords::ANGLE)?;
                    (rest, Attitude::Angle(angle))
                } else {
                    self.orientation(at)?
                };
                read.attitude = Some((attitude, option.clone()));
                Ok((rest, ()))
            }
        }
    }

    /// `J` (an expression), `[A, B, C]` or `[[Ixx, Ixy, Ixz], [Ixy, Iyy, Iyz], [Ixz, Iyz, Izz]]`.
    fn inertia_value(&self, input: &'a str) -> PResult<'a, InertiaValue> {
        let at = self.skip_blanks(input, false);
        if let Ok((inside, open)) = self.punct(at, '[') {
            if self.punct(self.skip_blanks(inside, true), '[').is_ok() {
                return self.inertia_tensor(inside, open);
            }
            let (rest, vector) = self.vector(at, STATEMENT_LEVEL)?;
            return Ok((rest, InertiaValue::Principal(vector)));
        }
        let (rest, (value, _)) =
            self.required_expression(input, STATEMENT_LEVEL, keywords::INERTIA)?;
        Ok((rest, InertiaValue::Scalar(value)))
    }

    /// The rows of a tensor after its opening `[` (at `open`).
    fn inertia_tensor(
        &self,
        mut rest: &'a str,
        open: crate::parse::Span,
    ) -> PResult<'a, InertiaValue> {
        let mut rows = Vec::new();
        loop {
            let (after, row) = self.required(rest, true, "a row `[…]`", "[", |i| {
                self.vector(self.skip_blanks(i, true), STATEMENT_LEVEL)
            })?;
            rows.push(row);
            let after = self.skip_blanks(after, true);
            if let Ok((next, _)) = self.punct(after, ',') {
                rest = next;
                continue;
            }
            let (next, close) =
                self.required(after, true, "`,` or `]`", "]", |i| self.punct(i, ']'))?;
            return Ok((
                next,
                InertiaValue::Tensor(Spanned::new(rows, open.join(close))),
            ));
        }
    }

    /// `seq(a, b, c)` or `quaternion(e0, e1, e2, e3)` after `orientation`: read as a call,
    /// then checked to be a known sequence with three angles, or a quaternion with four.
    fn orientation(&self, input: &'a str) -> PResult<'a, Attitude> {
        let (rest, (node, _)) = self.required(
            input,
            false,
            "an Euler sequence such as `zyx(psi, th, phi)` or `quaternion(e0, e1, e2, e3)`",
            keywords::ORIENTATION,
            |i| self.expression(i, STATEMENT_LEVEL),
        )?;
        let span = node.span;
        let ExprNode { node, .. } = node;
        let sequences = keywords::EULER_SEQUENCES.join(", ");
        let Expr::Call { func, args } = *node else {
            let diagnostic = Diagnostic::new(
                span,
                "an orientation is an Euler sequence with its three angles, e.g. `zyx(psi, th, phi)`, or `quaternion(e0, e1, e2, e3)`",
            )
            .with_help(format!("the intrinsic sequences are {sequences}"));
            return Err(self.fail(rest, diagnostic));
        };
        let quaternion = func.node == keywords::QUATERNION;
        if !quaternion && !keywords::EULER_SEQUENCES.contains(&func.node.as_str()) {
            let mut diagnostic = Diagnostic::new(
                func.span,
                format!(
                    "unknown Euler sequence `{}`; the intrinsic sequences are {sequences}, or `{}(e0, e1, e2, e3)`",
                    func.node,
                    keywords::QUATERNION
                ),
            );
            let known: Vec<&str> = (keywords::EULER_SEQUENCES.iter().copied())
                .chain([keywords::QUATERNION])
                .collect();
            if let Some(close) = keywords::closest(&func.node, &known) {
                diagnostic = diagnostic.with_help(format!("did you mean `{close}`?"));
            }
            return Err(self.fail(rest, diagnostic));
        }
        let (count, what) = if quaternion {
            (4, "components")
        } else {
            (3, "angles")
        };
        if args.len() != count {
            let diagnostic = Diagnostic::new(
                span,
                format!("`{}` takes {count} {what}, found {}", func.node, args.len()),
            );
            return Err(self.fail(rest, diagnostic));
        }
        Ok((
            rest,
            Attitude::Orientation {
                sequence: func,
                angles: args,
            },
        ))
    }
}
