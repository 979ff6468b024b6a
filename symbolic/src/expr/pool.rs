//! The arena: hash-consed nodes, leaf constructors, definitions and simple queries.

use super::diff::Leaf;
use super::node::{Id, Node, Number};
use super::rational::Rational;
use super::symbol::{Symbol, SymbolKind, SymbolTable};
use rustc_hash::FxHashMap;

/// A flat, hash-consed arena of expressions (after egg's `RecExpr`).
///
/// **Invariant:** every child of a node has a smaller [`Id`] than the node, and the value
/// of a defined symbol (see [`define`](Self::define)) has a smaller id than that symbol's
/// `Sym` node. So ascending id order is a topological order: every pass over an expression
/// (derivatives, substitution, evaluation, compilation) visits the reachable ids in
/// ascending order, bottom-up, without recursion and in time linear in the DAG size.
///
/// Identical nodes are stored once, so equal ids mean equal expressions. The public
/// constructors keep every node in canonical form (see [`Node`]), so simplification
/// happens at construction: `x - x` is `0`, `2*x + 3*x` is `5*x`, `x*x` is `x^2`.
#[derive(Clone, Debug)]
pub struct ExprPool {
    nodes: Vec<Node>,
    /// Height of each node (a leaf is 0): a cheap structural key that settles most
    /// comparisons of deep expressions at once (see `structural_cmp`).
    heights: Vec<u32>,
    /// For each node, a filter of the symbols it depends on, through definitions: bit
    /// `s.index() % 64` for each such symbol `s` (see [`symbol_bit`]). A clear bit proves a
    /// symbol absent, so passes that only care about some symbols (∂/∂s, substitution)
    /// skip whole subtrees without visiting them; a set bit may be another symbol.
    symbol_masks: Vec<u64>,
    index: FxHashMap<Node, Id>,
    symbols: SymbolTable,
    definitions: FxHashMap<Symbol, Id>,
    /// Every derivative taken so far, of each node it visited (see `diff.rs`): nodes never
    /// change, so neither do their derivatives, and the Jacobian's many derivatives of
    /// the same rows share most of their work.
    pub(super) derivatives: FxHashMap<(Id, Leaf), Id>,
    /// The image of every node an
    /// [`expand_trig_arguments`](Self::expand_trig_arguments) visited: like derivatives, it
    /// never changes.
    pub(super) trig_images: FxHashMap<Id, Id>,
    /// The image of every node an [`expand`](Self::expand) visited, and every product of
    /// two terms its distribution formed: like derivatives, they never change, and the
    /// trigonometric reductions of a rigid body's momentum rates expand the same
    /// subexpressions and multiply the same pairs of terms again and again.
    pub(super) expansions: super::expand::Expansions,
    /// The ids of the integers −1, 0, 1, 2 once interned (every constructor asks for
    /// them, and interning hashes the node each time); filled on first use, so the order
    /// in which nodes are created does not change.
    small_ints: [Option<Id>; 4],
    /// The coefficient and rest of every term with a coefficient that a sum split (see
    /// `split_coefficient`): every sum built splits each of its terms, and the
    /// trigonometric reduction rebuilds sums of the same terms round after round.
    pub(super) splits: FxHashMap<Id, (super::node::Number, Id)>,
    /// The model's tables and their derivatives (`table_call.rs`).
    pub(super) tables: Vec<super::table_call::PoolTable>,
    /// The model's inputs: each one's name and argument names (`input_call.rs`).
    pub(super) inputs: Vec<super::input_call::PoolInput>,
}

/// Room reserved for nodes at the start: the example systems derive into 60 to 900 nodes
/// (the 3-link chain), and each growth of the interning index re-hashes every node stored
/// so far. (Not more: the index of 512 nodes already takes 64 KiB.)
const INITIAL_NODES: usize = 512;

/// The bit of `s` in a node's symbol filter: symbols 64 apart share a bit, which only
/// costs a pass some needless visits.
pub(crate) fn symbol_bit(s: Symbol) -> u64 {
    1 << (s.index() % 64)
}

