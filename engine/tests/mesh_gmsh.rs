//! gmsh reader: hand-written and gmsh-written files in both formats, and
//! line-numbered errors for malformed files.

/// Under `mesh::` so that `cargo test -p ctc-engine mesh` selects them.
mod mesh {

    use ctc_engine::mesh::gmsh::{parse, parse_bytes, read};
    use ctc_engine::mesh::quality::cell_area;
    use ctc_engine::mesh::validate::check;
    use ctc_engine::mesh::{Cell, CellKind, Mesh, MeshError};
    use std::collections::BTreeSet;
    use std::f64::consts::PI;
    use std::path::PathBuf;

    fn data(name: &str) -> PathBuf {
        PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("tests/data")
            .join(name)
    }

    fn text(name: &str) -> String {
        std::fs::read_to_string(data(name)).unwrap()
    }

    fn err(text: &str) -> MeshError {
        match parse(text) {
            Ok(m) => panic!("accepted: {} nodes", m.nodes.len()),
            Err(e) => e,
        }
    }

    /// Boundary edges (from the cells) equal the union of the named edge sets,
    /// all cells counter-clockwise, `check` passes; returns the area.
    fn boundary_is_union(m: &Mesh, names: &[&str]) -> f64 {
        check(m).unwrap_or_else(|e| panic!("{e:?}"));
        let boundary: BTreeSet<[usize; 2]> =
            m.boundary_edges(0..m.cells.len()).into_iter().collect();
        let union: BTreeSet<[usize; 2]> = names
            .iter()
            .flat_map(|n| m.edge_sets[*n].iter().copied())
            .collect();
        assert_eq!(boundary, union);
        m.cells
            .iter()
            .map(|c| {
                let a = cell_area(m, c);
                assert!(a > 0.0);
                a
            })
            .sum()
    }

    /// Area of the fan of triangles from the origin to the edges of `set`.
    fn fan_area(m: &Mesh, set: &str) -> f64 {
        m.edge_sets[set]
            .iter()
            .map(|e| {
                let (p, q) = (m.nodes[e[0]], m.nodes[e[1]]);
                0.5 * (p[0] * q[1] - p[1] * q[0]).abs()
            })
            .sum()
    }

    #[test]
    fn hand_two_quads_v22_and_v41_read_to_the_same_mesh() {
        let a = read(&data("hand_two_quads_v22.msh")).unwrap();
        let b = read(&data("hand_two_quads_v41.msh")).unwrap();
        assert_eq!(a, b);
        // node 99 (off the mesh) dropped, tags renumbered densely in file order
        assert_eq!(
            a.nodes,
            vec![
                [0.0, 0.0],
                [1.0, 0.0],
                [2.0, 0.0],
                [0.0, 1.0],
                [1.0, 1.0],
                [2.0, 1.0]
            ]
        );
        // the clockwise quad 20 50 60 30 is reversed
        assert_eq!(
            a.cells,
            [Cell::quad(0, 1, 4, 3), Cell::quad(1, 2, 5, 4)]
                .into_iter()
                .collect()
        );
        // lines oriented with the body on the left whatever their file direction
        assert_eq!(a.edge_sets["top"], vec![[4, 3], [5, 4]]);
        assert_eq!(a.node_sets["top"], vec![3, 4, 5]);
        assert_eq!(a.edge_sets["physical_5"], vec![[3, 0]]);
        assert_eq!(a.node_sets["pin"], vec![0]);
        assert_eq!(a.node_sets["body"], vec![0, 1, 2, 3, 4, 5]);
        assert!(!a.edge_sets.contains_key("body"));
        assert_eq!(check(&a), Ok(()));
    }

    #[test]
    fn gmsh_plate_with_hole_v22_and_v41_same_mesh() {
        let a = parse(&text("gmsh_plate_hole_v22.msh")).unwrap();
        let b = parse(&text("gmsh_plate_hole_v41.msh")).unwrap();
        // gmsh numbers nodes alike in both versions: identical meshes
        assert_eq!(a, b);
        let area = boundary_is_union(&a, &["left", "bottom", "right", "top", "hole"]);
        let exact = 2.0 - PI * 0.09 / 4.0;
        // the mesh fills the plate minus the polygon inscribed in the hole
        let polygonal = 2.0 - fan_area(&a, "hole");
        println!(
            "gmsh plate with hole: {} nodes, {} triangles, area {area:.12} (plate minus inscribed \
         hole polygon {polygonal:.12}, exact circle {exact:.6})",
            a.nodes.len(),
            a.cells.len()
        );
        assert!((area - polygonal).abs() < 1e-12);
        assert!(area > exact && area - exact < 1e-2);
        assert!(a.cells.iter().all(|c| c.kind == CellKind::Tri3));
        assert_eq!(a.nodes[a.node_sets["corner"][0]], [2.0, 1.0]);
        for &n in &a.node_sets["hole"] {
            let r = a.nodes[n][0].hypot(a.nodes[n][1]);
            assert!((r - 0.3).abs() < 1e-12);
        }
        for &n in &a.node_sets["right"] {
            assert_eq!(a.nodes[n][0], 2.0);
        }
        assert_eq!(a.node_sets["plate"].len(), a.nodes.len());
    }

