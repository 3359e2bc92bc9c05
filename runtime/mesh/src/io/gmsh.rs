//! Gmsh `.msh` (ASCII) reader: format versions 2.x, 4.0 and 4.1.
//!
//! Sections other than `$MeshFormat`, `$Nodes` and `$Elements` (e.g.
//! `$PhysicalNames`, `$Entities`, `$NodeData`, or IPC's `$Surface`) are
//! skipped up to their `$End…` line. Node tags may be arbitrary; vertices
//! keep the order in which nodes appear in the file. Points and lines
//! (element types 15, 1, 8) are ignored; 3-node triangles (type 2) and
//! 4-node tets (type 4) are read; any other element type is rejected. When
//! the file has tets, the triangles (boundary / physical faces) are not
//! kept. Binary files are rejected.

use std::collections::HashMap;

use super::text::{Tokens, capacity_hint, shorten};
use crate::error::ParseError;
use crate::types::{AnyMesh, TetMesh, TriMesh};

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Version {
    V2,
    V40,
    V41,
}

/// Node count and name of the Gmsh element types 1..=19.
fn element_type(ty: i64) -> Option<(usize, &'static str)> {
    Some(match ty {
        1 => (2, "2-node line"),
        2 => (3, "3-node triangle"),
        3 => (4, "4-node quadrangle"),
        4 => (4, "4-node tetrahedron"),
        5 => (8, "8-node hexahedron"),
        6 => (6, "6-node prism"),
        7 => (5, "5-node pyramid"),
        8 => (3, "3-node second-order line"),
        9 => (6, "6-node second-order triangle"),
        10 => (9, "9-node second-order quadrangle"),
        11 => (10, "10-node second-order tetrahedron"),
        12 => (27, "27-node second-order hexahedron"),
        13 => (18, "18-node second-order prism"),
        14 => (14, "14-node second-order pyramid"),
        15 => (1, "1-node point"),
        16 => (8, "8-node second-order quadrangle"),
        17 => (20, "20-node second-order hexahedron"),
        18 => (15, "15-node second-order prism"),
        19 => (13, "13-node second-order pyramid"),
        _ => return None,
    })
}

/// Check an element type and return its node count.
fn check_type(ty: i64, line: usize) -> Result<usize, ParseError> {
    match element_type(ty) {
        Some((n, _)) if matches!(ty, 1 | 2 | 4 | 8 | 15) => Ok(n),
        Some((_, name)) => Err(ParseError::line(
            line,
            format!(
                "unsupported element type {ty} ({name}): only 3-node triangles and 4-node tetrahedra are supported"
            ),
        )),
        None => Err(ParseError::line(
            line,
            format!("unknown Gmsh element type {ty}"),
        )),
    }
}

#[derive(Default)]
struct Data {
    positions: Vec<[f64; 3]>,
    tag_to_index: HashMap<usize, usize>,
    tris: Vec<[usize; 3]>,
    tets: Vec<[usize; 4]>,
    saw_nodes: bool,
    saw_elements: bool,
}

impl Data {
    fn add_node(&mut self, tag: usize, p: [f64; 3], line: usize) -> Result<(), ParseError> {
        let index = self.positions.len();
        if self.tag_to_index.insert(tag, index).is_some() {
            return Err(ParseError::line(
                line,
                format!("node tag {tag} appears twice"),
            ));
        }
        self.positions.push(p);
        Ok(())
    }

    fn node(&self, tag: usize, line: usize) -> Result<usize, ParseError> {
        self.tag_to_index.get(&tag).copied().ok_or_else(|| {
            ParseError::line(
                line,
                format!("element refers to node tag {tag}, which is not in $Nodes"),
            )
        })
    }

    /// Read `nodes` node tags of an element of type `ty` and store it.
    fn add_element(&mut self, t: &mut Tokens<'_>, ty: i64, nodes: usize) -> Result<(), ParseError> {
        // Supported types (points, lines, triangles, tets) have ≤ 4 nodes.
        let mut idx = [0usize; 4];
        for slot in idx.iter_mut().take(nodes) {
            let (tag, l) = t.usize("an element node tag")?;
            *slot = self.node(tag, l)?;
        }
        match ty {
            2 => self.tris.push([idx[0], idx[1], idx[2]]),
            4 => self.tets.push(idx),
            _ => {}
        }
        Ok(())
    }
}