/// What `node` answers for an id that is not in the pool (an id of another pool).
static FOREIGN: Node = Node::Num(Rational::ZERO);

impl Default for ExprPool {
    fn default() -> Self {
        ExprPool::new()
    }
}

impl ExprPool {
    /// An empty pool with an empty symbol table.
    pub fn new() -> ExprPool {
        ExprPool {
            nodes: Vec::with_capacity(INITIAL_NODES),
            heights: Vec::with_capacity(INITIAL_NODES),
            symbol_masks: Vec::with_capacity(INITIAL_NODES),
            index: FxHashMap::with_capacity_and_hasher(INITIAL_NODES, Default::default()),
            symbols: SymbolTable::new(),
            definitions: FxHashMap::default(),
            derivatives: FxHashMap::default(),
            trig_images: FxHashMap::default(),
            expansions: Default::default(),
            small_ints: [None; 4],
            splits: FxHashMap::default(),
            tables: Vec::new(),
            inputs: Vec::new(),
        }
    }

    /// The symbol table.
    pub fn symbols(&self) -> &SymbolTable {
        &self.symbols
    }

    /// The symbol table, to declare symbols.
    pub fn symbols_mut(&mut self) -> &mut SymbolTable {
        &mut self.symbols
    }

    /// The node behind `id` (a zero constant for an id of another pool).
    pub fn node(&self, id: Id) -> &Node {
        self.nodes.get(id.index()).unwrap_or(&FOREIGN)
    }

    /// Number of distinct nodes stored.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// The height of `e`'s tree: 0 for a leaf, else 1 + the largest child height.
    pub fn height(&self, e: Id) -> u32 {
        self.heights.get(e.index()).copied().unwrap_or(0)
    }

    /// The filter of the symbols `e` depends on (see [`symbol_bit`]): 0 for a constant.
    pub(crate) fn symbol_mask(&self, e: Id) -> u64 {
        self.symbol_masks.get(e.index()).copied().unwrap_or(0)
    }

    /// Every id of the pool, ascending (children before parents).
    pub fn ids(&self) -> impl Iterator<Item = Id> {
        (0..self.nodes.len() as u32).map(Id)
    }

    /// Whether no node is stored yet.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Stores `node` once. Only the canonical constructors call this.
    pub(crate) fn intern(&mut self, node: Node) -> Id {
        if let Some(&id) = self.index.get(&node) {
            return id;
        }
        // 2^32 nodes would need far more memory than any derivation uses.
        let id = Id(self.nodes.len() as u32);
        let (mut height, mut mask) = (0, 0);
        node.for_each_child(|c| {
            height = height.max(self.height(c).saturating_add(1));
            mask |= self.symbol_mask(c);
        });
        if let Node::Sym(s) = node {
            // A defined symbol depends on its value's symbols (the value exists already).
            mask = symbol_bit(s) | self.definition(s).map_or(0, |v| self.symbol_mask(v));
        }
        self.heights.push(height);
        self.symbol_masks.push(mask);
        self.nodes.push(node.clone());
        self.index.insert(node, id);
        id
    }

    /// The integer `n`.
    pub fn int(&mut self, n: i64) -> Id {
        let Some(slot) = usize::try_from(n + 1)
            .ok()
            .filter(|i| *i < self.small_ints.len())
        else {
            return self.rational(Rational::from(n));
        };
        if let Some(id) = self.small_ints[slot] {
            return id;
        }
        let id = self.rational(Rational::from(n));
        self.small_ints[slot] = Some(id);
        id
    }

    /// An exact rational constant.
    pub fn rational(&mut self, r: Rational) -> Id {
        self.intern(Node::Num(r))
    }

    /// An inexact constant. `0.0` (either sign) is the exact zero.
    pub fn float(&mut self, x: f64) -> Id {
        self.number(Number::Inexact(x))
    }

