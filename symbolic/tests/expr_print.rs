//! Printing: DSL text that reads back to the same expression, and LaTeX samples.
//!
//! The round trip here reads the printed text with the test reader in `expr_support`
//! (an independent recursive-descent parser of the expression grammar of docs/dsl.md#grammar), then lowers
//! it; the parser-based round trip belongs to the integration of the real nom parser.

mod expr_support;

use expr_support::{build, read, sled_pool};
use varmass_symbolic::expr::{lower, ExprPool, TableResolver};

fn round_trip(pool: &mut ExprPool, text: &str) {
    let e = build(pool, text);
    let printed = pool.display(e).to_string();
    let ast = read(&printed).unwrap_or_else(|err| panic!("`{printed}` unreadable: {err}"));
    let back = lower(pool, &ast, &mut TableResolver).unwrap();
    assert_eq!(
        back, e,
        "`{text}` printed as `{printed}` reads back differently"
    );
}

#[test]
fn printed_text_reads_back_to_the_same_expression() {
    let mut p = sled_pool();
    for text in [
        "1/2*m*x'^2 + m*g*x*sin(theta)",
        "p_x^2/(2*m) - m*g*x*sin(theta)",
        "x - 1",
        "-x^2 + 3",
        "-x^2*g",
        "sqrt(x)/(m0 + c*x)^2",
        "x^(-g)",
        "x^(-2*g)",
        "x^(-g/2)",
        "(x^2)^(1/3)",
        "-3/4*x*g^-2",
        "2^(1/2)",
        "2^200",
        "-1/2",
        "(-2)^(1/2)",
        "(1/2)^x",
        "exp(x)^2*sin(theta)^2",
        "1/sqrt(m)",
        "x^(3/2)",
        "x^g^2",
        "(x^g)^2",
        "m0*c*x''",
        "atan2(x, -g)",
        "min(x, g) - max(-x, 2*g)",
        "abs(x - g)",
        "-(x + g)",
        "-(x + g)^2",
        "(x + g)*(x - g)/(c*(m0 + x))",
        "1/(x*g)",
        "-1/x",
        "sin(-x)*t - cos(2*t)",
        "9.81*x",
        "1e-3*x - 6.02E23",
        "u_e*ln(m0/m) - g*t",
        "tan(theta)^-1 + tanh(x)^(1/3)",
    ] {
        round_trip(&mut p, text);
    }
}

#[test]
fn printing_reads_naturally() {
    let mut p = sled_pool();
    let cases = [
        ("x - 1", "x - 1"),
        ("1/2*m*x'^2", "m*x'^2/2"),
        ("-3/4*x*g^-2", "-3*x/(4*g^2)"),
        ("1/sqrt(m)", "1/sqrt(m)"),
        ("x^(3/2)", "x^(3/2)"),
        ("x^(-g)", "1/x^g"),
        ("-(x + g)", "-g - x"),
        ("-(x + g)^2", "-(g + x)^2"),
        ("atan2(x, -g)", "atan2(x, -g)"),
        ("g - x", "g - x"),
        ("-x - 1", "-x - 1"),
        ("3 - x", "3 - x"),
    ];
    for (text, want) in cases {
        let e = build(&mut p, text);
        assert_eq!(p.display(e).to_string(), want, "display of `{text}`");
    }
}

#[test]
fn inexact_constants_print_to_the_same_value() {
    let mut p = sled_pool();
    let e = build(&mut p, "1e50*x + 0.1");
    let printed = p.display(e).to_string();
    assert_eq!(printed, "1e50*x + 1/10");
    let big = p.float(1.234_567_890_123e-300);
    let printed = p.display(big).to_string();
    assert_eq!(printed.parse::<f64>().unwrap(), 1.234_567_890_123e-300);
}

#[test]
fn latex_samples() {
    let mut p = sled_pool();
    let cases = [
        ("1/2*m*x'^2", r"\frac{m \dot{x}^{2}}{2}"),
        ("m*x''", r"m \ddot{x}"),
        ("p_x^2/(2*m)", r"\frac{p_{x}^{2}}{2 m}"),
        ("m0*sin(theta)", r"m_{0} \sin\left(\theta\right)"),
        ("u_e*ln(m0/m)", r"u_{e} \ln\left(\frac{m_{0}}{m}\right)"),
        ("sqrt(g/c)", r"\sqrt{\frac{g}{c}}"),
        ("x^(-1/2)", r"\frac{1}{\sqrt{x}}"),
        (
            "sin(theta)^2 - cos(theta)",
            r"\sin^{2}\left(\theta\right) - \cos\left(\theta\right)",
        ),
        ("abs(x)*mu", r"\mu \left|x\right|"),
        ("exp(-x)", r"e^{-x}"),
        ("(x + g)^2", r"\left(g + x\right)^{2}"),
        ("2*3^x", r"2 \cdot 3^{x}"),
        ("f_d*g*cos(theta)", r"g f_{d} \cos\left(\theta\right)"),
        ("atan2(x, g)", r"\operatorname{atan2}\left(x, g\right)"),
        ("1e50*x", r"10^{50} x"),
    ];
    for (text, want) in cases {
        let e = build(&mut p, text);
        assert_eq!(p.latex(e), want, "latex of `{text}`");
    }
}

#[test]
fn printing_a_deep_expression_needs_no_deep_stack() {
    // The printers walk the arena bottom-up without recursion: an expression 5000 calls
    // deep prints on a 256 KiB stack (a recursive printer needs several frames per level).
    let depth = 5000;
    let handle = std::thread::Builder::new()
        .stack_size(256 << 10)
        .spawn(move || {
            let mut p = sled_pool();
            let x = p.symbols().lookup("x").expect("the sled's coordinate");
            let mut e = p.sym(x);
            for _ in 0..depth {
                e = p.call(varmass_symbolic::expr::Func::Sin, &[e]);
            }
            (p.display(e).to_string(), p.latex(e))
        })
        .expect("a thread");
    let (text, latex) = handle.join().expect("printing does not overflow the stack");
    assert_eq!(
        text,
        format!("{}x{}", "sin(".repeat(depth), ")".repeat(depth))
    );
    let tex = format!(
        "{}x{}",
        r"\sin\left(".repeat(depth),
        r"\right)".repeat(depth)
    );
    assert_eq!(latex, tex);
}
