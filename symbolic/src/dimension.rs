//! Physical dimensions over the SI base units kg, m, s, K and mol, with exact rational
//! exponents.
//!
//! The kelvin and the mole are there for thermodynamics (an atmosphere's temperature, a gas
//! constant in J/(mol·K)); mechanics needs only kg, m and s. An angle (rad) is
//! dimensionless: it multiplies like the number 1, so a torque and an energy share
//! `kg·m²/s²`. Exponents are [`Rational`]s so that `sqrt(m)` is `m^(1/2)`
//! exactly; every operation is checked and gives `None` rather than overflow.

use crate::expr::Rational;
use std::fmt;

/// A dimension `kg^a · m^b · s^c · K^d · mol^e`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Dimension {
    exponents: [Rational; 5],
}

/// The base units, in display order.
const BASES: [&str; 5] = ["kg", "m", "s", "K", "mol"];

impl Dimension {
    /// Dimensionless (a pure number, or an angle in rad).
    pub const NONE: Dimension = Dimension::integer(0, 0, 0);
    /// kg.
    pub const MASS: Dimension = Dimension::integer(1, 0, 0);
    /// m.
    pub const LENGTH: Dimension = Dimension::integer(0, 1, 0);
    /// s.
    pub const TIME: Dimension = Dimension::integer(0, 0, 1);
    /// m/s.
    pub const VELOCITY: Dimension = Dimension::integer(0, 1, -1);
    /// kg·m/s² (N).
    pub const FORCE: Dimension = Dimension::integer(1, 1, -2);
    /// kg·m²/s² (J).
    pub const ENERGY: Dimension = Dimension::integer(1, 2, -2);
    /// kg·m²/s³ (W).
    pub const POWER: Dimension = Dimension::integer(1, 2, -3);
    /// kg/(m·s²) (Pa).
    pub const PRESSURE: Dimension = Dimension::integer(1, -1, -2);
    /// kg/s.
    pub const MASS_FLOW: Dimension = Dimension::integer(1, 0, -1);
    /// kg·m² (a moment of inertia).
    pub const INERTIA: Dimension = Dimension::integer(1, 2, 0);
    /// K (a thermodynamic temperature).
    pub const TEMPERATURE: Dimension = Dimension::thermal([0, 0, 0, 1, 0]);
    /// mol (an amount of substance).
    pub const AMOUNT: Dimension = Dimension::thermal([0, 0, 0, 0, 1]);

    /// `kg^kg · m^m · s^s` with integer exponents (no kelvin, no mole).
    pub const fn integer(kg: i128, m: i128, s: i128) -> Dimension {
        Dimension::thermal([kg, m, s, 0, 0])
    }

    /// `kg^a · m^b · s^c · K^d · mol^e` from the integer exponents `[a, b, c, d, e]`.
    pub const fn thermal(exponents: [i128; 5]) -> Dimension {
        let [kg, m, s, kelvin, mole] = exponents;
        Dimension {
            exponents: [
                Rational::integer(kg),
                Rational::integer(m),
                Rational::integer(s),
                Rational::integer(kelvin),
                Rational::integer(mole),
            ],
        }
    }

    /// The exponents of kg, m, s, K and mol.
    pub fn exponents(self) -> [Rational; 5] {
        self.exponents
    }

    /// Whether this is dimensionless.
    pub fn is_dimensionless(self) -> bool {
        self == Dimension::NONE
    }

    /// Applies `f` to the exponents pairwise; `None` if any overflows.
    fn zip(
        self,
        other: Dimension,
        f: impl Fn(Rational, Rational) -> Option<Rational>,
    ) -> Option<Dimension> {
        let mut exponents = self.exponents;
        for (mine, theirs) in exponents.iter_mut().zip(other.exponents) {
            *mine = f(*mine, theirs)?;
        }
        Some(Dimension { exponents })
    }

    /// The dimension of a product.
    pub fn checked_mul(self, other: Dimension) -> Option<Dimension> {
        self.zip(other, Rational::checked_add)
    }

    /// The dimension of a quotient.
    pub fn checked_div(self, other: Dimension) -> Option<Dimension> {
        self.zip(other, Rational::checked_sub)
    }

    /// The dimension of `self^power`.
    pub fn pow(self, power: Rational) -> Option<Dimension> {
        self.zip(Dimension::NONE, |a, _| a.checked_mul(power))
    }

    /// The dimension of a square root.
    pub fn sqrt(self) -> Option<Dimension> {
        self.pow(Rational::HALF)
    }