    #[test]
    fn gmsh_quarter_disc_quads_v22_and_v41_same_mesh() {
        let a = parse(&text("gmsh_quarter_disc_quads_v22.msh")).unwrap();
        let b = parse(&text("gmsh_quarter_disc_quads_v41.msh")).unwrap();
        // gmsh numbers nodes alike in both versions: identical meshes
        assert_eq!(a, b);
        let area = boundary_is_union(&a, &["arc", "axis", "flat"]);
        let quads = a.cells.iter().filter(|c| c.kind == CellKind::Quad4).count();
        println!(
            "gmsh quarter disc: {} nodes, {quads} quads of {} cells, area {area:.6} (pi/4 = {:.6})",
            a.nodes.len(),
            a.cells.len(),
            PI / 4.0
        );
        assert!(quads >= 20 && quads < a.cells.len(), "a mixed mesh");
        assert!((area - fan_area(&a, "arc")).abs() < 1e-12);
        assert!(area < PI / 4.0 && PI / 4.0 - area < 1e-2);
        // the unnamed physical surface 7
        assert_eq!(a.node_sets["physical_7"].len(), a.nodes.len());
        for &n in &a.node_sets["axis"] {
            assert_eq!(a.nodes[n][0], 0.0);
        }
    }

    /// Every prefix of a valid file (cut at a line end) is an error at a line
    /// of the prefix, never a panic.
    #[test]
    fn truncated_files_give_line_numbered_errors() {
        for name in ["hand_two_quads_v22.msh", "hand_two_quads_v41.msh"] {
            let t = text(name);
            let lines: Vec<&str> = t.lines().collect();
            for k in 0..lines.len() {
                let prefix = lines[..k].join("\n");
                let e = err(&prefix);
                let line = e.line.expect("line number");
                assert!(line >= 1 && line <= k.max(1), "{name} cut at {k}: {e}");
            }
        }
        let e = err(&text("hand_two_quads_v41.msh").replace("$EndElements\n", ""));
        assert!(e.message.contains("end of file"), "{e}");
    }

    #[test]
    fn bad_counts_give_line_numbered_errors() {
        let v2 = text("hand_two_quads_v22.msh");
        // more nodes announced than listed: the $EndNodes line
        let e = err(&v2.replace("$Nodes\n7\n", "$Nodes\n8\n"));
        assert_eq!(e.line, Some(25), "{e}");
        assert!(e.message.contains("$EndNodes"), "{e}");
        // fewer: the first unread entry
        let e = err(&v2.replace("$Nodes\n7\n", "$Nodes\n6\n"));
        assert_eq!(e.line, Some(24), "{e}");
        let v41 = text("hand_two_quads_v41.msh");
        // block sizes do not add up to the header count
        let e = err(&v41.replace("$Nodes\n3 7 10 99", "$Nodes\n3 9 10 99"));
        assert_eq!(e.line, Some(19), "{e}");
        assert!(e.message.contains("announces 9 nodes"), "{e}");
        let e = err(&v41.replace("$Elements\n4 6 1 6", "$Elements\n4 5 1 6"));
        assert_eq!(e.line, Some(39), "{e}");
    }

    #[test]
    fn unknown_node_tag_and_duplicate_tag_reported_at_their_line() {
        let v2 = text("hand_two_quads_v22.msh");
        let e = err(&v2.replace("6 3 2 2 1 20 50 60 30", "6 3 2 2 1 20 50 61 30"));
        assert_eq!(e.line, Some(33), "{e}");
        assert!(e.message.contains("node tag 61"), "{e}");
        let e = err(&v2.replace("99 5 5 0", "20 5 5 0"));
        assert_eq!(e.line, Some(24), "{e}");
        assert!(
            e.message.contains("defined twice (first at line 19)"),
            "{e}"
        );
    }

