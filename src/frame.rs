//! The contact frame: a change of basis at the nodes of $\Gamma_3$ when the foundation's
//! outward normal $n_f$ is not the paper's $(0, -1)$.
//!
//! The step solvers, the condensation and the certificate work on one dof per contact
//! node, the second of its pair, and read the normal displacement as
//! $u_{\nu,i} = -(\text{that dof})$. With $n_f = (0, -1)$ the pair is Cartesian,
//! $(u_x, u_y)$, and $-u_y = u\cdot n_f$. For another normal each node of $\Gamma_3$
//! carries its displacement in the orthonormal frame
//! $$e = -n_f, \qquad \tau = (e_y, -e_x), \qquad u = a\,\tau + b\,e,$$
//! so that its pair is $(a, b) = (u\cdot\tau, u\cdot e)$ and $-b = u\cdot n_f$ again
//! (with $n_f = (0, -1)$: $\tau = (1, 0)$, $e = (0, 1)$, the identity). Every operator
//! and load is assembled in these coordinates: a block $K_{ij}$ of nodes $i$, $j$
//! becomes $R_i^\top K_{ij} R_j$ and a nodal force $f_i$ becomes $R_i^\top f_i$, with
//! $R = [\tau\ e]$ at a node of the frame and $R = I$ elsewhere. The change is
//! orthogonal, so energies, norms and the solution are the same; only the coordinates
//! of $\Gamma_3$'s nodes differ, and [`crate::mesh::Dofs::expand`] turns them back. A
//! support on $\Gamma_3$ then holds a component of the frame: one parallel or normal
//! to $n_f$ ([`crate::body`] refuses any other).

/// The frame of the nodes of $\Gamma_3$: unit tangent $\tau$ and $e = -n_f$.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// $\tau = (e_y, -e_x)$, the first coordinate's direction.
    pub tau: [f64; 2],
    /// $e = -n_f$, the second coordinate's direction (into the body).
    pub e: [f64; 2],
}

/// The paper's foundation normal, for which no node needs a frame.
pub const PAPER_NORMAL: [f64; 2] = [0.0, -1.0];

impl Frame {
    /// The frame of the outward unit normal `n_f`; `None` for the paper's $(0, -1)$,
    /// where the frame is the Cartesian one.
    pub fn of_normal(n_f: [f64; 2]) -> Option<Frame> {
        (n_f != PAPER_NORMAL).then(|| {
            let e = [-n_f[0], -n_f[1]];
            Frame {
                tau: [e[1], -e[0]],
                e,
            }
        })
    }

    /// The coordinates $(u\cdot\tau, u\cdot e)$ of a Cartesian vector.
    pub fn to_frame(&self, u: [f64; 2]) -> [f64; 2] {
        [
            u[0] * self.tau[0] + u[1] * self.tau[1],
            u[0] * self.e[0] + u[1] * self.e[1],
        ]
    }

    /// The Cartesian vector $a\tau + b e$ of frame coordinates $(a, b)$.
    pub fn to_cartesian(&self, [a, b]: [f64; 2]) -> [f64; 2] {
        [
            a * self.tau[0] + b * self.e[0],
            a * self.tau[1] + b * self.e[1],
        ]
    }

    /// $R = [\tau\ e]$ as rows: `r[c][k]` is Cartesian component `c` of frame direction `k`.
    pub fn matrix(&self) -> [[f64; 2]; 2] {
        [[self.tau[0], self.e[0]], [self.tau[1], self.e[1]]]
    }

    /// Which frame coordinate a Cartesian component `c` (0 = x, 1 = y) is, up to sign,
    /// when the axis is parallel (the normal, 1) or normal (the tangent, 0) to $n_f$;
    /// `None` when it is neither, so a support holding it is not a frame component.
    pub fn slot_of_axis(&self, c: usize) -> Option<usize> {
        let tol = 1e-12;
        if self.e[c].abs() >= 1.0 - tol {
            Some(1)
        } else if self.tau[c].abs() >= 1.0 - tol {
            Some(0)
        } else {
            None
        }
    }
}

/// $R_i^\top M R_j$ for 2×2 blocks, `ri`/`rj` `None` for the identity.
pub fn rotate_block(
    m: [[f64; 2]; 2],
    ri: Option<[[f64; 2]; 2]>,
    rj: Option<[[f64; 2]; 2]>,
) -> [[f64; 2]; 2] {
    let mut out = m;
    if let Some(r) = rj {
        out = std::array::from_fn(|a| {
            std::array::from_fn(|k| out[a][0] * r[0][k] + out[a][1] * r[1][k])
        });
    }
    if let Some(r) = ri {
        out = std::array::from_fn(|k| {
            std::array::from_fn(|b| r[0][k] * out[0][b] + r[1][k] * out[1][b])
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_paper_normal_has_no_frame_and_others_are_orthonormal_with_minus_b_the_normal_part() {
        assert!(Frame::of_normal(PAPER_NORMAL).is_none());
        let s = 0.5f64.sqrt();
        let f = Frame::of_normal([s, -s]).expect("a frame");
        let u = [0.3, -0.7];
        let ab = f.to_frame(u);
        assert!((-ab[1] - (u[0] * s - u[1] * s)).abs() < 1e-15, "-b = u.n_f");
        let back = f.to_cartesian(ab);
        assert!((back[0] - u[0]).abs() < 1e-15 && (back[1] - u[1]).abs() < 1e-15);
        // R^T I R = I: the block of an isotropic term is unchanged.
        let m = rotate_block([[2.0, 0.0], [0.0, 2.0]], Some(f.matrix()), Some(f.matrix()));
        assert!((m[0][0] - 2.0).abs() < 1e-15 && m[0][1].abs() < 1e-15);
        // A normal along x: the y axis is the tangent, x the normal.
        let g = Frame::of_normal([1.0, 0.0]).expect("a frame");
        assert_eq!((g.slot_of_axis(0), g.slot_of_axis(1)), (Some(1), Some(0)));
        assert_eq!((f.slot_of_axis(0), f.slot_of_axis(1)), (None, None));
    }
}
