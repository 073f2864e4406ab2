//! The scene: the rectangle $\Omega = (0, W) \times (0, H)$, what holds each part of its
//! boundary, and the contact boundary $\Gamma_3$, a segment of the bottom.
//!
//! Each side is cut into segments, each held by a support kind of [`crate::support`]
//! (`clamped`: both displacement components zero; `rollers`: the normal component
//! zero, free to slide; `free`); the parts a scenario does not name are free. The
//! file's supports are read by [`crate::support::file`], the presets and side names
//! here. The paper's scene is the preset
//! [`Geometry::paper`]: $W = 2$, $H = 1$, the sides clamped on $[\tfrac12, 1]$, the
//! whole bottom in contact. [`Geometry::rollers`] is the smooth scene of the
//! regularity study. A point of the boundary is held by every segment that contains
//! it (a corner by both of its sides); a clamped segment holds its end points.

use crate::error::{InputError, in_range};
use crate::support::Hold;

/// A side of the rectangle.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// $x = 0$.
    Left,
    /// $x = W$.
    Right,
    /// $y = 0$, where $\Gamma_3$ lies.
    Bottom,
    /// $y = H$.
    Top,
}

impl Side {
    /// The four sides: left, right, bottom, top.
    pub const ALL: [Side; 4] = [Side::Left, Side::Right, Side::Bottom, Side::Top];

    /// The name used in scenario files.
    pub fn name(self) -> &'static str {
        match self {
            Side::Left => "left",
            Side::Right => "right",
            Side::Bottom => "bottom",
            Side::Top => "top",
        }
    }

    /// The displacement component normal to the side (0 = x, 1 = y).
    pub fn normal(self) -> usize {
        match self {
            Side::Left | Side::Right => 0,
            Side::Bottom | Side::Top => 1,
        }
    }

    /// The coordinate of `p` along the side: $y$ on the left and right, $x$ on the
    /// bottom and top.
    pub fn along(self, p: [f64; 2]) -> f64 {
        p[1 - self.normal()]
    }
}

/// A held segment of one side, from `from` to `to` along it.
#[derive(Debug, Clone, PartialEq)]
pub struct Segment {
    /// The side the segment lies on.
    pub side: Side,
    /// Where the segment starts, in the coordinate along the side ([`Side::along`]).
    pub from: f64,
    /// Where the segment ends, in the coordinate along the side ([`Side::along`]).
    pub to: f64,
    /// What holds the segment.
    pub hold: Hold,
    /// Where the scenario says it (`geometry.supports.left[0]`), for messages.
    pub field: String,
}

/// A traction: a constant force density `f` (N/m) on `[from, to]` along `side`.
#[derive(Debug, Clone, PartialEq)]
pub struct Traction {
    /// The side the traction acts on.
    pub side: Side,
    /// Where it starts, in the coordinate along the side ([`Side::along`]).
    pub from: f64,
    /// Where it ends, in the coordinate along the side ([`Side::along`]).
    pub to: f64,
    /// The force density $(f_x, f_y)$, in N/m.
    pub f: [f64; 2],
    /// Where the scenario says it (`loads.traction[0]`, `loads.f2`), for messages.
    pub field: String,
}

/// A point where the solution is expected to be singular: the holds that meet there,
/// at a corner (opening $\pi/2$) or inside a side (opening $\pi$), or an end of
/// $\Gamma_3$ inside the bottom, where the free boundary meets the contact zone.
#[derive(Debug, Clone, PartialEq)]
pub struct Singularity {
    /// The point $(x, y)$.
    pub point: [f64; 2],
    /// The holds that meet there: inside a side, the hold just before and just after
    /// the point along it; at a corner, the hold of the left or right side, then that
    /// of the bottom or top, each just beside the corner.
    pub holds: [Hold; 2],
    /// Whether the point is a corner of the rectangle.
    pub corner: bool,
    /// An end of $\Gamma_3$ inside the bottom: the boundary condition changes from free
    /// to normal compliance (and, where the limit is reached there, to a unilateral
    /// one). No exponent is known for it in general, so none is predicted; graded
    /// meshes refine towards it as towards the others.
    pub contact_end: bool,
}

