//! Units of table calls (docs/tables.md#statements): `units F: N` gives the value's unit;
//! the argument's unit is inferred from the call's argument, and every call of one table
//! must agree with the first (a diagnostic at the later call otherwise).

use super::check::Checker;
use super::infer::Dim;
use super::text::text;
use crate::parse::ast::ExprNode;
use crate::parse::Diagnostic;
use crate::parse::Span;

impl Checker<'_> {
    /// The dimension of the call `name(args)` of a table: its declared unit.
    pub(crate) fn table_call(
        &mut self,
        name: &str,
        args: &[ExprNode],
        argument: Option<Dim>,
        span: Span,
    ) -> Option<Dim> {
        if let (Some(Dim::Of(d)), Some(arg)) = (argument, args.first()) {
            match self.tables.get(name).copied().flatten() {
                None => {
                    self.tables.insert(name.to_string(), Some((d, arg.span)));
                }
                Some((first, at)) if first != d => {
                    let message = format!(
                        "the argument of table `{name}`, {}, has {d}, but at {}:{} it has {first}",
                        text(arg),
                        at.line,
                        at.column
                    );
                    self.report(
                        Diagnostic::new(arg.span, message)
                            .with_help("a table's argument has one unit at every call"),
                    );
                }
                Some(_) => {}
            }
        }
        self.name(name, span)
    }
}
