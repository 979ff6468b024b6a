//! The n-link chain of variable-mass bobs that measures how the derivation scales: link i
//! hangs from bob i − 1 at length l, at angle aᵢ from the vertical, and bob i accretes dust
//! at rest at the constant rate c (mᵢ = m0 + c t, `inflow … velocity [0, 0]`), so every bob
//! carries an impact force R2 and every coordinate couples to all the others.

/// The DSL of the n-link chain.
pub fn chain_source(links: usize) -> String {
    let angles: Vec<String> = (1..=links).map(|i| format!("a{i}")).collect();
    let mut lines = vec![format!("coordinates {}", angles.join(", "))];
    for i in 1..=links {
        lines.push(format!("mass m{i} = m0 + c*t"));
    }
    let mut heights = Vec::new();
    for i in 1..=links {
        let x: Vec<String> = angles[..i].iter().map(|a| format!("l*sin({a})")).collect();
        let y: Vec<String> = angles[..i].iter().map(|a| format!("l*cos({a})")).collect();
        let height = format!("-{}", y.join(" - "));
        lines.push(format!(
            "body bob{i}: mass m{i}, position [{}, {height}]",
            x.join(" + ")
        ));
        heights.push(format!("m{i}*({height})"));
    }
    lines.push(format!("potential g*({})", heights.join(" + ")));
    for i in 1..=links {
        lines.push(format!("inflow bob{i}: velocity [0, 0]"));
    }
    lines.join("\n")
}
