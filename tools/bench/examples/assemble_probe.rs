//! Probe (not a test): the assembly stages of one mesh's cotangent Laplacian, each repeated
//! in one process, medians printed.
//! `cargo run --release -p conformap-bench --example assemble_probe -- MESH.obj [RUNS]`
use std::time::Instant;

use conformap_operators::{cotan_laplacian, LaplacianBlocks, Partition};

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn time<T>(runs: usize, mut f: impl FnMut() -> T) -> f64 {
    median(
        (0..runs)
            .map(|_| {
                let t = Instant::now();
                std::hint::black_box(f());
                t.elapsed().as_secs_f64() * 1e3
            })
            .collect(),
    )
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let path = args.next().ok_or("MESH.obj")?;
    let runs: usize = args.next().map_or(Ok(7), |r| r.parse())?;
    let bytes = std::fs::read(&path)?;
    let raw = conformap_io::read_mesh(std::path::Path::new(&path))?;
    let mesh = raw.mesh;
    let (p, f) = (mesh.positions().to_vec(), mesh.faces().to_vec());
    println!(
        "{path}: {} vertices, {} faces, {} bytes",
        mesh.num_vertices(),
        mesh.num_faces(),
        bytes.len()
    );
    println!(
        "TriMesh::try_new {:.1} ms",
        time(runs, || conformap_mesh::TriMesh::try_new(
            p.clone(),
            f.clone()
        ))
    );
    println!(
        "vertex_adjacency {:.1} ms",
        time(runs, || mesh.vertex_adjacency())
    );
    println!(
        "corner_cotangents {:.1} ms",
        time(runs, || conformap_operators::corner_cotangents(&mesh))
    );
    println!(
        "cotan_laplacian {:.1} ms",
        time(runs, || cotan_laplacian(&mesh))
    );
    let l = cotan_laplacian(&mesh);
    let part = Partition::new(mesh.num_vertices(), &[0]);
    println!(
        "Partition::new {:.1} ms",
        time(runs, || Partition::new(mesh.num_vertices(), &[0]))
    );
    println!(
        "LaplacianBlocks::new {:.1} ms",
        time(runs, || LaplacianBlocks::new(&l, &part))
    );
    let blocks = LaplacianBlocks::new(&l, &part);
    let each: Vec<String> = (0..runs)
        .map(|_| {
            let t = Instant::now();
            let c = conformap_operators::Cholesky::factor_with(
                &blocks.ii,
                &conformap_operators::CholeskyOptions::DEFAULT,
            );
            let ms = t.elapsed().as_secs_f64() * 1e3;
            match c {
                Ok(c) => format!(
                    "{ms:.0} ({:.0}+{:.0})",
                    c.stats().analyse_ms,
                    c.stats().factor_ms
                ),
                Err(e) => e.to_string(),
            }
        })
        .collect();
    println!("factor runs: {}", each.join(", "));
    if mesh.genus().unwrap_or(0) > 0 && mesh.boundary_loops().is_empty() {
        println!(
            "homology_basis {:.1} ms",
            time(runs, || conformap_mesh::homology_basis(&mesh, None))
        );
        let basis = conformap_mesh::homology_basis(&mesh, None)?;
        println!(
            "cut_graph {:.1} ms",
            time(runs, || conformap_mesh::cut_graph(&mesh, &basis))
        );
        let on_cut = conformap_mesh::cut_graph(&mesh, &basis);
        println!(
            "cut_mesh {:.1} ms",
            time(runs, || conformap_mesh::cut_mesh(
                &mesh,
                &basis,
                on_cut.clone()
            ))
        );
    }
    Ok(())
}
