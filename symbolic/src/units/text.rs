//! An expression of the AST written back as DSL text (`m*g*x'*sin(theta)`), with only the
//! parentheses its precedence needs, for quoting a term in a message.

use crate::parse::ast::{BinOp, Expr, ExprNode};

/// Binding strength: a node of lower strength than its slot needs parentheses there.
fn strength(expr: &Expr) -> u8 {
    match expr {
        Expr::Binary {
            op: BinOp::Add | BinOp::Sub,
            ..
        } => 1,
        Expr::Binary {
            op: BinOp::Mul | BinOp::Div,
            ..
        } => 2,
        Expr::Neg(_) => 3,
        Expr::Binary { op: BinOp::Pow, .. } => 4,
        _ => 5,
    }
}

/// `node` as DSL text.
pub fn text(node: &ExprNode) -> String {
    let mut out = String::new();
    write(node, &mut out);
    out
}

/// Writes `node`, in parentheses if it binds less than `needed`.
fn slot(node: &ExprNode, needed: u8, out: &mut String) {
    if strength(&node.node) < needed {
        out.push('(');
        write(node, out);
        out.push(')');
    } else {
        write(node, out);
    }
}

fn write(node: &ExprNode, out: &mut String) {
    match &*node.node {
        Expr::Number(text) | Expr::Name(text) => out.push_str(text),
        Expr::Derivative { name, order } => {
            out.push_str(name);
            out.push_str(&"'".repeat(usize::from(*order)));
        }
        Expr::Neg(operand) => {
            out.push('-');
            slot(operand, 3, out);
        }
        Expr::Binary { op, lhs, rhs } => {
            let (left, right, spaced) = match op {
                BinOp::Add | BinOp::Sub => (1, 2, true),
                BinOp::Mul | BinOp::Div => (2, 3, false),
                BinOp::Pow => (5, 3, false),
            };
            slot(lhs, left, out);
            if spaced {
                out.push_str(&format!(" {op} "));
            } else {
                out.push_str(&op.to_string());
            }
            slot(rhs, right, out);
        }
        Expr::Call { func, args } => {
            out.push_str(&func.node);
            out.push('(');
            for (k, arg) in args.iter().enumerate() {
                if k > 0 {
                    out.push_str(", ");
                }
                write(arg, out);
            }
            out.push(')');
        }
    }
}

#[cfg(test)]
mod tests {
    use super::text;
    use crate::parse::parse_expression;

    #[test]
    fn text_keeps_only_needed_parentheses_and_reparses_to_the_same_tree() {
        for (written, shown) in [
            ("m * g * x' * sin(theta)", "m*g*x'*sin(theta)"),
            ("1/2*k*(r - l0)^2", "1/2*k*(r - l0)^2"),
            ("a - (b - c)", "a - (b - c)"),
            ("(a - b) - c", "a - b - c"),
            ("a / (b * c)", "a/(b*c)"),
            ("(-x)^2 + -x^2", "(-x)^2 + -x^2"),
            ("x^-2 * atan2(y, x)", "x^-2*atan2(y, x)"),
            ("(x^2)^3 + x^2^3", "(x^2)^3 + x^2^3"),
            ("x''", "x''"),
        ] {
            let node = parse_expression(written).unwrap();
            assert_eq!(text(&node), shown);
            let again = parse_expression(shown).unwrap();
            assert_eq!(text(&again), shown, "{written}");
        }
    }
}
