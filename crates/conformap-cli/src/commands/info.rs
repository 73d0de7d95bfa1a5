//! `conformap info MESH [--json]`: topology and validity of a mesh.

use std::path::PathBuf;

use clap::Args;
use conformap_mesh::TriMesh;
use conformap_operators::{corner_angles, cotan_laplacian, surface_area};
use serde_json::json;

use crate::commands::say;
use crate::failure::Failure;

/// Arguments of `conformap info`.
#[derive(Debug, Args)]
pub struct InfoArgs {
    /// The mesh (.obj, .gltf, .glb).
    pub mesh: PathBuf,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
}

/// Runs `conformap info`.
pub fn run(args: &InfoArgs) -> Result<(), Failure> {
    let loaded = conformap_io::read_mesh(&args.mesh)?;
    let value = describe(&loaded.mesh, &args.mesh);
    if args.json {
        say(&serde_json::to_string_pretty(&value).unwrap_or_default());
    } else {
        print_text(&value);
    }
    Ok(())
}

/// Everything `info` reports about a valid mesh, as JSON.
pub fn describe(mesh: &TriMesh, path: &std::path::Path) -> serde_json::Value {
    let loops: Vec<usize> = mesh.boundary_loops().iter().map(Vec::len).collect();
    let wc = mesh.well_conditioned();
    let l = cotan_laplacian(mesh);
    // an edge's weight is −L_ij; count edges (upper triangle) with negative weight
    let mut negative = 0usize;
    for (j, col) in l.outer_iterator().enumerate() {
        for (i, &v) in col.iter() {
            if i < j && v > 0.0 {
                negative += 1;
            }
        }
    }
    let angles = corner_angles(mesh);
    let (mut amin, mut amax) = (f64::INFINITY, 0.0f64);
    for a in angles.iter().flatten() {
        amin = amin.min(*a);
        amax = amax.max(*a);
    }
    json!({
        "path": path.display().to_string(),
        "valid": true,
        "vertices": mesh.num_vertices(),
        "faces": mesh.num_faces(),
        "edges": mesh.num_edges(),
        "euler_characteristic": mesh.euler_characteristic(),
        "genus": mesh.genus(),
        "components": mesh.num_components(),
        "boundaries": loops.len(),
        "boundary_loop_sizes": loops,
        "topology": mesh.topology().to_string(),
        "bbox_diagonal": mesh.bbox_diagonal(),
        "surface_area": surface_area(mesh),
        "angle_min_deg": amin.to_degrees(),
        "angle_max_deg": amax.to_degrees(),
        "negative_cotan_edges": negative,
        "negative_cotan_edge_fraction": negative as f64 / mesh.num_edges() as f64,
        "well_conditioned": {
            "holds": wc.holds(),
            "connected": wc.connected,
            "interior_connected": wc.interior_connected,
            "boundary_connected": wc.boundary_connected,
            "boundary_vertices_without_interior_neighbor":
                wc.boundary_vertices_without_interior_neighbor.len(),
        },
    })
}

fn print_text(v: &serde_json::Value) {
    let g = |k: &str| v.get(k).cloned().unwrap_or(serde_json::Value::Null);
    say(&format!(
        "mesh:        {}",
        g("path").as_str().unwrap_or("")
    ));
    say(&format!(
        "topology:    {}",
        g("topology").as_str().unwrap_or("")
    ));
    say(&format!("vertices:    {}", g("vertices")));
    say(&format!("faces:       {}", g("faces")));
    say(&format!("edges:       {}", g("edges")));
    say(&format!("euler char.: {}", g("euler_characteristic")));
    say(&format!("genus:       {}", g("genus")));
    say(&format!("components:  {}", g("components")));
    say(&format!(
        "boundaries:  {} (sizes {})",
        g("boundaries"),
        g("boundary_loop_sizes")
    ));
    say(&format!(
        "bbox diag.:  {:.6e}",
        g("bbox_diagonal").as_f64().unwrap_or(f64::NAN)
    ));
    say(&format!(
        "area:        {:.6e}",
        g("surface_area").as_f64().unwrap_or(f64::NAN)
    ));
    say(&format!(
        "angles:      {:.2}° .. {:.2}°",
        g("angle_min_deg").as_f64().unwrap_or(f64::NAN),
        g("angle_max_deg").as_f64().unwrap_or(f64::NAN)
    ));
    say(&format!(
        "non-Delaunay edges (negative cotangent weight): {} ({:.1}%)",
        g("negative_cotan_edges"),
        100.0 * g("negative_cotan_edge_fraction").as_f64().unwrap_or(0.0)
    ));
    say(&format!(
        "CEM well-conditioned (Definition 1): {}",
        v["well_conditioned"]["holds"]
    ));
}
