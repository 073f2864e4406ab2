//! How long a mesh scene takes to read (`evhi bench --mesh-read`): the paper's
//! rectangle, data/meshes/paper_n16.msh refined uniformly to level $n$
//! ([`evhi::refine`]), written as ASCII MSH 4.1 into a scratch directory, then read
//! ([`evhi::msh::read`]: the bytes and the parse, with every check on the
//! triangulation), given its parts' roles ([`evhi::body::Body::new`]: the groups,
//! $\Gamma_3$ in order, the rigid-motion check) and made the mesh the loops solve on
//! ([`evhi::mesh::Mesh::from_body`]).

use super::tables::MeshReadRow;
use evhi::body::{Body, Foundation, PartTraction};
use evhi::study::{Ctx, ExpError};
use evhi::timing::median;
use std::time::Instant;

/// The committed paper mesh the generated ones refine (the mesh-solve bench's too).
pub const PAPER_N16: &[u8] = include_bytes!("../../data/meshes/paper_n16.msh");

/// Refuses a level that is not 16 times a power of two (the paper mesh refined).
pub fn check_level(n: usize) -> Result<usize, evhi::error::InputError> {
    let k = (n / 16).trailing_zeros() as usize;
    if n < 16 || n != 16 << k || k > 6 {
        return Err(evhi::error::InputError::field(
            "--mesh-read-levels",
            n,
            "16 times a power of two up to 1024 (data/meshes/paper_n16.msh refined)",
        ));
    }
    Ok(k)
}

/// Times each level's read `repeat` times and writes `bench_mesh.csv`.
pub fn run(ctx: &Ctx, levels: &[usize], repeat: usize, machine: &str) -> Result<(), ExpError> {
    let io = |path: &std::path::Path, e: std::io::Error| {
        ExpError::File(evhi::output::FileError::Io {
            path: path.display().to_string(),
            source: e,
        })
    };
    let dir = std::env::temp_dir().join(format!("evhi-bench-mesh-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| io(&dir, e))?;
    let mut coarse = evhi::msh::parse(PAPER_N16, "paper_n16.msh")?;
    let mut at = 16;
    let mut rows = vec![];
    for &n in levels {
        check_level(n)?;
        while at < n {
            coarse = evhi::refine::refine(&coarse).mesh;
            at *= 2;
        }
        let path = dir.join(format!("paper_n{n}.msh"));
        let text = evhi::msh::write(&coarse);
        std::fs::write(&path, &text).map_err(|e| io(&path, e))?;
        let file = path.display().to_string();
        let (mut read, mut body, mut mesh) = (vec![], vec![], vec![]);
        for r in 0..repeat {
            evhi::diag!("  mesh read: n = {n}, run {}", r + 1);
            let t = Instant::now();
            let bytes = evhi::msh::read_bytes(&path, &file)?;
            let m = evhi::msh::parse(&bytes, &file)?;
            read.push(t.elapsed().as_secs_f64());
            let t = Instant::now();
            let b = Body::new(
                &file,
                m,
                &[("clamped".into(), evhi::support::Hold::Clamped)],
                "bottom",
                vec![PartTraction {
                    part: "top".into(),
                    f: [0.0, -75.0],
                    field: "loads.traction[0]".into(),
                }],
                Foundation::default(),
                None,
                bytes,
            )?;
            body.push(t.elapsed().as_secs_f64());
            let t = Instant::now();
            let solved = evhi::mesh::Mesh::from_body(&b);
            mesh.push(t.elapsed().as_secs_f64());
            std::hint::black_box(solved);
        }
        let (r, b, m) = (median(read), median(body), median(mesh));
        rows.push(MeshReadRow {
            n: n as u64,
            triangles: coarse.triangles.len() as u64,
            nodes: coarse.nodes.len() as u64,
            file_mb: text.len() as f64 / 1e6,
            read_s: r,
            body_s: b,
            mesh_s: m,
            total_s: r + b + m,
        });
        let _ = std::fs::remove_file(&path);
    }
    let _ = std::fs::remove_dir_all(&dir);
    ctx.write_as(
        "bench_mesh.csv",
        &MeshReadRow::table(&rows),
        "bench --mesh-read",
        &format!(
            "machine: {machine}; the paper's rectangle, data/meshes/paper_n16.msh refined uniformly to level n and written as ASCII MSH 4.1; read_s = evhi::msh::read (the bytes and the parse, with its checks), body_s = Body::new (the parts' roles), mesh_s = Mesh::from_body; medians of {repeat} runs in one process; total_s the sum of the medians"
        ),
    )?;
    Ok(())
}
