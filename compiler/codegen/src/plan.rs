//! Straight-line code for a set of expression roots: constant folding, common
//! subexpression elimination, readable names, lazily evaluated branches.
//!
//! Given the roots a function must compute, each tagged with the [`Region`]
//! where it is needed, the plan
//!
//! 1. walks the DAG from the roots, folding every constant subexpression
//!    (no symbol below it) to one `f64` literal;
//! 2. assigns every node a region: [`Region::Psi`] if Ψ needs it (computed
//!    before the domain check), [`Region::Main`] if it is needed
//!    unconditionally afterwards, and the set of branches needing it if
//!    only sides of guarded `if`s do (so the limit form of a divided
//!    difference is only computed near the singularity; a value several
//!    branches need is computed in each of them);
//! 3. binds a node to a `let` when it is a root, used more than once in its
//!    region (each shared node is computed once), or the base of a power
//!    that is expanded into repeated products; every other node is inlined
//!    into its single user. Products of all σ, sums of all σ and sums of all
//!    σ² read the invariants I3, I1 and I2 instead, and two bindings that
//!    render to the same code are merged;
//! 4. names the bindings: the root's name, a hint (`psi_i2` for ∂Ψ/∂I2), a
//!    structural name (`inv_i3`, `s1_plus_s2`, `log_i3`, `i2_sq`) or `t{n}`.

use std::collections::{BTreeSet, HashMap, HashSet};

use ecc_dsl::cas::{Env, eval};
use ecc_dsl::{Graph, Id, Node, Sym};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive};
use proc_macro2::TokenStream;
use quote::{format_ident, quote};

use crate::render::Ex;

/// Where a root value is needed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub(crate) enum Region {
    /// Needed for Ψ itself (computed before the domain check).
    Psi,
    /// Needed unconditionally after the domain check.
    Main,
    /// Needed by one side of one guarded `if` only.
    Branch(u32),
}

/// Where a node is computed: the join of its users' places.
#[derive(Clone, Debug, PartialEq, Eq)]
enum Place {
    Psi,
    Main,
    /// Inside each of these branches.
    Branches(BTreeSet<u32>),
}

impl Place {
    fn of(r: Region) -> Place {
        match r {
            Region::Psi => Place::Psi,
            Region::Main => Place::Main,
            Region::Branch(b) => Place::Branches(BTreeSet::from([b])),
        }
    }

    fn join(&self, other: &Place) -> Place {
        match (self, other) {
            (Place::Psi, _) | (_, Place::Psi) => Place::Psi,
            (Place::Main, _) | (_, Place::Main) => Place::Main,
            (Place::Branches(a), Place::Branches(b)) => {
                Place::Branches(a.union(b).copied().collect())
            }
        }
    }

    fn contains(&self, r: Region) -> bool {
        match (self, r) {
            (Place::Psi, Region::Psi) | (Place::Main, Region::Main) => true,
            (Place::Branches(s), Region::Branch(b)) => s.contains(&b),
            _ => false,
        }
    }
}

/// Join `place` into the entry of `id`.
fn join_into(map: &mut HashMap<Id, Place>, id: Id, place: &Place) {
    let e = map.entry(id).or_insert_with(|| place.clone());
    *e = e.join(place);
}

/// A value the function must produce.
#[derive(Clone, Debug)]
pub(crate) struct Root {
    pub id: Id,
    pub region: Region,
    /// The name of its `let` (the first root naming a node wins).
    pub name: String,
    /// Whether the root gets a `let` of its own (false for the tail value of
    /// a branch block, which is inlined unless shared).
    pub bind: bool,
}

/// The code plan of one function.
pub(crate) struct Plan<'g> {
    g: &'g Graph,
    /// Composite nodes that are evaluated (not folded), ascending.
    active: Vec<Id>,
    place: HashMap<Id, Place>,
    bound: HashSet<Id>,
    /// Nodes that other evaluated nodes read.
    read_by_others: HashSet<Id>,
    /// Composite nodes equal to an invariant (Π σ = I3, Σ σ = I1).
    as_leaf: HashMap<Id, Sym>,
    /// Bound nodes whose code equals an earlier binding's.
    alias: HashMap<Id, Id>,
    names: HashMap<Id, String>,
    consts: HashMap<Id, f64>,
    leaves: BTreeSet<Sym>,
    leaf_names: HashMap<Sym, String>,
    /// Bound positive powers by (base, exponent), for reuse.
    pows: HashMap<(Id, BigRational), Id>,
    /// Final names of the `t{n}` bindings, renumbered in emission order.
    rename: HashMap<String, String>,
    /// The defining expression of each bound node.
    defs: HashMap<Id, Ex>,
    /// Bound nodes in an order where every node follows what it reads.
    order: Vec<Id>,
}