    /// A constant from a decimal literal (`9.81`, `1e-3`, `.5`, `6.02E23`): exact when the
    /// value fits a rational of `i128`s, else inexact. `None` if the text is not a literal
    /// or its value is not finite, or underflows a nonzero literal to 0.
    pub fn literal(&mut self, text: &str) -> Option<Id> {
        if let Some(r) = Rational::from_decimal(text) {
            return Some(self.rational(r));
        }
        let valid = text
            .bytes()
            .all(|b| b.is_ascii_digit() || matches!(b, b'.' | b'e' | b'E' | b'+' | b'-'));
        let x: f64 = text.parse().ok().filter(|x: &f64| x.is_finite())?;
        // `1e-400` parses to 0: refuse it rather than silently drop a nonzero constant.
        let mantissa = text.split(['e', 'E']).next().unwrap_or("");
        let underflows = x == 0.0 && mantissa.bytes().any(|b| matches!(b, b'1'..=b'9'));
        (valid && !underflows).then(|| self.float(x))
    }

    pub(crate) fn number(&mut self, n: Number) -> Id {
        match n.normalized() {
            Number::Exact(r) => self.rational(r),
            Number::Inexact(x) => self.intern(Node::Float(x.to_bits())),
        }
    }

    /// The expression that is just the symbol `s`.
    pub fn sym(&mut self, s: Symbol) -> Id {
        self.intern(Node::Sym(s))
    }

    /// Declares a [`SymbolKind::Definition`] `name` whose value is `value`: derivatives look
    /// through it, evaluation evaluates it, [`inline_definitions`](Self::inline_definitions)
    /// replaces it.
    ///
    /// If `name` is taken, the existing symbol is returned and nothing is recorded (so a
    /// definition can never refer to itself); [`try_define`](Self::try_define) reports it.
    pub fn define(&mut self, name: &str, value: Id) -> Symbol {
        match self.try_define(name, value) {
            Ok(s) | Err(s) => s,
        }
    }

    /// Like [`define`](Self::define), but `Err(existing)` if the name is taken.
    pub fn try_define(&mut self, name: &str, value: Id) -> Result<Symbol, Symbol> {
        let s = self.symbols.try_add(name, SymbolKind::Definition)?;
        // `value` exists already and `Sym(s)` cannot, so the value's id is the smaller one.
        self.definitions.insert(s, value);
        self.sym(s);
        Ok(s)
    }

    /// The value of a defined symbol.
    pub fn definition(&self, s: Symbol) -> Option<Id> {
        self.definitions.get(&s).copied()
    }

