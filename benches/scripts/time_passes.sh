#!/usr/bin/env bash
# The macro's expansion inside the compiler, as the README reports it: `expand_crate` of
# `-Z time-passes` (on stable through RUSTC_BOOTSTRAP=1) for a crate holding the 3-link
# chain (benches/common/chain.rs), the swinging tank and the double pendulum; the fastest
# of 7 builds, each after touching the crate so that only it is rebuilt.
#
#   bash benches/scripts/time_passes.sh              # the three systems
#   bash benches/scripts/time_passes.sh rocket_6dof  # models/rocket_6dof.vms alone
#
# With `rocket_6dof` the crate holds the six-degree-of-freedom rocket alone (issue 22's "expansion
# as users get it"), and the same crate without it is timed too: the difference is the macro's.
#
# The crate is made in a temporary folder and depends on this repository by path; its
# dependencies build once, unoptimized, as users get them (set CARGO_TARGET_DIR to reuse a
# target directory between runs).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
crate=$(mktemp -d)
trap 'rm -rf "$crate"' EXIT
mkdir -p "$crate/src" "$crate/models"
cp "$root/models/swinging_tank.vms" "$root/models/double_pendulum.vms" \
    "$root/models/rocket_6dof.vms" "$crate/models/"
cat > "$crate/Cargo.toml" <<TOML
[package]
name = "expansion-timing"
version = "0.0.0"
edition = "2021"
publish = false

[dependencies]
varmass = { path = "$root" }

[workspace]
TOML
cat > "$crate/src/lib.rs" <<'RUST'
#![allow(non_snake_case)]

use varmass::prelude::*;

#[variable_mass_system(
    "
    coordinates a1, a2, a3
    mass m1 = m0 + c*t
    mass m2 = m0 + c*t
    mass m3 = m0 + c*t
    body bob1: mass m1, position [l*sin(a1), -l*cos(a1)]
    body bob2: mass m2, position [l*sin(a1) + l*sin(a2), -l*cos(a1) - l*cos(a2)]
    body bob3: mass m3, position [l*sin(a1) + l*sin(a2) + l*sin(a3), -l*cos(a1) - l*cos(a2) - l*cos(a3)]
    potential g*(m1*(-l*cos(a1)) + m2*(-l*cos(a1) - l*cos(a2)) + m3*(-l*cos(a1) - l*cos(a2) - l*cos(a3)))
    inflow bob1: velocity [0, 0]
    inflow bob2: velocity [0, 0]
    inflow bob3: velocity [0, 0]
"
)]
pub struct Chain3 {
    pub m0: f64,
    pub c: f64,
    pub l: f64,
    pub g: f64,
}

#[variable_mass_system(file = "models/swinging_tank.vms")]
pub struct SwingingTank {
    pub mu: f64,
    pub M0: f64,
    pub J0: f64,
    pub l: f64,
    pub g: f64,
    pub K: f64,
    pub u_e: f64,
}

#[variable_mass_system(file = "models/double_pendulum.vms")]
pub struct DoublePendulum {
    pub M1: f64,
    pub M2: f64,
    pub l1: f64,
    pub l2: f64,
    pub g: f64,
}
RUST
if [ "${1:-}" = rocket_6dof ]; then
    cat > "$crate/src/lib.rs" <<'RUST'
#![allow(non_snake_case)]

use varmass::prelude::*;

#[variable_mass_system(file = "models/rocket_6dof.vms")]
pub struct Rocket6 {
    pub mu: f64,
    pub m_d: f64,
    pub A_d: f64,
    pub C_d: f64,
    pub k_a: f64,
    pub k_c: f64,
    pub g_c: f64,
    pub l: f64,
    pub u_e: f64,
    pub delta: f64,
    pub g: f64,
}
RUST
fi
cd "$crate"
cargo build --quiet --lib 2>/dev/null || cargo build --lib

# The fastest `expand_crate` of 7 builds of the crate as it stands.
fastest() {
    local best=""
    for _ in 1 2 3 4 5 6 7; do
        touch src/lib.rs
        seconds=$(RUSTC_BOOTSTRAP=1 cargo rustc --quiet --lib -- -Z time-passes 2>&1 |
            awk '$NF == "expand_crate" { sub(";", "", $2); print $2 }')
        echo "expand_crate ${seconds} s" >&2
        best=$(printf '%s\n%s\n' "$best" "$seconds" | sed '/^$/d' | sort -g | head -1)
    done
    echo "$best"
}
best=$(fastest)
echo "fastest of 7: ${best} s"
if [ "${1:-}" = rocket_6dof ]; then
    # The same crate without the struct: what expansion costs without the macro.
    printf '#![allow(non_snake_case)]\n\nuse varmass::prelude::*;\n' > src/lib.rs
    base=$(fastest)
    echo "without the struct, fastest of 7: ${base} s"
    awk -v a="$best" -v b="$base" 'BEGIN { printf "the macro: %.1f ms\n", (a - b) * 1000 }'
fi
# Wall-clock seconds: on a loaded machine they measure the load as much as the macro.
uptime