    /// What a physicist calls this dimension, if it has a common name ("an energy").
    pub fn name(self) -> Option<&'static str> {
        NAMES
            .iter()
            .find(|(dimension, _)| *dimension == self)
            .map(|(_, name)| *name)
    }

    /// The unit to show for a quantity of this dimension: `J`, `N`, `W` or `Pa` when it is
    /// one of those, else the base form (`kg·m/s`); `N·m` for an energy that is a torque
    /// (a generalized force on an angle).
    pub fn unit(self, torque: bool) -> String {
        match self {
            Dimension::ENERGY if torque => "N·m".to_string(),
            Dimension::ENERGY => "J".to_string(),
            Dimension::FORCE => "N".to_string(),
            Dimension::POWER => "W".to_string(),
            Dimension::PRESSURE => "Pa".to_string(),
            _ => self.to_string(),
        }
    }

    /// `an energy, kg·m²/s²` when the dimension has a name, else just `kg·m/s³`;
    /// `dimensionless` for a pure number.
    pub fn described(self) -> String {
        match self.name() {
            Some(name) if self.is_dimensionless() => name.to_string(),
            Some(name) => format!("{name}, {self}"),
            None => self.to_string(),
        }
    }
}

/// Named dimensions for messages, most specific first.
const NAMES: &[(Dimension, &str)] = &[
    (Dimension::NONE, "dimensionless"),
    (Dimension::MASS, "a mass"),
    (Dimension::LENGTH, "a length"),
    (Dimension::TIME, "a time"),
    (Dimension::VELOCITY, "a velocity"),
    (Dimension::integer(0, 1, -2), "an acceleration"),
    (Dimension::FORCE, "a force"),
    (Dimension::ENERGY, "an energy"),
    (Dimension::POWER, "a power"),
    (Dimension::PRESSURE, "a pressure"),
    (Dimension::MASS_FLOW, "a mass flow"),
    (Dimension::INERTIA, "a moment of inertia"),
    (Dimension::integer(1, 1, -1), "a momentum"),
    (Dimension::integer(1, 2, -1), "an angular momentum"),
    (Dimension::integer(0, 0, -1), "a rate"),
    (Dimension::TEMPERATURE, "a temperature"),
    (Dimension::AMOUNT, "an amount of substance"),
    (Dimension::integer(0, 2, -2), "a specific energy"),
];

/// `²` for 2, `⁻¹` for −1: an integer in Unicode superscripts.
fn superscript(n: i128) -> String {
    const DIGITS: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let mut out = String::new();
    if n < 0 {
        out.push('⁻');
    }
    for digit in n.unsigned_abs().to_string().bytes() {
        out.push(DIGITS[usize::from(digit - b'0')]);
    }
    out
}

/// One factor `m²`, `s`, or `m^(1/2)` with a positive exponent.
fn factor(base: &str, exponent: Rational) -> String {
    match exponent.as_integer() {
        Some(1) => base.to_string(),
        Some(n) => format!("{base}{}", superscript(n)),
        None => format!("{base}^({exponent})"),
    }
}

