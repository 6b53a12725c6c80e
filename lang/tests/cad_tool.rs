//! `tool NAME = iges { file = ".." }`: CAD faces of an IGES file as a rigid
//! surface tool of a `3d` deck. The file is written by `ctc_geom`'s IGES
//! writer next to the deck (a flat trimmed plate with a circular hole),
//! the deck names it relative to its own directory, and the lowered tool
//! holds the face, its hole and its free side; a missing file and a file
//! that is not IGES are located errors at the `file` value.

use ctc_engine::model::{AnyModel, SurfaceShape};
use ctc_geom::iges::Writer;
use ctc_geom::nurbs::build;
use ctc_geom::trim::TrimCurve;
use ctc_geom::{Vec2, Vec3};
use ctc_lang::Source;
use std::path::PathBuf;

/// A fresh directory under the system's temporary directory.
fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("ctc-cad-tool-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn plate_with_hole() -> String {
    let v = Vec2::new;
    let outer = vec![
        TrimCurve::line(v(0.0, 0.0), v(1.0, 0.0)).unwrap(),
        TrimCurve::line(v(1.0, 0.0), v(1.0, 1.0)).unwrap(),
        TrimCurve::line(v(1.0, 1.0), v(0.0, 1.0)).unwrap(),
        TrimCurve::line(v(0.0, 1.0), v(0.0, 0.0)).unwrap(),
    ];
    let hole = vec![TrimCurve::arc(v(0.5, 0.5), 0.125, 0.0, -std::f64::consts::TAU).unwrap()];
    let s = build::plane_patch(
        Vec3::new(-0.5, -0.5, 1.0),
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.0, 2.0, 0.0),
    );
    let mut w = Writer::new("ctc test: plate with a hole");
    let si = w.add_surface(&s);
    let o = w.add_loop(si, &outer);
    let h = w.add_loop(si, &hole);
    w.add_trimmed(si, Some(o), &[h]);
    w.finish()
}

fn deck(file: &str) -> String {
    format!(
        "analysis {{ dimension = 3d }}\n\
         material m {{ elastic {{ E = 1000  nu = 0.3 }} }}\n\
         body block {{ mesh = box {{ size = (1, 1, 1)  divisions = (3, 3, 3) }}  material = m }}\n\
         tool plate = iges {{ file = \"{file}\"  flip = true\n  motion {{ uz = ramp(0, -0.01) }} }}\n\
         contact block.zmax -> plate {{ method = penalty {{ stiffness = 1e5 }} }}\n\
         fix block.zmin {{ uz }}\nfix block.xmin {{ ux }}\nfix block.ymin {{ uy }}\n\
         step press {{ time = 0 .. 1  increments = 2 }}\n"
    )
}

#[test]
fn an_iges_file_next_to_the_deck_becomes_a_cad_tool() {
    let dir = scratch("ok");
    std::fs::write(dir.join("plate.igs"), plate_with_hole()).unwrap();
    let path = dir.join("press.ctc");
    std::fs::write(&path, deck("plate.igs")).unwrap();
    let src = Source::read(&path).unwrap();
    let model = match ctc_lang::compile_any(&src) {
        Ok(AnyModel::D3(m)) => m,
        Ok(_) => panic!("a 3d model"),
        Err(d) => panic!("{}", d.render(&src)),
    };
    let SurfaceShape::Brep(tool) = &model.surfaces[0].geometry else {
        panic!("a CAD tool");
    };
    assert_eq!(tool.faces.len(), 1);
    let holes = tool.faces[0].boundary.as_ref().map(|b| b.holes.len());
    assert_eq!(holes, Some(1));
    // flip = true: free space opposite S_u x S_v = +z, where the block is
    assert_eq!(tool.faces[0].orientation, -1.0);
    assert_eq!(model.contacts[0].faces.len(), 9);
    let plan = ctc_lang::explain::explain_solid(&model);
    assert!(
        plan.contains("CAD faces: 1 NURBS face (1 trimmed, 1 hole)"),
        "{plan}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_missing_or_broken_iges_file_is_an_error_at_the_file_value() {
    let dir = scratch("bad");
    let path = dir.join("press.ctc");
    std::fs::write(&path, deck("nowhere.igs")).unwrap();
    let src = Source::read(&path).unwrap();
    let text = ctc_lang::compile_any(&src).unwrap_err().render(&src);
    assert!(
        text.contains("cannot read IGES file `nowhere.igs`"),
        "{text}"
    );
    assert!(text.contains("press.ctc:4:"), "{text}");
    std::fs::write(dir.join("broken.igs"), "this is not an IGES file\n").unwrap();
    std::fs::write(&path, deck("broken.igs")).unwrap();
    let src = Source::read(&path).unwrap();
    let text = ctc_lang::compile_any(&src).unwrap_err().render(&src);
    assert!(
        text.contains("error in IGES file `broken.igs` (line 1)"),
        "{text}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
