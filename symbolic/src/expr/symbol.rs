//! Symbols and the table that names them.
//!
//! A symbol's *kind* decides how the frozen-mass calculus treats it (docs/mechanics.md#the-frozen-mass-rule): `Frozen`
//! and `Parameter` symbols have zero derivative under ∂* and d*/dt even where a mass law
//! makes them depend on q or t.

use rustc_hash::FxHashMap;

/// A symbol: an index into its pool's [`SymbolTable`]. Symbols are ordered by that index,
/// so the canonical order of expressions is the order of declaration.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Symbol(pub(crate) u32);

impl Symbol {
    /// The position in the table, also the slot of this symbol in an evaluation
    /// environment (`env[s.index()]`).
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// What a symbol stands for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SymbolKind {
    /// A generalized coordinate q.
    Coordinate,
    /// q̇, written `x'`.
    Velocity {
        /// The coordinate whose rate this is.
        coordinate: Symbol,
    },
    /// q̈, written `x''`.
    Acceleration {
        /// The coordinate whose second rate this is.
        coordinate: Symbol,
    },
    /// The generalized momentum p_q, written `p_x`.
    Momentum {
        /// The coordinate it is conjugate to.
        coordinate: Symbol,
    },
    /// Time t.
    Time,
    /// A parameter of the system (a struct field): constant.
    Parameter,
    /// A mass or inertia: zero derivative under ∂* and d*/dt (the frozen-mass rule).
    Frozen,
    /// A `let` name or a derived quantity; it may carry a value (see
    /// [`ExprPool::define`](super::ExprPool::define)) that calculus and evaluation look through.
    Definition,
}

/// The symbols derived from one coordinate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Family {
    velocity: Symbol,
    acceleration: Symbol,
    momentum: Symbol,
}

/// Names and kinds of the symbols of one [`ExprPool`](super::ExprPool), and for each
/// coordinate its velocity, acceleration and momentum.
#[derive(Clone, Debug, Default)]
pub struct SymbolTable {
    names: Vec<String>,
    kinds: Vec<SymbolKind>,
    families: Vec<Option<Family>>,
    by_name: FxHashMap<String, Symbol>,
}

impl SymbolTable {
    /// An empty table.
    pub fn new() -> SymbolTable {
        SymbolTable::default()
    }

    fn push(&mut self, name: &str, kind: SymbolKind) -> Symbol {
        // 2^32 symbols cannot be declared in a DSL text that fits in memory.
        let s = Symbol(self.names.len() as u32);
        self.names.push(name.to_owned());
        self.kinds.push(kind);
        self.families.push(None);
        // Never re-point an existing name: the first declaration keeps it.
        self.by_name.entry(name.to_owned()).or_insert(s);
        s
    }

    /// Adds a coordinate `name` together with `name'`, `name''` and `p_name`.
    ///
    /// If `name` is already a coordinate, that coordinate is returned. If it names a symbol
    /// of another kind, a new coordinate is created but the name keeps finding the first
    /// symbol: callers that must reject duplicates check [`lookup`](Self::lookup) first.
    pub fn add_coordinate(&mut self, name: &str) -> Symbol {
        if let Some(s) = self.lookup(name) {
            if self.kind(s) == SymbolKind::Coordinate {
                return s;
            }
        }
        let q = self.push(name, SymbolKind::Coordinate);
        let velocity = self.push(&format!("{name}'"), SymbolKind::Velocity { coordinate: q });
        let acceleration = self.push(
            &format!("{name}''"),
            SymbolKind::Acceleration { coordinate: q },
        );
        let momentum = self.push(&format!("p_{name}"), SymbolKind::Momentum { coordinate: q });
        if let Some(slot) = self.families.get_mut(q.index()) {
            *slot = Some(Family {
                velocity,
                acceleration,
                momentum,
            });
        }
        q
    }

    /// Adds a symbol of a plain kind (`Time`, `Parameter`, `Frozen`, `Definition`).
    ///
    /// If `name` exists already, the existing symbol is returned unchanged (its kind is
    /// not altered); use [`try_add`](Self::try_add) to detect that. Coordinates should be
    /// added with [`add_coordinate`](Self::add_coordinate) so that their family exists.
    pub fn add(&mut self, name: &str, kind: SymbolKind) -> Symbol {
        match self.lookup(name) {
            Some(s) => s,
            None => self.push(name, kind),
        }
    }

    /// Like [`add`](Self::add), but `Err(existing)` if the name is taken.
    pub fn try_add(&mut self, name: &str, kind: SymbolKind) -> Result<Symbol, Symbol> {
        match self.lookup(name) {
            Some(s) => Err(s),
            None => Ok(self.push(name, kind)),
        }
    }

    /// The symbol called `name` (`x'`, `x''` and `p_x` are names too).
    pub fn lookup(&self, name: &str) -> Option<Symbol> {
        self.by_name.get(name).copied()
    }

    /// The symbol's name; `"?"` for a symbol of another table.
    pub fn name(&self, s: Symbol) -> &str {
        self.names.get(s.index()).map_or("?", String::as_str)
    }

    /// The symbol's kind; `Parameter` (inert) for a symbol of another table.
    pub fn kind(&self, s: Symbol) -> SymbolKind {
        self.kinds
            .get(s.index())
            .copied()
            .unwrap_or(SymbolKind::Parameter)
    }

    fn family(&self, q: Symbol) -> Option<Family> {
        self.families.get(q.index()).copied().flatten()
    }

    /// q̇ of coordinate `q`.
    pub fn velocity_of(&self, q: Symbol) -> Option<Symbol> {
        self.family(q).map(|f| f.velocity)
    }

    /// q̈ of coordinate `q`.
    pub fn acceleration_of(&self, q: Symbol) -> Option<Symbol> {
        self.family(q).map(|f| f.acceleration)
    }

    /// p_q of coordinate `q`.
    pub fn momentum_of(&self, q: Symbol) -> Option<Symbol> {
        self.family(q).map(|f| f.momentum)
    }

    /// The coordinates, in declaration order.
    pub fn coordinates(&self) -> impl Iterator<Item = Symbol> + '_ {
        self.iter()
            .filter(|s| self.kind(*s) == SymbolKind::Coordinate)
    }

    /// Number of symbols.
    pub fn len(&self) -> usize {
        self.names.len()
    }

    /// Whether the table is empty.
    pub fn is_empty(&self) -> bool {
        self.names.is_empty()
    }

    /// Every symbol, in index order.
    pub fn iter(&self) -> impl Iterator<Item = Symbol> {
        (0..self.names.len() as u32).map(Symbol)
    }
}
