//! Morphs the shared faces (or any disk-like meshes with landmark files) and prints the
//! report and the time of every stage:
//!
//! ```text
//! cargo run --release -p conformap-morph --example faces -- [--hard] [--no-creases] [--lambda X] [--frames N] [--support R] [--step S] \
//!     S1.obj S1.landmarks.txt S2.obj S2.landmarks.txt [...]
//! ```
//!
//! Without surfaces it morphs `../shared/morph/ict_{neutral,wry,pout}`.

use std::time::Instant;

use conformap_morph::quality::{degenerate_faces, max_step, DEGENERATE_AREA_REL};
use conformap_morph::{morph, Landmarks, MorphOptions, Surface};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let mut options = MorphOptions::DEFAULT;
    let mut frames = 60;
    while let Some(k) = args.iter().position(|a| a.starts_with("--")) {
        let flag = args.remove(k);
        match flag.as_str() {
            "--hard" => options = options.with_hard_landmarks(),
            "--no-creases" => options = options.with_crease_matching(false),
            "--lambda" => options = options.with_lambda(args.remove(k).parse()?),
            "--frames" => frames = args.remove(k).parse()?,
            "--support" => options.register.warp.support = args.remove(k).parse()?,
            "--step" => options.register.warp.step = args.remove(k).parse()?,
            other => return Err(format!("unknown flag {other}").into()),
        }
    }
    if args.is_empty() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/morph");
        for name in ["ict_neutral", "ict_wry", "ict_pout"] {
            args.push(format!("{dir}/{name}.obj"));
            args.push(format!("{dir}/{name}.landmarks.txt"));
        }
    }
    let t = Instant::now();
    let mut surfaces = Vec::new();
    for pair in args.chunks(2) {
        let mesh = conformap_io::read_mesh(&pair[0])?.mesh;
        let landmarks = Landmarks::parse(&std::fs::read_to_string(&pair[1])?)?;
        surfaces.push(Surface::new(mesh, landmarks));
    }
    let read_ms = t.elapsed().as_secs_f64() * 1e3;
    let t = Instant::now();
    let m = morph(&surfaces, &options)?;
    let morph_ms = t.elapsed().as_secs_f64() * 1e3;
    let t = Instant::now();
    let times = m.frame_times(frames)?;
    let all: Vec<Vec<[f64; 3]>> = times.iter().map(|&t| m.frame(t)).collect();
    let frames_ms = t.elapsed().as_secs_f64() * 1e3;
    let diag = surfaces[0].mesh.bbox_diagonal();
    let steps: Vec<f64> = all
        .windows(2)
        .map(|w| max_step(&w[0], &w[1]) / diag)
        .collect();
    let degenerate: usize = all
        .iter()
        .map(|p| degenerate_faces(p, m.faces(), diag, DEGENERATE_AREA_REL))
        .max()
        .unwrap_or(0);
    println!("{}", serde_json::to_string_pretty(&m.report)?);
    println!(
        "read {read_ms:.0} ms, morph {morph_ms:.0} ms, {frames} frames {frames_ms:.0} ms; \
         largest frame step {:.3e} of the diagonal (mean {:.3e}); degenerate faces in the \
         worst frame {degenerate}",
        steps.iter().copied().fold(0.0, f64::max),
        steps.iter().sum::<f64>() / steps.len() as f64
    );
    Ok(())
}