/// The rectangle, its supports and its contact segment.
#[derive(Debug, Clone, PartialEq)]
pub struct Geometry {
    /// The width $W$ (extent in $x$).
    pub width: f64,
    /// The height $H$ (extent in $y$).
    pub height: f64,
    /// The segments a scenario names (clamped, rollers, or free); the rest of the
    /// boundary is free.
    pub supports: Vec<Segment>,
    /// $\Gamma_3 = [x_0, x_1] \times \{0\}$.
    pub contact: [f64; 2],
    /// The preset's name when the supports are one (`paper`, `rollers`).
    pub preset: Option<&'static str>,
}

impl Default for Geometry {
    fn default() -> Self {
        Geometry::paper()
    }
}

/// Relative tolerance for a point to lie on a segment's end (meshes place nodes by
/// products $i\,h_x$, a few units of rounding from the end written in the file).
const ON: f64 = 1e-9;

fn segment(side: Side, from: f64, to: f64, hold: Hold, field: &str) -> Segment {
    Segment {
        side,
        from,
        to,
        hold,
        field: field.to_string(),
    }
}

/// The singular points of the paper's scene ([`Geometry::paper`]): the clamp ends
/// $(0, \tfrac12)$, $(2, \tfrac12)$, then the top corners $(0, 1)$, $(2, 1)$. The book's
/// graded meshes refine towards them; [`Geometry::singular_points`] finds the same
/// points from the supports of any scene.
pub const PAPER_SINGULAR: [[f64; 2]; 4] = [[0.0, 0.5], [2.0, 0.5], [0.0, 1.0], [2.0, 1.0]];

impl Geometry {
    /// The paper's scene: $(0,2)\times(0,1)$, the sides clamped on $[\tfrac12, 1]$, the
    /// whole bottom in contact.
    pub fn paper() -> Geometry {
        let f = "geometry.supports = \"paper\"";
        Geometry {
            width: 2.0,
            height: 1.0,
            supports: vec![
                segment(Side::Left, 0.5, 1.0, Hold::Clamped, f),
                segment(Side::Right, 0.5, 1.0, Hold::Clamped, f),
            ],
            contact: [0.0, 2.0],
            preset: Some("paper"),
        }
    }

    /// The smooth scene: the top clamped, both sides on rollers.
    pub fn rollers() -> Geometry {
        let f = "geometry.supports = \"rollers\"";
        Geometry {
            width: 2.0,
            height: 1.0,
            supports: vec![
                segment(Side::Left, 0.0, 1.0, Hold::Rollers, f),
                segment(Side::Right, 0.0, 1.0, Hold::Rollers, f),
                segment(Side::Top, 0.0, 2.0, Hold::Clamped, f),
            ],
            contact: [0.0, 2.0],
            preset: Some("rollers"),
        }
    }

    /// The length of `side`.
    pub fn length(&self, side: Side) -> f64 {
        match side {
            Side::Left | Side::Right => self.height,
            Side::Bottom | Side::Top => self.width,
        }
    }

    /// A distance below which two boundary coordinates are the same point.
    pub fn tol(&self) -> f64 {
        ON * self.width.max(self.height)
    }

    /// Whether `p` lies on `side`.
    pub fn on(&self, side: Side, p: [f64; 2]) -> bool {
        let tol = self.tol();
        match side {
            Side::Left => p[0].abs() <= tol,
            Side::Right => (p[0] - self.width).abs() <= tol,
            Side::Bottom => p[1].abs() <= tol,
            Side::Top => (p[1] - self.height).abs() <= tol,
        }
    }

    /// The components held fixed at the boundary point `p` (none inside).
    pub fn fixed_at(&self, p: [f64; 2]) -> [bool; 2] {
        let tol = self.tol();
        let mut fixed = [false; 2];
        for s in &self.supports {
            let a = s.side.along(p);
            if self.on(s.side, p) && a >= s.from - tol && a <= s.to + tol {
                let f = s.hold.fixes(s.side.normal());
                fixed = [fixed[0] || f[0], fixed[1] || f[1]];
            }
        }
        fixed
    }

    /// What holds `side` at the coordinate `a` along it, strictly inside a segment
    /// or between segments (`a` should not be an end point).
    pub fn hold_at(&self, side: Side, a: f64) -> Hold {
        self.supports
            .iter()
            .find(|s| s.side == side && s.from < a && a < s.to)
            .map_or(Hold::Free, |s| s.hold)
    }

