//! Statements (docs/dsl.md#statements): one parser per statement form, dispatched on the head keyword.

use super::{Grammar, PResult, STATEMENT_LEVEL};
use crate::parse::ast::{
    BodyDecl, Flow, FlowVelocity, Frame, Load, LoadValue, MassDecl, MassLaw, Statement,
    StatementKind, UnitDecl, VectorNode,
};
use crate::parse::keywords::{self, closest};
use crate::parse::span::{Diagnostic, Span, Spanned};

/// What may follow a statement ending in an expression.
const AFTER_EXPRESSION: &str = "an operator, `;` or a newline";
/// What may follow a statement ending in a list of names or options.
const AFTER_LIST: &str = "`,`, `;` or a newline";
/// What may follow `inflow b` / `outflow b` without options.
const AFTER_FLOW_NAME: &str = "`:`, `;` or a newline";
/// What may follow a unit in a `units` statement.
const AFTER_UNIT: &str = "an operator, `,`, `;` or a newline";
/// What may follow a statement ending in a vector.
const AFTER_VECTOR: &str = "`;` or a newline";

/// A statement's content and what may follow it.
type Parts = (StatementKind, &'static str);

/// `` `a`, `b` or `c` `` for messages.
fn one_of(words: &[&str]) -> String {
    let quoted: Vec<String> = words.iter().map(|w| format!("`{w}`")).collect();
    match quoted.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
        _ => quoted.concat(),
    }
}

