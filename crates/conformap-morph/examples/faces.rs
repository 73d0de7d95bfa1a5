//! Morphs the shared faces (or any disk-like meshes with landmark files) and prints the
//! report and the time of every stage:
//!
//! ```text
//! cargo run --release -p conformap-morph --example faces -- [--hard] [--no-creases] [--no-refine] [--lambda X] [--frames N] [--support R] [--step S] \
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
            "--no-refine" => options = options.with_key_frame_refinement(false),
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
    // how much the correspondence bends S1's triangles: the largest change of a corner
    // angle per face, S1 against every key frame
    for (k, key) in m.keys().iter().enumerate().skip(1) {
        let mut change: Vec<f64> = m
            .faces()
            .iter()
            .map(|f| {
                let (a, b) = (
                    corner_angles(surfaces[0].mesh.positions(), f),
                    corner_angles(key, f),
                );
                (0..3)
                    .map(|c| (a[c] - b[c]).abs().to_degrees())
                    .fold(0.0, f64::max)
            })
            .collect();
        change.sort_by(f64::total_cmp);
        let q = |p: f64| change[((change.len() - 1) as f64 * p).round() as usize];
        println!(
            "key {k}: largest corner-angle change per face against S1: median {:.2}°, 90 % {:.2}°, 99 % {:.2}°",
            q(0.5),
            q(0.9),
            q(0.99)
        );
    }
    println!(
        "read {read_ms:.0} ms, morph {morph_ms:.0} ms, {frames} frames {frames_ms:.0} ms; \
         largest frame step {:.3e} of the diagonal (mean {:.3e}); degenerate faces in the \
         worst frame {degenerate}",
        steps.iter().copied().fold(0.0, f64::max),
        steps.iter().sum::<f64>() / steps.len() as f64
    );
    Ok(())
}

/// The three corner angles (radians) of face `f` of `p`.
fn corner_angles(p: &[[f64; 3]], f: &[u32; 3]) -> [f64; 3] {
    let [a, b, c] = f.map(|v| p[v as usize]);
    let angle = |o: [f64; 3], x: [f64; 3], y: [f64; 3]| {
        let u = [x[0] - o[0], x[1] - o[1], x[2] - o[2]];
        let w = [y[0] - o[0], y[1] - o[1], y[2] - o[2]];
        let dot = u[0] * w[0] + u[1] * w[1] + u[2] * w[2];
        let cross = [
            u[1] * w[2] - u[2] * w[1],
            u[2] * w[0] - u[0] * w[2],
            u[0] * w[1] - u[1] * w[0],
        ];
        (cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2])
            .sqrt()
            .atan2(dot)
    };
    [angle(a, b, c), angle(b, c, a), angle(c, a, b)]
}
