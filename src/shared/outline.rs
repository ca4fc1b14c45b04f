//! Pocket outlines from files: the file read as a bounded regular file ([`read_input`]), its
//! text parsed by the core (`outline::read`: DXF, SVG or an x,y point list, told apart by
//! content), messages starting with the file's name.

use super::files::read_input;
use std::path::Path;
use trochoplan_core::geom::P2;
use trochoplan_core::outline::{self, Pockets};

/// Every pocket of the outline file `path` (`what` names the file in read errors).
pub fn read_pockets(path: &Path, what: &str) -> Result<Pockets, String> {
    let text = read_input(path, what)?;
    outline::read(&path.display().to_string(), &text).map_err(|e| e.to_string())
}

/// The one boundary of the outline file `path`: an error names the file when it holds several
/// loops (islands or more pockets) or none.
pub fn read_single(path: &Path, what: &str) -> Result<Vec<P2>, String> {
    read_pockets(path, what)?.single().map(<[P2]>::to_vec).map_err(|e| e.to_string())
}

/// The one pocket of the outline file `path`: its boundary and its islands (the loops directly
/// inside it); an error names the file when it holds several pockets, a loop inside an
/// island, or none.
pub fn read_pocket(path: &Path, what: &str) -> Result<(Vec<P2>, Vec<Vec<P2>>), String> {
    let pockets = read_pockets(path, what)?;
    let (boundary, islands) = pockets.one_pocket().map_err(|e| e.to_string())?;
    Ok((boundary.to_vec(), islands.to_vec()))
}

/// `points` as the point-list text the pocket editor shows and `outline::read` reads back: one
/// "x,y" vertex per line.
pub fn points_text(points: &[P2]) -> String {
    points.iter().map(|p| format!("{},{}\n", p.x, p.y)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_outline_file_reads_to_its_vertices_and_back_to_the_same_text() {
        let dir = tempfile::tempdir().expect("tempdir");
        let file = dir.path().join("p.txt");
        let text = "0,0\n40,0\n40,25\n0,25\n";
        std::fs::write(&file, text).expect("written");
        let pts = read_single(&file, "outline").expect("one loop");
        assert_eq!(pts.len(), 4);
        assert_eq!(points_text(&pts), text);
        // two loops: refused with the file's name
        std::fs::write(&file, "0,0\n4,0\n4,4\n\n10,0\n14,0\n14,4\n").expect("written");
        let e = read_single(&file, "outline").expect_err("two loops");
        assert!(e.contains("p.txt"), "{e}");
    }
}
