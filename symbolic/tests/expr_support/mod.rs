//! Test support: a small recursive-descent reader of the DSL expression grammar (docs/dsl.md#grammar)
//! producing the parser's AST, so that tests can write expressions as text and exercise
//! `lower` too. It stands in for the real nom parser, which is built elsewhere; it is
//! independent of the engine's printer, so a display → read → lower round trip is a real
//! check.
#![allow(dead_code)]

use varmass_symbolic::expr::{lower, ExprPool, Id, SymbolKind, TableResolver};
use varmass_symbolic::parse::ast::{BinOp, Expr, ExprNode};
use varmass_symbolic::{parse::Spanned, Diagnostic, Span};

/// Reads `text` as one expression.
pub fn read(text: &str) -> Result<ExprNode, String> {
    let mut r = Reader {
        bytes: text.as_bytes(),
        text,
        at: 0,
    };
    let e = r.expr()?;
    r.skip_ws();
    if r.at != r.bytes.len() {
        return Err(format!("trailing input at {} in `{text}`", r.at));
    }
    Ok(e)
}

/// Reads and lowers `text`, resolving names in the pool's table.
pub fn build(pool: &mut ExprPool, text: &str) -> Id {
    let ast = read(text).unwrap_or_else(|e| panic!("{e}"));
    lower(pool, &ast, &mut TableResolver).unwrap_or_else(|e| panic!("lowering `{text}`: {e:?}"))
}

/// Reads and lowers, returning the diagnostics.
pub fn try_build(pool: &mut ExprPool, text: &str) -> Result<Id, Vec<Diagnostic>> {
    let ast = read(text).unwrap_or_else(|e| panic!("{e}"));
    lower(pool, &ast, &mut TableResolver)
}

/// A pool with the sled's symbols: coordinate x (with x', x'', p_x), time t,
/// parameters g, theta, c, m0, f_d, and frozen m.
pub fn sled_pool() -> ExprPool {
    let mut pool = ExprPool::new();
    let table = pool.symbols_mut();
    table.add_coordinate("x");
    table.add("t", SymbolKind::Time);
    for p in ["g", "theta", "c", "m0", "f_d", "u_e", "mu"] {
        table.add(p, SymbolKind::Parameter);
    }
    table.add("m", SymbolKind::Frozen);
    pool
}

struct Reader<'a> {
    bytes: &'a [u8],
    text: &'a str,
    at: usize,
}

fn span(start: usize, end: usize) -> Span {
    Span {
        start,
        end,
        line: 1,
        column: start as u32 + 1,
    }
}

fn node(e: Expr, start: usize, end: usize) -> ExprNode {
    Spanned::new(Box::new(e), span(start, end))
}

impl Reader<'_> {
    fn skip_ws(&mut self) {
        while self
            .bytes
            .get(self.at)
            .is_some_and(|b| b.is_ascii_whitespace())
        {
            self.at += 1;
        }
    }

    fn peek(&mut self) -> Option<u8> {
        self.skip_ws();
        self.bytes.get(self.at).copied()
    }

    fn eat(&mut self, c: u8) -> bool {
        if self.peek() == Some(c) {
            self.at += 1;
            true
        } else {
            false
        }
    }

    fn expr(&mut self) -> Result<ExprNode, String> {
        let start = self.at;
        let mut lhs = self.term()?;
        loop {
            let op = match self.peek() {
                Some(b'+') => BinOp::Add,
                Some(b'-') => BinOp::Sub,
                _ => return Ok(lhs),
            };
            self.at += 1;
            let rhs = self.term()?;
            lhs = node(Expr::Binary { op, lhs, rhs }, start, self.at);
        }
    }

    fn term(&mut self) -> Result<ExprNode, String> {
        let start = self.at;
        let mut lhs = self.unary()?;
        loop {
            let op = match self.peek() {
                Some(b'*') => BinOp::Mul,
                Some(b'/') => BinOp::Div,
                _ => return Ok(lhs),
            };
            self.at += 1;
            let rhs = self.unary()?;
            lhs = node(Expr::Binary { op, lhs, rhs }, start, self.at);
        }
    }

    /// Unary minus binds looser than `^`: `-x^2` is `-(x^2)`.
    fn unary(&mut self) -> Result<ExprNode, String> {
        let start = self.at;
        if self.eat(b'-') {
            let inner = self.unary()?;
            return Ok(node(Expr::Neg(inner), start, self.at));
        }
        self.power()
    }

    /// `^` is right-associative; its exponent may carry a unary minus (`x^-1`).
    fn power(&mut self) -> Result<ExprNode, String> {
        let start = self.at;
        let base = self.atom()?;
        if self.eat(b'^') {
            let exponent = self.unary()?;
            return Ok(node(
                Expr::Binary {
                    op: BinOp::Pow,
                    lhs: base,
                    rhs: exponent,
                },
                start,
                self.at,
            ));
        }
        Ok(base)
    }

    fn atom(&mut self) -> Result<ExprNode, String> {
        let c = self.peek().ok_or("unexpected end")?;
        let start = self.at;
        if c == b'(' {
            self.at += 1;
            let e = self.expr()?;
            if !self.eat(b')') {
                return Err(format!("expected `)` at {} in `{}`", self.at, self.text));
            }
            return Ok(e);
        }
        if c.is_ascii_digit() || c == b'.' {
            return Ok(self.number());
        }
        if c.is_ascii_alphabetic() || c == b'_' {
            while self
                .bytes
                .get(self.at)
                .is_some_and(|b| b.is_ascii_alphanumeric() || *b == b'_')
            {
                self.at += 1;
            }
            let name_end = self.at;
            let name = self.text[start..name_end].to_owned();
            let mut order = 0u8;
            while self.bytes.get(self.at) == Some(&b'\'') {
                order += 1;
                self.at += 1;
            }
            if order > 0 {
                return Ok(node(Expr::Derivative { name, order }, start, self.at));
            }
            if self.eat(b'(') {
                let func = Spanned::new(name, span(start, name_end));
                let mut args = vec![self.expr()?];
                while self.eat(b',') {
                    args.push(self.expr()?);
                }
                if !self.eat(b')') {
                    return Err(format!("expected `)` at {} in `{}`", self.at, self.text));
                }
                return Ok(node(Expr::Call { func, args }, start, self.at));
            }
            return Ok(node(Expr::Name(name), start, self.at));
        }
        Err(format!(
            "unexpected `{}` at {start} in `{}`",
            c as char, self.text
        ))
    }

    fn number(&mut self) -> ExprNode {
        let start = self.at;
        let digits = |r: &mut Self| {
            while r.bytes.get(r.at).is_some_and(u8::is_ascii_digit) {
                r.at += 1;
            }
        };
        digits(self);
        if self.bytes.get(self.at) == Some(&b'.') {
            self.at += 1;
            digits(self);
        }
        if matches!(self.bytes.get(self.at), Some(b'e' | b'E')) {
            let save = self.at;
            self.at += 1;
            if matches!(self.bytes.get(self.at), Some(b'+' | b'-')) {
                self.at += 1;
            }
            if self.bytes.get(self.at).is_some_and(u8::is_ascii_digit) {
                digits(self);
            } else {
                self.at = save;
            }
        }
        node(
            Expr::Number(self.text[start..self.at].to_owned()),
            start,
            self.at,
        )
    }
}