impl<'g> Plan<'g> {
    /// Plan the evaluation of `roots` in `g`.
    ///
    /// `leaf_name` names the symbols; `hints` proposes names for particular
    /// nodes; `taken` lists names that must not be reused (the leaves'
    /// names are added automatically).
    pub(crate) fn new(
        g: &'g Graph,
        dim: u8,
        roots: &[Root],
        hints: &HashMap<Id, String>,
        leaf_name: &dyn Fn(Sym) -> String,
        taken: &[&str],
    ) -> Plan<'g> {
        let mut plan = Plan {
            g,
            active: Vec::new(),
            place: HashMap::new(),
            bound: HashSet::new(),
            read_by_others: HashSet::new(),
            as_leaf: HashMap::new(),
            alias: HashMap::new(),
            names: HashMap::new(),
            consts: HashMap::new(),
            leaves: BTreeSet::new(),
            leaf_names: HashMap::new(),
            pows: HashMap::new(),
            rename: HashMap::new(),
            defs: HashMap::new(),
            order: Vec::new(),
        };
        plan.collect(dim, roots);
        plan.bind(roots);
        plan.name(roots, hints, leaf_name, taken);
        plan.define_and_order(roots);
        plan
    }

    /// Walk from the roots, folding constants and collecting leaves.
    fn collect(&mut self, dim: u8, roots: &[Root]) {
        let g = self.g;
        let mut seen: HashSet<Id> = HashSet::new();
        let mut stack: Vec<Id> = roots.iter().map(|r| r.id).collect();
        let env = Env::new(dim, &[], &[]);
        while let Some(id) = stack.pop() {
            if !seen.insert(id) {
                continue;
            }
            match g.get(id) {
                Node::Num(r) => {
                    self.consts.insert(id, r.to_f64().unwrap_or(f64::NAN));
                }
                Node::Sym(s) => {
                    self.leaves.insert(*s);
                }
                _ if g.is_constant(id) => {
                    self.consts.insert(id, eval(g, id, &env));
                }
                node if invariant_of(g, node, dim).is_some() => {
                    let s = invariant_of(g, node, dim).unwrap_or(Sym::I3);
                    self.as_leaf.insert(id, s);
                    self.leaves.insert(s);
                }
                node => {
                    self.active.push(id);
                    for &c in operands(g, node) {
                        stack.push(c);
                    }
                }
            }
        }
        self.active.sort();
    }

    /// Decide which composite nodes get a `let`: roots, bases of expanded
    /// powers, and nodes with more than one user in one place.
    fn bind(&mut self, roots: &[Root]) {
        let g = self.g;
        // Places on the DAG itself (users before children: descending ids).
        let mut place: HashMap<Id, Place> = HashMap::new();
        let mut forced: HashSet<Id> = HashSet::new();
        let mut root_uses: HashMap<Id, Vec<Place>> = HashMap::new();
        for r in roots {
            join_into(&mut place, r.id, &Place::of(r.region));
            if r.bind {
                forced.insert(r.id);
            } else {
                root_uses.entry(r.id).or_default().push(Place::of(r.region));
            }
        }
        let mut users: HashMap<Id, Vec<Id>> = HashMap::new();
        for &id in self.active.iter().rev() {
            let node = g.get(id);
            let p = place.get(&id).cloned().unwrap_or(Place::Main);
            for c in self.operands(node) {
                join_into(&mut place, c, &p);
                users.entry(c).or_default().push(id);
                self.read_by_others.insert(c);
            }
            if let Node::Pow([b, e]) = node
                && g.as_num(*e).is_some_and(repeats_base)
            {
                forced.insert(*b);
            }
        }
        for &id in &self.active {
            let mut user_places: Vec<Place> = users
                .get(&id)
                .map(|us| {
                    us.iter()
                        .map(|u| place.get(u).cloned().unwrap_or(Place::Main))
                        .collect()
                })
                .unwrap_or_default();
            user_places.extend(root_uses.get(&id).cloned().unwrap_or_default());
            let shared = match place.get(&id) {
                Some(Place::Branches(set)) => set.iter().any(|&b| {
                    user_places
                        .iter()
                        .filter(|p| p.contains(Region::Branch(b)))
                        .count()
                        > 1
                }),
                _ => user_places.len() > 1,
            };
            // A negation of a name is cheaper inlined (sums subtract it).
            let cheap = self.negated_of(id).is_some_and(|x| {
                self.bound.contains(&x)
                    || self.as_leaf.contains_key(&x)
                    || matches!(g.get(x), Node::Sym(_))
            });
            if forced.contains(&id) || (shared && !cheap) {
                self.bound.insert(id);
                if let Node::Pow([b, e]) = g.get(id)
                    && let Some(r) = g.as_num(*e).filter(|r| r.is_positive())
                {
                    self.pows.insert((*b, r.clone()), id);
                }
            }
        }
    }

    /// The children of `node` that code reads (not folded exponents, not
    /// nodes read as invariants).
    fn operands(&self, node: &Node) -> Vec<Id> {
        operands(self.g, node)
            .iter()
            .copied()
            .filter(|c| !self.consts.contains_key(c))
            .collect()
    }

    fn name(
        &mut self,
        roots: &[Root],
        hints: &HashMap<Id, String>,
        leaf_name: &dyn Fn(Sym) -> String,
        taken: &[&str],
    ) {
        let mut used: HashSet<String> = taken.iter().map(|s| s.to_string()).collect();
        for &s in &self.leaves {
            let n = leaf_name(s);
            used.insert(n.clone());
            self.leaf_names.insert(s, n);
        }
        // Root names are claimed first, in root order: Ψ always, other roots
        // only when the value is theirs alone (a value shared by several
        // slots or read by other values gets a name of its own below).
        let mut root_count: HashMap<Id, usize> = HashMap::new();
        for r in roots {
            *root_count.entry(r.id).or_default() += 1;
        }
        for r in roots {
            let own = root_count[&r.id] == 1 && !self.read_by_others.contains(&r.id);
            if (own || r.region == Region::Psi)
                && self.bound.contains(&r.id)
                && !self.names.contains_key(&r.id)
            {
                let n = unique(&r.name, &mut used);
                self.names.insert(r.id, n);
            }
        }
        let mut counter = 0;
        for &id in &self.active.clone() {
            if !self.bound.contains(&id) || self.names.contains_key(&id) {
                continue;
            }
            let base = hints
                .get(&id)
                .cloned()
                .or_else(|| self.derived_name(id))
                .unwrap_or_else(|| {
                    counter += 1;
                    format!("t{counter}")
                });
            let n = unique(&base, &mut used);
            self.names.insert(id, n);
        }
    }

    /// Render every bound node once (merging bindings whose code is
    /// identical), record what it reads, order the bindings so that each
    /// follows what it reads, and place every binding where its readers are.
    fn define_and_order(&mut self, roots: &[Root]) {
        let mut reads: HashMap<Id, Vec<Id>> = HashMap::new();
        let mut seen: HashMap<String, Id> = HashMap::new();
        let mut bound: Vec<Id> = Vec::new();
        for id in self.active.clone() {
            if !self.bound.contains(&id) {
                continue;
            }
            let mut refs = Vec::new();
            let ex = self.expr(id, &mut refs);
            let key = ex.tokens().to_string();
            if let Some(&first) = seen.get(&key) {
                self.alias.insert(id, first);
                continue;
            }
            seen.insert(key, id);
            self.defs.insert(id, ex);
            reads.insert(id, refs);
            bound.push(id);
        }
        // A binding may read a node merged into an equal one after it was
        // read (a bound power reused by a later power): read the survivor.
        for refs in reads.values_mut() {
            for r in refs.iter_mut() {
                *r = self.alias.get(r).copied().unwrap_or(*r);
            }
        }
        // Depth-first post-order: dependencies first.
        let mut state: HashMap<Id, u8> = HashMap::new();
        let mut order = Vec::with_capacity(bound.len());
        for &id in &bound {
            visit(id, &reads, &mut state, &mut order);
        }
        // Places: what each root reads, then readers before what they read.
        for r in roots {
            let mut refs = Vec::new();
            let _ = self.operand(r.id, &mut refs);
            for x in refs {
                let x = self.alias.get(&x).copied().unwrap_or(x);
                join_into(&mut self.place, x, &Place::of(r.region));
            }
        }
        for &id in order.iter().rev() {
            let Some(p) = self.place.get(&id).cloned() else {
                continue;
            };
            for &x in &reads[&id] {
                join_into(&mut self.place, x, &p);
            }
        }
        // Renumber the `t{n}` names in emission order (merged bindings left gaps).
        let mut k = 0;
        for &id in &order {
            let n = &self.names[&id];
            if is_fallback(n) {
                k += 1;
                self.rename.insert(n.clone(), format!("t{k}"));
            }
        }
        // Text that names a merged node refers to the survivor's final name.
        let merged: Vec<(String, String)> = self
            .alias
            .iter()
            .filter_map(|(p, first)| {
                let np = self.names.get(p)?;
                let nf = self.names.get(first)?;
                (np != nf).then(|| (np.clone(), self.final_name(nf).to_string()))
            })
            .collect();
        self.rename.extend(merged);
        self.order = order;
    }

    /// A short descriptive name from the node's structure, if it has one.
    fn derived_name(&self, id: Id) -> Option<String> {
        let g = self.g;
        let name = match g.get(id) {
            Node::Pow([b, e]) => {
                let bn = self.short(*b)?;
                let r = g.as_num(*e)?;
                if r.is_integer() {
                    match r.to_i64()? {
                        -1 => format!("inv_{bn}"),
                        2 => format!("{bn}_sq"),
                        3 => format!("{bn}_cu"),
                        n if n > 0 => format!("{bn}_pow{n}"),
                        n => format!("inv_{bn}_pow{}", -n),
                    }
                } else if *r == half() {
                    format!("sqrt_{bn}")
                } else if *r == -half() {
                    format!("inv_sqrt_{bn}")
                } else if *r == BigRational::new(1.into(), 3.into()) {
                    format!("cbrt_{bn}")
                } else {
                    return None;
                }
            }
            Node::Log(x) => format!("log_{}", self.short(*x)?),
            Node::Exp(x) => format!("exp_{}", self.short(*x)?),
            Node::Add(c) if c.len() == 2 => {
                let (a, b) = (c[0], c[1]);
                if let Some(k) = self.small_int(a) {
                    let bn = self.short(b)?;
                    if k < 0 {
                        format!("{bn}_minus_{}", -k)
                    } else {
                        format!("{bn}_plus_{k}")
                    }
                } else if let Some(y) = self.negated_of(b) {
                    format!("{}_minus_{}", self.short(a)?, self.short(y)?)
                } else if let Some(y) = self.negated_of(a) {
                    format!("{}_minus_{}", self.short(b)?, self.short(y)?)
                } else {
                    format!("{}_plus_{}", self.short(a)?, self.short(b)?)
                }
            }
            Node::Mul(c) if c.len() == 2 => {
                let (a, b) = (c[0], c[1]);
                if let Some(k) = self.small_int(a) {
                    let bn = self.short(b)?;
                    if k == -1 {
                        format!("neg_{bn}")
                    } else if k < 0 {
                        format!("{bn}_x_neg{}", -k)
                    } else {
                        format!("{bn}_x{k}")
                    }
                } else {
                    format!("{}_{}", self.short(a)?, self.short(b)?)
                }
            }
            _ => return None,
        };
        (name.len() <= 20).then_some(name)
    }

    /// The name of `id` for use inside a derived name, if short enough.
    fn short(&self, id: Id) -> Option<String> {
        let n = match self.g.get(id) {
            Node::Sym(s) => self.leaf_names.get(s).cloned()?,
            _ => match self.names.get(&id) {
                Some(n) => n.clone(),
                None => self.derived_name(id)?,
            },
        };
        (n.len() <= 10 && !is_fallback(&n)).then_some(n)
    }

    fn small_int(&self, id: Id) -> Option<i64> {
        let r = self.g.as_num(id)?;
        if !r.is_integer() {
            return None;
        }
        r.to_i64().filter(|k| k.abs() <= 99)
    }

    /// `y` when `id` is `-1·y`.
    fn negated_of(&self, id: Id) -> Option<Id> {
        match self.g.get(id) {
            Node::Mul(c) if c.len() == 2 && self.small_int(c[0]) == Some(-1) => Some(c[1]),
            _ => None,
        }
    }

    /// Whether `id` has a `let` of its own.
    pub(crate) fn is_bound(&self, id: Id) -> bool {
        self.names.contains_key(&id)
    }

    /// The symbols the planned code reads.
    pub(crate) fn leaves(&self) -> &BTreeSet<Sym> {
        &self.leaves
    }

    /// `let` statements of every binding in `region`, in dependency order.
    pub(crate) fn lets(&self, region: Region) -> TokenStream {
        let mut out = TokenStream::new();
        for &id in &self.order {
            if self.place.get(&id).is_some_and(|p| p.contains(region)) {
                let name = format_ident!("{}", self.final_name(&self.names[&id]));
                let value = self.defs[&id].clone().renamed(&self.rename).tokens();
                out.extend(quote!(let #name = #value;));
            }
        }
        out
    }

    /// The bindings of `region` as (name, defining expression), in the order
    /// of [`Plan::lets`] (for back ends other than Rust tokens, e.g. C++).
    pub(crate) fn bindings(&self, region: Region) -> Vec<(String, Ex)> {
        self.order
            .iter()
            .filter(|id| self.place.get(id).is_some_and(|p| p.contains(region)))
            .map(|id| {
                let name = self.final_name(&self.names[id]).to_string();
                (name, self.defs[id].clone().renamed(&self.rename))
            })
            .collect()
    }

    /// How generated code refers to the value of `id` (a name, a literal,
    /// or the inlined expression of an unbound node).
    pub(crate) fn value(&self, id: Id) -> TokenStream {
        self.value_ex(id).tokens()
    }

    /// [`Plan::value`] as an expression, for further composition.
    pub(crate) fn value_ex(&self, id: Id) -> Ex {
        self.operand(id, &mut Vec::new()).renamed(&self.rename)
    }

    fn final_name<'a>(&'a self, n: &'a str) -> &'a str {
        self.rename.get(n).map_or(n, String::as_str)
    }

    /// The value of `id` as an operand; bound nodes read are pushed to `refs`.
    fn operand(&self, id: Id, refs: &mut Vec<Id>) -> Ex {
        let id = self.alias.get(&id).copied().unwrap_or(id);
        if let Some(&v) = self.consts.get(&id) {
            return Ex::Lit(v);
        }
        if let Some(s) = self.as_leaf.get(&id) {
            return Ex::Var(self.leaf_names[s].clone());
        }
        match self.g.get(id) {
            Node::Sym(s) => Ex::Var(self.leaf_names[s].clone()),
            _ => match self.names.get(&id) {
                Some(n) => {
                    refs.push(id);
                    Ex::Var(n.clone())
                }
                None => self.expr(id, refs),
            },
        }
    }

    /// The defining expression of a composite node.
    fn expr(&self, id: Id, refs: &mut Vec<Id>) -> Ex {
        let g = self.g;
        match g.get(id) {
            Node::Add(children) => {
                let mut constant = 0.0;
                let mut terms = Vec::new();
                for &c in children {
                    match self.consts.get(&c) {
                        Some(v) => constant += v,
                        None => terms.push((false, self.operand(c, refs))),
                    }
                }
                if constant != 0.0 || terms.is_empty() {
                    terms.push((false, Ex::Lit(constant)));
                }
                Ex::Sum(terms)
            }
            Node::Mul(children) => {
                let mut coef = 1.0;
                let (mut num, mut den) = (Vec::new(), Vec::new());
                for &c in children {
                    if let Some(v) = self.consts.get(&c) {
                        coef *= v;
                    } else if self.names.contains_key(&c) || self.as_leaf.contains_key(&c) {
                        num.push(self.operand(c, refs));
                    } else if let Node::Pow([b, e]) = g.get(c) {
                        let (n, d) = self.pow_parts(c, *b, *e, refs);
                        num.extend(n);
                        den.extend(d);
                    } else {
                        num.push(self.operand(c, refs));
                    }
                }
                product(coef, num, den)
            }
            Node::Pow([b, e]) => {
                let (num, den) = self.pow_parts(id, *b, *e, refs);
                product(1.0, num, den)
            }
            Node::Log(x) => Ex::Method(Box::new(self.operand(*x, refs)), "ln", vec![]),
            Node::Exp(x) => Ex::Method(Box::new(self.operand(*x, refs)), "exp", vec![]),
            Node::Num(_) | Node::Sym(_) => self.operand(id, refs),
        }
    }

    /// Numerator and denominator factors of the node `this` = `b^e`.
    fn pow_parts(&self, this: Id, b: Id, e: Id, refs: &mut Vec<Id>) -> (Vec<Ex>, Vec<Ex>) {
        let base = self.operand(b, refs);
        let Some(r) = self.g.as_num(e) else {
            let ex = self.operand(e, refs);
            return (vec![Ex::Method(Box::new(base), "powf", vec![ex])], vec![]);
        };
        let neg = r.is_negative();
        let a = r.abs();
        let numer = a.numer().to_u64();
        let denom = a.denom().to_u64();
        let factors = match (numer, denom) {
            (Some(n), Some(1)) if n <= 64 => self.power(this, b, &base, n, refs),
            (Some(n), Some(2)) if n <= 65 => {
                let mut f = self.power(this, b, &base, n / 2, refs);
                let root = self
                    .bound_power(this, b, half(), refs)
                    .unwrap_or_else(|| Ex::Method(Box::new(base.clone()), "sqrt", vec![]));
                f.push(root);
                f
            }
            (Some(n), Some(3)) if n <= 64 => {
                let c = Ex::Method(Box::new(base.clone()), "cbrt", vec![]);
                if n == 1 {
                    vec![c]
                } else {
                    vec![Ex::Method(Box::new(c), "powi", vec![Ex::Int(n as i32)])]
                }
            }
            (Some(n), Some(q)) if q % 2 == 1 => {
                // Real odd roots of negative bases: |b|^(n/q) with b's sign when n is odd.
                let abs = Ex::Method(Box::new(base.clone()), "abs", vec![]);
                let p = Ex::Method(Box::new(abs), "powf", vec![Ex::Lit(n as f64 / q as f64)]);
                if n % 2 == 1 {
                    vec![Ex::Method(Box::new(p), "copysign", vec![base.clone()])]
                } else {
                    vec![p]
                }
            }
            _ => {
                let v = r.to_f64().unwrap_or(f64::NAN);
                return (
                    vec![Ex::Method(Box::new(base), "powf", vec![Ex::Lit(v)])],
                    vec![],
                );
            }
        };
        if neg {
            (vec![], factors)
        } else {
            (factors, vec![])
        }
    }

    /// The name of the bound node `b^r` other than `this`, if there is one.
    fn bound_power(&self, this: Id, b: Id, r: BigRational, refs: &mut Vec<Id>) -> Option<Ex> {
        let &p = self.pows.get(&(b, r))?;
        if p == this {
            return None;
        }
        refs.push(p);
        Some(Ex::Var(self.names[&p].clone()))
    }

    /// `b^n` (n ≥ 0) as product factors, reusing bound powers of `b` other
    /// than `this`: b, b·b, b·b·b, then by squaring, e.g.
    /// b⁴ = (b·b)·(b·b) or `b_sq * b_sq`, b⁵ = b⁴·b.
    fn power(&self, this: Id, b: Id, base: &Ex, n: u64, refs: &mut Vec<Id>) -> Vec<Ex> {
        if let Some(v) = self.bound_power(this, b, BigRational::from_integer(n.into()), refs) {
            return vec![v];
        }
        match n {
            0 => vec![],
            1 => vec![base.clone()],
            _ if n.is_multiple_of(2) => {
                let h = self.power(this, b, base, n / 2, refs);
                let hx = if h.len() == 1 {
                    h[0].clone()
                } else {
                    product(1.0, h, vec![])
                };
                vec![hx.clone(), hx]
            }
            _ => {
                let mut f = self.power(this, b, base, n - 1, refs);
                f.push(base.clone());
                f
            }
        }
    }
}

/// Post-order depth-first visit (0 = new, 1 = in progress, 2 = done); a
/// cycle (impossible by construction) is broken rather than looped on.
fn visit(id: Id, reads: &HashMap<Id, Vec<Id>>, state: &mut HashMap<Id, u8>, order: &mut Vec<Id>) {
    if state.get(&id).copied().unwrap_or(0) != 0 {
        return;
    }
    state.insert(id, 1);
    if let Some(rs) = reads.get(&id) {
        for &r in rs {
            if r != id {
                visit(r, reads, state, order);
            }
        }
    }
    state.insert(id, 2);
    order.push(id);
}

/// I3 for a product of all σ, I1 for a sum of all σ, I2 for a sum of all
/// σ² (in dimension `dim`): the same values, computed the same way.
fn invariant_of(g: &Graph, node: &Node, dim: u8) -> Option<Sym> {
    let all_sigma = |c: &[Id]| {
        c.len() == dim as usize
            && (0..dim).all(|k| {
                c.iter()
                    .any(|&x| matches!(g.get(x), Node::Sym(Sym::Sigma(j)) if *j == k))
            })
    };
    let all_squares = |c: &[Id]| {
        c.len() == dim as usize
            && (0..dim).all(|k| {
                c.iter().any(|&x| match g.get(x) {
                    Node::Pow([b, e]) => {
                        matches!(g.get(*b), Node::Sym(Sym::Sigma(j)) if *j == k) && g.is_int(*e, 2)
                    }
                    _ => false,
                })
            })
    };
    match node {
        Node::Mul(c) if all_sigma(c) => Some(Sym::I3),
        Node::Add(c) if all_sigma(c) => Some(Sym::I1),
        Node::Add(c) if all_squares(c) => Some(Sym::I2),
        _ => None,
    }
}

/// The children that are evaluated as operands (the exponent of a rational
/// power is folded into the code, not evaluated).
fn operands<'a>(g: &Graph, node: &'a Node) -> &'a [Id] {
    match node {
        Node::Pow([b, e]) if g.as_num(*e).is_some() => std::slice::from_ref(b),
        n => n.children(),
    }
}

