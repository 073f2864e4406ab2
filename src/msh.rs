//! The mesh reader: a Gmsh MSH 4.1 file, ASCII or binary, as a P1 body.
//!
//! The file is parsed by the `mshio` crate; this room turns what it parsed into
//! $\overline\Omega = \bigcup_T T$: the nodes, the triangles $T$ (three nodes each,
//! counter-clockwise), and the boundary edges of each physical group of curves, by
//! the group's name (from the file's `$PhysicalNames`, which `mshio` skips and which
//! is plain text in both encodings; a group without a name is named by its number).
//! Each group edge is oriented as the boundary runs counter-clockwise, so that the
//! body lies on its left and its outward normal is the edge's direction turned
//! clockwise.
//!
//! Anything a P1 body cannot be is refused with the file, the element or group, and
//! what to change: quadrangles, second-order elements, 3-D elements, a triangle of
//! zero area, a tangled mesh (two triangles on the same side of an edge, or an edge
//! of three), a body in several pieces, a group edge that is not on the boundary. A
//! parser's failure (including a panic inside it) is a refusal too, never a panic.
//! What the scene asks of the groups (that they exist, that contact and supports do
//! not overlap, that the supports hold the body) is checked where the scene gives
//! the groups their roles ([`crate::body`]).

use crate::error::InputError;
use mshio::ElementType;
use std::collections::HashMap;
use std::path::Path;

/// A file larger than this is refused before it is read (some 10 million triangles in
/// ASCII).
pub const MAX_FILE_BYTES: u64 = 1 << 30;

/// A triangulated body read from a mesh file.
#[derive(Debug, Clone, PartialEq)]
pub struct MshMesh {
    /// The file, as the caller named it (for messages).
    pub file: String,
    /// The nodes the triangles use, in the file's order ($z$ dropped, it is 0).
    pub nodes: Vec<[f64; 2]>,
    /// The triangles, counter-clockwise.
    pub triangles: Vec<[usize; 3]>,
    /// The physical groups of curves, in the order of their numbers.
    pub groups: Vec<EdgeGroup>,
}

/// A physical group of curves: boundary edges with a name.
#[derive(Debug, Clone, PartialEq)]
pub struct EdgeGroup {
    /// The group's name (its number as text when the file gives none).
    pub name: String,
    /// Its number in the file.
    pub tag: i32,
    /// Its edges, each oriented with the body on its left.
    pub edges: Vec<[usize; 2]>,
}

impl MshMesh {
    /// The group named `name`.
    pub fn group(&self, name: &str) -> Option<&EdgeGroup> {
        self.groups.iter().find(|g| g.name == name)
    }

    /// The groups' names, quoted and joined, for messages.
    pub fn group_names(&self) -> String {
        if self.groups.is_empty() {
            return "none".into();
        }
        let names: Vec<String> = self
            .groups
            .iter()
            .map(|g| format!("\"{}\"", g.name))
            .collect();
        names.join(", ")
    }
}

/// Reads and parses the mesh file at `path`; `file` names it in messages.
pub fn read(path: &Path, file: &str) -> Result<MshMesh, InputError> {
    parse(&read_bytes(path, file)?, file)
}

/// The bytes of the mesh file at `path` (a regular file of at most
/// [`MAX_FILE_BYTES`]); `file` names it in messages.
pub fn read_bytes(path: &Path, file: &str) -> Result<Vec<u8>, InputError> {
    let io = |e: std::io::Error| InputError::mesh(file, format!("cannot read it: {e}"));
    let meta = std::fs::metadata(path).map_err(io)?;
    if !meta.is_file() {
        return Err(InputError::mesh(
            file,
            "not a regular file: give the path of a Gmsh .msh file (relative to the scenario file)",
        ));
    }
    if meta.len() > MAX_FILE_BYTES {
        return Err(InputError::mesh(
            file,
            format!(
                "{} bytes, more than the {MAX_FILE_BYTES} a mesh file may have",
                meta.len()
            ),
        ));
    }
    std::fs::read(path).map_err(io)
}

