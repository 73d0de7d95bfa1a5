//! Time of writing morph frames as OBJ: 60 frames of one mesh (default the shared neutral
//! face), the old path (`write_flat` per frame, in order) against [`ObjFrames`] in order
//! and on all threads, formatting alone, and the same bytes written with
//! `std::fs::write` (no temporary sibling, no rename).
//!
//! ```text
//! cargo run --release -p conformap-io --example frames_speed -- [MESH.obj] [FRAMES] [OUT_DIR]
//! ```

use std::time::Instant;

use conformap_io::{read_mesh, write_flat, ObjFrames};
use rayon::prelude::*;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mesh_path = args.first().cloned().unwrap_or_else(|| {
        concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../../shared/morph/ict_neutral.obj"
        )
        .into()
    });
    let n: usize = args.get(1).map_or(Ok(60), |s| s.parse())?;
    let out = std::path::PathBuf::from(
        args.get(2)
            .cloned()
            .unwrap_or_else(|| "target/frames_speed".into()),
    );
    std::fs::create_dir_all(&out)?;
    let mesh = read_mesh(&mesh_path)?.mesh;
    let frame = |i: usize| -> Vec<[f64; 3]> {
        let s = 1.0 + i as f64 * 1e-3;
        mesh.positions()
            .iter()
            .map(|p| [p[0] * s, p[1], p[2]])
            .collect()
    };
    let path = |tag: &str, i: usize| out.join(format!("{tag}_{i:04}.obj"));
    let time =
        |name: &str, f: &dyn Fn() -> Result<(), Box<dyn std::error::Error + Send + Sync>>| {
            let t = Instant::now();
            let r = f();
            println!(
                "{name:<40} {:>7.1} ms {:?}",
                t.elapsed().as_secs_f64() * 1e3,
                r.err()
            );
        };
    let frames = ObjFrames::new(mesh.faces());
    time("write_flat, in order (before)", &|| {
        for i in 0..n {
            write_flat(path("a", i), &frame(i), mesh.faces())?;
        }
        Ok(())
    });
    time("ObjFrames, in order", &|| {
        for i in 0..n {
            frames.write(path("b", i), &frame(i))?;
        }
        Ok(())
    });
    time("ObjFrames, all threads", &|| {
        (0..n)
            .into_par_iter()
            .try_for_each(|i| frames.write(path("c", i), &frame(i)).map_err(Into::into))
    });
    time("ObjFrames encode only, all threads", &|| {
        let total: usize = (0..n)
            .into_par_iter()
            .map(|i| frames.encode(&frame(i)).map_or(0, |b| b.len()))
            .sum();
        std::hint::black_box(total);
        Ok(())
    });
    time("encode + fs::write, in order", &|| {
        for i in 0..n {
            std::fs::write(
                path("d", i),
                frames.encode(&frame(i)).map_err(|e| format!("{e:?}"))?,
            )?;
        }
        Ok(())
    });
    time("encode + fs::write, all threads", &|| {
        (0..n).into_par_iter().try_for_each(|i| {
            let bytes = frames.encode(&frame(i)).map_err(|e| format!("{e:?}"))?;
            std::fs::write(path("e", i), bytes).map_err(Into::into)
        })
    });
    std::fs::remove_dir_all(&out)?;
    Ok(())
}