fn coords(t: &mut Tokens<'_>, extra: usize) -> Result<[f64; 3], ParseError> {
    let x = t.f64("node x")?;
    let y = t.f64("node y")?;
    let z = t.f64("node z")?;
    for _ in 0..extra {
        t.f64("a parametric node coordinate")?;
    }
    Ok([x, y, z])
}

fn read_nodes(t: &mut Tokens<'_>, v: Version, d: &mut Data, line: usize) -> Result<(), ParseError> {
    if d.saw_nodes {
        return Err(ParseError::line(line, "a second $Nodes section"));
    }
    d.saw_nodes = true;
    if v == Version::V2 {
        let (n, _) = t.usize("the number of nodes")?;
        d.positions.reserve(capacity_hint(n, t.text_len()));
        for _ in 0..n {
            let (tag, l) = t.usize("a node tag")?;
            let p = coords(t, 0)?;
            d.add_node(tag, p, l)?;
        }
    } else {
        let (blocks, _) = t.usize("the number of node blocks")?;
        let (n, nline) = t.usize("the number of nodes")?;
        if v == Version::V41 {
            t.usize("the minimum node tag")?;
            t.usize("the maximum node tag")?;
        }
        d.positions.reserve(capacity_hint(n, t.text_len()));
        let mut total = 0usize;
        for _ in 0..blocks {
            let (a, _) = t.usize("a node block header")?;
            let (b, _) = t.usize("a node block header")?;
            // 4.1: entityDim entityTag; 4.0: entityTag entityDim.
            let entity_dim = if v == Version::V41 { a } else { b };
            let (parametric, pline) = t.usize("the parametric flag")?;
            if parametric > 1 || entity_dim > 3 {
                return Err(ParseError::line(pline, "malformed node block header"));
            }
            let extra = parametric * entity_dim;
            let (count, _) = t.usize("the number of nodes in the block")?;
            total = total.saturating_add(count);
            if v == Version::V41 {
                let mut tags = Vec::with_capacity(capacity_hint(count, t.text_len()));
                for _ in 0..count {
                    tags.push(t.usize("a node tag")?);
                }
                for (tag, l) in tags {
                    let p = coords(t, extra)?;
                    d.add_node(tag, p, l)?;
                }
            } else {
                for _ in 0..count {
                    let (tag, l) = t.usize("a node tag")?;
                    let p = coords(t, extra)?;
                    d.add_node(tag, p, l)?;
                }
            }
        }
        if total != n {
            return Err(ParseError::line(
                nline,
                format!("$Nodes declares {n} nodes but its blocks hold {total}"),
            ));
        }
    }
    t.keyword("$EndNodes")?;
    Ok(())
}

fn read_elements(
    t: &mut Tokens<'_>,
    v: Version,
    d: &mut Data,
    line: usize,
) -> Result<(), ParseError> {
    if d.saw_elements {
        return Err(ParseError::line(line, "a second $Elements section"));
    }
    if !d.saw_nodes {
        return Err(ParseError::line(line, "$Elements before $Nodes"));
    }
    d.saw_elements = true;
    if v == Version::V2 {
        let (n, _) = t.usize("the number of elements")?;
        for _ in 0..n {
            t.usize("an element tag")?;
            let (ty, l) = t.i64("an element type")?;
            let nodes = check_type(ty, l)?;
            let (ntags, _) = t.usize("the number of element tags")?;
            for _ in 0..ntags {
                t.i64("an element tag")?;
            }
            d.add_element(t, ty, nodes)?;
        }
    } else {
        let (blocks, _) = t.usize("the number of element blocks")?;
        let (n, nline) = t.usize("the number of elements")?;
        if v == Version::V41 {
            t.usize("the minimum element tag")?;
            t.usize("the maximum element tag")?;
        }
        let mut total = 0usize;
        for _ in 0..blocks {
            t.i64("an element block header")?;
            t.i64("an element block header")?;
            let (ty, l) = t.i64("an element type")?;
            let nodes = check_type(ty, l)?;
            let (count, _) = t.usize("the number of elements in the block")?;
            total = total.saturating_add(count);
            for _ in 0..count {
                t.usize("an element tag")?;
                d.add_element(t, ty, nodes)?;
            }
        }
        if total != n {
            return Err(ParseError::line(
                nline,
                format!("$Elements declares {n} elements but its blocks hold {total}"),
            ));
        }
    }
    t.keyword("$EndElements")?;
    Ok(())
}

