//! `tool NAME = stl { file = ".." }`: the triangles of an STL file (ASCII
//! or binary) as a rigid surface tool of a `3d` deck. The files are
//! written by `ctc_geom::trimesh::stl` next to the deck (a closed cube of
//! 12 triangles, and the same cube without its top: an open surface); the
//! lowered tool holds the merged mesh with its pseudonormals. Bad files
//! are located errors at the `file` value that name the file and the
//! cause: missing, truncated, a NaN coordinate, a zero-area triangle, an
//! open surface where `closed = true` asks for a solid, inconsistent
//! orientation. Nothing panics.

use ctc_engine::model::{AnyModel, SurfaceShape};
use ctc_geom::trimesh::stl;
use ctc_geom::Vec3;
use ctc_lang::Source;
use std::path::PathBuf;

/// A fresh directory under the system's temporary directory.
fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("ctc-stl-tool-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The 12 triangles of the cube `[-0.5, 1.5] x [-0.5, 1.5] x [1, 2]`,
/// counter-clockwise seen from outside (the top two last).
fn cube() -> Vec<[Vec3; 3]> {
    let p = |x: f64, y: f64, z: f64| Vec3::new(-0.5 + 2.0 * x, -0.5 + 2.0 * y, 1.0 + z);
    let quads = [
        // bottom (z = 1), seen from below
        [p(0., 0., 0.), p(0., 1., 0.), p(1., 1., 0.), p(1., 0., 0.)],
        [p(0., 0., 0.), p(1., 0., 0.), p(1., 0., 1.), p(0., 0., 1.)],
        [p(1., 0., 0.), p(1., 1., 0.), p(1., 1., 1.), p(1., 0., 1.)],
        [p(1., 1., 0.), p(0., 1., 0.), p(0., 1., 1.), p(1., 1., 1.)],
        [p(0., 1., 0.), p(0., 0., 0.), p(0., 0., 1.), p(0., 1., 1.)],
        // top
        [p(0., 0., 1.), p(1., 0., 1.), p(1., 1., 1.), p(0., 1., 1.)],
    ];
    quads
        .iter()
        .flat_map(|[a, b, c, d]| [[*a, *b, *c], [*a, *c, *d]])
        .collect()
}

fn deck(tool: &str) -> String {
    format!(
        "analysis {{ dimension = 3d }}\n\
         material m {{ elastic {{ E = 1000  nu = 0.3 }} }}\n\
         body block {{ mesh = box {{ size = (1, 1, 1)  divisions = (3, 3, 3) }}  material = m }}\n\
         {tool}\n\
         contact block.zmax -> punch {{ method = penalty {{ stiffness = 1e5 }} }}\n\
         fix block.zmin {{ uz }}\nfix block.xmin {{ ux }}\nfix block.ymin {{ uy }}\n\
         step press {{ time = 0 .. 1  increments = 2 }}\n"
    )
}

fn compile(dir: &std::path::Path, tool: &str) -> Result<ctc_engine::model::Model<3>, String> {
    let path = dir.join("press.ctc");
    std::fs::write(&path, deck(tool)).unwrap();
    let src = Source::read(&path).unwrap();
    match ctc_lang::compile_any(&src) {
        Ok(AnyModel::D3(m)) => Ok(m),
        Ok(_) => panic!("a 3d model"),
        Err(d) => Err(d.render(&src)),
    }
}

#[test]
fn ascii_and_binary_stl_files_become_the_same_triangulated_tool() {
    let dir = scratch("ok");
    std::fs::write(dir.join("cube.stl"), stl::write_ascii("cube", &cube())).unwrap();
    std::fs::write(dir.join("cube_bin.stl"), stl::write_binary(&cube())).unwrap();
    let mut meshes = Vec::new();
    for file in ["cube.stl", "cube_bin.stl"] {
        let m = compile(
            &dir,
            &format!(
                "tool punch = stl {{ file = \"{file}\"  closed = true\n  motion {{ uz = ramp(0, -0.01) }} }}"
            ),
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let SurfaceShape::Mesh(mesh) = &m.surfaces[0].geometry else {
            panic!("a triangulated tool");
        };
        // 12 triangles, corners merged into the cube's 8 vertices, closed
        assert_eq!((mesh.triangles.len(), mesh.vertices.len()), (12, 8));
        assert!(mesh.edge_free.iter().all(|f| !f));
        // the block's top z = 1 is on the cube's bottom face, outside it
        let p = mesh.project(&Vec3::new(0.5, 0.5, 0.9)).unwrap();
        assert!((p.gap - 0.1).abs() < 1e-12 && (p.normal + Vec3::z()).norm() < 1e-12);
        let plan = ctc_lang::explain::explain_solid(&m);
        assert!(
            plan.contains("triangulated surface (STL): 12 triangles, 8 vertices, closed"),
            "{plan}"
        );
        meshes.push(mesh.clone());
    }
    // binary coordinates are f32: the cube's are exact in both
    assert_eq!(meshes[0].vertices, meshes[1].vertices);
    // flip = true: free space inside the cube
    let m = compile(
        &dir,
        "tool punch = stl { file = \"cube.stl\"  flip = true }",
    )
    .unwrap();
    let SurfaceShape::Mesh(mesh) = &m.surfaces[0].geometry else {
        panic!("a triangulated tool");
    };
    assert!(mesh.project(&Vec3::new(0.5, 0.5, 0.9)).unwrap().gap < 0.0);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_stl_files_are_errors_naming_the_file_and_the_cause() {
    let dir = scratch("bad");
    let tool =
        |file: &str, extra: &str| format!("tool punch = stl {{ file = \"{file}\" {extra} }}");
    let expect = |tool: String, words: &[&str]| {
        let text = compile(&dir, &tool)
            .err()
            .unwrap_or_else(|| panic!("{tool}: accepted"));
        assert!(text.contains("press.ctc:4:"), "{text}");
        for w in words {
            assert!(text.contains(w), "missing `{w}` in\n{text}");
        }
    };
    expect(
        tool("nowhere.stl", ""),
        &["cannot read STL file `nowhere.stl`", "file not found"],
    );
    // a binary file cut in the middle of its last triangle
    let mut bin = stl::write_binary(&cube());
    bin.truncate(bin.len() - 20);
    std::fs::write(dir.join("truncated.stl"), &bin).unwrap();
    expect(
        tool("truncated.stl", ""),
        &["error in STL file `truncated.stl`", "neither a binary STL"],
    );
    // an ASCII file that stops after a vertex
    let text = stl::write_ascii("cube", &cube());
    let cut: String = text.lines().take(5).map(|l| format!("{l}\n")).collect();
    std::fs::write(dir.join("cut.stl"), cut).unwrap();
    expect(
        tool("cut.stl", ""),
        &["error in STL file `cut.stl`", "the file ends"],
    );
    // a NaN coordinate
    let nan = text.replacen("vertex -5e-1", "vertex nan", 1);
    assert_ne!(nan, text);
    std::fs::write(dir.join("nan.stl"), nan).unwrap();
    expect(
        tool("nan.stl", ""),
        &["`nan.stl`", "three finite coordinates"],
    );
    // a zero-area (degenerate) triangle
    let mut tris = cube();
    tris.push([tris[0][0], tris[0][0], tris[0][1]]);
    std::fs::write(dir.join("sliver.stl"), stl::write_ascii("s", &tris)).unwrap();
    expect(
        tool("sliver.stl", ""),
        &["`sliver.stl`", "triangle 13 has zero area"],
    );
    // the cube without its top: open, refused where a solid is required
    let open: Vec<_> = cube().into_iter().take(10).collect();
    std::fs::write(dir.join("open.stl"), stl::write_ascii("open", &open)).unwrap();
    expect(
        tool("open.stl", "closed = true"),
        &["`open.stl`", "the surface is not closed", "4 such edges"],
    );
    assert!(compile(&dir, &tool("open.stl", "")).is_ok());
    // a triangle turned the other way
    let mut turned = cube();
    turned[3].swap(1, 2);
    std::fs::write(dir.join("turned.stl"), stl::write_ascii("t", &turned)).unwrap();
    expect(
        tool("turned.stl", ""),
        &["`turned.stl`", "oriented inconsistently"],
    );
    let _ = std::fs::remove_dir_all(&dir);
}