impl<'a> Grammar<'a> {
    /// One statement, from its keyword up to (not including) the `;`, newline or end of
    /// input that ends it.
    pub(super) fn statement(&self, input: &'a str) -> PResult<'a, Statement> {
        let (input, tags) = self.tags(input)?;
        let head = match self.identifier(input) {
            Ok((_, head)) => head,
            Err(_) => {
                let mut diagnostic = self.unexpected_diagnostic(input, "a statement");
                if diagnostic.help.is_none() {
                    diagnostic = diagnostic.with_help(format!(
                        "a statement starts with one of {}",
                        keywords::STATEMENTS.join(", ")
                    ));
                }
                return Err(self.fail(input, diagnostic));
            }
        };
        let after = self.source.get(head.span.end..).unwrap_or("");
        let (rest, (kind, follow)) = match head.node.as_str() {
            keywords::COORDINATES => self.coordinates(after)?,
            keywords::MASS => {
                let (rest, decl) = self.mass_declaration(after, keywords::MASS)?;
                (rest, (StatementKind::Mass(decl), AFTER_EXPRESSION))
            }
            keywords::INERTIA => {
                let (rest, decl) = self.mass_declaration(after, keywords::INERTIA)?;
                (rest, (StatementKind::Inertia(decl), AFTER_EXPRESSION))
            }
            keywords::LET => self.definition(after)?,
            keywords::BODY => self.body(after)?,
            keywords::KINETIC => self.energy(after, keywords::KINETIC, StatementKind::Kinetic)?,
            keywords::POTENTIAL => {
                self.energy(after, keywords::POTENTIAL, StatementKind::Potential)?
            }
            keywords::LAGRANGIAN => {
                self.energy(after, keywords::LAGRANGIAN, StatementKind::Lagrangian)?
            }
            keywords::FORCE => self.load(after, keywords::FORCE, StatementKind::Force)?,
            keywords::THRUST => self.load(after, keywords::THRUST, StatementKind::Thrust)?,
            keywords::IMPACT => self.load(after, keywords::IMPACT, StatementKind::Impact)?,
            keywords::OUTFLOW => self.flow(after, keywords::OUTFLOW, StatementKind::Outflow)?,
            keywords::INFLOW => self.flow(after, keywords::INFLOW, StatementKind::Inflow)?,
            keywords::CHECK => self.check(after)?,
            keywords::UNITS => self.units(after)?,
            keywords::RIGID => self.rigid(after)?,
            keywords::TORQUE => self.load(after, keywords::TORQUE, StatementKind::Torque)?,
            keywords::TABLE => self.table(after)?,
            keywords::INPUT => self.input(after)?,
            keywords::USE => self.use_component(after)?,
            keywords::PARAMETER => self.parameter(after)?,
            _ => return Err(self.unknown_statement(head, after)),
        };
        let span = self.span(head.span.start, self.offset(rest));
        let at = self.skip_blanks(rest, false);
        if !(at.is_empty() || at.starts_with('\n') || at.starts_with(';')) {
            return Err(self.unexpected(at, follow));
        }
        Ok((rest, Statement { kind, span, tags }))
    }

    /// The optional tags before a statement's keyword: `[tag]` or `[tag1, tag2]`.
    fn tags(&self, input: &'a str) -> PResult<'a, Vec<Spanned<String>>> {
        let Ok((rest, _)) = self.punct(input, '[') else {
            return Ok((input, Vec::new()));
        };
        let (rest, tags) = self.comma_list(
            rest,
            ("[", ']'),
            "a tag name",
            |i| self.name(i),
            |tag| tag.node.clone(),
        )?;
        Ok((self.skip_blanks(rest, false), tags))
    }

    fn unknown_statement(
        &self,
        head: Spanned<String>,
        after: &'a str,
    ) -> nom::Err<super::ParseError> {
        let message = format!(
            "unknown statement `{}`; expected one of {}",
            head.node,
            keywords::STATEMENTS.join(", ")
        );
        let mut diagnostic = Diagnostic::new(head.span, message);
        if let Some(keyword) = closest(&head.node, keywords::STATEMENTS) {
            diagnostic = diagnostic.with_help(format!("did you mean `{keyword}`?"));
        } else if self.punct_after_blanks(after, '=').is_ok() {
            diagnostic = diagnostic.with_help(format!(
                "to define a name, write `{} {} = …`",
                keywords::LET,
                head.node
            ));
        }
        self.fail(after, diagnostic)
    }

    /// `coordinates x, y, …`
    fn coordinates(&self, input: &'a str) -> PResult<'a, Parts> {
        let what = "a coordinate name";
        let (mut rest, first) =
            self.required(input, false, what, keywords::COORDINATES, |i| self.name(i))?;
        let mut names = vec![first];
        while let Ok((after, _)) = self.punct_after_blanks(rest, ',') {
            let (after, name) = self.required(after, false, what, ",", |i| self.name(i))?;
            names.push(name);
            rest = after;
        }
        Ok((rest, (StatementKind::Coordinates(names), AFTER_LIST)))
    }

    /// `mass m = law` or `mass m: state, rate expr` (and the same for `inertia`).
    fn mass_declaration(&self, input: &'a str, keyword: &str) -> PResult<'a, MassDecl> {
        let (rest, name) = self.required(input, false, "a name", keyword, |i| self.name(i))?;
        if let Ok((after, _)) = self.punct_after_blanks(rest, '=') {
            let (rest, (law, _)) = self.required_expression(after, STATEMENT_LEVEL, "=")?;
            let law = MassLaw::Law(law);
            return Ok((rest, MassDecl { name, law }));
        }
        let after = self.punct_or_help(rest, ':', "`=` or `:`", || {
            format!(
                "write `{keyword} {name} = <law>` or `{keyword} {name}: {}, {} <expression>`",
                keywords::STATE,
                keywords::RATE
            )
        })?;
        let state = format!("`{}`", keywords::STATE);
        let (after, _) = self.required(after, false, &state, ":", |i| {
            self.keyword(i, keywords::STATE)
        })?;
        let rate = format!("`, {} <expression>`", keywords::RATE);
        let (after, _) = self.required(after, false, &rate, keywords::STATE, |i| {
            self.punct_after_blanks(i, ',')
        })?;
        let (after, _) =
            self.required(after, false, &format!("`{}`", keywords::RATE), ",", |i| {
                self.keyword(i, keywords::RATE)
            })?;
        let (rest, (rate, _)) = self.required_expression(after, STATEMENT_LEVEL, keywords::RATE)?;
        Ok((
            rest,
            MassDecl {
                name,
                law: MassLaw::State { rate },
            },
        ))
    }

    /// `let w = expr`
    fn definition(&self, input: &'a str) -> PResult<'a, Parts> {
        let (rest, name) =
            self.required(input, false, "a name", keywords::LET, |i| self.name(i))?;
        let (after, _) = self.required(rest, false, "`=`", &name.node, |i| {
            self.punct_after_blanks(i, '=')
        })?;
        let (rest, (value, _)) = self.required_expression(after, STATEMENT_LEVEL, "=")?;
        Ok((rest, (StatementKind::Let { name, value }, AFTER_EXPRESSION)))
    }

    /// `kinetic expr`, `potential expr`, `lagrangian expr`.
    fn energy(
        &self,
        input: &'a str,
        keyword: &str,
        kind: fn(crate::parse::ast::ExprNode) -> StatementKind,
    ) -> PResult<'a, Parts> {
        let (rest, (value, _)) = self.required_expression(input, STATEMENT_LEVEL, keyword)?;
        Ok((rest, (kind(value), AFTER_EXPRESSION)))
    }

    /// `force x: expr` (generalized, on a coordinate) or `force b: [..]` (on a body), and
    /// the same for `thrust` and `impact`.
    fn load(
        &self,
        input: &'a str,
        keyword: &str,
        kind: fn(Load) -> StatementKind,
    ) -> PResult<'a, Parts> {
        let what = "a coordinate or body name";
        let (rest, target) = self.required(input, false, what, keyword, |i| self.name(i))?;
        let (after, _) = self.required(rest, false, "`:`", &target.node, |i| {
            self.punct_after_blanks(i, ':')
        })?;
        match self.framed_vector(after) {
            Ok((rest, (frame, vector))) => {
                let value = LoadValue::Vector(vector);
                let (rest, at) = self.load_point(rest, keyword)?;
                let load = Load {
                    target,
                    value,
                    frame,
                    at,
                };
                return Ok((rest, (kind(load), AFTER_VECTOR)));
            }
            // No `[` here: a scalar.
            Err(nom::Err::Error(_)) => {}
            Err(error) => return Err(error),
        }
        let what = "an expression or a vector `[…]`";
        let (rest, (value, _)) = self.required(after, false, what, ":", |i| {
            self.expression(i, STATEMENT_LEVEL)
        })?;
        let value = LoadValue::Scalar(value);
        // Read here only to be refused by the derivation with a better message than a
        // syntax error: a planar torque is a scalar, and a torque has no point.
        let (rest, at) = if keyword == keywords::TORQUE {
            self.load_point(rest, keyword)?
        } else {
            (rest, None)
        };
        let load = Load {
            target,
            value,
            frame: Frame::World,
            at,
        };
        Ok((rest, (kind(load), AFTER_EXPRESSION)))
    }

    /// `check lhs = rhs`
    fn check(&self, input: &'a str) -> PResult<'a, Parts> {
        let (rest, (lhs, _)) = self.required_expression(input, STATEMENT_LEVEL, keywords::CHECK)?;
        let after = self.punct_or_help(rest, '=', "an operator or `=`", || {
            format!(
                "a check is written `{} <expression> = <expression>`",
                keywords::CHECK
            )
        })?;
        let (rest, (rhs, _)) = self.required_expression(after, STATEMENT_LEVEL, "=")?;
        let text = self.source.get(lhs.span.start..rhs.span.end);
        let text = text.unwrap_or_default().to_string();
        Ok((
            rest,
            (StatementKind::Check { lhs, rhs, text }, AFTER_EXPRESSION),
        ))
    }

    /// `units x: m, g: m/s^2, …`: each unit is read as an expression here; the `units`
    /// module checks that it is made of known units.
    fn units(&self, input: &'a str) -> PResult<'a, Parts> {
        let mut entries = Vec::new();
        let mut rest = input;
        let mut after = keywords::UNITS;
        loop {
            let (at, name) = self.required(rest, false, "a name", after, |i| self.name(i))?;
            let (at, _) = self.required(at, false, "`:`", &name.node, |i| {
                self.punct_after_blanks(i, ':')
            })?;
            let (at, (unit, _)) = self.required_expression(at, STATEMENT_LEVEL, ":")?;
            entries.push(UnitDecl { name, unit });
            match self.punct_after_blanks(at, ',') {
                Ok((next, _)) => {
                    rest = next;
                    after = ",";
                }
                Err(_) => return Ok((at, (StatementKind::Units(entries), AFTER_UNIT))),
            }
        }
    }

    /// `body b: mass m, position [..]`, options in any order, each exactly once.
    fn body(&self, input: &'a str) -> PResult<'a, Parts> {
        let (after, name) = self.name_then(input, "a body name", keywords::BODY, ':')?;
        let mut mass: Option<Spanned<String>> = None;
        let mut position: Option<VectorNode> = None;
        let (rest, ()) = self.options(
            after,
            keywords::BODY,
            &name,
            keywords::BODY_OPTIONS,
            |option, at| {
                if option.node == keywords::MASS {
                    let (rest, value) =
                        self.required(at, false, "a mass name", keywords::MASS, |i| self.name(i))?;
                    mass = Some(value);
                    Ok((rest, ()))
                } else {
                    let (rest, value) = self.required_vector(at, keywords::POSITION)?;
                    position = Some(value);
                    Ok((rest, ()))
                }
            },
        )?;
        let help = format!(
            "a body is written `{} {}: {} m, {} [x, y]`",
            keywords::BODY,
            name.node,
            keywords::MASS,
            keywords::POSITION
        );
        let missing = |option| self.missing_option(rest, ("body", &name), option, &help);
        let Some(mass) = mass else {
            return Err(missing(keywords::MASS));
        };
        let Some(position) = position else {
            return Err(missing(keywords::POSITION));
        };
        let body = BodyDecl {
            name,
            mass,
            position,
        };
        Ok((rest, (StatementKind::Body(body), AFTER_LIST)))
    }

    /// `outflow b` or `outflow b: rate …, velocity […]` (and `inflow`); each option at most
    /// once, `velocity` and `relative_velocity` not both.
    fn flow(
        &self,
        input: &'a str,
        keyword: &str,
        kind: fn(Flow) -> StatementKind,
    ) -> PResult<'a, Parts> {
        let (rest, body) = self.required(input, false, "a body name", keyword, |i| self.name(i))?;
        let Ok((after, _)) = self.punct_after_blanks(rest, ':') else {
            let flow = Flow {
                body,
                rate: None,
                velocity: None,
                frame: Frame::World,
                at: None,
            };
            return Ok((rest, (kind(flow), AFTER_FLOW_NAME)));
        };
        let mut rate = None;
        let mut at_point = None;
        let mut frame = Frame::World;
        let mut velocity: Option<(FlowVelocity, Span)> = None;
        let (rest, ()) = self.options(
            after,
            keyword,
            &body,
            keywords::FLOW_OPTIONS,
            |option, at| {
                if option.node == keywords::RATE {
                    let (rest, (value, _)) =
                        self.required_expression(at, STATEMENT_LEVEL, keywords::RATE)?;
                    rate = Some(value);
                    return Ok((rest, ()));
                }
                if option.node == keywords::AT {
                    let (rest, value) = self.required_vector(at, keywords::AT)?;
                    at_point = Some(value);
                    return Ok((rest, ()));
                }
                if let Some(first) = &velocity {
                    let diagnostic = two_velocities(first, option, (keyword, &body.node));
                    return Err(self.fail(at, diagnostic));
                }
                let (rest, (written_in, vector)) = self.required(
                    at,
                    false,
                    "a vector `[…]` or `body […]`",
                    &option.node,
                    |i| self.framed_vector(i),
                )?;
                frame = written_in;
                let value = if option.node == keywords::VELOCITY {
                    FlowVelocity::Absolute(vector)
                } else {
                    FlowVelocity::Relative(vector)
                };
                velocity = Some((value, option.span));
                Ok((rest, ()))
            },
        )?;
        let flow = Flow {
            body,
            rate,
            velocity: velocity.map(|(value, _)| value),
            frame,
            at: at_point,
        };
        Ok((rest, (kind(flow), AFTER_LIST)))
    }

    /// A vector that must be there, after `after`.
    fn required_vector(&self, input: &'a str, after: &str) -> PResult<'a, VectorNode> {
        self.required(input, false, "a vector `[…]`", after, |i| {
            self.vector(i, STATEMENT_LEVEL)
        })
    }

    /// `option value { , option value }` after the `:` of `statement` `owner`: checks that
    /// each option is one of `valid` and appears once; `value` reads the value of an option
    /// (given the option and the input after it).
    pub(super) fn options(
        &self,
        input: &'a str,
        statement: &str,
        owner: &Spanned<String>,
        valid: &[&str],
        mut value: impl FnMut(&Spanned<String>, &'a str) -> PResult<'a, ()>,
    ) -> PResult<'a, ()> {
        let expected = one_of(valid);
        let mut seen: Vec<Spanned<String>> = Vec::new();
        let mut rest = input;
        let mut after = ":";
        loop {
            let (at, option) = self.required(rest, false, &expected, after, |i| self.name(i))?;
            if !valid.contains(&option.node.as_str()) {
                let mut diagnostic = Diagnostic::new(
                    option.span,
                    format!(
                        "unknown option `{}` for {statement}; expected {expected}",
                        option.node
                    ),
                );
                if let Some(suggestion) = closest(&option.node, valid) {
                    diagnostic = diagnostic.with_help(format!("did you mean `{suggestion}`?"));
                }
                return Err(self.fail(at, diagnostic));
            }
            if let Some(first) = seen.iter().find(|s| s.node == option.node) {
                let diagnostic = Diagnostic::new(
                    option.span,
                    format!(
                        "`{}` given twice for {statement} `{}`",
                        option.node, owner.node
                    ),
                )
                .with_help(format!(
                    "first given at {}:{}",
                    first.span.line, first.span.column
                ));
                return Err(self.fail(at, diagnostic));
            }
            let (next, ()) = value(&option, at)?;
            seen.push(option);
            match self.punct_after_blanks(next, ',') {
                Ok((next, _)) => {
                    rest = next;
                    after = ",";
                }
                Err(_) => return Ok((next, ())),
            }
        }
    }
}

/// A flow given both `velocity` and `relative_velocity`: `option` the second, `first` the
/// one given before with its span, `(keyword, body)` the statement's.
fn two_velocities(
    (previous, first): &(FlowVelocity, Span),
    option: &Spanned<String>,
    (keyword, body): (&str, &str),
) -> Diagnostic {
    let given = match previous {
        FlowVelocity::Absolute(_) => keywords::VELOCITY,
        FlowVelocity::Relative(_) => keywords::RELATIVE_VELOCITY,
    };
    Diagnostic::new(
        option.span,
        format!(
            "`{}` and `{given}` cannot both be given for {keyword} `{body}`",
            option.node
        ),
    )
    .with_help(format!(
        "`{given}` was given at {}:{}; `{}` is the absolute velocity of the \
                     flowing mass, `{}` its velocity relative to the body: give one",
        first.line,
        first.column,
        keywords::VELOCITY,
        keywords::RELATIVE_VELOCITY
    ))
}
