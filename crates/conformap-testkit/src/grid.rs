//! Faces of a rectangular vertex grid: the pattern under the square grid, the cylinder and
//! the tori, and under the grids tests build with their own positions.

/// The faces of the `nx × ny` cells of an `(nx + 1) × (ny + 1)` vertex grid, vertex `(i, j)`
/// at index `j · (nx + 1) + i`: each cell `(i, j)–(i+1, j+1)` split along that diagonal,
/// counter-clockwise when `i` runs along x and `j` along y. Cell by cell, row by row.
///
/// ```
/// let faces = conformap_testkit::grid_faces(1, 1);
/// assert_eq!(faces, vec![[0, 1, 3], [0, 3, 2]]);
/// ```
pub fn grid_faces(nx: usize, ny: usize) -> Vec<[u32; 3]> {
    wrapped_grid_faces(nx + 1, ny + 1, false, false)
}

/// Triangulates a `(columns × rows)` vertex grid, periodic in the column direction if
/// `wrap_columns` and in the row direction if `wrap_rows`; vertex `(i, j)` has index
/// `j · columns + i`. Each cell `(i, j)–(i+1, j+1)` is split along that diagonal with the
/// orientation of `∂i × ∂j`.
pub(crate) fn wrapped_grid_faces(
    columns: usize,
    rows: usize,
    wrap_columns: bool,
    wrap_rows: bool,
) -> Vec<[u32; 3]> {
    let id = |i: usize, j: usize| ((j % rows) * columns + i % columns) as u32;
    let cell_columns = if wrap_columns { columns } else { columns - 1 };
    let cell_rows = if wrap_rows { rows } else { rows - 1 };
    let mut faces = Vec::with_capacity(2 * cell_columns * cell_rows);
    for j in 0..cell_rows {
        for i in 0..cell_columns {
            faces.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            faces.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    faces
}