/// Node tag -> the node's position in the file's order: a table over the tags'
/// range when they are about dense (as Gmsh writes them), else a hash map.
enum TagIndex {
    Dense { min: u64, at: Vec<usize> },
    Sparse(HashMap<u64, usize>),
}

impl TagIndex {
    fn new(nodes: &mshio::Nodes<u64, i32, f64>) -> TagIndex {
        let count: usize = nodes.node_blocks.iter().map(|b| b.nodes.len()).sum();
        let (min, max) = (nodes.min_node_tag, nodes.max_node_tag);
        let span = max.saturating_sub(min).saturating_add(1);
        if min <= max && span <= 2 * count as u64 + 1024 {
            TagIndex::Dense {
                min,
                at: vec![usize::MAX; span as usize],
            }
        } else {
            TagIndex::Sparse(HashMap::with_capacity(count))
        }
    }
    /// Records `tag` at `v`; false if the tag was recorded before.
    fn insert(&mut self, tag: u64, v: usize) -> bool {
        match self {
            TagIndex::Dense { min, at } => {
                match tag.checked_sub(*min).and_then(|k| at.get_mut(k as usize)) {
                    Some(slot) if *slot == usize::MAX => {
                        *slot = v;
                        true
                    }
                    Some(_) => false,
                    // A tag outside the header's range: kept, as the map would.
                    None => {
                        let mut map: HashMap<u64, usize> = (at.iter().enumerate())
                            .filter(|&(_, &w)| w != usize::MAX)
                            .map(|(k, &w)| (*min + k as u64, w))
                            .collect();
                        map.insert(tag, v);
                        *self = TagIndex::Sparse(map);
                        true
                    }
                }
            }
            TagIndex::Sparse(map) => map.insert(tag, v).is_none(),
        }
    }
    fn get(&self, tag: u64) -> Option<usize> {
        match self {
            TagIndex::Dense { min, at } => (tag.checked_sub(*min))
                .and_then(|k| at.get(k as usize))
                .copied()
                .filter(|&v| v != usize::MAX),
            TagIndex::Sparse(map) => map.get(&tag).copied(),
        }
    }
}