    /// Every symbol that carries a value, in no particular order.
    pub(crate) fn defined_symbols(&self) -> impl Iterator<Item = Symbol> + '_ {
        self.definitions.keys().copied()
    }

    /// The value behind a `Sym` node of a defined symbol.
    pub(crate) fn definition_of_node(&self, id: Id) -> Option<Id> {
        match self.node(id) {
            Node::Sym(s) => self.definition(*s),
            _ => None,
        }
    }

    /// Whether `e` is the constant zero.
    pub fn is_zero(&self, e: Id) -> bool {
        self.node(e).number().is_some_and(Number::is_zero)
    }

    /// Whether `e` is the constant one.
    pub fn is_one(&self, e: Id) -> bool {
        self.node(e).number().is_some_and(Number::is_one)
    }

    /// The exact value of a rational constant.
    pub fn as_rational(&self, e: Id) -> Option<Rational> {
        match self.node(e) {
            Node::Num(r) => Some(*r),
            _ => None,
        }
    }

    /// The value of any constant, exact or not.
    pub fn as_f64(&self, e: Id) -> Option<f64> {
        self.node(e).number().map(Number::to_f64)
    }

    /// The symbol, if `e` is a bare symbol.
    pub fn as_symbol(&self, e: Id) -> Option<Symbol> {
        match self.node(e) {
            Node::Sym(s) => Some(*s),
            _ => None,
        }
    }

    /// The terms of a sum, or `[e]` — to name an offending term in a diagnostic.
    pub fn terms(&self, e: Id) -> Vec<Id> {
        match self.node(e) {
            Node::Add(terms) => terms.to_vec(),
            _ => vec![e],
        }
    }

    /// The factors of a product (coefficient included), or `[e]`.
    pub fn factors(&self, e: Id) -> Vec<Id> {
        match self.node(e) {
            Node::Mul(factors) => factors.to_vec(),
            _ => vec![e],
        }
    }

    /// Every id reachable from `roots` (looking through definitions if asked), ascending,
    /// hence children before parents. Iterative: no recursion on deep expressions.
    pub(crate) fn reachable(&self, roots: &[Id], through_definitions: bool) -> Vec<Id> {
        self.reachable_where(roots, through_definitions, |_| true)
    }

    /// Like [`reachable`](Self::reachable) through definitions, but only through the nodes
    /// that may depend on a symbol of `symbols` (a union of [`symbol_bit`]s): every other
    /// node is left out with its whole subtree. Every node that contains such a symbol is
    /// in the answer.
    pub(crate) fn reachable_depending_on(&self, roots: &[Id], symbols: u64) -> Vec<Id> {
        self.reachable_where(roots, true, |id| self.symbol_mask(id) & symbols != 0)
    }

    /// The ids reachable from `roots` through nodes that pass `keep`, ascending.
    pub(crate) fn reachable_where(
        &self,
        roots: &[Id],
        through_definitions: bool,
        keep: impl Fn(Id) -> bool,
    ) -> Vec<Id> {
        let roots: Vec<Id> = roots
            .iter()
            .copied()
            .filter(|r| r.index() < self.nodes.len() && keep(*r))
            .collect();
        // Everything reachable from a node has a smaller id (children and definition
        // values come first), so a bitmap up to the largest root holds the visited set:
        // no hashing per node.
        let mut seen = Visited::up_to(roots.iter().copied().max());
        let mut stack: Vec<Id> = Vec::new();
        for r in roots {
            if seen.insert(r) {
                stack.push(r);
            }
        }
        while let Some(id) = stack.pop() {
            let definition = through_definitions
                .then(|| self.definition_of_node(id))
                .flatten();
            let mut visit = |c: Id| {
                if keep(c) && seen.insert(c) {
                    stack.push(c);
                }
            };
            self.node(id).for_each_child(&mut visit);
            definition.into_iter().for_each(visit);
        }
        seen.into_ascending()
    }
}

/// A set of ids below a bound, as a bitmap, that also lists its members in insertion
/// order (for small sets of a large pool, sorting that list is cheaper than scanning
/// the bitmap).
struct Visited {
    bits: Vec<u64>,
    members: Vec<Id>,
}

impl Visited {
    /// An empty set for the ids up to `top` (none if `None`).
    fn up_to(top: Option<Id>) -> Visited {
        let words = top.map_or(0, |t| t.index() / 64 + 1);
        Visited {
            bits: vec![0; words],
            members: Vec::new(),
        }
    }

    /// Adds `id`; false if it was there already. `id` must not exceed the bound.
    fn insert(&mut self, id: Id) -> bool {
        let (word, bit) = (id.index() / 64, 1u64 << (id.index() % 64));
        let Some(w) = self.bits.get_mut(word) else {
            return false;
        };
        let fresh = *w & bit == 0;
        *w |= bit;
        if fresh {
            self.members.push(id);
        }
        fresh
    }

    /// The members, ascending: the bitmap's bits in order when the set fills a fair part
    /// of it, else the sorted list.
    fn into_ascending(mut self) -> Vec<Id> {
        if self.members.len() < self.bits.len() {
            self.members.sort_unstable();
            return self.members;
        }
        let mut out = Vec::with_capacity(self.members.len());
        for (w, &word) in self.bits.iter().enumerate() {
            let mut rest = word;
            while rest != 0 {
                // At most 2^32 nodes, so the id fits a u32.
                out.push(Id((w * 64) as u32 + rest.trailing_zeros()));
                rest &= rest - 1;
            }
        }
        out
    }
}