    #[test]
    fn unsupported_elements_and_binary_give_clear_errors() {
        let v2 = text("hand_two_quads_v22.msh");
        // a third-order (10-node) triangle; second order is read
        let e = err(&v2.replace("5 3 2 2 1 10 20 50 40", "5 21 2 2 1 10 20 50 40 30 60"));
        assert_eq!(e.line, Some(32));
        assert!(e.message.contains("higher-order"), "{e}");
        let e = err(&v2.replace("5 3 2 2 1 10 20 50 40", "5 4 2 2 1 10 20 50 40"));
        assert!(e.message.contains("3D"), "{e}");
        let e = err(&v2.replace("2.2 0 8", "2.2 1 8"));
        assert_eq!(e.line, Some(2));
        assert!(e.message.contains("binary"), "{e}");
        // a real binary file: header then raw bytes
        let mut bytes = b"$MeshFormat\n4.1 1 8\n".to_vec();
        bytes.extend_from_slice(&1i32.to_le_bytes());
        bytes.extend_from_slice(b"\n$EndMeshFormat\n$Nodes\n");
        bytes.extend_from_slice(&[0x80, 0xff, 0x00, 0x13]);
        let e = parse_bytes(&bytes).unwrap_err();
        assert_eq!(e.line, Some(2));
        assert!(e.message.contains("binary"), "{e}");
    }

    #[test]
    fn group_errors_line_off_mesh_unnamed_clash_mixed_interior() {
        let v2 = text("hand_two_quads_v22.msh");
        // a physical line that is no cell edge (diagonal 10-50)
        let e = err(&v2.replace("4 1 2 5 4 10 40", "4 1 2 5 4 10 50"));
        assert_eq!(e.line, Some(31));
        assert!(e.message.contains("not an edge"), "{e}");
        // unnamed groups of dimensions 1 and 2 with the same tag
        let e = err(&v2
            .replace("4 1 2 5 4 10 40", "4 1 2 2 4 10 40")
            .replace("2 2 \"body\"\n", "")
            .replace("PhysicalNames\n3", "PhysicalNames\n2"));
        assert!(e.message.contains("physical_2"), "{e}");
        // the interior edge 20-50 in a group with boundary lines
        let e = err(&v2.replace("3 1 2 1 3 60 50", "3 1 2 1 3 20 50"));
        assert_eq!(e.line, Some(30));
        assert!(e.message.contains("shared by two cells"), "{e}");
        // interior only: a node set, no edge set
        let m = parse(&v2.replace("4 1 2 5 4 10 40", "4 1 2 5 4 20 50")).unwrap();
        assert_eq!(m.node_sets["physical_5"], vec![1, 4]);
        assert!(!m.edge_sets.contains_key("physical_5"));
        // a physical point off the mesh
        let e = err(&v2.replace("1 15 2 3 1 10", "1 15 2 3 1 99"));
        assert_eq!(e.line, Some(28));
    }

    #[test]
    fn no_cells_hints_at_physical_surface() {
        let v2 = text("hand_two_quads_v22.msh")
            .replace("5 3 2 2 1 10 20 50 40\n6 3 2 2 1 20 50 60 30\n", "")
            .replace("$Elements\n6", "$Elements\n4");
        let e = err(&v2);
        assert!(e.message.contains("Physical Surface"), "{e}");
    }

    #[test]
    fn malformed_tokens_and_sections() {
        let v2 = text("hand_two_quads_v22.msh");
        for (from, to, line, word) in [
            ("40 0 1 0", "40 0 one 0", 21, "the node's y"),
            ("40 0 1 0", "40 0 nan 0", 21, "finite"),
            ("1 1 \"top\"", "1 1 top", 13, "quoted"),
            ("$EndNodes", "$EndNode", 25, "$EndNodes"),
            ("$Elements\n6", "$Elements\n-6", 27, "number of elements"),
            ("3 1 2 1 3 60 50", "3 1 2 1 3 60 0", 30, "positive"),
            ("$EndElements", "$EndElements\n$EndNodes", 35, "without"),
            ("$EndElements", "$EndElements\n12", 35, "section header"),
        ] {
            let e = err(&v2.replace(from, to));
            assert_eq!(e.line, Some(line), "{from} -> {to}: {e}");
            assert!(e.message.contains(word), "{from} -> {to}: {e}");
        }
    }

    #[test]
    fn read_missing_file_names_the_path() {
        let e = read(&data("no_such_file.msh")).unwrap_err();
        assert!(e.message.contains("no_such_file.msh"));
    }
}
