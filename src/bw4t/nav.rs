//! Path planning: Dijkstra on the zone graph (zone centres, undirected neighbour links weighted
//! by centre distance) with deterministic tie-breaking.

use super::world::Zone;
use petgraph::algo::dijkstra;
use petgraph::graph::{NodeIndex, UnGraph};
use petgraph::visit::EdgeRef;

/// Relative tolerance when comparing path lengths for ties.
const TIE_EPS: f64 = 1e-9;

/// The zone graph; node `i` is zone `i`.
#[derive(Clone, Debug, Default)]
pub struct Nav {
    graph: UnGraph<(), f64>,
}

impl Nav {
    /// The graph of `zones` and their neighbour links.
    pub fn new(zones: &[Zone]) -> Nav {
        let mut graph = UnGraph::with_capacity(zones.len(), zones.len() * 2);
        for _ in zones {
            graph.add_node(());
        }
        for (i, z) in zones.iter().enumerate() {
            for &n in z.neighbours.iter().filter(|&&n| n > i) {
                let w = (zones[n].centre() - z.centre()).norm();
                graph.add_edge(NodeIndex::new(i), NodeIndex::new(n), w);
            }
        }
        Nav { graph }
    }

    /// The shortest zone path from `from` to `to` (both included), or `None` when unreachable.
    /// Among equally short paths, each step back from the target takes the predecessor that
    /// comes first in map file order, so the answer never depends on hashing or timing.
    pub fn path(&self, from: usize, to: usize) -> Option<Vec<usize>> {
        let n = self.graph.node_count();
        if from >= n || to >= n {
            return None;
        }
        let (s, t) = (NodeIndex::new(from), NodeIndex::new(to));
        let dist = dijkstra(&self.graph, s, None, |e| *e.weight());
        dist.get(&t)?;
        let mut path = vec![to];
        let mut cur = t;
        while cur != s {
            if path.len() > n {
                return None;
            }
            let dc = dist[&cur];
            let mut best: Option<NodeIndex> = None;
            for e in self.graph.edges(cur) {
                let u = if e.source() == cur {
                    e.target()
                } else {
                    e.source()
                };
                let Some(du) = dist.get(&u) else { continue };
                if *du < dc
                    && (du + e.weight() - dc).abs() <= TIE_EPS * dc.max(1.0)
                    && best.is_none_or(|b| u.index() < b.index())
                {
                    best = Some(u);
                }
            }
            cur = best?;
            path.push(cur.index());
        }
        path.reverse();
        Some(path)
    }
}
