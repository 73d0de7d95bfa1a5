//! Writes the round-mouth face of the test `round_mouth` (the ICT neutral face with its
//! mouth pursed into an "O" and pushed forward, `doc_support::round_mouth` with
//! `Pucker::DEFAULT`) as an OBJ with its landmark file, to morph, render or measure it:
//!
//! ```text
//! cargo build --release --workspace --examples
//! target/release/examples/round_mouth [NEUTRAL.obj NEUTRAL.landmarks.txt] OUT_DIR/
//! ```
//!
//! Writes `OUT_DIR/ict_round.obj` and `OUT_DIR/ict_round.landmarks.txt` (the neutral
//! face's landmarks: the vertex order is the neutral face's). Without the two inputs it
//! reads `fixtures/morph/ict_neutral`.

use std::fmt::Write as _;
use std::path::PathBuf;

use conformap_morph::doc_support::{round_mouth, Pucker};
use conformap_morph::Landmarks;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (obj, lm, out) = match args.as_slice() {
        [out] => {
            let dir = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../fixtures/morph"));
            (
                dir.join("ict_neutral.obj"),
                dir.join("ict_neutral.landmarks.txt"),
                PathBuf::from(out),
            )
        }
        [obj, lm, out] => (obj.into(), lm.into(), PathBuf::from(out)),
        _ => return Err("usage: round_mouth [NEUTRAL.obj NEUTRAL.landmarks.txt] OUT_DIR/".into()),
    };
    let mesh = conformap_io::read_mesh(&obj)?.mesh;
    let text = std::fs::read_to_string(&lm)?;
    let landmarks = Landmarks::parse(&text)?;
    let find = |name: &str| {
        landmarks
            .names()
            .iter()
            .position(|n| n == name)
            .map(|k| landmarks.vertices()[k])
            .ok_or_else(|| format!("{}: no landmark {name}", lm.display()))
    };
    let corners = (find("mouth_right")?, find("mouth_left")?);
    let round = round_mouth(&mesh, corners, &Pucker::DEFAULT);
    let mut s =
        String::from("# ict_round: ict_neutral with the mouth pursed (examples/round_mouth.rs)\n");
    for p in round.positions() {
        writeln!(s, "v {} {} {}", p[0], p[1], p[2])?;
    }
    for f in round.faces() {
        writeln!(s, "f {} {} {}", f[0] + 1, f[1] + 1, f[2] + 1)?;
    }
    std::fs::create_dir_all(&out)?;
    std::fs::write(out.join("ict_round.obj"), s)?;
    std::fs::write(out.join("ict_round.landmarks.txt"), text)?;
    println!("wrote {}", out.join("ict_round.obj").display());
    Ok(())
}
