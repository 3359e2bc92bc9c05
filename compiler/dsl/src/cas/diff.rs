//! Symbolic differentiation and substitution.
//!
//! Both sweep the nodes reachable from the root in increasing id order
//! (children before parents), so they never recurse and cannot overflow the
//! stack on deep expressions.
//!
//! Rules (d = ∂/∂x):
//! d(Σ tᵢ) = Σ d tᵢ;  d(Π fᵢ) = Σᵢ d fᵢ Π_{j≠i} fⱼ;
//! d(bᵉ) = e b^(e−1) db when e does not depend on x, else bᵉ (de log b + e db / b);
//! d log u = du / u;  d exp u = exp u · du.

use std::collections::HashMap;

use super::graph::Graph;
use super::node::{Id, Node, Sym};

impl Graph {
    /// ∂`root`/∂`x`, simplified by the smart constructors.
    pub fn diff(&mut self, root: Id, x: Sym) -> Id {
        let order = self.reachable(&[root]);
        let mut d: HashMap<Id, Id> = HashMap::with_capacity(order.len());
        let zero = self.zero();
        for id in order {
            let di = if !self.may_depend(id, x) {
                zero
            } else {
                self.diff_node(id, x, &d)
            };
            d.insert(id, di);
        }
        d[&root]
    }

    fn diff_node(&mut self, id: Id, x: Sym, d: &HashMap<Id, Id>) -> Id {
        match self.get(id).clone() {
            Node::Num(_) => self.zero(),
            Node::Sym(s) => {
                if s == x {
                    self.one()
                } else {
                    self.zero()
                }
            }
            Node::Add(children) => {
                let terms: Vec<Id> = children.iter().map(|c| d[c]).collect();
                self.sum(&terms)
            }
            Node::Mul(children) => {
                let mut terms = Vec::new();
                for (i, c) in children.iter().enumerate() {
                    let dc = d[c];
                    if self.is_int(dc, 0) {
                        continue;
                    }
                    let mut factors: Vec<Id> = children
                        .iter()
                        .enumerate()
                        .filter(|(j, _)| *j != i)
                        .map(|(_, f)| *f)
                        .collect();
                    factors.push(dc);
                    terms.push(self.product(&factors));
                }
                self.sum(&terms)
            }
            Node::Pow([b, e]) => {
                let (db, de) = (d[&b], d[&e]);
                if self.is_int(de, 0) {
                    // e * b^(e-1) * db
                    let m1 = self.int(-1);
                    let em1 = self.sum(&[e, m1]);
                    let p = self.pow(b, em1);
                    self.product(&[e, p, db])
                } else {
                    // b^e * (de * log b + e * db / b)
                    let lb = self.log(b);
                    let t1 = self.product(&[de, lb]);
                    let q = self.div(db, b);
                    let t2 = self.product(&[e, q]);
                    let s = self.sum(&[t1, t2]);
                    self.product(&[id, s])
                }
            }
            Node::Log(u) => self.div(d[&u], u),
            Node::Exp(u) => self.product(&[id, d[&u]]),
        }
    }

    /// Replace symbols by expressions: every `Sym(s)` with `map(s) = Some(e)`
    /// becomes `e`, and the result is re-canonicalised.
    pub fn substitute(&mut self, root: Id, map: &dyn Fn(Sym) -> Option<Id>) -> Id {
        self.substitute_many(&[root], map)[0]
    }

    /// [`Graph::substitute`] on several roots sharing one sweep.
    pub fn substitute_many(&mut self, roots: &[Id], map: &dyn Fn(Sym) -> Option<Id>) -> Vec<Id> {
        let order = self.reachable(roots);
        let mut new: HashMap<Id, Id> = HashMap::with_capacity(order.len());
        for id in order {
            let n = match self.get(id).clone() {
                Node::Sym(s) => map(s).unwrap_or(id),
                Node::Num(_) => id,
                node => {
                    if node.children().iter().all(|c| new[c] == *c) {
                        id
                    } else {
                        self.rebuild(&node, &|c| new[&c])
                    }
                }
            };
            new.insert(id, n);
        }
        roots.iter().map(|r| new[r]).collect()
    }

    /// Build `node`'s operation over mapped children, canonicalising.
    pub(crate) fn rebuild(&mut self, node: &Node, child: &dyn Fn(Id) -> Id) -> Id {
        match node {
            Node::Num(_) | Node::Sym(_) => self.add(node.clone()),
            Node::Add(c) => {
                let c: Vec<Id> = c.iter().map(|&x| child(x)).collect();
                self.sum(&c)
            }
            Node::Mul(c) => {
                let c: Vec<Id> = c.iter().map(|&x| child(x)).collect();
                self.product(&c)
            }
            Node::Pow([b, e]) => self.pow(child(*b), child(*e)),
            Node::Log(x) => self.log(child(*x)),
            Node::Exp(x) => self.exp(child(*x)),
        }
    }

    /// Copy the expressions `roots` into a fresh graph holding only what they
    /// reach (garbage collection). Returns the new graph and the new root ids.
    pub fn extract(&self, roots: &[Id]) -> (Graph, Vec<Id>) {
        let mut g = Graph::new(self.param_names().to_vec());
        let mut map: HashMap<Id, Id> = HashMap::new();
        for id in self.reachable(roots) {
            let node = match self.get(id) {
                Node::Add(c) => Node::Add(c.iter().map(|x| map[x]).collect()),
                Node::Mul(c) => Node::Mul(c.iter().map(|x| map[x]).collect()),
                Node::Pow([b, e]) => Node::Pow([map[b], map[e]]),
                Node::Log(x) => Node::Log(map[x]),
                Node::Exp(x) => Node::Exp(map[x]),
                n => n.clone(),
            };
            // Ids are remapped monotonically, so child order is preserved and
            // the copied nodes stay canonical.
            let nid = g.add(node);
            map.insert(id, nid);
        }
        let new_roots = roots.iter().map(|r| map[r]).collect();
        (g, new_roots)
    }
}
