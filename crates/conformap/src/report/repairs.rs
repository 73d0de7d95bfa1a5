//! The `repairs` object of a report: the [`RepairLog`] of `--repair`, written as what it
//! changed and the sizes of the maps back to the input.

use conformap_mesh::RepairLog;
use serde::ser::SerializeStruct;
use serde::{Serialize, Serializer};

/// What `--repair` changed: the mesh crate's [`RepairLog`], serialized for the report
/// (the vertex and face maps by their sizes only).
#[derive(Debug, Clone)]
pub struct RepairsReport(pub RepairLog);

/// The sizes of the vertex maps (keys sorted).
#[derive(Serialize)]
struct VertexMapSizes {
    input_to_repaired: usize,
    repaired_to_input: usize,
}

/// The size of the face map.
#[derive(Serialize)]
struct FaceMapSizes {
    repaired_to_input: usize,
}

impl Serialize for RepairsReport {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let log = &self.0;
        let mut s = serializer.serialize_struct("RepairsReport", 11)?;
        s.serialize_field("applied", &log.actions())?;
        s.serialize_field("input_vertices", &log.input_vertices)?;
        s.serialize_field("input_faces", &log.input_faces)?;
        s.serialize_field("duplicate_faces", &log.duplicate_faces)?;
        s.serialize_field("components", &log.components)?;
        s.serialize_field("component_faces_dropped", &log.component_faces_dropped)?;
        s.serialize_field(
            "component_vertices_dropped",
            &log.component_vertices_dropped,
        )?;
        s.serialize_field("flipped_faces", &log.flipped_faces)?;
        s.serialize_field("unreferenced_vertices", &log.unreferenced_vertices)?;
        let vertex_map = VertexMapSizes {
            input_to_repaired: log.input_to_vertex.len(),
            repaired_to_input: log.vertex_to_input.len(),
        };
        s.serialize_field("vertex_map", &vertex_map)?;
        let face_map = FaceMapSizes {
            repaired_to_input: log.face_to_input.len(),
        };
        s.serialize_field("face_map", &face_map)?;
        s.end()
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test
mod tests {
    use conformap_mesh::{repair, RepairOptions};

    use super::*;

    /// A square of two triangles with the second one given twice and an unused vertex:
    /// the report says so in the order of the report schema, the maps by their sizes.
    #[test]
    fn repairs_are_written_from_the_log_in_schema_order() {
        let positions = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [5.0, 5.0, 5.0],
        ];
        let faces = [[0, 1, 2], [0, 2, 3], [0, 2, 3]];
        let log = repair(&positions, &faces, &RepairOptions::DEFAULT)
            .unwrap()
            .log;
        let json = serde_json::to_string(&RepairsReport(log)).unwrap();
        let keys: Vec<&str> = json
            .split('"')
            .skip(1)
            .step_by(2)
            .filter(|k| k.chars().all(|c| c == '_' || c.is_ascii_lowercase()))
            .collect();
        let order = [
            "applied",
            "input_vertices",
            "input_faces",
            "duplicate_faces",
            "components",
            "component_faces_dropped",
            "component_vertices_dropped",
            "flipped_faces",
            "unreferenced_vertices",
            "vertex_map",
            "input_to_repaired",
            "repaired_to_input",
            "face_map",
            "repaired_to_input",
        ];
        assert_eq!(keys, order, "{json}");
        let v: serde_json::Value = serde_json::from_str(&json).unwrap();
        assert_eq!(v["duplicate_faces"], 1);
        assert_eq!(v["unreferenced_vertices"], 1);
        assert_eq!(v["vertex_map"]["repaired_to_input"], 4);
        assert_eq!(v["vertex_map"]["input_to_repaired"], 5);
        assert_eq!(v["face_map"]["repaired_to_input"], 2);
    }
}