    /// The held segments of `side` that overlap $(a, b)$ in more than a point.
    pub fn holds_on(&self, side: Side, a: f64, b: f64) -> Vec<&Segment> {
        let tol = self.tol();
        self.supports
            .iter()
            .filter(|s| s.side == side && s.from.max(a) < s.to.min(b) - tol)
            .collect()
    }

    /// Whether $\Gamma_3$ is the whole bottom.
    pub fn contact_is_whole_bottom(&self) -> bool {
        self.contact == [0.0, self.width]
    }

    /// The points where the solution is expected to be singular (see
    /// [`Geometry::singularities`]).
    pub fn singular_points(&self) -> Vec<[f64; 2]> {
        self.singularities().into_iter().map(|s| s.point).collect()
    }

    /// The points where the solution is expected to be singular, each once: on a
    /// side, where the hold changes (a clamp or roller ending on a free part, a clamp
    /// meeting rollers); at a corner, where a clamped side meets a free one. A corner
    /// with rollers reflects across the roller side to a straight edge or a regular
    /// corner; two clamped sides meet with a leading exponent above 1, so the solution
    /// is in $H^2$ there and P1 keeps its order. $\Gamma_3$ counts as free here: its
    /// compliance is not a support. Used by graded meshes.
    pub fn singularities(&self) -> Vec<Singularity> {
        let (w, h) = (self.width, self.height);
        let point = |side: Side, a: f64| match side {
            Side::Left => [0.0, a],
            Side::Right => [w, a],
            Side::Bottom => [a, 0.0],
            Side::Top => [a, h],
        };
        let mut out = vec![];
        let tol = self.tol();
        for side in Side::ALL {
            let len = self.length(side);
            let mut ends: Vec<f64> = self
                .supports
                .iter()
                .filter(|s| s.side == side)
                .flat_map(|s| [s.from, s.to])
                .filter(|&a| a > tol && a < len - tol)
                .collect();
            ends.sort_by(f64::total_cmp);
            ends.dedup_by(|a, b| (*a - *b).abs() <= tol);
            for a in ends {
                let d = 1e-6 * len;
                let holds = [self.hold_at(side, a - d), self.hold_at(side, a + d)];
                if holds[0] != holds[1] {
                    out.push(Singularity {
                        point: point(side, a),
                        holds,
                        corner: false,
                        contact_end: false,
                    });
                }
            }
        }
        // Corners: the hold of each side just beside the corner.
        let corners = [
            (Side::Left, 0.0, Side::Bottom, 0.0),
            (Side::Right, 0.0, Side::Bottom, 1.0),
            (Side::Left, 1.0, Side::Top, 0.0),
            (Side::Right, 1.0, Side::Top, 1.0),
        ];
        for (s1, f1, s2, f2) in corners {
            let near = |side: Side, frac: f64| {
                let len = self.length(side);
                let d = 1e-6 * len;
                self.hold_at(side, if frac == 0.0 { d } else { len - d })
            };
            let holds = [near(s1, f1), near(s2, f2)];
            if holds.contains(&Hold::Clamped) && holds.contains(&Hold::Free) {
                out.push(Singularity {
                    point: point(s1, f1 * self.length(s1)),
                    holds,
                    corner: true,
                    contact_end: false,
                });
            }
        }
        // The ends of Gamma_3 inside the bottom (the ends of the zone held at the limit
        // move with the solution and are not graded towards).
        let tol = self.tol();
        for a in self.contact {
            let inside = a > tol && a < w - tol;
            let known = out
                .iter()
                .any(|s| (s.point[0] - a).abs() <= tol && s.point[1] == 0.0);
            if inside && !known {
                let d = 1e-6 * w;
                out.push(Singularity {
                    point: [a, 0.0],
                    holds: [
                        self.hold_at(Side::Bottom, a - d),
                        self.hold_at(Side::Bottom, a + d),
                    ],
                    corner: false,
                    contact_end: true,
                });
            }
        }
        out
    }