/// Whether `b^r` is expanded with its base appearing more than once.
fn repeats_base(r: &BigRational) -> bool {
    let a = r.abs();
    (a.is_integer() && a > BigRational::one())
        || (*a.denom() == BigInt::from(2) && a > BigRational::new(1.into(), 2.into()))
}

fn half() -> BigRational {
    BigRational::new(1.into(), 2.into())
}

/// `coef · Π num / Π den` as one expression.
fn product(coef: f64, mut num: Vec<Ex>, den: Vec<Ex>) -> Ex {
    if coef == 0.0 {
        return Ex::Lit(0.0);
    }
    let neg = coef < 0.0;
    let c = coef.abs();
    if c != 1.0 {
        num.insert(0, Ex::Lit(c));
    }
    if num.len() == 1 && den.is_empty() && !neg {
        return num.pop().unwrap_or(Ex::Lit(1.0));
    }
    if num.is_empty() && den.is_empty() {
        return Ex::Lit(coef);
    }
    Ex::Prod { neg, num, den }
}

/// `t{n}`: a name that says nothing and is not worth composing.
fn is_fallback(name: &str) -> bool {
    name.strip_prefix('t')
        .is_some_and(|rest| !rest.is_empty() && rest.bytes().all(|b| b.is_ascii_digit()))
}

pub(crate) fn unique(base: &str, used: &mut HashSet<String>) -> String {
    let valid = base.starts_with(|c: char| c.is_ascii_lowercase() || c == '_')
        && base.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_')
        && base != "_";
    let base = if valid { base } else { "v" };
    let mut name = base.to_string();
    let mut k = 2;
    while used.contains(&name) || is_keyword(&name) {
        name = format!("{base}_{k}");
        k += 1;
    }
    used.insert(name.clone());
    name
}

/// Rust keywords (strict and reserved) that cannot be plain identifiers.
pub(crate) fn is_keyword(s: &str) -> bool {
    const KW: &[&str] = &[
        "as", "break", "const", "continue", "crate", "else", "enum", "extern", "false", "fn",
        "for", "if", "impl", "in", "let", "loop", "match", "mod", "move", "mut", "pub", "ref",
        "return", "self", "Self", "static", "struct", "super", "trait", "true", "type", "unsafe",
        "use", "where", "while", "async", "await", "dyn", "abstract", "become", "box", "do",
        "final", "macro", "override", "priv", "typeof", "unsized", "virtual", "yield", "try",
        "gen", "_",
    ];
    KW.contains(&s)
}
