//! Tables in the expression engine (docs/tables.md#a-table-call-in-the-expression-engine):
//! the pool keeps each table of the model with the derivative tables the calculus has asked
//! for, and a call `Table{i, k}(a)` is an opaque [`Func`] node. Differentiation is the
//! chain rule ∂/∂s Table{i, k}(a) = Table{i, k+1}(a) · ∂a/∂s (`diff.rs`).

use super::func::Func;
use super::node::Id;
use super::pool::ExprPool;
use std::sync::Arc;
use varmass_table::Table;

/// One table of the pool: its name in the model and the table with its derivatives,
/// `orders[k]` the k-th (built on demand, a table of the same kind and rule).
#[derive(Clone, Debug)]
pub(crate) struct PoolTable {
    pub(crate) name: String,
    pub(crate) orders: Vec<Arc<Table>>,
    /// `= runtime`: generated code reads the struct's field, not a static of `orders`
    /// (whose data are a placeholder the derivation's checks evaluate).
    pub(crate) runtime: bool,
}

impl ExprPool {
    /// Registers `table` under `name` and returns the index calls use
    /// ([`table_call`](Self::table_call)); `None` past `u16::MAX` tables.
    pub fn add_table(&mut self, name: &str, table: Table) -> Option<u16> {
        let index = u16::try_from(self.tables.len()).ok()?;
        self.tables.push(PoolTable {
            name: name.to_owned(),
            orders: vec![Arc::new(table)],
            runtime: false,
        });
        Some(index)
    }

    /// Registers a `= runtime` table under `name`, `placeholder` standing in for its data
    /// where the derivation evaluates it (the checks at random points test algebra, not
    /// data); generated code reads the struct's field instead ([`is_runtime_table`]).
    ///
    /// [`is_runtime_table`]: Self::is_runtime_table
    pub fn add_runtime_table(&mut self, name: &str, placeholder: Table) -> Option<u16> {
        let index = self.add_table(name, placeholder)?;
        self.tables[usize::from(index)].runtime = true;
        Some(index)
    }

    /// Whether table `table` is `= runtime` (its data not known to the derivation).
    pub fn is_runtime_table(&self, table: u16) -> bool {
        self.tables
            .get(usize::from(table))
            .is_some_and(|t| t.runtime)
    }

    /// The call `Table{table, order}(argument)`, building the derivative tables up to
    /// `order` on first use. An unknown table, or an order past `u8::MAX`, is NaN.
    pub fn table_call(&mut self, table: u16, order: u8, argument: Id) -> Id {
        let Some(entry) = self.tables.get_mut(usize::from(table)) else {
            return self.float(f64::NAN);
        };
        while entry.orders.len() <= usize::from(order) {
            let next = match entry.orders.last() {
                Some(last) => last.derivative(),
                None => return self.float(f64::NAN),
            };
            entry.orders.push(Arc::new(next));
        }
        self.call(Func::Table { table, order }, &[argument])
    }

    /// The order-`order` derivative of table `table`, if it has been built (every call in
    /// the pool has built its own).
    pub fn table(&self, table: u16, order: u8) -> Option<&Arc<Table>> {
        self.tables
            .get(usize::from(table))
            .and_then(|t| t.orders.get(usize::from(order)))
    }

    /// The model's name of table `table` (empty if unknown).
    pub fn table_name(&self, table: u16) -> &str {
        self.tables
            .get(usize::from(table))
            .map_or("", |t| t.name.as_str())
    }

    /// Number of tables registered.
    pub fn table_count(&self) -> usize {
        self.tables.len()
    }

    /// How a call of `Table{table, order}` is written: `F`, `F'`, `F''`, then `F^(k)`.
    pub fn table_call_name(&self, table: u16, order: u8) -> String {
        let name = self.table_name(table);
        match order {
            0 => name.to_owned(),
            1 | 2 => format!("{name}{}", "'".repeat(usize::from(order))),
            k => format!("{name}^({k})"),
        }
    }
}
