//! VTK XML unstructured grid (`.vtu`, ASCII) of the deformed body for ParaView:
//! points in the reference configuration, the displacement as point data (use
//! ParaView's "Warp By Vector" to deform), and the contact state on $\Gamma_3$.

use crate::certificate::ContactState;
use crate::mesh::Mesh;
use std::fmt::Write;

/// A ParaView collection (`.pvd`) of `(time, file)` pairs: one dataset per time step,
/// so that ParaView animates the evolution.
pub fn pvd(steps: &[(f64, String)]) -> String {
    let mut s = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n<Collection>\n",
    );
    for (t, file) in steps {
        let _ = writeln!(
            s,
            "<DataSet timestep=\"{t:e}\" group=\"\" part=\"0\" file=\"{file}\"/>"
        );
    }
    s.push_str("</Collection>\n</VTKFile>\n");
    s
}

/// The grid as VTU text. `disp` holds one displacement per node; `contact` the
/// states of the contact nodes (in `mesh.contact` order) and `regimes` their regime
/// codes ([`ContactState::regime_code`]; written as `regime`, $-1$ off $\Gamma_3$).
pub fn vtu(mesh: &Mesh, disp: &[[f64; 2]], contact: &[ContactState], regimes: &[i32]) -> String {
    vtu_cells(mesh, disp, contact, regimes, &[])
}

/// [`vtu`] with cell fields: each `(name, values)` one value per triangle (the
/// estimator's `eta`, [`crate::estimator`]).
pub fn vtu_cells(
    mesh: &Mesh,
    disp: &[[f64; 2]],
    contact: &[ContactState],
    regimes: &[i32],
    cells: &[(&str, &[f64])],
) -> String {
    let (np, nc) = (mesh.nodes.len(), mesh.triangles.len());
    let mut s = String::new();
    let _ = writeln!(s, r#"<?xml version="1.0"?>"#);
    let _ = writeln!(
        s,
        r#"<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian">"#
    );
    let _ = writeln!(
        s,
        "<UnstructuredGrid><Piece NumberOfPoints=\"{np}\" NumberOfCells=\"{nc}\">"
    );
    let _ = writeln!(
        s,
        r#"<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">"#
    );
    for p in &mesh.nodes {
        let _ = writeln!(s, "{} {} 0", p[0], p[1]);
    }
    let _ = writeln!(s, "</DataArray></Points>");
    let _ = writeln!(
        s,
        r#"<Cells><DataArray type="Int64" Name="connectivity" format="ascii">"#
    );
    for t in &mesh.triangles {
        let _ = writeln!(s, "{} {} {}", t[0], t[1], t[2]);
    }
    let _ = writeln!(
        s,
        r#"</DataArray><DataArray type="Int64" Name="offsets" format="ascii">"#
    );
    for c in 0..nc {
        let _ = write!(s, "{} ", 3 * (c + 1));
    }
    let _ = writeln!(
        s,
        r#"</DataArray><DataArray type="UInt8" Name="types" format="ascii">"#
    );
    for _ in 0..nc {
        let _ = write!(s, "5 ");
    }
    let _ = writeln!(s, "</DataArray></Cells>");
    let _ = writeln!(s, r#"<PointData Vectors="displacement">"#);
    let _ = writeln!(
        s,
        r#"<DataArray type="Float64" Name="displacement" NumberOfComponents="3" format="ascii">"#
    );
    for d in disp {
        let _ = writeln!(s, "{} {} 0", d[0], d[1]);
    }
    let _ = writeln!(s, "</DataArray>");
    let mut sig = vec![[0.0f64; 2]; np];
    for (i, &v) in mesh.contact.iter().enumerate() {
        if let Some(c) = contact.get(i) {
            sig[v] = [c.sigma_nu1, c.sigma_nu2];
        }
    }
    for (k, name) in ["sigma_nu1", "sigma_nu2"].iter().enumerate() {
        let _ = writeln!(
            s,
            r#"<DataArray type="Float64" Name="{name}" format="ascii">"#
        );
        for v in &sig {
            let _ = write!(s, "{} ", v[k]);
        }
        let _ = writeln!(s, "\n</DataArray>");
    }
    let mut code = vec![-1i32; np];
    for (i, &v) in mesh.contact.iter().enumerate() {
        if let Some(&r) = regimes.get(i) {
            code[v] = r;
        }
    }
    let _ = writeln!(
        s,
        r#"<DataArray type="Int32" Name="regime" format="ascii">"#
    );
    for r in &code {
        let _ = write!(s, "{r} ");
    }
    let _ = writeln!(s, "\n</DataArray>");
    let _ = writeln!(s, "</PointData>");
    if !cells.is_empty() {
        let _ = writeln!(s, "<CellData>");
        for (name, vals) in cells {
            let _ = writeln!(
                s,
                r#"<DataArray type="Float64" Name="{name}" format="ascii">"#
            );
            for v in vals.iter() {
                let _ = write!(s, "{v} ");
            }
            let _ = writeln!(s, "\n</DataArray>");
        }
        let _ = writeln!(s, "</CellData>");
    }
    let _ = writeln!(s, "</Piece></UnstructuredGrid></VTKFile>");
    s
}