/// Parses the bytes of an MSH 4.1 file; `file` names it in messages.
pub fn parse(bytes: &[u8], file: &str) -> Result<MshMesh, InputError> {
    let refuse = |m: String| InputError::mesh(file, m);
    // The parser is another crate's: a panic inside it on a malformed file is a
    // refusal here. (Its message still reaches stderr through the panic hook.)
    let parsed = std::panic::catch_unwind(|| {
        mshio::parse_msh_bytes(bytes).map_err(|e| parser_message(bytes, &e))
    })
    .map_err(|_| {
        refuse("the MSH parser failed on it (a malformed file): save it again from Gmsh".into())
    })?
    .map_err(|m| {
        refuse(format!(
            "{m}; save it from Gmsh as MSH 4.1 (Mesh.MshFileVersion = 4.1)"
        ))
    })?;
    let names = physical_names(bytes);
    let data = parsed.data;
    let (Some(nodes), Some(elements)) = (data.nodes, data.elements) else {
        return Err(refuse(
            "no $Nodes or no $Elements section: mesh the body first (gmsh -2)".into(),
        ));
    };
    // Curve entity -> its physical groups.
    let mut curve_groups: HashMap<i32, Vec<i32>> = HashMap::new();
    if let Some(ent) = &data.entities {
        for c in &ent.curves {
            curve_groups.insert(c.tag, c.physical_tags.iter().map(|t| t.abs()).collect());
        }
    }

    // The nodes, by tag. Dense tags are not stored by mshio: they run from the
    // smallest tag in the file's order, as Gmsh writes them.
    let mut coords: Vec<[f64; 3]> = Vec::new();
    let mut index = TagIndex::new(&nodes);
    let mut next = nodes.min_node_tag;
    for block in &nodes.node_blocks {
        let mut tags: Vec<(u64, usize)> = match &block.node_tags {
            Some(map) => map.iter().map(|(&t, &i)| (t, i)).collect(),
            None => (0..block.nodes.len())
                .map(|i| (next + i as u64, i))
                .collect(),
        };
        tags.sort_by_key(|&(_, i)| i);
        next += block.nodes.len() as u64;
        for (tag, i) in tags {
            let p = &block.nodes[i];
            if !index.insert(tag, coords.len()) {
                return Err(refuse(format!(
                    "node {tag} is defined twice: save the mesh again from Gmsh"
                )));
            }
            coords.push([p.x, p.y, p.z]);
        }
    }
    let scale = coords
        .iter()
        .flat_map(|p| p.iter())
        .fold(0.0f64, |m, x| m.max(x.abs()));
    if let Some(p) = coords.iter().find(|p| !p.iter().all(|x| x.is_finite())) {
        return Err(refuse(format!(
            "a node at ({}, {}, {}) is not finite: fix the geometry",
            p[0], p[1], p[2]
        )));
    }
    if let Some(p) = coords.iter().find(|p| p[2].abs() > 1e-12 * scale.max(1.0)) {
        return Err(refuse(format!(
            "a node at ({}, {}, {}) is off the plane z = 0: the body must be a 2-D mesh in \
             the (x, y) plane",
            p[0], p[1], p[2]
        )));
    }
    // `what` names the element, made only for the message.
    let node = |tag: u64, what: &dyn Fn() -> String| {
        index.get(tag).ok_or_else(|| {
            refuse(format!(
                "{} uses node {tag}, which the file does not define: save the mesh again \
                 from Gmsh",
                what()
            ))
        })
    };

    let mut triangles: Vec<([usize; 3], u64)> = Vec::new();
    let mut curve_edges: Vec<(i32, [usize; 2], u64)> = Vec::new();
    for block in &elements.element_blocks {
        let ty = block.element_type;
        let first = block.elements.first().map_or(0, |e| e.element_tag);
        match kind(ty, block.entity_dim) {
            Kind::Triangle => {
                for e in &block.elements {
                    let what = || format!("triangle {}", e.element_tag);
                    let t = [
                        node(e.nodes[0], &what)?,
                        node(e.nodes[1], &what)?,
                        node(e.nodes[2], &what)?,
                    ];
                    triangles.push((t, e.element_tag));
                }
            }
            Kind::Line => {
                for e in &block.elements {
                    let what = || format!("line element {}", e.element_tag);
                    let a = node(e.nodes[0], &what)?;
                    let b = node(e.nodes[1], &what)?;
                    curve_edges.push((block.entity_tag, [a, b], e.element_tag));
                }
            }
            Kind::Point => {}
            Kind::Refused(why) => {
                let others = match block.elements.len().saturating_sub(1) {
                    0 => String::new(),
                    k => format!(" and {k} more like it"),
                };
                return Err(refuse(format!(
                    "element {first}{others} (on entity {} of dimension {}) is {why}",
                    block.entity_tag, block.entity_dim
                )));
            }
        }
    }
    if triangles.is_empty() {
        return Err(refuse(
            "no triangles: mesh the surface with linear triangles (gmsh -2)".into(),
        ));
    }

    // Keep the nodes the triangles use, in the file's order.
    let mut used = vec![usize::MAX; coords.len()];
    for (t, _) in &triangles {
        for &v in t {
            used[v] = 0;
        }
    }
    let mut kept = Vec::new();
    for (v, u) in used.iter_mut().enumerate() {
        if *u == 0 {
            *u = kept.len();
            kept.push([coords[v][0], coords[v][1]]);
        }
    }
    let tol = 1e-12 * scale.max(f64::MIN_POSITIVE);
    let mut tris = Vec::with_capacity(triangles.len());
    for (t, tag) in &triangles {
        let mut t = t.map(|v| used[v]);
        let p = t.map(|v| kept[v]);
        let twice =
            (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
        let longest = (0..3)
            .map(|i| {
                let (a, b) = (p[i], p[(i + 1) % 3]);
                (b[0] - a[0]).hypot(b[1] - a[1])
            })
            .fold(0.0f64, f64::max);
        if twice.abs() <= 1e-10 * longest * longest || longest <= tol {
            return Err(refuse(format!(
                "triangle {tag} has zero area (nodes at ({}, {}), ({}, {}), ({}, {})): remove \
                 the degenerate triangle, or mesh the surface again",
                p[0][0], p[0][1], p[1][0], p[1][1], p[2][0], p[2][1]
            )));
        }
        if twice < 0.0 {
            t.swap(1, 2);
        }
        tris.push(t);
    }

    // Each directed edge once: two counter-clockwise triangles on the same side of an
    // edge overlap (the mesh is folded), and an edge of three triangles is no surface.
    // Sorted (a, b, triangle, edge) entries put the triangles of one directed edge
    // side by side; the refusal names the pair a scan in the file's order meets first.
    let mut directed: Vec<(usize, usize, usize, usize)> = Vec::with_capacity(3 * tris.len());
    for (i, t) in tris.iter().enumerate() {
        for e in 0..3 {
            directed.push((t[e], t[(e + 1) % 3], i, e));
        }
    }
    directed.sort_unstable();
    let folded = (directed.windows(2))
        .filter(|w| (w[0].0, w[0].1) == (w[1].0, w[1].1))
        .min_by_key(|w| (w[1].2, w[1].3));
    if let Some(w) = folded {
        let ((a, b, j, _), i) = (w[0], w[1].2);
        let [pa, pb] = [kept[a], kept[b]];
        return Err(refuse(format!(
            "the mesh is tangled: triangles {} and {} lie on the same side of the edge \
             from ({}, {}) to ({}, {}) (they overlap, or the edge has more than two \
             triangles): mesh the surface again, without overlapping or folded parts",
            triangles[j].1, triangles[i].1, pa[0], pa[1], pb[0], pb[1]
        )));
    }

    // One piece: the triangles joined through shared nodes.
    let mut parent: Vec<usize> = (0..kept.len()).collect();
    fn find(parent: &mut [usize], mut v: usize) -> usize {
        while parent[v] != v {
            parent[v] = parent[parent[v]];
            v = parent[v];
        }
        v
    }
    for t in &tris {
        let r = find(&mut parent, t[0]);
        for &v in &t[1..] {
            let s = find(&mut parent, v);
            parent[s] = r;
        }
    }
    let root = find(&mut parent, tris[0][0]);
    if let Some(v) = (0..kept.len()).find(|&v| find(&mut parent, v) != root) {
        let mut roots: Vec<usize> = (0..kept.len()).map(|v| find(&mut parent, v)).collect();
        roots.sort_unstable();
        roots.dedup();
        return Err(refuse(format!(
            "the body is in {} pieces (one holds the node at ({}, {}), another the node at \
             ({}, {})): a body must be one connected piece; remove the other pieces or join \
             them (Gmsh: BooleanFragments, or one surface)",
            roots.len(),
            kept[tris[0][0]][0],
            kept[tris[0][0]][1],
            kept[v][0],
            kept[v][1]
        )));
    }

    // The groups of curves, each edge oriented as the boundary runs.
    let has = |a: usize, b: usize| (directed.binary_search_by(|x| (x.0, x.1).cmp(&(a, b)))).is_ok();
    let mut by_tag: std::collections::BTreeMap<i32, Vec<[usize; 2]>> = Default::default();
    for (entity, [a, b], tag) in &curve_edges {
        let Some(groups) = curve_groups.get(entity).filter(|g| !g.is_empty()) else {
            continue;
        };
        let (a, b) = (used[*a], used[*b]);
        if a == usize::MAX || b == usize::MAX {
            return Err(refuse(format!(
                "line element {tag} (curve {entity}) has a node that no triangle uses: a group's \
                 curves must lie on the body's boundary"
            )));
        }
        let edge = if has(a, b) && !has(b, a) {
            [a, b]
        } else if has(b, a) && !has(a, b) {
            [b, a]
        } else {
            let inside = has(a, b);
            return Err(refuse(format!(
                "line element {tag} (curve {entity}, from ({}, {}) to ({}, {})) is {}: a \
                 group's curves must lie on the body's boundary (mesh the curves with the \
                 surface, so that their nodes are shared)",
                kept[a][0],
                kept[a][1],
                kept[b][0],
                kept[b][1],
                if inside {
                    "inside the body"
                } else {
                    "not an edge of any triangle"
                }
            )));
        };
        for g in groups {
            by_tag.entry(*g).or_default().push(edge);
        }
    }
    let groups = by_tag
        .into_iter()
        .map(|(tag, mut edges)| {
            edges.sort_unstable();
            edges.dedup();
            EdgeGroup {
                name: names
                    .get(&(1, tag))
                    .cloned()
                    .unwrap_or_else(|| tag.to_string()),
                tag,
                edges,
            }
        })
        .collect();
    Ok(MshMesh {
        file: file.to_string(),
        nodes: kept,
        triangles: tris,
        groups,
    })
}

/// What the reader makes of an element type.
enum Kind {
    Triangle,
    Line,
    Point,
    Refused(String),
}

fn kind(ty: ElementType, dim: i32) -> Kind {
    use ElementType as E;
    let name = format!("{ty:?}");
    match ty {
        E::Tri3 => Kind::Triangle,
        E::Lin2 => Kind::Line,
        E::Pnt => Kind::Point,
        _ if dim == 3
            || ["Tet", "Hex", "Pri", "Pyr", "Polyh"]
                .iter()
                .any(|p| name.starts_with(p)) =>
        {
            Kind::Refused(format!(
                "a 3-D element ({name}): the body must be a 2-D mesh; mesh the surface only \
                 (gmsh -2)"
            ))
        }
        _ if name.starts_with("Qua") => Kind::Refused(format!(
            "a quadrangle ({name}): P1 needs triangles; do not recombine (Mesh.RecombineAll = \
             0, no Recombine in the .geo)"
        )),
        _ if name.starts_with("Tri") || name.starts_with("Lin") => Kind::Refused(format!(
            "a second- or higher-order element ({name}): P1 needs linear elements; set \
             Mesh.ElementOrder = 1 (gmsh -order 1)"
        )),
        _ => Kind::Refused(format!(
            "an element of a kind a P1 body cannot use ({name}): mesh the surface with linear \
             triangles"
        )),
    }
}

/// The `$PhysicalNames` section: `(dimension, tag) -> name`. It is text in both
/// encodings and comes before the binary sections; a malformed one names nothing.
fn physical_names(bytes: &[u8]) -> HashMap<(i32, i32), String> {
    let mut out = HashMap::new();
    let find = |tag: &[u8]| bytes.windows(tag.len()).position(|w| w == tag);
    let head = [find(b"$Entities"), find(b"$Nodes")]
        .into_iter()
        .flatten()
        .min()
        .unwrap_or(bytes.len());
    let text = String::from_utf8_lossy(&bytes[..head]);
    let Some(start) = text.find("$PhysicalNames") else {
        return out;
    };
    let Some(end) = text[start..].find("$EndPhysicalNames") else {
        return out;
    };
    for line in text[start..start + end].lines().skip(2) {
        let mut parts = line.trim().splitn(3, char::is_whitespace);
        let (Some(d), Some(t), Some(n)) = (parts.next(), parts.next(), parts.next()) else {
            continue;
        };
        if let (Ok(d), Ok(t)) = (d.parse(), t.parse()) {
            out.insert((d, t), n.trim().trim_matches('"').to_string());
        }
    }
    out
}

/// The parser's failure in words: what it was reading, where (the line, for a text
/// file), and why.
fn parser_message(bytes: &[u8], e: &mshio::MshParserError<&[u8]>) -> String {
    let trace = e.filtered_backtrace();
    let Some((at, why)) = trace.first() else {
        return "the MSH parser could not read it".into();
    };
    // Where the parser stopped: its slice lies within the file's bytes.
    let offset = (at.as_ptr() as usize)
        .checked_sub(bytes.as_ptr() as usize)
        .filter(|&o| o <= bytes.len())
        .unwrap_or(0);
    let line = bytes[..offset].iter().filter(|&&b| b == b'\n').count() + 1;
    let within: Vec<String> = trace[1..]
        .iter()
        .rev()
        .filter_map(|(_, k)| k.context().map(str::to_string))
        .take(4)
        .collect();
    format!(
        "not a readable MSH 4.1 file: {why} (at byte {offset}, line {line}{}{})",
        if within.is_empty() { "" } else { ", in " },
        within.join(" > ")
    )
}

/// The body as an ASCII MSH 4.1 file that [`read`] reads back to the same nodes,
/// triangles and groups: all nodes on one surface entity, one curve entity per group
/// (holding that group's physical tag and name), the triangles on the surface. (A
/// refined mesh written for a record, a generated mesh for the bench.)
pub fn write(mesh: &MshMesh) -> String {
    use std::fmt::Write as _;
    let mut s = String::with_capacity(40 * mesh.nodes.len() + 30 * mesh.triangles.len());
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in &mesh.nodes {
        for c in 0..2 {
            lo[c] = lo[c].min(p[c]);
            hi[c] = hi[c].max(p[c]);
        }
    }
    let bbox = format!("{:?} {:?} 0 {:?} {:?} 0", lo[0], lo[1], hi[0], hi[1]);
    let g = mesh.groups.len();
    s.push_str("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n");
    let _ = writeln!(s, "{g}");
    for gr in &mesh.groups {
        let _ = writeln!(s, "1 {} \"{}\"", gr.tag, gr.name);
    }
    s.push_str("$EndPhysicalNames\n$Entities\n");
    let _ = writeln!(s, "0 {g} 1 0");
    for (i, gr) in mesh.groups.iter().enumerate() {
        let _ = writeln!(s, "{} {bbox} 1 {} 0", i + 1, gr.tag);
    }
    let _ = writeln!(s, "1 {bbox} 0 0\n$EndEntities\n$Nodes");
    let n = mesh.nodes.len();
    let _ = writeln!(s, "1 {n} 1 {n}\n2 1 0 {n}");
    for i in 1..=n {
        let _ = writeln!(s, "{i}");
    }
    for p in &mesh.nodes {
        // `{:?}` prints the shortest text that reads back to the same f64.
        let _ = writeln!(s, "{:?} {:?} 0", p[0], p[1]);
    }
    let edges: usize = mesh.groups.iter().map(|g| g.edges.len()).sum();
    let total = edges + mesh.triangles.len();
    let _ = writeln!(s, "$EndNodes\n$Elements\n{} {total} 1 {total}", g + 1);
    let mut tag = 0;
    for (i, gr) in mesh.groups.iter().enumerate() {
        let _ = writeln!(s, "1 {} 1 {}", i + 1, gr.edges.len());
        for e in &gr.edges {
            tag += 1;
            let _ = writeln!(s, "{tag} {} {}", e[0] + 1, e[1] + 1);
        }
    }
    let _ = writeln!(s, "2 1 2 {}", mesh.triangles.len());
    for t in &mesh.triangles {
        tag += 1;
        let _ = writeln!(s, "{tag} {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1);
    }
    s.push_str("$EndElements\n");
    s
}