impl fmt::Display for Dimension {
    /// `kg·m²/s²`, `1/s`, `kg/(m·s²)`, `m^(1/2)`; `1` when dimensionless.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut numerator = Vec::new();
        let mut denominator = Vec::new();
        for (base, exponent) in BASES.iter().zip(self.exponents) {
            if exponent.is_negative() {
                let positive = exponent.checked_neg().unwrap_or(exponent);
                denominator.push(factor(base, positive));
            } else if !exponent.is_zero() {
                numerator.push(factor(base, exponent));
            }
        }
        let top = if numerator.is_empty() {
            "1".to_string()
        } else {
            numerator.join("·")
        };
        match denominator.len() {
            0 => f.write_str(&top),
            1 => write!(f, "{top}/{}", denominator[0]),
            _ => write!(f, "{top}/({})", denominator.join("·")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn r(num: i128, den: i128) -> Rational {
        Rational::new(num, den).unwrap()
    }

    #[test]
    fn products_and_quotients_add_and_subtract_exponents() {
        let velocity = Dimension::LENGTH.checked_div(Dimension::TIME).unwrap();
        assert_eq!(velocity, Dimension::VELOCITY);
        let momentum = Dimension::MASS.checked_mul(velocity).unwrap();
        let energy = momentum.checked_mul(velocity).unwrap();
        assert_eq!(energy, Dimension::ENERGY);
        assert_eq!(
            energy.checked_div(Dimension::LENGTH),
            Some(Dimension::FORCE)
        );
        assert_eq!(energy.checked_div(energy), Some(Dimension::NONE));
    }

    #[test]
    fn rational_powers_and_square_roots_scale_exponents() {
        let area = Dimension::LENGTH.pow(r(2, 1)).unwrap();
        assert_eq!(area.sqrt(), Some(Dimension::LENGTH));
        let root_length = Dimension::LENGTH.sqrt().unwrap();
        assert_eq!(root_length.exponents()[1], r(1, 2));
        assert_eq!(root_length.pow(r(2, 1)), Some(Dimension::LENGTH));
        // (kg·m²/s²)^(-3/2) = kg^(-3/2)·m^(-3)·s^3
        let e = Dimension::ENERGY.pow(r(-3, 2)).unwrap();
        let zero = Rational::ZERO;
        assert_eq!(e.exponents(), [r(-3, 2), r(-3, 1), r(3, 1), zero, zero]);
        assert_eq!(Dimension::ENERGY.pow(Rational::ZERO), Some(Dimension::NONE));
    }

    #[test]
    fn an_exponent_that_overflows_is_none_not_a_panic() {
        let huge = Dimension::LENGTH.pow(Rational::integer(i128::MAX)).unwrap();
        assert_eq!(huge.checked_mul(Dimension::LENGTH), None);
        assert_eq!(huge.pow(r(2, 1)), None);
    }

    #[test]
    fn display_uses_superscripts_and_one_slash() {
        assert_eq!(Dimension::ENERGY.to_string(), "kg·m²/s²");
        assert_eq!(Dimension::FORCE.to_string(), "kg·m/s²");
        assert_eq!(Dimension::PRESSURE.to_string(), "kg/(m·s²)");
        assert_eq!(Dimension::integer(0, 0, -1).to_string(), "1/s");
        assert_eq!(Dimension::NONE.to_string(), "1");
        assert_eq!(Dimension::integer(0, -12, 0).to_string(), "1/m¹²");
        assert_eq!(Dimension::LENGTH.sqrt().unwrap().to_string(), "m^(1/2)");
        let odd = Dimension::integer(1, 0, 0).pow(r(-3, 2)).unwrap();
        assert_eq!(odd.to_string(), "1/kg^(3/2)");
    }

    #[test]
    fn kelvin_and_mole_are_base_dimensions_of_their_own() {
        // The 1976 atmosphere's gas constant R* = 8.31432 J/(mol·K) and molar mass M0 in
        // kg/mol: R*/M0 is J/(kg·K) = m²/(s²·K), and times a temperature a specific energy
        // (m²/s², the square of a speed of sound).
        let joule_per_mol_kelvin = Dimension::ENERGY
            .checked_div(Dimension::AMOUNT)
            .and_then(|d| d.checked_div(Dimension::TEMPERATURE))
            .unwrap();
        assert_eq!(joule_per_mol_kelvin.to_string(), "kg·m²/(s²·K·mol)");
        let molar_mass = Dimension::MASS.checked_div(Dimension::AMOUNT).unwrap();
        assert_eq!(molar_mass.to_string(), "kg/mol");
        let specific = joule_per_mol_kelvin.checked_div(molar_mass).unwrap();
        assert_eq!(specific.to_string(), "m²/(s²·K)");
        let square_speed = specific.checked_mul(Dimension::TEMPERATURE).unwrap();
        assert_eq!(square_speed.sqrt(), Some(Dimension::VELOCITY));
        assert_eq!(square_speed.described(), "a specific energy, m²/s²");
        // A temperature is not a mass, a length, a time nor dimensionless, and a lapse rate
        // K/m times a length is a temperature again.
        for other in [
            Dimension::NONE,
            Dimension::MASS,
            Dimension::LENGTH,
            Dimension::TIME,
        ] {
            assert_ne!(Dimension::TEMPERATURE, other);
        }
        let lapse = Dimension::TEMPERATURE
            .checked_div(Dimension::LENGTH)
            .unwrap();
        assert_eq!(lapse.to_string(), "K/m");
        assert_eq!(
            lapse.checked_mul(Dimension::LENGTH),
            Some(Dimension::TEMPERATURE)
        );
        assert_eq!(Dimension::TEMPERATURE.described(), "a temperature, K");
        assert_eq!(
            Dimension::TEMPERATURE.pow(r(-1, 2)).unwrap().to_string(),
            "1/K^(1/2)"
        );
    }

    #[test]
    fn units_use_the_si_names_of_derived_units() {
        assert_eq!(Dimension::ENERGY.unit(false), "J");
        assert_eq!(Dimension::ENERGY.unit(true), "N·m");
        assert_eq!(Dimension::FORCE.unit(true), "N");
        assert_eq!(Dimension::integer(1, 1, -1).unit(false), "kg·m/s");
    }

    #[test]
    fn named_dimensions_read_as_a_physicist_says_them() {
        assert_eq!(Dimension::ENERGY.described(), "an energy, kg·m²/s²");
        assert_eq!(Dimension::MASS_FLOW.described(), "a mass flow, kg/s");
        assert_eq!(Dimension::NONE.described(), "dimensionless");
        assert_eq!(Dimension::integer(1, 2, -4).described(), "kg·m²/s⁴");
        assert_eq!(Dimension::POWER.name(), Some("a power"));
    }
}