fn read_format(t: &mut Tokens<'_>) -> Result<Version, ParseError> {
    let (ver, line) = t.expect("the format version")?;
    let (ft, ftline) = t.usize("the file type")?;
    t.usize("the data size")?;
    if ft != 0 {
        return Err(ParseError::line(
            ftline,
            "binary Gmsh files are not supported: save the mesh as ASCII",
        ));
    }
    let v = match ver {
        "4.1" => Version::V41,
        "4" | "4.0" => Version::V40,
        v if v.starts_with("2.") || v == "2" => Version::V2,
        other => {
            return Err(ParseError::line(
                line,
                format!(
                    "unsupported Gmsh format version `{}` (supported: 2.x, 4.0, 4.1)",
                    shorten(other)
                ),
            ));
        }
    };
    t.keyword("$EndMeshFormat")?;
    Ok(v)
}

/// Parse Gmsh `.msh` ASCII text (see the module docs).
pub fn parse_gmsh(text: &str) -> Result<AnyMesh, ParseError> {
    let mut t = Tokens::new(text, None);
    let mut version: Option<Version> = None;
    let mut d = Data::default();
    if t.peek().is_none() {
        return Err(ParseError::format("empty file: expected `$MeshFormat`"));
    }
    while let Some((tok, line)) = t.next_token() {
        let Some(name) = tok.strip_prefix('$') else {
            return Err(ParseError::line(
                line,
                format!("expected a `$Section`, found `{}`", shorten(tok)),
            ));
        };
        if name == "MeshFormat" {
            version = Some(read_format(&mut t)?);
            continue;
        }
        let Some(v) = version else {
            return Err(ParseError::line(
                line,
                format!("expected `$MeshFormat` first, found `{}`", shorten(tok)),
            ));
        };
        match name {
            "Nodes" => read_nodes(&mut t, v, &mut d, line)?,
            "Elements" => read_elements(&mut t, v, &mut d, line)?,
            _ => {
                let end = format!("$End{name}");
                loop {
                    let (tok, _) = t.next_token().ok_or_else(|| {
                        ParseError::line(line, format!("section `${name}` has no `{end}`"))
                    })?;
                    if tok == end {
                        break;
                    }
                }
            }
        }
    }
    if !d.saw_nodes {
        return Err(ParseError::format("no $Nodes section in the Gmsh file"));
    }
    if !d.saw_elements {
        return Err(ParseError::format("no $Elements section in the Gmsh file"));
    }
    if !d.tets.is_empty() {
        Ok(AnyMesh::Tet(TetMesh::new(d.positions, d.tets)))
    } else if !d.tris.is_empty() {
        Ok(AnyMesh::Tri(TriMesh::new(d.positions, d.tris)))
    } else {
        Err(ParseError::format(
            "the Gmsh file has no triangles and no tetrahedra",
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const V41: &str = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n0 0 0 1\n1 0 0 0 1 1 1 0 0\n$EndEntities\n\
        $Nodes\n2 4 1 40\n0 1 0 1\n10\n0 0 0\n3 1 1 3\n20\n30\n40\n1 0 0 0.5 0.5 0.5\n0 1 0 0.1 0.1 0.1\n0 0 1 0.2 0.2 0.2\n$EndNodes\n\
        $Elements\n2 2 1 2\n2 1 2 1\n1 10 20 30\n3 1 4 1\n2 10 20 30 40\n$EndElements\n$Surface\n1\n1 2 3\n$EndSurface\n";

    #[test]
    fn reads_v41_with_tags_parametric_nodes_and_unknown_sections() {
        let AnyMesh::Tet(m) = parse_gmsh(V41).unwrap() else {
            panic!("expected tets")
        };
        assert_eq!(
            m.positions,
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, 1.0]
            ]
        );
        assert_eq!(m.tets, vec![[0, 1, 2, 3]]);
    }

    #[test]
    fn reads_v2_and_v40() {
        let v2 = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n2 1 \"s\"\n$EndPhysicalNames\n\
                  $Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n$Elements\n3\n1 15 2 0 1 1\n2 1 2 0 1 1 2\n3 2 2 1 1 1 2 3\n$EndElements\n";
        let AnyMesh::Tri(m) = parse_gmsh(v2).unwrap() else {
            panic!("expected triangles")
        };
        assert_eq!(m.triangles, vec![[0, 1, 2]]);
        let v40 = "$MeshFormat\n4 0 8\n$EndMeshFormat\n$Nodes\n1 3\n7 2 0 3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n\
                   $Elements\n1 1\n7 2 2 1\n1 3 2 1\n$EndElements\n";
        let AnyMesh::Tri(m) = parse_gmsh(v40).unwrap() else {
            panic!("expected triangles")
        };
        assert_eq!(m.triangles, vec![[2, 1, 0]]);
    }

    #[test]
    fn malformed_inputs_are_rejected_with_lines() {
        let head = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
        let nodes = "$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n";
        let cases: Vec<(String, &str)> = vec![
            (String::new(), "empty file"),
            ("$Nodes\n".into(), "line 1: expected `$MeshFormat` first"),
            ("$MeshFormat\n2.2 1 8\n$EndMeshFormat\n".into(), "line 2: binary Gmsh files are not supported"),
            ("$MeshFormat\n3.0 0 8\n$EndMeshFormat\n".into(), "line 2: unsupported Gmsh format version `3.0`"),
            (format!("{head}$Nodes\n2\n1 0 0 0\n"), "unexpected end of file: expected a node tag"),
            (format!("{head}$Nodes\n1\n1 0 y 0\n$EndNodes\n"), "line 6: expected node y (a number), found `y`"),
            (format!("{head}$Nodes\n2\n1 0 0 0\n1 0 0 0\n$EndNodes\n"), "line 7: node tag 1 appears twice"),
            (format!("{head}$Nodes\n1\n1 0 0 0\n2 0 0 0\n$EndNodes\n"), "line 7: expected `$EndNodes`, found `2`"),
            (format!("{head}{nodes}$Elements\n1\n1 2 0 1 2 4\n$EndElements\n"), "line 12: element refers to node tag 4, which is not in $Nodes"),
            (format!("{head}{nodes}$Elements\n1\n1 3 0 1 2 3 1\n$EndElements\n"), "line 12: unsupported element type 3 (4-node quadrangle)"),
            (format!("{head}{nodes}$Elements\n1\n1 99 0 1\n$EndElements\n"), "line 12: unknown Gmsh element type 99"),
            (format!("{head}{nodes}$Elements\n1\n1 1 0 1 2\n$EndElements\n"), "no triangles and no tetrahedra"),
            (format!("{head}{nodes}"), "no $Elements section"),
            (format!("{head}$Foo\n1 2\n"), "line 4: section `$Foo` has no `$EndFoo`"),
            (format!("{head}junk\n"), "line 4: expected a `$Section`, found `junk`"),
            (format!("{head}$Elements\n0\n$EndElements\n"), "line 4: $Elements before $Nodes"),
            ("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 2 1 2\n0 1 0 1\n1\n0 0 0\n$EndNodes\n".into(), "line 5: $Nodes declares 2 nodes but its blocks hold 1"),
        ];
        for (text, want) in &cases {
            let err = parse_gmsh(text).unwrap_err().to_string();
            assert!(err.contains(want), "{text:?}: got {err:?}, want {want:?}");
        }
    }
}