    /// The scene in words, one line each: the rectangle and $\Gamma_3$, the supports,
    /// the singular points.
    pub fn describe(&self) -> Vec<String> {
        let held: Vec<String> = self
            .supports
            .iter()
            .map(|s| format!("{} [{}, {}] {}", s.side.name(), s.from, s.to, s.hold))
            .collect();
        let sing = self.singularities();
        let pts: Vec<String> = sing
            .iter()
            .map(|s| format!("({}, {})", s.point[0], s.point[1]))
            .collect();
        vec![
            format!(
                "  geometry: (0, {}) x (0, {}), Gamma_3 = [{}, {}] x {{0}}",
                self.width, self.height, self.contact[0], self.contact[1]
            ),
            format!(
                "  supports{}: {}; the rest of the boundary free",
                self.preset
                    .map_or(String::new(), |p| format!(" (preset \"{p}\")")),
                held.join(", ")
            ),
            format!(
                "  singular points (clamp or roller ends, clamped corners beside free sides{}): {}",
                if sing.iter().any(|s| s.contact_end) {
                    ", ends of Gamma_3 inside the bottom"
                } else {
                    ""
                },
                if pts.is_empty() {
                    "none".to_string()
                } else {
                    pts.join(", ")
                }
            ),
        ]
    }

    /// Parses `[geometry]`'s `width`, `height`, `supports` (a preset's name or a table
    /// of sides) and `contact`.
    pub fn from_toml(
        width: Option<f64>,
        height: Option<f64>,
        supports: Option<&toml::Value>,
        contact: Option<&[f64]>,
    ) -> Result<Geometry, InputError> {
        let mut geo = match supports {
            None => Geometry::paper(),
            Some(toml::Value::String(s)) => match s.as_str() {
                "paper" => Geometry::paper(),
                "rollers" => Geometry::rollers(),
                other => {
                    return Err(InputError::field(
                        "geometry.supports",
                        other,
                        "a preset, \"paper\" (the sides clamped on [H/2, H]) or \"rollers\" \
                         (the top clamped, the sides on rollers), or a table of sides \
                         ([geometry.supports] left = ..., right = ..., bottom = ..., top = ...)",
                    ));
                }
            },
            Some(toml::Value::Table(t)) => {
                let mut g = Geometry::paper();
                g.supports = vec![];
                g.preset = None;
                for key in t.keys() {
                    if !Side::ALL.iter().any(|s| s.name() == key) {
                        return Err(InputError::field(
                            format!("geometry.supports.{key}"),
                            "a value",
                            "nothing: the sides are left, right, bottom and top",
                        ));
                    }
                }
                for side in Side::ALL {
                    if let Some(v) = t.get(side.name()) {
                        let field = format!("geometry.supports.{}", side.name());
                        let pieces = crate::support::file::side(&field, v)?;
                        g.supports.extend(pieces.into_iter().map(|p| Segment {
                            side,
                            from: p.from,
                            to: p.to.unwrap_or(f64::NAN),
                            hold: p.hold,
                            field: p.field,
                        }));
                    }
                }
                g
            }
            Some(other) => {
                return Err(InputError::field(
                    "geometry.supports",
                    other.type_str(),
                    "a preset's name (\"paper\", \"rollers\") or a table of sides",
                ));
            }
        };
        if let Some(w) = width {
            geo.width = in_range("geometry.width", w, 1e-6, 1e6)?;
        }
        if let Some(h) = height {
            geo.height = in_range("geometry.height", h, 1e-6, 1e6)?;
        }
        let ratio = geo.height / geo.width;
        if !(1.0 / 64.0..=64.0).contains(&ratio) {
            return Err(InputError::field(
                "geometry.height",
                geo.height,
                format!(
                    "a height between W/64 and 64 W (W = {}): the mesh's cells are near squares",
                    geo.width
                ),
            ));
        }
        // A whole side's segment ends at the side's length, known only now.
        for s in &mut geo.supports {
            if s.to.is_nan() {
                s.to = match s.side {
                    Side::Left | Side::Right => geo.height,
                    Side::Bottom | Side::Top => geo.width,
                };
            }
        }
        // The presets scale with the rectangle (the paper's clamp starts at H/2).
        if geo.preset.is_some() {
            let (w, h) = (geo.width, geo.height);
            for s in &mut geo.supports {
                let len = if s.side.normal() == 0 { h } else { w };
                let base = if s.side.normal() == 0 { 1.0 } else { 2.0 };
                s.from *= len / base;
                s.to *= len / base;
            }
        }
        geo.contact = match contact {
            None => [0.0, geo.width],
            Some([a, b]) => [*a, *b],
            Some(v) => {
                return Err(InputError::field(
                    "geometry.contact",
                    format!("{} number(s)", v.len()),
                    "two numbers [x0, x1]: Gamma_3 = [x0, x1] x {0} on the bottom",
                ));
            }
        };
        let [a, b] = geo.contact;
        if !(a.is_finite() && b.is_finite() && 0.0 <= a && a < b && b <= geo.width) {
            return Err(InputError::field(
                "geometry.contact",
                format!("[{a}, {b}]"),
                format!(
                    "[x0, x1] with 0 <= x0 < x1 <= W = {} (a segment of the bottom)",
                    geo.width
                ),
            ));
        }
        for side in Side::ALL {
            let len = geo.length(side);
            let mut on_side: Vec<&Segment> =
                geo.supports.iter().filter(|s| s.side == side).collect();
            on_side.sort_by(|x, y| x.from.total_cmp(&y.from));
            for s in &on_side {
                if !(s.from.is_finite() && s.to.is_finite())
                    || s.from < 0.0
                    || s.to > len * (1.0 + ON)
                    || s.from >= s.to
                {
                    return Err(InputError::field(
                        &s.field,
                        format!("from = {}, to = {}", s.from, s.to),
                        format!(
                            "0 <= from < to <= {len} (the length of the {} side)",
                            side.name()
                        ),
                    ));
                }
            }
            for w in on_side.windows(2) {
                if w[1].from < w[0].to {
                    return Err(InputError::field(
                        &w[1].field,
                        format!("from = {}", w[1].from),
                        format!(
                            "a segment that does not overlap {} (which ends at {})",
                            w[0].field, w[0].to
                        ),
                    ));
                }
            }
        }
        if let Some(s) = geo
            .holds_on(Side::Bottom, a, b)
            .into_iter()
            .find(|s| s.hold != Hold::Free)
        {
            return Err(InputError::field(
                "geometry.contact",
                format!("[{a}, {b}]"),
                format!(
                    "a contact segment beside the held bottom segment {} ([{}, {}], {}): \
                     Gamma_3 must be free to move normally",
                    s.field,
                    s.from,
                    s.to,
                    s.hold.name()
                ),
            ));
        }
        // A scene with no held component in x or y leaves a rigid motion free, and
        // the elasticity operator singular.
        let held = |c: usize| {
            (geo.supports.iter()).any(|s| s.hold.holds(s.hold.fixes(s.side.normal()))[c])
        };
        for (c, name, rollers) in [(0, "x", "left or right"), (1, "y", "bottom or top")] {
            if !held(c) {
                return Err(InputError::field(
                    "geometry.supports",
                    format!("nothing that holds {name}"),
                    format!(
                        "supports that hold the body in {name} (a clamped segment, or rollers \
                         on the {rollers} side): else it may move rigidly and the elasticity \
                         operator is singular"
                    ),
                ));
            }
        }
        Ok(geo)
    }
}

