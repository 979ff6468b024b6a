//! A table with its derivative tables built once: the field a generated system holds for a
//! `table F(t) = runtime` statement (docs/tables.md#runtime-tables), whose data the user
//! gives when making the system rather than the macro at compile time.

use alloc::vec::Vec;

use crate::interpolant::Interpolation;
use crate::points::Points;
use crate::table::{Outside, Table};

/// A [`Table`] and every derivative table of it, built once when the table is made (a
/// generated system's methods look them up call after call and build nothing).
///
/// A piecewise polynomial of degree d has d + 1 nonzero derivatives at most; the
/// (d + 1)-th is the zero table, whose own derivative is itself. So the orders 0 … d + 1
/// are built and [`order`](Tabulated::order) gives the last for any higher one: whatever
/// order the derivation asks for, it is there.
///
/// ```
/// use varmass_table::{Interpolation, Outside, Points, Tabulated};
///
/// // A thrust curve: 0 → 100 N in 1 s, back to 0 at 2 s.
/// let points = Points::new(vec![0.0, 1.0, 2.0], vec![0.0, 100.0, 0.0]).unwrap();
/// let thrust = Tabulated::new(&points, Interpolation::Linear, Outside::Zero);
/// assert_eq!(thrust.order(0).value(0.5), Ok(50.0));
/// assert_eq!(thrust.order(1).value(1.5), Ok(-100.0));
/// // Dispersed: 10 % more thrust, burning 20 % longer (impulse × 1.1 · 1.2).
/// let dispersed = thrust.transformed(1.1, 1.2).unwrap();
/// assert!((dispersed.order(0).value(1.2).unwrap() - 110.0).abs() < 1e-12);
/// assert_eq!(dispersed.order(0).domain(), (0.0, 2.4));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Tabulated {
    /// `orders[k]` the k-th derivative table, k = 0 … degree + 1.
    orders: Vec<Table>,
}

impl Tabulated {
    /// The table interpolating `points` as `interpolation` says, with `outside`'s rule, and
    /// its derivative tables.
    pub fn new(points: &Points, interpolation: Interpolation, outside: Outside) -> Self {
        Self::from_table(Table::new(points, interpolation, outside))
    }

    /// `table` and its derivative tables.
    pub fn from_table(table: Table) -> Self {
        let count = table.curve().degree() + 2;
        let mut orders = Vec::with_capacity(count);
        orders.push(table);
        while orders.len() < count {
            let next = orders[orders.len() - 1].derivative();
            orders.push(next);
        }
        Self { orders }
    }

    /// The table itself (order 0).
    pub fn table(&self) -> &Table {
        &self.orders[0]
    }

    /// The `k`-th derivative table (past degree + 1, the zero table of order degree + 1:
    /// the derivative of the zero table is itself).
    #[inline]
    pub fn order(&self, k: usize) -> &Table {
        &self.orders[k.min(self.orders.len() - 1)]
    }

    /// The table scaled by `value_scale` and stretched by `argument_scale`, k·F(x/s), and
    /// its derivatives built again from it (see [`Table::transformed`]): an ensemble's
    /// member with a dispersed thrust curve. `None` for a scale [`Piecewise::transformed`]
    /// refuses.
    ///
    /// [`Piecewise::transformed`]: crate::Piecewise::transformed
    pub fn transformed(&self, value_scale: f64, argument_scale: f64) -> Option<Self> {
        let table = self.table().transformed(value_scale, argument_scale)?;
        Some(Self::from_table(table))
    }
}
