//! The hash-consed expression DAG.

use std::collections::HashMap;

use num_rational::BigRational;

use super::node::{Id, Node, Sym};

thread_local! {
    static WORK: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
}

/// Elementary CAS operations done on this thread so far: per node looked up
/// or created, 1 + its number of children (what hashing and comparing it
/// costs); per node visited by a sweep, 1; per polynomial term copied or
/// combined, 1 (see `poly`). A deterministic, machine-independent measure of
/// compile cost: take the difference around a compile. Tests use it to
/// check that compile cost grows near-linearly with the energy's size.
pub fn work_count() -> u64 {
    WORK.with(|w| w.get())
}

/// Add `ops` to [`work_count`].
pub(crate) fn count_work(ops: u64) {
    WORK.with(|w| w.set(w.get().wrapping_add(ops)));
}

thread_local! {
    static LARGEST_NUM: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
}

/// The size in bits (numerator + denominator) of the largest constant added
/// to any graph on this thread since [`reset_largest_number_bits`]. Exact
/// arithmetic on constants costs more than linearly in their size, so an
/// energy written with small constants whose compile builds huge ones (e.g.
/// a rational content lcm(1…n)) compiles super-linearly; tests bound it.
pub fn largest_number_bits() -> u64 {
    LARGEST_NUM.with(|m| m.get())
}

/// Restart [`largest_number_bits`] from 0.
pub fn reset_largest_number_bits() {
    LARGEST_NUM.with(|m| m.set(0));
}

/// A hash-consed expression DAG (egg/naga style arena).
///
/// Nodes are stored children-before-parents: every child id is smaller than
/// its parent's id, so a single forward sweep over `nodes()` evaluates any
/// expression. [`Graph::add`] is the only way a node enters the graph, and it
/// returns the existing id for a structurally equal node (hash-consing), so
/// equal canonical expressions share one id.
///
/// Use the smart constructors (`add_terms`, `mul`, `pow`, …, see `cas::build`)
/// rather than `add` directly: they put nodes in canonical form first.
#[derive(Clone, Debug, Default)]
pub struct Graph {
    nodes: Vec<Node>,
    index: HashMap<Node, Id>,
    /// Per node: a conservative bitmask of the symbols it depends on
    /// (bits 0..3: I1..I3, 3..6: σ0..σ2, 6..64: parameters, folded modulo 58).
    masks: Vec<u64>,
    /// Parameter names, by parameter index (for printing).
    params: Vec<String>,
    /// `add_content` of each sum asked so far (a pure function of the node:
    /// recomputing it would rebuild the same nodes).
    pub(super) contents: HashMap<Id, Option<(BigRational, Id)>>,
}

impl Graph {
    /// An empty graph whose parameters are named `params` (index = position).
    pub fn new(params: Vec<String>) -> Self {
        Graph {
            params,
            ..Default::default()
        }
    }

    /// Insert `node` (whose children must already be in the graph) or return
    /// the id of the equal node already present.
    ///
    /// This does not canonicalise: callers use the smart constructors.
    pub fn add(&mut self, node: Node) -> Id {
        count_work(1 + node.children().len() as u64);
        if let Some(&id) = self.index.get(&node) {
            return id;
        }
        let id = Id(u32::try_from(self.nodes.len()).expect("expression graph exceeds 2^32 nodes"));
        debug_assert!(
            node.children().iter().all(|c| *c < id),
            "children before parents"
        );
        let mask = match &node {
            Node::Num(r) => {
                let bits = r.numer().bits() + r.denom().bits();
                LARGEST_NUM.with(|m| m.set(m.get().max(bits)));
                0
            }
            Node::Sym(s) => sym_mask(*s),
            n => n
                .children()
                .iter()
                .fold(0, |m, c| m | self.masks[c.index()]),
        };
        self.nodes.push(node.clone());
        self.masks.push(mask);
        self.index.insert(node, id);
        id
    }

    /// The node behind `id`.
    #[inline]
    pub fn get(&self, id: Id) -> &Node {
        &self.nodes[id.index()]
    }

    /// All nodes, children before parents.
    pub fn nodes(&self) -> &[Node] {
        &self.nodes
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// True when the graph holds no node.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Parameter names by index.
    pub fn param_names(&self) -> &[String] {
        &self.params
    }

    /// The node id of `sym`.
    pub fn sym(&mut self, sym: Sym) -> Id {
        self.add(Node::Sym(sym))
    }

    /// The node id of an exact rational constant.
    pub fn num(&mut self, value: BigRational) -> Id {
        self.add(Node::Num(value))
    }

    /// The node id of an integer constant.
    pub fn int(&mut self, value: i64) -> Id {
        self.num(BigRational::from_integer(value.into()))
    }

    /// The constant behind `id`, if it is one.
    pub fn as_num(&self, id: Id) -> Option<&BigRational> {
        match self.get(id) {
            Node::Num(r) => Some(r),
            _ => None,
        }
    }

    /// Whether `id` may depend on `sym` (conservative: `false` is exact,
    /// `true` may be a false positive only for parameters beyond index 54).
    pub fn may_depend(&self, id: Id, sym: Sym) -> bool {
        self.masks[id.index()] & sym_mask(sym) != 0
    }

    /// Whether `id` may depend on any singular value σk.
    pub fn uses_sigma(&self, id: Id) -> bool {
        self.masks[id.index()] & 0b111_000 != 0
    }

    /// Whether `id` may depend on any of I1, I2, I3.
    pub fn uses_invariants(&self, id: Id) -> bool {
        self.masks[id.index()] & 0b111 != 0
    }

    /// Whether `id` may depend on a fibre symbol (I4, I5, sign(I4)).
    pub fn uses_fibre(&self, id: Id) -> bool {
        self.masks[id.index()] & 0b111_000_000 != 0
    }

    /// Whether `id` is a constant expression (no symbol at all).
    pub fn is_constant(&self, id: Id) -> bool {
        self.masks[id.index()] == 0
    }

    /// The ids reachable from `roots`, in increasing (topological) order.
    ///
    /// O(R log R) for R reached nodes, not O(size of the graph): many small
    /// sweeps over one big graph stay linear overall.
    pub fn reachable(&self, roots: &[Id]) -> Vec<Id> {
        self.reachable_except(roots, |_| false)
    }

    /// The ids reachable from `roots` without passing through a node for
    /// which `stop` holds (such nodes are neither returned nor entered), in
    /// increasing (topological) order.
    pub fn reachable_except(&self, roots: &[Id], stop: impl Fn(Id) -> bool) -> Vec<Id> {
        // Zeroed allocation: untouched pages of a big graph cost nothing.
        let mut seen = vec![false; self.nodes.len()];
        let mut out: Vec<Id> = Vec::new();
        let mut stack: Vec<Id> = roots.to_vec();
        while let Some(id) = stack.pop() {
            if std::mem::replace(&mut seen[id.index()], true) || stop(id) {
                continue;
            }
            out.push(id);
            stack.extend_from_slice(self.get(id).children());
        }
        count_work(out.len() as u64);
        out.sort_unstable();
        out
    }
}

fn sym_mask(sym: Sym) -> u64 {
    match sym {
        Sym::I1 => 1,
        Sym::I2 => 2,
        Sym::I3 => 4,
        Sym::Sigma(k) => 8 << (k % 3),
        Sym::I4 => 64,
        Sym::I5 => 128,
        Sym::SignI4 => 256,
        Sym::Param(k) => 512 << (k % 55),
    }
}