/// How each square cell is cut into triangles.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Pattern {
    /// The paper's: one diagonal, lower-left to upper-right.
    #[default]
    Diagonal,
    /// One diagonal, lower-right to upper-left.
    Antidiagonal,
    /// Both diagonals: a node at each cell's centre and four triangles per cell.
    /// The centre nodes are numbered after the grid nodes, cell by cell.
    CrissCross,
    /// Not a grid: a mesh of newest-vertex bisection ([`crate::bisection`]), whose
    /// contact segments may differ in length.
    Bisected,
    /// Not a grid: a mesh read from a file ([`crate::msh`], a mesh scene's body).
    File,
}

impl Pattern {
    /// The name used in scenario files (`geometry.pattern`).
    pub fn name(self) -> &'static str {
        match self {
            Pattern::Diagonal => "diagonal",
            Pattern::Antidiagonal => "antidiagonal",
            Pattern::CrissCross => "crisscross",
            Pattern::Bisected => "bisected",
            Pattern::File => "file",
        }
    }

    /// Whether the mesh is a structured grid (nodes numbered row by row, `n` columns and
    /// `ny` rows of cells): not a bisected mesh, not a file's.
    pub fn is_grid(self) -> bool {
        !matches!(self, Pattern::Bisected | Pattern::File)
    }
}
